//! The element contract: what an element supplies to the assembler, and the three elements
//! that implement it.
//!
//! An element is a reference domain $`\hat\Omega`$ (the line $`[-1, 1]`$ or the square
//! $`[-1, 1]^2`$), nodes, and per field the shape functions $`\varphi_b`$,
//! $`b = 0, \dots, B-1`$, of its local dofs: a field $`f`$ is, on element $`e`$,
//! $$`f(\mathbf X) = \sum_{b} U^f_{e,b}\,\varphi_b(\mathbf X),`$$
//! with $`B = `$ nodes × components. A Lagrange element has one component per node and field (the
//! value); the cubic Hermite line has two, the value and the slope $`\partial f/\partial X`$.
//! The element says which derivatives of $`\varphi_b`$ it supplies (the rows of its basis, value
//! first): a model whose jet reads another is refused when the problem is built.
//!
//! | element | reference | nodes | components | $`B`$ | derivatives | VTK cell |
//! | --- | --- | --- | --- | --- | --- | --- |
//! | [`Quad8`] | square | 8 | 1 | 8 | value, $`X`$, $`Y`$ | 23 (quadratic quad) |
//! | [`Line3`] | line | 3 | 1 | 3 | value, $`X`$ | 21 (quadratic edge) |
//! | [`Hermite2`] | line | 2 | 2 | 4 | value, $`X`$, $`XX`$ | 3 (line) |
//!
//! Line elements lie on the X axis ($`Y = 0`$); their derivatives are along X.
//!
//! **Kinds and monomorphisation.** A mesh holds elements of one [`ElementKind`] (data, not a
//! type parameter: a problem is generic over its model only). Code that loops over elements
//! matches the kind once, with the crate-private macro `with_element!`, and runs a
//! function generic over [`Element`], whose associated constants (nodes, components, $`B`$)
//! are compile-time loop bounds and array lengths — the Q8 loops compile as if Q8 were the only
//! element.

mod hermite2;
mod line3;
mod quad8;
mod quadrature;
mod values;

pub use hermite2::Hermite2;
pub use line3::{Line3, quadratic_line_rule};
pub use quad8::{QUAD8_NODES, QUAD8_REFERENCE_NODES, Quad8};
pub use quadrature::GaussRule;
pub use values::{ElementValues, JacobianError};

use crate::model::{Derivative, QuadratureRule};

/// The geometry of a reference point mapped onto an element: its physical position and the
/// Jacobian of the map ($`\det J`$ on the square, $`dX/d\xi`$ on the line).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mapping {
    /// Physical coordinates $`(X, Y)`$.
    pub point: [f64; 2],
    /// $`\det J`$ (plane) or $`dX/d\xi`$ (line); positive for a valid element.
    pub jacobian: f64,
}

/// What an element supplies to the assembler. Implemented by [`Quad8`], [`Line3`] and
/// [`Hermite2`]; each names its [`ElementKind`].
pub trait Element: Copy + Default + std::fmt::Debug + Send + Sync + 'static {
    /// The kind a mesh stores for this element.
    const KIND: ElementKind;
    /// Nodes per element.
    const NODES: usize;
    /// Dimension of the reference domain (1 line, 2 square).
    const DIMENSION: usize;
    /// Dofs per node and field: 1 (Lagrange: the value), 2 (cubic Hermite: value and slope).
    const COMPONENTS: usize;
    /// Shape functions per field, $`B`$ = nodes × components; local function $`b`$ belongs to
    /// node `b / COMPONENTS`, component `b % COMPONENTS`.
    const FUNCTIONS: usize = Self::NODES * Self::COMPONENTS;
    /// The derivatives the element supplies, in the order of its basis rows (value first).
    const DERIVATIVES: &'static [Derivative];
    /// Reference coordinates of the nodes ($`(\xi, 0)`$ on the line).
    const REFERENCE_NODES: &'static [[f64; 2]];
    /// Boundary facets as local node lists: the edges `[end, end, middle]` of a plane element,
    /// the end points of a line element.
    const FACETS: &'static [&'static [usize]];
    /// VTK cell type number (its nodes in element order are the cell's points).
    const VTK_CELL_TYPE: u8;

    /// The rule a term asks for. `Full` integrates the element's mass matrix exactly;
    /// `Reduced` is one order lower (exact for products of the highest derivatives).
    fn quadrature(rule: QuadratureRule) -> GaussRule;

    /// Physical basis at the reference point `reference` of the element with node coordinates
    /// `coordinates`: row $`r`$ of [`Self::DERIVATIVES`] into
    /// `rows[r * FUNCTIONS..(r + 1) * FUNCTIONS]`. Returns the mapped point and Jacobian
    /// (not checked: see [`ElementValues::new`]).
    fn basis(coordinates: &[[f64; 2]], reference: [f64; 2], rows: &mut [f64]) -> Mapping;

    /// The value row of the basis alone (interpolation weights of the nodal dofs) at
    /// `reference`, into `weights` (length `FUNCTIONS`).
    fn value_weights(coordinates: &[[f64; 2]], reference: [f64; 2], weights: &mut [f64]);

    /// Reference coordinates of the physical `point` if it lies in the element (within a small
    /// tolerance), by inverting the element's map.
    fn reference_of(coordinates: &[[f64; 2]], point: [f64; 2]) -> Option<[f64; 2]>;

    /// Row of the basis holding `derivative`, if the element supplies it.
    fn row_of(derivative: Derivative) -> Option<usize> {
        Self::DERIVATIVES.iter().position(|&d| d == derivative)
    }
}

