//! External loads: edge tractions and body loads, fixed or proportional to the load parameter.
//!
//! The discrete external force is $`F(\lambda) = F_0 + \lambda F_1`$ over the free dofs.

use super::dofs::DofMap;
use super::element::{ElementValues, GaussRule, quadratic_line_rule};
use super::mesh::Mesh;

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

/// A uniform load per unit area on one field (e.g. a small transverse load on the envelope).
#[derive(Clone, Debug, PartialEq)]
pub struct BodyLoad {
    /// Field index.
    pub field: usize,
    /// Load density.
    pub value: f64,
    /// Scaled by the load parameter or fixed.
    pub proportional: bool,
}

/// $`F_0`$ and $`F_1`$ over the free dofs.
#[derive(Clone, Debug, PartialEq)]
pub struct LoadVectors {
    /// Fixed part $`F_0`$.
    pub fixed: Vec<f64>,
    /// Proportional part $`F_1`$.
    pub proportional: Vec<f64>,
}

/// Unknown edge in a load.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("load on unknown edge `{0}`")]
pub struct UnknownEdgeError(pub String);

impl LoadVectors {
    /// Integrates the tractions along their edges (3-point Gauss on each quadratic segment) and
    /// the body loads over the elements (3×3 Gauss).
    pub fn assemble(
        mesh: &Mesh,
        dofs: &DofMap,
        tractions: &[EdgeTraction],
        body_loads: &[BodyLoad],
    ) -> Result<Self, UnknownEdgeError> {
        let mut fixed = vec![0.0; dofs.free_count];
        let mut proportional = vec![0.0; dofs.free_count];
        let rule = quadratic_line_rule();
        for t in tractions {
            let segments = mesh
                .edges
                .get(&t.edge)
                .ok_or_else(|| UnknownEdgeError(t.edge.clone()))?;
            let target = if t.proportional {
                &mut proportional
            } else {
                &mut fixed
            };
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
        }
        if !body_loads.is_empty() {
            let rule = GaussRule::square(3);
            for e in 0..mesh.elements.len() {
                let values = ElementValues::new(e, &mesh.element_coordinates(e), &rule, false)
                    .expect("mesh elements were checked when the assembler was built");
                for b in body_loads {
                    let target = if b.proportional {
                        &mut proportional
                    } else {
                        &mut fixed
                    };
                    for q in 0..values.weights.len() {
                        for (k, &node) in mesh.elements[e].iter().enumerate() {
                            if let Some(i) = dofs.free(node, b.field) {
                                target[i] += b.value * values.values[q][k] * values.weights[q];
                            }
                        }
                    }
                }
            }
        }
        Ok(LoadVectors {
            fixed,
            proportional,
        })
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
            &[EdgeTraction {
                edge: "right".into(),
                fields: [0, 1],
                traction: [-1.5, 0.25],
                proportional: true,
            }],
            &[BodyLoad {
                field: 1,
                value: 2.0,
                proportional: false,
            }],
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
