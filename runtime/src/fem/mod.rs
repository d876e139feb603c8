//! Finite-element building blocks: the element contract and its elements (Q8, Line3,
//! Hermite2), meshes with named boundary sets (structured, or read from Gmsh files), dofs, loads,
//! assembly.

pub mod assembly;
pub mod dofs;
pub mod element;
pub mod gmsh;
pub mod loads;
pub mod mesh;
pub mod mesh_bins;
pub mod parameter_profile;

pub use assembly::{Assembler, Parallelism, TaylorTape};
pub use dofs::{DirichletCondition, DofMap, NodalComponent};
pub use element::{
    Element, ElementKind, ElementValues, GaussRule, Hermite2, JacobianError, Line3, Quad8,
};
pub use loads::{BodyLoad, EdgeTraction, LoadError, LoadVectors, Loads, NormalTraction, PointLoad};
pub use mesh::{Mesh, MeshError, StructuredGrid};
pub use parameter_profile::{ParameterProfile, ProfileAxis, ProfileError};
