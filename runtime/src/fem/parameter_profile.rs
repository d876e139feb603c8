//! Model parameters that vary over the domain: a parameter declared `[varying]` in the DSL
//! (`docs/dsl.md`) may be given a profile, a piecewise-linear function of one coordinate,
//! which the assembler evaluates at every quadrature point.
//!
//! A profile along the axis $`X`$ (or $`Y`$) is a table of points $`(X_k, p_k)`$ with
//! $`X_0 < X_1 < \dots`$:
//! $$`p(X) = p_k + \frac{X - X_k}{X_{k+1} - X_k}\,(p_{k+1} - p_k),\qquad X_k \le X \le X_{k+1},`$$
//! and $`p_0`$ before the first point, the last value after the last (constant extension). A
//! table of one point is a constant. The model's density at a point is the model's with the
//! profiled parameters replaced by their values there; its kernels are unchanged, so the
//! energy → residual → tangent triad (and the Taylor-mode kernels) stay consistent point by
//! point, and a model whose derivation assumes a parameter varies slowly on the wavelength
//! (the paper's foundation $`c(X)`$ of a beam, THEORY.md §7) reads it as the local value.

/// The coordinate a profile is a function of.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileAxis {
    /// $`X`$ (the beam's axis).
    X,
    /// $`Y`$.
    Y,
}

/// Why a table is not a profile.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProfileError {
    /// No points.
    #[error("a profile needs at least one point (coordinate, value)")]
    Empty,
    /// A coordinate or value that is NaN or infinite.
    #[error("point {index} of the profile is not finite")]
    NotFinite {
        /// Index of the point in the table.
        index: usize,
    },
    /// Coordinates not strictly increasing.
    #[error(
        "the profile's coordinates must increase strictly: point {index} ({coordinate}) does not come after {previous}"
    )]
    NotIncreasing {
        /// Index of the offending point.
        index: usize,
        /// Its coordinate.
        coordinate: f64,
        /// The previous point's coordinate.
        previous: f64,
    },
}

/// A piecewise-linear function of one coordinate (see the module documentation).
#[derive(Clone, Debug, PartialEq)]
pub struct ParameterProfile {
    axis: ProfileAxis,
    table: Vec<[f64; 2]>,
}

impl ParameterProfile {
    /// The profile through the points `table` ($`(X_k, p_k)`$, coordinates strictly increasing)
    /// along `axis`.
    pub fn new(axis: ProfileAxis, table: Vec<[f64; 2]>) -> Result<Self, ProfileError> {
        if table.is_empty() {
            return Err(ProfileError::Empty);
        }
        for (index, point) in table.iter().enumerate() {
            if !point.iter().all(|v| v.is_finite()) {
                return Err(ProfileError::NotFinite { index });
            }
            if index > 0 && point[0] <= table[index - 1][0] {
                return Err(ProfileError::NotIncreasing {
                    index,
                    coordinate: point[0],
                    previous: table[index - 1][0],
                });
            }
        }
        Ok(ParameterProfile { axis, table })
    }

    /// The axis the profile varies along.
    pub fn axis(&self) -> ProfileAxis {
        self.axis
    }

    /// The table's points $`(X_k, p_k)`$.
    pub fn table(&self) -> &[[f64; 2]] {
        &self.table
    }

    /// $`p`$ at the physical point `point` $`(X, Y)`$.
    pub fn value_at(&self, point: [f64; 2]) -> f64 {
        let coordinate = match self.axis {
            ProfileAxis::X => point[0],
            ProfileAxis::Y => point[1],
        };
        self.value_along(coordinate)
    }

    /// $`p`$ at the coordinate `coordinate` along the profile's axis.
    pub fn value_along(&self, coordinate: f64) -> f64 {
        let table = &self.table;
        let after = table.partition_point(|point| point[0] <= coordinate);
        if after == 0 {
            return table[0][1];
        }
        if after == table.len() {
            return table[table.len() - 1][1];
        }
        let ([x0, p0], [x1, p1]) = (table[after - 1], table[after]);
        p0 + (coordinate - x0) / (x1 - x0) * (p1 - p0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn piecewise_linear_with_constant_ends() {
        let profile =
            ParameterProfile::new(ProfileAxis::X, vec![[0.0, 1.0], [2.0, 3.0], [4.0, 3.0]])
                .unwrap();
        assert_eq!(profile.value_at([-1.0, 5.0]), 1.0);
        assert_eq!(profile.value_at([1.0, 0.0]), 2.0);
        assert_eq!(profile.value_at([2.0, 0.0]), 3.0);
        assert_eq!(profile.value_at([9.0, 0.0]), 3.0);
        let along_y = ParameterProfile::new(ProfileAxis::Y, vec![[0.0, 0.0], [1.0, 2.0]]).unwrap();
        assert_eq!(along_y.value_at([7.0, 0.25]), 0.5);
        let constant = ParameterProfile::new(ProfileAxis::X, vec![[0.0, 4.0]]).unwrap();
        assert_eq!(constant.value_at([-3.0, 0.0]), 4.0);
    }

    #[test]
    fn bad_tables_are_refused() {
        assert_eq!(
            ParameterProfile::new(ProfileAxis::X, vec![]),
            Err(ProfileError::Empty)
        );
        assert!(matches!(
            ParameterProfile::new(ProfileAxis::X, vec![[0.0, 1.0], [0.0, 2.0]]),
            Err(ProfileError::NotIncreasing { index: 1, .. })
        ));
        assert!(matches!(
            ParameterProfile::new(ProfileAxis::X, vec![[0.0, f64::NAN]]),
            Err(ProfileError::NotFinite { index: 0 })
        ));
    }
}
