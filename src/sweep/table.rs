//! A sweep's table: one row per point, its inputs then its result ([`table_columns`],
//! [`table_cells`]), written as `sweep.csv` ([`write_table_csv`]; columns in
//! `docs/outputs.md`).

use super::plan::SweepRow;
use crate::compare::AMPLITUDE_LEVELS;
use std::path::Path;

/// Name of the table in a sweep directory.
pub const TABLE_FILE: &str = "sweep.csv";

/// One cell of the table.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
#[serde(untagged)]
pub enum Cell {
    /// Empty (no value).
    Empty,
    /// Text, or an input value as given.
    Text(String),
    /// An integer.
    Integer(i64),
    /// A number.
    Number(f64),
    /// `true` or `false`.
    Flag(bool),
}

impl Cell {
    /// The CSV text of the cell: numbers in the shortest form that reads back exactly, text
    /// quoted when it holds a comma, a quote or a line break.
    pub fn csv(&self) -> String {
        match self {
            Cell::Empty => String::new(),
            Cell::Text(text) if text.contains([',', '"', '\n', '\r']) => {
                format!("\"{}\"", text.replace('"', "\"\""))
            }
            Cell::Text(text) => text.clone(),
            Cell::Integer(value) => value.to_string(),
            Cell::Number(value) => format!("{value:e}"),
            Cell::Flag(value) => value.to_string(),
        }
    }
}

/// The result columns, after `index` and the inputs.
pub fn result_columns() -> Vec<String> {
    let mut columns: Vec<String> = [
        "outcome",
        "exit_code",
        "reason",
        "model",
        "dofs",
        "critical_load",
        "load_unit",
        "closed_form_critical_load",
        "closed_form_relative_difference",
        "closed_form_wavenumber",
        "wavenumber",
        "wavelength",
    ]
    .map(String::from)
    .into();
    columns.extend(
        AMPLITUDE_LEVELS
            .iter()
            .map(|a| format!("load_at_amplitude_{a}")),
    );
    columns.extend(
        [
            "steps",
            "failed_checks",
            "seconds",
            "peak_memory_bytes",
            "reused",
            "hash",
            "directory",
        ]
        .map(String::from),
    );
    columns
}

/// The columns of `rows`: `index`, each input key in the order first met, the result columns.
pub fn table_columns(rows: &[SweepRow]) -> Vec<String> {
    let mut columns = vec!["index".to_string()];
    for row in rows {
        for (key, _) in &row.inputs {
            if !columns.contains(key) {
                columns.push(key.clone());
            }
        }
    }
    columns.extend(result_columns());
    columns
}

/// The cells of `row` under `columns` ([`table_columns`]).
pub fn table_cells(row: &SweepRow, columns: &[String]) -> Vec<Cell> {
    let result = &row.result;
    let number = |value: Option<f64>| value.map_or(Cell::Empty, Cell::Number);
    let integer = |value: Option<i64>| value.map_or(Cell::Empty, Cell::Integer);
    let text = |value: Option<&str>| value.map_or(Cell::Empty, |t| Cell::Text(t.to_string()));
    let count = |value: Option<usize>| integer(value.and_then(|v| i64::try_from(v).ok()));
    columns
        .iter()
        .map(|column| match column.as_str() {
            "index" => count(Some(row.index)),
            "outcome" => Cell::Text(result.outcome.clone()),
            "exit_code" => integer(result.exit_code.map(i64::from)),
            "reason" => text(result.reason.as_deref()),
            "model" => text(result.model.as_deref()),
            "dofs" => count(result.dofs),
            "critical_load" => number(result.critical_load),
            "load_unit" => text(result.load_unit.as_deref()),
            "closed_form_critical_load" => number(result.closed_form_critical_load),
            "closed_form_relative_difference" => number(result.closed_form_relative_difference),
            "closed_form_wavenumber" => number(result.closed_form_wavenumber),
            "wavenumber" => number(result.wavenumber),
            "wavelength" => number(result.wavelength),
            "steps" => count(result.steps),
            "failed_checks" => Cell::Text(result.failed_checks.join(";")),
            "seconds" => Cell::Number(result.seconds),
            "peak_memory_bytes" => {
                integer(result.peak_memory_bytes.and_then(|b| i64::try_from(b).ok()))
            }
            "reused" => Cell::Flag(result.reused),
            "hash" => Cell::Text(result.hash.clone()),
            "directory" => Cell::Text(result.directory.clone()),
            other => match amplitude_index(other) {
                Some(level) => number(result.load_at_amplitude.get(level).copied().flatten()),
                None => row
                    .inputs
                    .iter()
                    .find(|(key, _)| key == other)
                    .map_or(Cell::Empty, |(_, value)| Cell::Text(value.clone())),
            },
        })
        .collect()
}

/// The position in [`AMPLITUDE_LEVELS`] of a `load_at_amplitude_A` column.
fn amplitude_index(column: &str) -> Option<usize> {
    let level = column.strip_prefix("load_at_amplitude_")?;
    AMPLITUDE_LEVELS
        .iter()
        .position(|a| format!("{a}") == level)
}

/// The table of `rows` as CSV text: a header line, one line per row.
pub fn table_csv(rows: &[SweepRow]) -> String {
    let columns = table_columns(rows);
    let header: Vec<String> = columns
        .iter()
        .map(|c| Cell::Text(c.clone()).csv())
        .collect();
    let mut text = header.join(",");
    text.push('\n');
    for row in rows {
        let cells: Vec<String> = table_cells(row, &columns).iter().map(Cell::csv).collect();
        text.push_str(&cells.join(","));
        text.push('\n');
    }
    text
}

/// Writes the table of `rows` to `path`, atomically.
pub fn write_table_csv(path: &Path, rows: &[SweepRow]) -> std::io::Result<()> {
    crate::output::write_bytes_atomically(path, table_csv(rows).as_bytes())
}
