//! TOML text in and out: syntax-error positions, `--set` values, how a value is named in an
//! error message, and floats, strings and keys written so that TOML reads them back unchanged.

use toml::Value;

/// One-line description of a TOML syntax error with its line and column.
pub(super) fn syntax_message(text: &str, error: &toml::de::Error) -> String {
    let message = error.message().trim().replace('\n', " ");
    match error.span() {
        Some(span) => {
            let offset = span.start.min(text.len());
            let before = &text[..offset];
            let line = before.matches('\n').count() + 1;
            let column = before
                .rsplit('\n')
                .next()
                .map_or(0, |tail| tail.chars().count())
                + 1;
            format!("TOML syntax error at line {line}, column {column}: {message}")
        }
        None => format!("TOML syntax error: {message}"),
    }
}

/// Parses the value of a `--set` override.
pub(super) fn parse_override_value(text: &str) -> Result<Value, String> {
    if text.is_empty() {
        return Err("missing value after `=`".to_string());
    }
    match text.parse::<Value>() {
        Ok(value) => Ok(value),
        Err(_) if is_bare_word(text) => Ok(Value::String(text.to_string())),
        Err(error) => Err(format!(
            "`{text}` is not a TOML value ({}); quote strings, e.g. '\"text\"'",
            error.message().trim().replace('\n', " ")
        )),
    }
}

/// A word that can stand for a string without quotes: starts with a letter, then letters,
/// digits, `-` or `_`.
fn is_bare_word(text: &str) -> bool {
    let mut characters = text.chars();
    characters
        .next()
        .is_some_and(|first| first.is_ascii_alphabetic())
        && characters.all(|character| {
            character.is_ascii_alphanumeric() || character == '-' || character == '_'
        })
}

/// How a TOML value is named in error messages.
pub(super) fn describe(value: &Value) -> String {
    match value {
        Value::String(text) => format!("string {}", toml_string(text)),
        Value::Integer(number) => format!("integer {number}"),
        Value::Float(number) => format!("float {}", short_number(*number)),
        Value::Boolean(flag) => format!("boolean {flag}"),
        Value::Datetime(datetime) => format!("datetime {datetime}"),
        Value::Array(_) => "an array".to_string(),
        Value::Table(_) => "a table".to_string(),
    }
}

/// A number as a reader wants it in a message or a table: as written (`0.6`, `70000`) unless
/// that takes more than ten characters and the exponent form is shorter (`1e300`, `1e-12`).
pub(super) fn short_number(value: f64) -> String {
    let plain = value.to_string();
    let exponent = format!("{value:e}");
    if plain.len() > 10 && exponent.len() < plain.len() {
        exponent
    } else {
        plain
    }
}

/// A float written so that TOML reads it back as the same float.
pub(super) fn toml_float(value: f64) -> String {
    if value.is_finite() {
        format!("{value:?}")
    } else if value.is_nan() {
        "nan".to_string()
    } else if value > 0.0 {
        "inf".to_string()
    } else {
        "-inf".to_string()
    }
}

/// A TOML basic string literal.
pub(super) fn toml_string(text: &str) -> String {
    Value::String(text.to_string()).to_string()
}

/// A TOML key, bare when possible.
pub(super) fn toml_key(name: &str) -> String {
    if !name.is_empty()
        && name.chars().all(|character| {
            character.is_ascii_alphanumeric() || character == '-' || character == '_'
        })
    {
        name.to_string()
    } else {
        toml_string(name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn floats_round_trip_through_toml_text() {
        for value in [400.0, 0.05, 1e-7, 0.1 + 0.2, -3.5e12, 0.0] {
            let parsed: Value = toml_float(value).parse().unwrap();
            let number = match parsed {
                Value::Float(number) => number,
                other => panic!("{other:?}"),
            };
            assert_eq!(number, value);
        }
    }

    #[test]
    fn short_numbers_keep_small_values_as_written_and_shorten_long_ones() {
        assert_eq!(short_number(0.6), "0.6");
        assert_eq!(short_number(70000.0), "70000");
        assert_eq!(short_number(-1.0), "-1");
        assert_eq!(short_number(1e300), "1e300");
        assert_eq!(short_number(1e-12), "1e-12");
        assert_eq!(short_number(0.1 + 0.2), "0.30000000000000004");
        assert_eq!(short_number(f64::NAN), "NaN");
    }
}
