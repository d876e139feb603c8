//! External loads: edge tractions, point loads and body loads, each fixed or proportional to
//! the load parameter.
//!
//! The discrete external force is $`F(\lambda) = F_0 + \lambda F_1`$ over the free dofs, with
//! * an edge traction $`\mathbf t`$ (force per length) on the quadratic segments of an edge set:
//!   $`F_{a} \mathrel{+}= \int_\Gamma t_c\,N_k\,ds`$ (3-point Gauss per segment);
//! * a point load $`P`$ on one nodal component of one field at every node of a point set:
//!   $`F_a \mathrel{+}= P`$ (a force on a value, a moment on a Hermite slope);
//! * a body load $`b`$ (per unit area, or per unit length on a line mesh) on one field:
//!   $`F_a \mathrel{+}= \int_\Omega b\,\varphi_b\,d\Omega`$ with the element's full rule (on a
//!   Hermite mesh the slope functions take their share, the consistent load).

use super::dofs::{DofMap, NodalComponent};
use super::element::{Element, ElementValues, quadratic_line_rule, with_element};
use super::mesh::Mesh;
use crate::model::QuadratureRule;

/// A traction (force per unit length, N/mm) on a named edge, acting on two fields
/// (the in-plane displacements).
#[derive(Clone, Debug, PartialEq)]
pub struct EdgeTraction {
    /// Edge name.
    pub edge: String,
    /// Field indices receiving the X and Y components.
    pub fields: [usize; 2],
    /// Traction vector $`(t_X, t_Y)`$.
    pub traction: [f64; 2],
    /// `true`: scaled by the load parameter ($`F_1`$); `false`: fixed ($`F_0`$).
    pub proportional: bool,
}

/// A concentrated load on one nodal component of one field at every node of a named point
/// set (a beam's end force; on a Hermite slope, an end moment).
#[derive(Clone, Debug, PartialEq)]
pub struct PointLoad {
    /// Point set name.
    pub point: String,
    /// Field index.
    pub field: usize,
    /// The component it acts on.
    pub component: NodalComponent,
    /// The load at each node of the set.
    pub value: f64,
    /// Scaled by the load parameter or fixed.
    pub proportional: bool,
}

/// A uniform load per unit area (per unit length on a line mesh) on one field (e.g. a small
/// transverse load on the envelope).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyLoad {
    /// Field index.
    pub field: usize,
    /// Load density.
    pub value: f64,
    /// Scaled by the load parameter or fixed.
    pub proportional: bool,
}

/// Every external load of a problem.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Loads {
    /// Edge tractions (plane meshes).
    pub tractions: Vec<EdgeTraction>,
    /// Point loads.
    pub point_loads: Vec<PointLoad>,
    /// Body loads.
    pub body_loads: Vec<BodyLoad>,
}

/// $`F_0`$ and $`F_1`$ over the free dofs.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadVectors {
    /// Fixed part $`F_0`$.
    pub fixed: Vec<f64>,
    /// Proportional part $`F_1`$.
    pub proportional: Vec<f64>,
}

/// A load that names something the mesh or the element does not have.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LoadError {
    /// An edge traction on a missing edge set.
    #[error("load on unknown edge `{edge}` (edges: {available})")]
    UnknownEdge {
        /// The edge asked for.
        edge: String,
        /// Edge sets that exist.
        available: String,
    },
    /// A point load on a missing point set.
    #[error("load on unknown point set `{point}` (point sets: {available})")]
    UnknownPoint {
        /// The point set asked for.
        point: String,
        /// Point sets that exist.
        available: String,
    },
    /// A point load on a component the element does not carry.
    #[error("point load on the {component} of field {field} at `{point}`, but {element} nodes carry no {component}", component = component.name())]
    MissingComponent {
        /// The point set.
        point: String,
        /// Field index.
        field: usize,
        /// The component asked for.
        component: NodalComponent,
        /// The mesh's element.
        element: super::element::ElementKind,
    },
}

/// Names of a set map, for messages.
fn names<T>(sets: &std::collections::BTreeMap<String, T>) -> String {
    sets.keys().cloned().collect::<Vec<_>>().join(", ")
}

impl LoadVectors {
    /// Integrates the tractions along their edges, adds the point loads, and integrates the
    /// body loads over the elements (the element's full rule).
    pub fn assemble(mesh: &Mesh, dofs: &DofMap, loads: &Loads) -> Result<Self, LoadError> {
        let mut vectors = LoadVectors {
            fixed: vec![0.0; dofs.free_count],
            proportional: vec![0.0; dofs.free_count],
        };
        for traction in &loads.tractions {
            vectors.add_traction(mesh, dofs, traction)?;
        }
        for load in &loads.point_loads {
            vectors.add_point_load(mesh, dofs, load)?;
        }
        if !loads.body_loads.is_empty() {
            with_element!(mesh.kind, E => vectors.add_body_loads::<E>(mesh, dofs, &loads.body_loads));
        }
        Ok(vectors)
    }

