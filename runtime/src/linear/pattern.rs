//! Symmetric sparsity pattern in compressed sparse column (CSC) form and matrices sharing it.

use std::sync::Arc;

use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use rayon::prelude::*;

use super::error::LinearError;

/// Symmetric sparsity pattern of an $`n \times n`$ matrix in compressed sparse column (CSC) form.
///
/// Both triangles are stored, the row indices of every column are sorted and unique, and the
/// diagonal is always present. The pattern is built once per mesh and dof map and shared (behind an
/// [`Arc`]) by every matrix assembled on it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SparsityPattern {
    dimension: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl SparsityPattern {
    /// Builds the pattern from element dof lists: every pair $`(a, b)`$ of free dofs appearing
    /// together in one element list is a non-zero. Entries `None` are constrained dofs and are
    /// skipped. The diagonal is always present for $`0 \le i < n`$.
    ///
    /// # Panics
    /// Panics if a dof index is not below `n` (a broken dof map, a programming error); use
    /// [`SparsityPattern::try_from_element_dofs`] to get an error instead.
    pub fn from_element_dofs<'a>(
        n: usize,
        elements: impl Iterator<Item = &'a [Option<usize>]>,
    ) -> Self {
        match Self::try_from_element_dofs(n, elements) {
            Ok(pattern) => pattern,
            Err(error) => panic!("invalid element dof list: {error}"),
        }
    }

    /// Fallible version of [`SparsityPattern::from_element_dofs`]: returns
    /// [`LinearError::IndexOutOfRange`] when a dof index is not below `n`.
    pub fn try_from_element_dofs<'a>(
        n: usize,
        elements: impl Iterator<Item = &'a [Option<usize>]>,
    ) -> Result<Self, LinearError> {
        Self::try_from_coupled_element_dofs(n, elements, |_, _| true)
    }

    /// [`SparsityPattern::try_from_element_dofs`] keeping only the pairs of element-local dofs
    /// $`(a, b)`$ for which `coupled(a, b)` holds (symmetric in its arguments): e.g. only the
    /// pairs of fields some term of the energy couples, so that a field block of the tangent
    /// that is identically zero is neither stored nor factorised.
    pub fn try_from_coupled_element_dofs<'a>(
        n: usize,
        elements: impl Iterator<Item = &'a [Option<usize>]>,
        coupled: impl Fn(usize, usize) -> bool,
    ) -> Result<Self, LinearError> {
        let mut columns: Vec<Vec<usize>> = (0..n).map(|column| vec![column]).collect();
        let mut free = Vec::new();
        for dofs in elements {
            free.clear();
            for (local, dof) in dofs.iter().enumerate() {
                let Some(dof) = *dof else { continue };
                if dof >= n {
                    return Err(LinearError::IndexOutOfRange {
                        index: dof,
                        dimension: n,
                    });
                }
                free.push((local, dof));
            }
            for &(a, column) in &free {
                columns[column].extend(
                    free.iter()
                        .filter(|&&(b, _)| coupled(a, b))
                        .map(|&(_, row)| row),
                );
            }
        }
        Ok(Self::from_columns(n, columns))
    }

    /// Builds the pattern from explicit entries $`(i, j)`$; the transposed entry $`(j, i)`$ and
    /// the diagonal are added automatically. Returns [`LinearError::IndexOutOfRange`] when an
    /// index is not below `n`.
    pub fn from_symmetric_entries(
        n: usize,
        entries: impl IntoIterator<Item = (usize, usize)>,
    ) -> Result<Self, LinearError> {
        let mut columns: Vec<Vec<usize>> = (0..n).map(|column| vec![column]).collect();
        for (row, column) in entries {
            for index in [row, column] {
                if index >= n {
                    return Err(LinearError::IndexOutOfRange {
                        index,
                        dimension: n,
                    });
                }
            }
            columns[column].push(row);
            columns[row].push(column);
        }
        Ok(Self::from_columns(n, columns))
    }

    fn from_columns(n: usize, mut columns: Vec<Vec<usize>>) -> Self {
        // Each column on its own (both cores: a third of building a 61 k-unknown pattern).
        columns.par_iter_mut().for_each(|rows| {
            rows.sort_unstable();
            rows.dedup();
        });
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut total = 0;
        for rows in &columns {
            total += rows.len();
            col_ptr.push(total);
        }
        let mut row_idx = Vec::with_capacity(total);
        for rows in columns {
            row_idx.extend(rows);
        }
        Self {
            dimension: n,
            col_ptr,
            row_idx,
        }
    }

    /// Dimension $`n`$ of the (square) matrix.
    pub fn dimension(&self) -> usize {
        self.dimension
    }

    /// Number of structurally non-zero entries (both triangles).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Column pointers: the rows of column $`j`$ are `row_idx()[col_ptr()[j]..col_ptr()[j + 1]]`.
    pub fn col_ptr(&self) -> &[usize] {
        &self.col_ptr
    }

    /// Row indices, sorted within each column.
    pub fn row_idx(&self) -> &[usize] {
        &self.row_idx
    }

    /// Row indices of column `column` (empty when out of range).
    pub fn rows_of_column(&self, column: usize) -> &[usize] {
        if column >= self.dimension {
            return &[];
        }
        &self.row_idx[self.col_ptr[column]..self.col_ptr[column + 1]]
    }

    /// Slot of entry $`(\mathrm{row}, \mathrm{col})`$ in the values array, found by binary
    /// search; `None` if the entry is structurally zero or out of range.
    pub fn slot(&self, row: usize, col: usize) -> Option<usize> {
        if col >= self.dimension {
            return None;
        }
        let start = self.col_ptr[col];
        self.rows_of_column(col)
            .binary_search(&row)
            .ok()
            .map(|offset| start + offset)
    }

    /// For an element dof list of length $`m`$, the $`m \times m`$ row-major table of value
    /// slots: entry $`i m + j`$ is the slot of $`(\mathrm{dofs}_i, \mathrm{dofs}_j)`$, `None`
    /// where either dof is `None` (or the pair is not in the pattern). Computed once per element
    /// and reused at every assembly.
    pub fn element_slots(&self, dofs: &[Option<usize>]) -> Vec<Option<usize>> {
        let mut slots = Vec::with_capacity(dofs.len() * dofs.len());
        for row in dofs {
            for column in dofs {
                slots.push(match (row, column) {
                    (Some(row), Some(column)) => self.slot(*row, *column),
                    _ => None,
                });
            }
        }
        slots
    }

    /// The pattern as a faer symbolic CSC matrix (copies the index arrays).
    pub fn to_faer_symbolic(&self) -> SymbolicSparseColMat<usize> {
        SymbolicSparseColMat::new_checked(
            self.dimension,
            self.dimension,
            self.col_ptr.clone(),
            None,
            self.row_idx.clone(),
        )
    }
}

