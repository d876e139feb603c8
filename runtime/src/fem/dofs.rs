//! Degrees of freedom: field × node numbering and Dirichlet constraints.
//!
//! Every node carries every field of the model. A dof is free (numbered `0..free_count`) or
//! prescribed with value $`g = g_0 + \lambda g_1`$, where $`\lambda`$ is the load parameter:
//! $`g_1 \neq 0`$ is displacement control.

use super::mesh::Mesh;
use crate::scalar::Scalar;

/// A Dirichlet condition on one field along one named edge: $`f = g_0 + \lambda g_1`$.
#[derive(Clone, Debug, PartialEq)]
pub struct DirichletCondition {
    /// Edge name in the mesh (`left`, `right`, `bottom`, `top` for rectangles).
    pub edge: String,
    /// Field index in the model.
    pub field: usize,
    /// $`g_0`$.
    pub value: f64,
    /// $`g_1`$ (value per unit load parameter).
    pub value_per_load: f64,
}

/// Errors building the dof map.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DofError {
    /// The condition names an edge the mesh does not have.
    #[error("boundary condition on unknown edge `{edge}` (edges: {available})")]
    UnknownEdge {
        /// Edge asked for.
        edge: String,
        /// Edges that exist.
        available: String,
    },
    /// Field index out of range.
    #[error("boundary condition on field index {field}, but the model has {count} fields")]
    UnknownField {
        /// Field asked for.
        field: usize,
        /// Number of fields.
        count: usize,
    },
    /// Two conditions prescribe different values at one dof (e.g. at a corner).
    #[error(
        "conflicting boundary values for field {field} at node {node}: ({a0} + λ {a1}) vs ({b0} + λ {b1})"
    )]
    Conflict {
        /// Node index.
        node: usize,
        /// Field index.
        field: usize,
        /// First g0.
        a0: f64,
        /// First g1.
        a1: f64,
        /// Second g0.
        b0: f64,
        /// Second g1.
        b1: f64,
    },
    /// Nothing left to solve for.
    #[error("every degree of freedom is prescribed; nothing to solve")]
    NoFreeDofs,
}

/// Numbering of the unknowns and the prescribed values.
#[derive(Clone, Debug)]
pub struct DofMap {
    /// Number of fields per node.
    pub field_count: usize,
    /// Number of nodes.
    pub node_count: usize,
    /// Number of free dofs.
    pub free_count: usize,
    /// `free_index[node * field_count + field]`: the free number, or `None` if prescribed.
    free_index: Vec<Option<usize>>,
    /// For each free dof, its global index `node * field_count + field`.
    free_to_global: Vec<usize>,
    /// $`g_0`$ per global dof (0 for free dofs).
    prescribed_value: Vec<f64>,
    /// $`g_1`$ per global dof (0 for free dofs).
    prescribed_value_per_load: Vec<f64>,
}

impl DofMap {
    /// Numbers the dofs of `mesh` for `field_count` fields under `conditions`. Free dofs are
    /// numbered node-major (all fields of node 0, then node 1, …).
    pub fn new(
        mesh: &Mesh,
        field_count: usize,
        conditions: &[DirichletCondition],
    ) -> Result<Self, DofError> {
        let total = mesh.nodes.len() * field_count;
        let mut prescribed: Vec<Option<(f64, f64)>> = vec![None; total];
        for c in conditions {
            if c.field >= field_count {
                return Err(DofError::UnknownField {
                    field: c.field,
                    count: field_count,
                });
            }
            let nodes = mesh
                .edge_nodes(&c.edge)
                .ok_or_else(|| DofError::UnknownEdge {
                    edge: c.edge.clone(),
                    available: mesh.edge_names().join(", "),
                })?;
            for node in nodes {
                let g = node * field_count + c.field;
                let new = (c.value, c.value_per_load);
                match prescribed[g] {
                    Some(old) if old != new => {
                        return Err(DofError::Conflict {
                            node,
                            field: c.field,
                            a0: old.0,
                            a1: old.1,
                            b0: new.0,
                            b1: new.1,
                        });
                    }
                    _ => prescribed[g] = Some(new),
                }
            }
        }
        let mut free_index = vec![None; total];
        let mut free_to_global = Vec::new();
        let mut prescribed_value = vec![0.0; total];
        let mut prescribed_value_per_load = vec![0.0; total];
        for g in 0..total {
            match prescribed[g] {
                Some((a, b)) => {
                    prescribed_value[g] = a;
                    prescribed_value_per_load[g] = b;
                }
                None => {
                    free_index[g] = Some(free_to_global.len());
                    free_to_global.push(g);
                }
            }
        }
        if free_to_global.is_empty() {
            return Err(DofError::NoFreeDofs);
        }
        Ok(DofMap {
            field_count,
            node_count: mesh.nodes.len(),
            free_count: free_to_global.len(),
            free_index,
            free_to_global,
            prescribed_value,
            prescribed_value_per_load,
        })
    }

