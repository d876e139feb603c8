//! Runtime of the wrinkle toolkit: the kernel contract models are generated against, the element
//! contract and its elements (Q8, quadratic and cubic Hermite lines), meshes with named
//! boundary sets, dof maps, loads, assembly, sparse linear algebra and solvers.

pub mod model;
pub mod scalar;

pub use model::{
    Derivative, EnergyModel, FieldRole, JetEntry, ModelSpec, QuadratureRule, TermSpec,
};
pub use scalar::Scalar;
pub mod fem;
pub mod linear;
pub mod memo;
pub mod problem;
pub mod series;
mod simd;
pub mod solve;
pub mod wavelength;