/// Which element a mesh is made of. Its methods answer the [`Element`] questions at run time.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ElementKind {
    /// The 8-node serendipity quadrilateral.
    Quad8,
    /// The 3-node quadratic Lagrange line.
    Line3,
    /// The 2-node cubic Hermite line (value and slope per node).
    Hermite2,
}

/// Runs `$body` with the type alias `$element` set to the element type of the
/// [`ElementKind`] `$kind`: one `match`, then code monomorphised per element.
///
/// ```ignore
/// with_element!(mesh.kind, E => assemble::<E, { E::FUNCTIONS }>(mesh))
/// ```
macro_rules! with_element {
    ($kind:expr, $element:ident => $body:expr) => {
        match $kind {
            $crate::fem::element::ElementKind::Quad8 => {
                type $element = $crate::fem::element::Quad8;
                $body
            }
            $crate::fem::element::ElementKind::Line3 => {
                type $element = $crate::fem::element::Line3;
                $body
            }
            $crate::fem::element::ElementKind::Hermite2 => {
                type $element = $crate::fem::element::Hermite2;
                $body
            }
        }
    };
}
pub(crate) use with_element;

impl ElementKind {
    /// Every kind.
    pub const ALL: [ElementKind; 3] = [
        ElementKind::Quad8,
        ElementKind::Line3,
        ElementKind::Hermite2,
    ];

    /// The name errors and outputs use (`Q8`, `Line3`, `Hermite2`).
    pub const fn name(self) -> &'static str {
        match self {
            ElementKind::Quad8 => "Q8",
            ElementKind::Line3 => "Line3",
            ElementKind::Hermite2 => "Hermite2",
        }
    }
    /// Nodes per element.
    pub fn nodes(self) -> usize {
        with_element!(self, E => E::NODES)
    }
    /// Reference dimension.
    pub fn dimension(self) -> usize {
        with_element!(self, E => E::DIMENSION)
    }
    /// Dofs per node and field.
    pub fn components(self) -> usize {
        with_element!(self, E => E::COMPONENTS)
    }
    /// Shape functions per field.
    pub fn functions(self) -> usize {
        with_element!(self, E => E::FUNCTIONS)
    }
    /// The derivatives supplied, value first.
    pub fn derivatives(self) -> &'static [Derivative] {
        with_element!(self, E => E::DERIVATIVES)
    }
    /// Whether the element supplies `derivative`.
    pub fn supplies(self, derivative: Derivative) -> bool {
        self.derivatives().contains(&derivative)
    }
    /// Boundary facets as local node lists.
    pub fn facets(self) -> &'static [&'static [usize]] {
        with_element!(self, E => E::FACETS)
    }
    /// VTK cell type number.
    pub fn vtk_cell_type(self) -> u8 {
        with_element!(self, E => E::VTK_CELL_TYPE)
    }
}

impl std::fmt::Display for ElementKind {
    fn fmt(&self, formatter: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        formatter.write_str(self.name())
    }
}