    /// The fixed or proportional part.
    fn target(&mut self, proportional: bool) -> &mut Vec<f64> {
        if proportional {
            &mut self.proportional
        } else {
            &mut self.fixed
        }
    }

    /// One edge traction: 3-point Gauss on each quadratic segment.
    fn add_traction(
        &mut self,
        mesh: &Mesh,
        dofs: &DofMap,
        t: &EdgeTraction,
    ) -> Result<(), LoadError> {
        let segments = mesh
            .edges
            .get(&t.edge)
            .ok_or_else(|| LoadError::UnknownEdge {
                edge: t.edge.clone(),
                available: names(&mesh.edges),
            })?;
        let rule = quadratic_line_rule();
        let target = self.target(t.proportional);
        for seg in segments {
            let x: Vec<[f64; 2]> = seg.iter().map(|&n| mesh.nodes[n]).collect();
            for (n, w) in &rule {
                // s at this point from the end-node functions: recover dN/ds.
                let s = n[1] - n[0];
                let dn = [s - 0.5, s + 0.5, -2.0 * s];
                let dx = [
                    dn[0] * x[0][0] + dn[1] * x[1][0] + dn[2] * x[2][0],
                    dn[0] * x[0][1] + dn[1] * x[1][1] + dn[2] * x[2][1],
                ];
                let ds = (dx[0] * dx[0] + dx[1] * dx[1]).sqrt();
                for (k, &node) in seg.iter().enumerate() {
                    for c in 0..2 {
                        if let Some(i) = dofs.free(node, t.fields[c]) {
                            target[i] += t.traction[c] * n[k] * ds * w;
                        }
                    }
                }
            }
        }
        Ok(())
    }

    /// One point load, at every node of its point set.
    fn add_point_load(
        &mut self,
        mesh: &Mesh,
        dofs: &DofMap,
        load: &PointLoad,
    ) -> Result<(), LoadError> {
        let nodes = mesh
            .points
            .get(&load.point)
            .ok_or_else(|| LoadError::UnknownPoint {
                point: load.point.clone(),
                available: names(&mesh.points),
            })?;
        if load.component.index() >= dofs.components {
            return Err(LoadError::MissingComponent {
                point: load.point.clone(),
                field: load.field,
                component: load.component,
                element: mesh.kind,
            });
        }
        let target = self.target(load.proportional);
        for &node in nodes {
            if let Some(i) = dofs.free_component(node, load.field, load.component) {
                target[i] += load.value;
            }
        }
        Ok(())
    }

    /// The body loads, element by element with the full rule of element `E`.
    fn add_body_loads<E: Element>(&mut self, mesh: &Mesh, dofs: &DofMap, body_loads: &[BodyLoad]) {
        let rule = E::quadrature(QuadratureRule::Full);
        for e in 0..mesh.element_count() {
            let values = ElementValues::new::<E>(e, &mesh.element_coordinates(e), &rule)
                .expect("mesh elements were checked when the assembler was built");
            let nodes = mesh.nodes_of::<E>(e);
            for b in body_loads {
                let target = self.target(b.proportional);
                for q in 0..values.point_count() {
                    let basis = values.row(q, 0);
                    for (k, &weight) in basis.iter().enumerate() {
                        let component = NodalComponent::first(E::COMPONENTS)[k % E::COMPONENTS];
                        let node = nodes[k / E::COMPONENTS];
                        if let Some(i) = dofs.free_component(node, b.field, component) {
                            target[i] += b.value * weight * values.weights[q];
                        }
                    }
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn traction_resultant_equals_traction_times_length() {
        let mesh = Mesh::rectangle(3.0, 2.0, 3, 4, 2.0).unwrap();
        let dofs = DofMap::new(&mesh, 2, &[]).unwrap();
        let loads = LoadVectors::assemble(
            &mesh,
            &dofs,
            &Loads {
                tractions: vec![EdgeTraction {
                    edge: "right".into(),
                    fields: [0, 1],
                    traction: [-1.5, 0.25],
                    proportional: true,
                }],
                body_loads: vec![BodyLoad {
                    field: 1,
                    value: 2.0,
                    proportional: false,
                }],
                ..Loads::default()
            },
        )
        .unwrap();
        let fx: f64 = (0..dofs.free_count)
            .filter(|&i| dofs.global_of_free(i).is_multiple_of(2))
            .map(|i| loads.proportional[i])
            .sum();
        let fy: f64 = (0..dofs.free_count)
            .filter(|&i| !dofs.global_of_free(i).is_multiple_of(2))
            .map(|i| loads.proportional[i])
            .sum();
        assert!((fx + 1.5 * 2.0).abs() < 1e-12);
        assert!((fy - 0.25 * 2.0).abs() < 1e-12);
        let body: f64 = loads.fixed.iter().sum();
        assert!((body - 2.0 * 6.0).abs() < 1e-12);
    }
}