/// Rows per parallel task of [`SparseMatrix::try_multiply_symmetric_into`].
const SYMMETRIC_PRODUCT_CHUNK: usize = 1024;

/// A matrix on a shared [`SparsityPattern`]: only the values are owned, the pattern sits behind an
/// [`Arc`]. `values[k]` is the entry at row `pattern.row_idx()[k]` of the column whose range
/// contains `k`.
#[derive(Clone, Debug)]
pub struct SparseMatrix {
    /// Shared sparsity pattern.
    pub pattern: Arc<SparsityPattern>,
    /// Values, one per structural non-zero, in pattern order.
    pub values: Vec<f64>,
}

impl SparseMatrix {
    /// The zero matrix on `pattern`.
    pub fn zeros(pattern: Arc<SparsityPattern>) -> Self {
        let values = vec![0.0; pattern.nnz()];
        Self { pattern, values }
    }

    /// Sets every value to zero (keeps the pattern), e.g. before a new assembly.
    pub fn fill_zero(&mut self) {
        self.values.fill(0.0);
    }

    /// Dimension $`n`$ of the matrix.
    pub fn dimension(&self) -> usize {
        self.pattern.dimension()
    }

    /// Entry $`(\mathrm{row}, \mathrm{col})`$, zero when structurally zero.
    pub fn get(&self, row: usize, col: usize) -> f64 {
        self.pattern
            .slot(row, col)
            .map_or(0.0, |slot| self.values[slot])
    }

