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

/// A traction given in the frame of the boundary (force per unit length, N/mm): a normal
/// component $`t_n`$ along the **outward** unit normal $`\mathbf n`$ (positive pulls, negative
/// pushes) and a tangential one $`t_s`$ along $`\mathbf s`$, the normal turned a quarter turn
/// counter-clockwise (the direction in which the boundary runs with the domain on its left):
/// $`\mathbf t = t_n\mathbf n + t_s\mathbf s`$. The normal of a straight segment is that of
/// its chord (exactly $`(\pm1, 0)`$ or $`(0, \pm1)`$ on an axis-parallel edge); on a curved one
/// it is evaluated at each Gauss point. Outward is decided by the element the segment bounds.
#[derive(Clone, Debug, PartialEq)]
pub struct NormalTraction {
    /// Edge name.
    pub edge: String,
    /// Field indices of the X and Y displacement.
    pub fields: [usize; 2],
    /// $`t_n`$, along the outward normal.
    pub normal: f64,
    /// $`t_s`$, along the boundary.
    pub tangential: f64,
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
    /// Edge tractions in the boundary's normal–tangential frame (plane meshes).
    pub normal_tractions: Vec<NormalTraction>,
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
    /// A segment of an edge set that is not a side of any element (no outward normal).
    #[error("edge `{edge}`: segment {nodes:?} is not a side of any element")]
    NotABoundarySide {
        /// The edge set.
        edge: String,
        /// The segment's nodes `[end, end, middle]`.
        nodes: [usize; 3],
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

/// The sides of the elements by their middle node: `(first end, second end)` in the element's
/// counter-clockwise order (Q8: corners $`k`$, $`k+1`$ around mid-side node $`4 + k`$).
fn element_sides(mesh: &Mesh) -> std::collections::HashMap<usize, Vec<(usize, usize)>> {
    let mut sides: std::collections::HashMap<usize, Vec<(usize, usize)>> =
        std::collections::HashMap::new();
    if mesh.kind != super::element::ElementKind::Quad8 {
        return sides;
    }
    for element in mesh.elements() {
        for k in 0..4 {
            sides
                .entry(element[4 + k])
                .or_default()
                .push((element[k], element[(k + 1) % 4]));
        }
    }
    sides
}

/// $`+1`$ when segment `[a, b, middle]` runs as its element's side (counter-clockwise),
/// $`-1`$ when against it, `None` when it is no element's side.
fn segment_orientation(
    sides: &std::collections::HashMap<usize, Vec<(usize, usize)>>,
    segment: &[usize; 3],
) -> Option<f64> {
    let [a, b, middle] = *segment;
    sides.get(&middle)?.iter().find_map(|&side| {
        if side == (a, b) {
            Some(1.0)
        } else if side == (b, a) {
            Some(-1.0)
        } else {
            None
        }
    })
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
        for traction in &loads.normal_tractions {
            vectors.add_normal_traction(mesh, dofs, traction)?;
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
        let segments = edge_segments(mesh, &t.edge)?;
        let rule = quadratic_line_rule();
        let target = self.target(t.proportional);
        for seg in segments {
            let x: Vec<[f64; 2]> = seg.iter().map(|&n| mesh.nodes[n]).collect();
            for (n, w) in &rule {
                let dx = segment_tangent(&x, n);
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

    /// One traction in the boundary's frame: 3-point Gauss on each quadratic segment, the
    /// outward normal from the element whose side the segment is.
    fn add_normal_traction(
        &mut self,
        mesh: &Mesh,
        dofs: &DofMap,
        t: &NormalTraction,
    ) -> Result<(), LoadError> {
        let segments = edge_segments(mesh, &t.edge)?;
        let sides = element_sides(mesh);
        let rule = quadratic_line_rule();
        let target = self.target(t.proportional);
        for seg in segments {
            let orientation =
                segment_orientation(&sides, seg).ok_or_else(|| LoadError::NotABoundarySide {
                    edge: t.edge.clone(),
                    nodes: *seg,
                })?;
            let x: Vec<[f64; 2]> = seg.iter().map(|&n| mesh.nodes[n]).collect();
            let chord = [x[1][0] - x[0][0], x[1][1] - x[0][1]];
            let straight = (0..2).all(|c| {
                let middle = 0.5 * (x[0][c] + x[1][c]);
                (x[2][c] - middle).abs() <= 1e-12 * chord[0].abs().max(chord[1].abs())
            });
            for (n, w) in &rule {
                let dx = segment_tangent(&x, n);
                let ds = (dx[0] * dx[0] + dx[1] * dx[1]).sqrt();
                let along = if straight { chord } else { dx };
                let length = (along[0] * along[0] + along[1] * along[1]).sqrt();
                // Outward normal: the run direction turned clockwise (the domain is on the
                // left of a side run counter-clockwise); s: the normal turned counter-clockwise.
                let normal = [
                    orientation * along[1] / length,
                    -(orientation * along[0]) / length,
                ];
                let tangent = [-normal[1], normal[0]];
                let traction = [
                    t.normal * normal[0] + t.tangential * tangent[0],
                    t.normal * normal[1] + t.tangential * tangent[1],
                ];
                for (k, &node) in seg.iter().enumerate() {
                    for (&field, &component) in t.fields.iter().zip(&traction) {
                        if let Some(i) = dofs.free(node, field) {
                            target[i] += component * n[k] * ds * w;
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

/// The segments of the named edge, or [`LoadError::UnknownEdge`] listing the edges there are.
fn edge_segments<'m>(mesh: &'m Mesh, edge: &str) -> Result<&'m [[usize; 3]], LoadError> {
    mesh.edges
        .get(edge)
        .map(Vec::as_slice)
        .ok_or_else(|| LoadError::UnknownEdge {
            edge: edge.to_string(),
            available: names(&mesh.edges),
        })
}

/// $`dX/ds`$ of the quadratic segment through `x` (end, end, middle) at the quadrature point
/// whose shape-function values are `n`: $`s = N_1 - N_0`$ is recovered from the end-node
/// functions and $`dN/ds = (s - \tfrac12,\ s + \tfrac12,\ -2s)`$.
fn segment_tangent(x: &[[f64; 2]], n: &[f64; 3]) -> [f64; 2] {
    let s = n[1] - n[0];
    let dn = [s - 0.5, s + 0.5, -2.0 * s];
    [
        dn[0] * x[0][0] + dn[1] * x[1][0] + dn[2] * x[2][0],
        dn[0] * x[0][1] + dn[1] * x[1][1] + dn[2] * x[2][1],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_tractions_push_along_the_outward_normal_of_each_edge() {
        let mesh = Mesh::rectangle(3.0, 2.0, 3, 4, 2.0).unwrap();
        let dofs = DofMap::new(&mesh, 2, &[]).unwrap();
        let traction = |edge: &str, normal, tangential| NormalTraction {
            edge: edge.into(),
            fields: [0, 1],
            normal,
            tangential,
            proportional: false,
        };
        let resultant = |tractions: Vec<NormalTraction>| {
            let loads = Loads {
                normal_tractions: tractions,
                ..Loads::default()
            };
            let vectors = LoadVectors::assemble(&mesh, &dofs, &loads).unwrap();
            let mut sum = [0.0; 2];
            for (i, f) in vectors.fixed.iter().enumerate() {
                sum[dofs.global_of_free(i) % 2] += f;
            }
            sum
        };
        // Outward: −X on `left`, +X on `right`, −Y on `bottom`, +Y on `top`; the tangent is the
        // normal turned counter-clockwise.
        let close = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).abs() + (a[1] - b[1]).abs() < 1e-12;
        assert!(close(
            resultant(vec![traction("left", 1.5, 0.0)]),
            [-3.0, 0.0]
        ));
        assert!(close(
            resultant(vec![traction("right", 1.5, 0.0)]),
            [3.0, 0.0]
        ));
        assert!(close(
            resultant(vec![traction("bottom", 1.5, 0.0)]),
            [0.0, -4.5]
        ));
        assert!(close(
            resultant(vec![traction("top", 0.0, 1.0)]),
            [-3.0, 0.0]
        ));
        assert!(close(
            resultant(vec![traction("right", 0.0, 1.0)]),
            [0.0, 2.0]
        ));
        // A uniform pressure on the closed boundary is self-equilibrated.
        let all = ["left", "right", "bottom", "top"].map(|edge| traction(edge, -0.7, 0.0));
        assert!(close(resultant(all.to_vec()), [0.0, 0.0]));
    }

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