    /// Free number of `(node, field)`, if free.
    #[inline]
    pub fn free(&self, node: usize, field: usize) -> Option<usize> {
        self.free_index[node * self.field_count + field]
    }

    /// Global index `node * field_count + field` of a free dof.
    #[inline]
    pub fn global_of_free(&self, free: usize) -> usize {
        self.free_to_global[free]
    }

    /// Local dof list of an element: entry `k * field_count + f` is node `k`, field `f`.
    pub fn element_dofs(&self, element_nodes: &[usize]) -> Vec<Option<usize>> {
        let mut out = Vec::with_capacity(element_nodes.len() * self.field_count);
        for &n in element_nodes {
            for f in 0..self.field_count {
                out.push(self.free(n, f));
            }
        }
        out
    }

    /// All nodal values (global numbering) from the free values and the load parameter:
    /// prescribed dofs get $`g_0 + \lambda g_1`$.
    pub fn expand<S: Scalar>(&self, free_values: &[S], load: S) -> Vec<S> {
        let total = self.node_count * self.field_count;
        let mut out = Vec::with_capacity(total);
        for g in 0..total {
            out.push(match self.free_index[g] {
                Some(k) => free_values[k],
                None => load * self.prescribed_value_per_load[g] + self.prescribed_value[g],
            });
        }
        out
    }

    /// The global vector of an *increment* (a Taylor coefficient of order ≥ 1): free values
    /// from `free_values`, prescribed values $`g_1\,\delta\lambda`$ (the fixed part $`g_0`$ does
    /// not vary along a path).
    pub fn expand_increment(&self, free_values: &[f64], load_increment: f64) -> Vec<f64> {
        (0..self.node_count * self.field_count)
            .map(|g| match self.free_index[g] {
                Some(k) => free_values[k],
                None => load_increment * self.prescribed_value_per_load[g],
            })
            .collect()
    }

    /// The free values extracted from a global vector.
    pub fn restrict<S: Scalar>(&self, global: &[S]) -> Vec<S> {
        self.free_to_global.iter().map(|&g| global[g]).collect()
    }

    /// Whether any prescribed value depends on the load (displacement control).
    pub fn has_load_dependent_values(&self) -> bool {
        self.prescribed_value_per_load.iter().any(|v| *v != 0.0)
    }

    /// Whether global dof `g` is prescribed.
    pub fn is_prescribed(&self, g: usize) -> bool {
        self.free_index[g].is_none()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_conflict_is_reported() {
        let mesh = Mesh::rectangle(1.0, 1.0, 2, 2, 1.0).unwrap();
        let conditions = vec![
            DirichletCondition {
                edge: "left".into(),
                field: 0,
                value: 0.0,
                value_per_load: 0.0,
            },
            DirichletCondition {
                edge: "bottom".into(),
                field: 0,
                value: 1.0,
                value_per_load: 0.0,
            },
        ];
        assert!(matches!(
            DofMap::new(&mesh, 2, &conditions),
            Err(DofError::Conflict { .. })
        ));
    }

    #[test]
    fn expand_restrict_round_trip_and_prescribed_values() {
        let mesh = Mesh::rectangle(1.0, 1.0, 2, 1, 1.0).unwrap();
        let conditions = vec![DirichletCondition {
            edge: "right".into(),
            field: 1,
            value: 0.5,
            value_per_load: 2.0,
        }];
        let dofs = DofMap::new(&mesh, 2, &conditions).unwrap();
        assert_eq!(dofs.free_count, 2 * mesh.nodes.len() - 3);
        let free: Vec<f64> = (0..dofs.free_count).map(|i| i as f64).collect();
        let full = dofs.expand(&free, 3.0);
        assert_eq!(dofs.restrict(&full), free);
        for n in mesh.edge_nodes("right").unwrap() {
            assert_eq!(full[n * 2 + 1], 0.5 + 2.0 * 3.0);
        }
        assert!(dofs.has_load_dependent_values());
        assert!(matches!(
            DofMap::new(
                &mesh,
                2,
                &[DirichletCondition {
                    edge: "middle".into(),
                    field: 0,
                    value: 0.0,
                    value_per_load: 0.0
                }]
            ),
            Err(DofError::UnknownEdge { .. })
        ));
    }
}