    /// Adds `value` to entry $`(\mathrm{row}, \mathrm{col})`$; returns
    /// [`LinearError::StructuralZero`] when the entry is not in the pattern.
    pub fn add_to(&mut self, row: usize, col: usize, value: f64) -> Result<(), LinearError> {
        let slot = self
            .pattern
            .slot(row, col)
            .ok_or(LinearError::StructuralZero { row, column: col })?;
        self.values[slot] += value;
        Ok(())
    }

    /// $`y = A x`$.
    ///
    /// # Panics
    /// Panics if `x` or `y` does not have length $`n`$ (a programming error); see
    /// [`SparseMatrix::try_multiply_into`].
    pub fn multiply_into(&self, x: &[f64], y: &mut [f64]) {
        if let Err(error) = self.try_multiply_into(x, y) {
            panic!("{error}");
        }
    }

    /// [`LinearError::DimensionMismatch`] when `x`, `y` or the values do not fit the pattern.
    fn check_product(&self, x: &[f64], y: &[f64]) -> Result<(), LinearError> {
        let n = self.dimension();
        for (what, length) in [("x", x.len()), ("y", y.len())] {
            if length != n {
                return Err(LinearError::DimensionMismatch {
                    what: what.to_owned(),
                    expected: n,
                    found: length,
                });
            }
        }
        if self.values.len() != self.pattern.nnz() {
            return Err(LinearError::DimensionMismatch {
                what: "matrix values".to_owned(),
                expected: self.pattern.nnz(),
                found: self.values.len(),
            });
        }
        Ok(())
    }

    /// $`y = A x`$, returning [`LinearError::DimensionMismatch`] on wrong lengths.
    pub fn try_multiply_into(&self, x: &[f64], y: &mut [f64]) -> Result<(), LinearError> {
        self.check_product(x, y)?;
        y.fill(0.0);
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        for (column, &x_column) in x.iter().enumerate() {
            if x_column == 0.0 {
                continue;
            }
            let range = col_ptr[column]..col_ptr[column + 1];
            for (&row, &value) in row_idx[range.clone()].iter().zip(&self.values[range]) {
                y[row] += value * x_column;
            }
        }
        Ok(())
    }

    /// $`y = A x`$ for a matrix whose values are symmetric (a tangent, a geometric stiffness):
    /// then row $`i`$ equals column $`i`$, and each $`y_i`$ is a gathered dot product, computed
    /// in parallel over rows and independent of the thread count. Same errors as
    /// [`SparseMatrix::try_multiply_into`]; the values are not checked for symmetry.
    pub fn try_multiply_symmetric_into(&self, x: &[f64], y: &mut [f64]) -> Result<(), LinearError> {
        self.check_product(x, y)?;
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        y.par_chunks_mut(SYMMETRIC_PRODUCT_CHUNK)
            .enumerate()
            .for_each(|(chunk, rows)| {
                let first = chunk * SYMMETRIC_PRODUCT_CHUNK;
                for (offset, target) in rows.iter_mut().enumerate() {
                    let range = col_ptr[first + offset]..col_ptr[first + offset + 1];
                    *target = row_idx[range.clone()]
                        .iter()
                        .zip(&self.values[range])
                        .map(|(&column, &value)| value * x[column])
                        .sum();
                }
            });
        Ok(())
    }

    /// Copy as a faer CSC matrix.
    pub fn to_faer(&self) -> SparseColMat<usize, f64> {
        SparseColMat::new(self.pattern.to_faer_symbolic(), self.values.clone())
    }

