//! The traced equilibrium path as a table: one [`PathPoint`] per row, written as CSV by
//! [`write_path_csv`]; the same points serialise to JSON with [`serde`] (the caller assembles
//! `summary.json`).

use super::files::write_atomically;
use std::io::{self, Write};
use std::path::Path;

/// One point of a traced equilibrium path.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct PathPoint {
    /// ANM step index (0 = the start point).
    pub step: usize,
    /// `true`: the series was evaluated inside a step (dense output); `false`: a step end point.
    pub interior: bool,
    /// Load parameter $`\lambda`$.
    pub lambda: f64,
    /// Membrane force $`N_x = -\lambda`$ for the biaxial load, `None` otherwise (a negative
    /// zero is serialised as `0`).
    #[serde(serialize_with = "serialize_without_negative_zero")]
    pub n_x: Option<f64>,
    /// Maximum physical wrinkle amplitude over the domain (mm): $`\max|w|`$ for a plate,
    /// $`2\max|w_\text{env}|`$ (or $`2\max|w_1|`$) for envelope models.
    pub max_amplitude: f64,
    /// `max_amplitude` over the thickness $`h`$.
    pub max_amplitude_over_h: f64,
    /// Local physical wrinkle amplitude at the centre of the domain over $`h`$: half the
    /// peak-to-peak of $`w`$ within one wavelength of the centre for a plate,
    /// $`2|w_\text{env}|`$ (or $`2|w_1|`$) at the centre for envelope models.
    pub centre_amplitude_over_h: f64,
    /// Relative residual $`\lVert R \rVert / \lVert F \rVert`$ at that point.
    pub residual: f64,
    /// `true` when the Legendre–Hadamard (strong ellipticity) condition holds everywhere.
    pub elliptic: bool,
    /// Closed-form physical amplitude at the centre over $`h`$ at this load, $`2a/h`$ of
    /// THEORY.md eq. (61)/(62), for a clamped rectangle under biaxial load.
    pub closed_form_amplitude_over_h: Option<f64>,
}

/// Column names of the CSV written by [`write_path_csv`], in order; they are the field names of
/// [`PathPoint`].
pub const PATH_CSV_COLUMNS: [&str; 10] = [
    "step",
    "interior",
    "lambda",
    "n_x",
    "max_amplitude",
    "max_amplitude_over_h",
    "centre_amplitude_over_h",
    "residual",
    "elliptic",
    "closed_form_amplitude_over_h",
];

/// Writes the path as CSV to the file `path` (replaced atomically): a header line with
/// [`PATH_CSV_COLUMNS`], then one line per point. Numbers are written so that they parse back to
/// the same `f64` bit for bit (a negative zero as `0`); booleans as `true`/`false`; `None` as an empty cell.
pub fn write_path_csv(path: &Path, points: &[PathPoint]) -> io::Result<()> {
    write_atomically(path, |writer| write_path_csv_to(writer, points))
}

/// Writes the CSV of [`write_path_csv`] to any writer.
pub fn write_path_csv_to(mut writer: impl Write, points: &[PathPoint]) -> io::Result<()> {
    writeln!(writer, "{}", PATH_CSV_COLUMNS.join(","))?;
    for point in points {
        let cells = [
            point.step.to_string(),
            point.interior.to_string(),
            format_number(point.lambda),
            point.n_x.map(format_number).unwrap_or_default(),
            format_number(point.max_amplitude),
            format_number(point.max_amplitude_over_h),
            format_number(point.centre_amplitude_over_h),
            format_number(point.residual),
            point.elliptic.to_string(),
            point
                .closed_form_amplitude_over_h
                .map(format_number)
                .unwrap_or_default(),
        ];
        writeln!(writer, "{}", cells.join(","))?;
    }
    Ok(())
}

/// Serialises an optional number with $`-0`$ written as `0` (e.g. $`N_X = -\lambda`$ at
/// $`\lambda = 0`$).
fn serialize_without_negative_zero<S: serde::Serializer>(
    value: &Option<f64>,
    serializer: S,
) -> Result<S::Ok, S::Error> {
    serde::Serialize::serialize(&value.map(|number| number + 0.0), serializer)
}

/// Shortest representation that parses back to the same `f64`: plain decimal for moderate
/// magnitudes, scientific notation for very small or very large ones; both zeros are written
/// `0` (a negative zero, e.g. $`N_X = -\lambda`$ at $`\lambda = 0`$, is not worth a sign).
fn format_number(value: f64) -> String {
    let magnitude = value.abs();
    if value == 0.0 {
        "0".to_string()
    } else if !value.is_finite() || (1e-4..1e7).contains(&magnitude) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

#[cfg(test)]
mod tests {
    use super::format_number;

    #[test]
    fn numbers_round_trip_exactly() {
        for value in [
            0.0,
            0.09,
            1.0 / 3.0,
            1e-300,
            -2.5e12,
            123456.789,
            f64::MIN_POSITIVE,
        ] {
            let text = format_number(value);
            assert_eq!(
                text.parse::<f64>().unwrap().to_bits(),
                value.to_bits(),
                "{text}"
            );
        }
        assert_eq!(format_number(0.09), "0.09");
        assert_eq!(format_number(1e-9), "1e-9");
    }

    /// $`N_X = -\lambda`$ at $`\lambda = 0`$ is written `0`, not `-0`, in the CSV and the JSON.
    #[test]
    fn negative_zero_is_written_as_zero() {
        assert_eq!(format_number(-0.0), "0");
        let point = super::PathPoint {
            step: 0,
            interior: false,
            lambda: 0.0,
            n_x: Some(-0.0),
            max_amplitude: 0.0,
            max_amplitude_over_h: 0.0,
            centre_amplitude_over_h: 0.0,
            residual: 0.0,
            elliptic: true,
            closed_form_amplitude_over_h: None,
        };
        let json = serde_json::to_string(&point).unwrap();
        assert!(json.contains("\"n_x\":0.0"), "{json}");
    }
}
