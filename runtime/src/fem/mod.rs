//! Finite-element building blocks: Q8 element values, meshes, dofs, loads, assembly.

pub mod assembly;
pub mod dofs;
pub mod element;
pub mod loads;
pub mod mesh;

pub use assembly::{Assembler, Parallelism, TaylorTape};
pub use dofs::{DirichletCondition, DofMap};
pub use element::{ElementValues, GaussRule, Quad8};
pub use loads::{BodyLoad, EdgeTraction, LoadVectors};
pub use mesh::{Mesh, StructuredGrid};