    /// Dense nalgebra copy, for tests and small problems.
    pub fn to_dense(&self) -> nalgebra::DMatrix<f64> {
        let n = self.dimension();
        let mut dense = nalgebra::DMatrix::zeros(n, n);
        let col_ptr = self.pattern.col_ptr();
        let row_idx = self.pattern.row_idx();
        for column in 0..n {
            for slot in col_ptr[column]..col_ptr[column + 1] {
                dense[(row_idx[slot], column)] = self.values[slot];
            }
        }
        dense
    }

    /// Largest absolute value of each column, used as the scale of pivots.
    pub(crate) fn column_max_abs(&self) -> Vec<f64> {
        let col_ptr = self.pattern.col_ptr();
        (0..self.dimension())
            .map(|column| {
                self.values[col_ptr[column]..col_ptr[column + 1]]
                    .iter()
                    .fold(0.0_f64, |max, value| max.max(value.abs()))
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pattern_from_elements_couples_free_dofs_only() {
        let elements: Vec<Vec<Option<usize>>> = vec![
            vec![Some(0), Some(2), None],
            vec![Some(2), Some(3), Some(1)],
        ];
        let pattern = SparsityPattern::from_element_dofs(5, elements.iter().map(Vec::as_slice));
        assert_eq!(pattern.dimension(), 5);
        // Column 0: {0, 2}; 1: {1, 2, 3}; 2: {0, 1, 2, 3}; 3: {1, 2, 3}; 4: {4}.
        assert_eq!(pattern.col_ptr(), &[0, 2, 5, 9, 12, 13]);
        assert_eq!(pattern.row_idx(), &[0, 2, 1, 2, 3, 0, 1, 2, 3, 1, 2, 3, 4]);
        assert_eq!(pattern.nnz(), 13);
        assert_eq!(pattern.slot(3, 2), Some(8));
        assert_eq!(pattern.slot(0, 3), None);
        assert_eq!(pattern.slot(0, 7), None);
        let slots = pattern.element_slots(&elements[0]);
        assert_eq!(
            slots,
            vec![
                Some(0),
                Some(5),
                None,
                Some(1),
                Some(7),
                None,
                None,
                None,
                None
            ]
        );
    }

    #[test]
    fn out_of_range_dof_is_an_error() {
        let elements = [vec![Some(0), Some(9)]];
        let result = SparsityPattern::try_from_element_dofs(3, elements.iter().map(Vec::as_slice));
        assert!(matches!(
            result,
            Err(LinearError::IndexOutOfRange {
                index: 9,
                dimension: 3
            })
        ));
    }

    #[test]
    fn multiply_matches_dense_product() {
        let pattern =
            Arc::new(SparsityPattern::from_symmetric_entries(4, [(1, 0), (3, 1), (2, 2)]).unwrap());
        let mut matrix = SparseMatrix::zeros(pattern);
        let entries = [
            (0, 0, 4.0),
            (1, 0, -1.5),
            (0, 1, 2.0),
            (1, 1, 3.0),
            (3, 1, 0.5),
        ];
        for (row, column, value) in entries {
            matrix.add_to(row, column, value).unwrap();
        }
        matrix.add_to(2, 2, 7.0).unwrap();
        matrix.add_to(3, 3, -2.0).unwrap();
        assert!(matches!(
            matrix.add_to(0, 3, 1.0),
            Err(LinearError::StructuralZero { row: 0, column: 3 })
        ));
        let x = [1.0, -2.0, 0.25, 3.0];
        let mut y = [0.0; 4];
        matrix.multiply_into(&x, &mut y);
        let dense = matrix.to_dense();
        let expected = &dense * nalgebra::DVector::from_row_slice(&x);
        for (computed, reference) in y.iter().zip(expected.iter()) {
            assert!((computed - reference).abs() < 1e-15);
        }
        // Hand check of row 1: -1.5·1 + 3·(-2) + 0 = -7.5 (the (1,3) entry is zero).
        assert!((y[1] + 7.5).abs() < 1e-15);
        let mut short = [0.0; 3];
        assert!(matrix.try_multiply_into(&x, &mut short).is_err());
        let faer_matrix = matrix.to_faer();
        assert_eq!(faer_matrix.compute_nnz(), matrix.pattern.nnz());
    }
}
