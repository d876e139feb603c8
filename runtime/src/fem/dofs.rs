//! Degrees of freedom: node × field × component numbering and Dirichlet constraints.
//!
//! Every node carries every field of the model, each with the element's components per node
//! ([`ElementKind::components`](super::element::ElementKind::components)): the value for
//! Lagrange elements, the value and the slope $`\partial f/\partial X`$ for the cubic Hermite
//! line. The global index of component $`c`$ of field $`f`$ at node $`n`$ is
//! $$`g = (n\,N_f + f)\,N_c + c`$$
//! (node-major: with one component, $`g = n N_f + f`$). A dof is free (numbered
//! `0..free_count` in the order of $`g`$) or prescribed with value $`g_0 + \lambda g_1`$,
//! where $`\lambda`$ is the load parameter: $`g_1 \neq 0`$ is displacement control.

use super::mesh::Mesh;
use crate::scalar::Scalar;

/// A nodal component of a field.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum NodalComponent {
    /// The field's value (component 0 of every element).
    Value,
    /// The slope $`\partial f/\partial X`$ (component 1 of a cubic Hermite node).
    Slope,
}

impl NodalComponent {
    /// The component's index at a node.
    pub const fn index(self) -> usize {
        match self {
            NodalComponent::Value => 0,
            NodalComponent::Slope => 1,
        }
    }

    /// The components of a node with `count` of them (value, then slope).
    pub fn first(count: usize) -> &'static [NodalComponent] {
        &[NodalComponent::Value, NodalComponent::Slope][..count.min(2)]
    }

    /// Name in messages.
    pub const fn name(self) -> &'static str {
        match self {
            NodalComponent::Value => "value",
            NodalComponent::Slope => "slope",
        }
    }
}

/// A Dirichlet condition on one nodal component of one field at every node of a named
/// boundary set (edge or point set): $`f_c = g_0 + \lambda g_1`$.
#[derive(Clone, Debug, PartialEq)]
pub struct DirichletCondition {
    /// Boundary set name in the mesh (`left`, `right`, `bottom`, `top` for rectangles; `left`,
    /// `right` for lines; any point set).
    pub boundary: String,
    /// Field index in the model.
    pub field: usize,
    /// Which nodal component is prescribed.
    pub component: NodalComponent,
    /// $`g_0`$.
    pub value: f64,
    /// $`g_1`$ (value per unit load parameter).
    pub value_per_load: f64,
}

impl DirichletCondition {
    /// $`f = g_0 + \lambda g_1`$ (the value component) on `boundary`: `value` $`= g_0`$,
    /// `value_per_load` $`= g_1`$ — a prescribed displacement, constant ($`g_1 = 0`$) or
    /// proportional to the load parameter (displacement control). How the solvers treat it:
    /// [`crate::problem`].
    pub fn prescribed(boundary: &str, field: usize, value: f64, value_per_load: f64) -> Self {
        DirichletCondition {
            value,
            value_per_load,
            ..DirichletCondition::fixed(boundary, field)
        }
    }

    /// $`f = 0`$ (the value component) on `boundary`.
    pub fn fixed(boundary: &str, field: usize) -> Self {
        DirichletCondition {
            boundary: boundary.to_string(),
            field,
            component: NodalComponent::Value,
            value: 0.0,
            value_per_load: 0.0,
        }
    }

    /// Every component of `field` zero on `boundary` — a clamp: the value alone on a Lagrange
    /// mesh, value and slope on a cubic Hermite one.
    pub fn clamped(boundary: &str, field: usize, kind: super::element::ElementKind) -> Vec<Self> {
        NodalComponent::first(kind.components())
            .iter()
            .map(|&component| DirichletCondition {
                component,
                ..DirichletCondition::fixed(boundary, field)
            })
            .collect()
    }
}

/// Errors building the dof map.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DofError {
    /// The condition names a boundary set the mesh does not have.
    #[error("boundary condition on unknown boundary `{boundary}` (boundaries: {available})")]
    UnknownBoundary {
        /// Boundary asked for.
        boundary: String,
        /// Boundaries that exist.
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
    /// The condition prescribes a component the mesh's element does not carry (a slope on a
    /// Lagrange element).
    #[error("boundary condition on the {component} of field {field} on `{boundary}`, but {element} nodes carry no {component}", component = component.name())]
    MissingComponent {
        /// Boundary set.
        boundary: String,
        /// Field index.
        field: usize,
        /// Component asked for.
        component: NodalComponent,
        /// The mesh's element.
        element: super::element::ElementKind,
    },
    /// Two conditions prescribe different values at one dof (e.g. at a corner).
    #[error(
        "conflicting boundary values for field {field} ({component}) at node {node}: ({a0} + λ {a1}) vs ({b0} + λ {b1})",
        component = component.name()
    )]
    Conflict {
        /// Node index.
        node: usize,
        /// Field index.
        field: usize,
        /// Component.
        component: NodalComponent,
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
    /// Components per node and field (the element's).
    pub components: usize,
    /// Number of nodes.
    pub node_count: usize,
    /// Number of free dofs.
    pub free_count: usize,
    /// `free_index[g]`: the free number of global dof `g`, or `None` if prescribed.
    free_index: Vec<Option<usize>>,
    /// For each free dof, its global index.
    free_to_global: Vec<usize>,
    /// $`g_0`$ per global dof (0 for free dofs).
    prescribed_value: Vec<f64>,
    /// $`g_1`$ per global dof (0 for free dofs).
    prescribed_value_per_load: Vec<f64>,
}

impl DofMap {
    /// Numbers the dofs of `mesh` for `field_count` fields under `conditions`. Free dofs are
    /// numbered in global order (node-major: every field and component of node 0, then
    /// node 1, …).
    pub fn new(
        mesh: &Mesh,
        field_count: usize,
        conditions: &[DirichletCondition],
    ) -> Result<Self, DofError> {
        let components = mesh.kind.components();
        let total = mesh.nodes.len() * field_count * components;
        let mut prescribed: Vec<Option<(f64, f64)>> = vec![None; total];
        for c in conditions {
            if c.field >= field_count {
                return Err(DofError::UnknownField {
                    field: c.field,
                    count: field_count,
                });
            }
            if c.component.index() >= components {
                return Err(DofError::MissingComponent {
                    boundary: c.boundary.clone(),
                    field: c.field,
                    component: c.component,
                    element: mesh.kind,
                });
            }
            let nodes =
                mesh.boundary_nodes(&c.boundary)
                    .ok_or_else(|| DofError::UnknownBoundary {
                        boundary: c.boundary.clone(),
                        available: mesh.boundary_names().join(", "),
                    })?;
            for node in nodes {
                let g = (node * field_count + c.field) * components + c.component.index();
                let new = (c.value, c.value_per_load);
                match prescribed[g] {
                    Some(old) if old != new => {
                        return Err(DofError::Conflict {
                            node,
                            field: c.field,
                            component: c.component,
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
            components,
            node_count: mesh.nodes.len(),
            free_count: free_to_global.len(),
            free_index,
            free_to_global,
            prescribed_value,
            prescribed_value_per_load,
        })
    }

    /// Global index of component `component` of `field` at `node`.
    #[inline]
    pub fn global_index(&self, node: usize, field: usize, component: usize) -> usize {
        (node * self.field_count + field) * self.components + component
    }

    /// Free number of the value of `field` at `node`, if free.
    #[inline]
    pub fn free(&self, node: usize, field: usize) -> Option<usize> {
        self.free_index[self.global_index(node, field, 0)]
    }

    /// Free number of a component of `field` at `node`, if free (`None` also when the
    /// element has no such component).
    #[inline]
    pub fn free_component(
        &self,
        node: usize,
        field: usize,
        component: NodalComponent,
    ) -> Option<usize> {
        let c = component.index();
        (c < self.components)
            .then(|| self.free_index[self.global_index(node, field, c)])
            .flatten()
    }

    /// Global index of a free dof.
    #[inline]
    pub fn global_of_free(&self, free: usize) -> usize {
        self.free_to_global[free]
    }

    /// The field a global dof belongs to.
    #[inline]
    pub fn field_of_global(&self, global: usize) -> usize {
        (global / self.components) % self.field_count
    }

    /// The field a free dof belongs to.
    #[inline]
    pub fn field_of_free(&self, free: usize) -> usize {
        self.field_of_global(self.free_to_global[free])
    }

    /// Local dof list of an element with nodes `element_nodes`: entry
    /// `(k * field_count + f) * components + c` is node `k`, field `f`, component `c` (the
    /// global order restricted to the element).
    pub fn element_dofs(&self, element_nodes: &[usize]) -> Vec<Option<usize>> {
        let per_node = self.field_count * self.components;
        let mut out = Vec::with_capacity(element_nodes.len() * per_node);
        for &n in element_nodes {
            out.extend_from_slice(&self.free_index[n * per_node..][..per_node]);
        }
        out
    }

    /// The value of every field at every node, node-major (`out[node * field_count + field]`),
    /// from a global vector: the global vector itself for Lagrange elements, its value
    /// components for Hermite ones (what a writer of nodal fields needs).
    pub fn nodal_values(&self, global: &[f64]) -> Vec<f64> {
        global.iter().step_by(self.components).copied().collect()
    }

    /// All nodal values (global numbering) from the free values and the load parameter:
    /// prescribed dofs get $`g_0 + \lambda g_1`$.
    pub fn expand<S: Scalar>(&self, free_values: &[S], load: S) -> Vec<S> {
        let total = self.free_index.len();
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
        (0..self.free_index.len())
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

    /// Whether global dof `g` is prescribed with a value that depends on the load
    /// ($`g_1 \ne 0`$ in $`g_0 + \lambda g_1`$).
    pub fn is_load_dependent(&self, g: usize) -> bool {
        self.free_index[g].is_none() && self.prescribed_value_per_load[g] != 0.0
    }

    /// Whether global dof `g` is prescribed.
    pub fn is_prescribed(&self, g: usize) -> bool {
        self.free_index[g].is_none()
    }

    /// The rigid in-plane motions $`u = a - \theta Y`$, $`v = b + \theta X`$ that the
    /// prescribed values of the in-plane fields `in_plane` (X and Y displacement) leave free:
    /// those the in-plane stiffness cannot resist (a singular problem). A translation along X
    /// is free when no $`u`$ is prescribed, along Y when no $`v`$ is; with both, a rotation is
    /// free exactly when every prescribed $`u`$ lies on one line $`Y = Y^*`$ and every
    /// prescribed $`v`$ on one line $`X = X^*`$ (it turns about $`(X^*, Y^*)`$). Positions
    /// agree within $`10^{-9}`$ of the mesh's extent.
    pub fn free_rigid_motions(&self, mesh: &Mesh, in_plane: [usize; 2]) -> Vec<RigidMotion> {
        let [x0, x1, y0, y1] = mesh.bounds();
        let tolerance = 1e-9 * (x1 - x0).abs().max((y1 - y0).abs());
        // The one coordinate every prescribed node of a component shares, if any.
        let mut lines: [Option<Option<f64>>; 2] = [None, None];
        for (node, position) in mesh.nodes.iter().enumerate() {
            for (c, &field) in in_plane.iter().enumerate() {
                if self.free(node, field).is_some() {
                    continue;
                }
                // u fixes the line of constant Y, v the line of constant X.
                let coordinate = position[1 - c];
                lines[c] = match lines[c] {
                    None => Some(Some(coordinate)),
                    Some(Some(line)) if (line - coordinate).abs() <= tolerance => Some(Some(line)),
                    _ => Some(None),
                };
            }
        }
        let mut free = Vec::new();
        match lines {
            [None, None] => free.extend([RigidMotion::TranslationX, RigidMotion::TranslationY]),
            [None, _] => free.push(RigidMotion::TranslationX),
            [_, None] => free.push(RigidMotion::TranslationY),
            [Some(Some(y)), Some(Some(x))] => free.push(RigidMotion::Rotation { centre: [x, y] }),
            _ => {}
        }
        free
    }
}

/// A rigid in-plane motion of the sheet (see [`DofMap::free_rigid_motions`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum RigidMotion {
    /// $`u = a`$.
    TranslationX,
    /// $`v = b`$.
    TranslationY,
    /// A rotation about `centre`.
    Rotation {
        /// The fixed point $`(X^*, Y^*)`$.
        centre: [f64; 2],
    },
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::element::ElementKind;

    #[test]
    fn corner_conflict_is_reported() {
        let mesh = Mesh::rectangle(1.0, 1.0, 2, 2, 1.0).unwrap();
        let conditions = vec![
            DirichletCondition::fixed("left", 0),
            DirichletCondition {
                value: 1.0,
                ..DirichletCondition::fixed("bottom", 0)
            },
        ];
        assert!(matches!(
            DofMap::new(&mesh, 2, &conditions),
            Err(DofError::Conflict { .. })
        ));
    }

    #[test]
    fn rigid_motions_left_free_by_the_constraints_are_named() {
        let mesh = Mesh::rectangle(4.0, 2.0, 4, 2, 1.0).unwrap();
        let free = |conditions: &[DirichletCondition]| {
            DofMap::new(&mesh, 3, conditions)
                .unwrap()
                .free_rigid_motions(&mesh, [0, 1])
        };
        let fixed = DirichletCondition::fixed;
        assert_eq!(
            free(&[fixed("left", 2)]),
            [RigidMotion::TranslationX, RigidMotion::TranslationY]
        );
        assert_eq!(free(&[fixed("centre", 0)]), [RigidMotion::TranslationY]);
        assert_eq!(
            free(&[fixed("centre", 0), fixed("centre", 1)]),
            [RigidMotion::Rotation { centre: [2.0, 1.0] }]
        );
        // The biaxial supports, a clamped edge, and u on one edge with v at one point.
        assert!(
            free(&[
                fixed("centre", 0),
                fixed("centre", 1),
                fixed("right_middle", 1)
            ])
            .is_empty()
        );
        assert!(free(&[fixed("left", 0), fixed("left", 1)]).is_empty());
        assert!(free(&[fixed("left", 0), fixed("bottom_left", 1)]).is_empty());
        // u along the bottom edge (one line Y = 0) and v at one corner: turns about it.
        assert_eq!(
            free(&[fixed("bottom", 0), fixed("bottom_right", 1)]),
            [RigidMotion::Rotation { centre: [4.0, 0.0] }]
        );
    }

    #[test]
    fn expand_restrict_round_trip_and_prescribed_values() {
        let mesh = Mesh::rectangle(1.0, 1.0, 2, 1, 1.0).unwrap();
        let conditions = vec![DirichletCondition {
            value: 0.5,
            value_per_load: 2.0,
            ..DirichletCondition::fixed("right", 1)
        }];
        let dofs = DofMap::new(&mesh, 2, &conditions).unwrap();
        assert_eq!(dofs.free_count, 2 * mesh.nodes.len() - 3);
        let free: Vec<f64> = (0..dofs.free_count).map(|i| i as f64).collect();
        let full = dofs.expand(&free, 3.0);
        assert_eq!(dofs.restrict(&full), free);
        for n in mesh.boundary_nodes("right").unwrap() {
            assert_eq!(full[n * 2 + 1], 0.5 + 2.0 * 3.0);
        }
        assert!(dofs.has_load_dependent_values());
        assert!(matches!(
            DofMap::new(&mesh, 2, &[DirichletCondition::fixed("middle", 0)]),
            Err(DofError::UnknownBoundary { .. })
        ));
        assert!(matches!(
            DofMap::new(
                &mesh,
                2,
                &[DirichletCondition {
                    component: NodalComponent::Slope,
                    ..DirichletCondition::fixed("left", 0)
                }]
            ),
            Err(DofError::MissingComponent {
                element: ElementKind::Quad8,
                ..
            })
        ));
    }

    #[test]
    fn hermite_nodes_carry_value_and_slope_numbered_node_major() {
        let mesh = Mesh::line(3.0, 3, 1.0, ElementKind::Hermite2).unwrap();
        let clamp = DirichletCondition::clamped("left", 1, ElementKind::Hermite2);
        assert_eq!(clamp.len(), 2);
        let dofs = DofMap::new(&mesh, 2, &clamp).unwrap();
        assert_eq!((dofs.components, dofs.free_count), (2, 4 * 2 * 2 - 2));
        // Node 0: u value, u slope, v value (fixed), v slope (fixed); node 1 starts at g = 4.
        assert_eq!(dofs.global_index(1, 0, 1), 5);
        assert_eq!(dofs.free(0, 1), None);
        assert_eq!(dofs.free_component(0, 1, NodalComponent::Slope), None);
        assert_eq!(dofs.free_component(0, 0, NodalComponent::Slope), Some(1));
        assert_eq!(dofs.free(1, 1), Some(4));
        assert_eq!(dofs.field_of_free(4), 1);
        assert_eq!(
            dofs.element_dofs(&[0, 1]),
            [
                Some(0),
                Some(1),
                None,
                None,
                Some(2),
                Some(3),
                Some(4),
                Some(5)
            ]
        );
        let global: Vec<f64> = (0..16).map(f64::from).collect();
        assert_eq!(
            dofs.nodal_values(&global),
            [0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 12.0, 14.0]
        );
    }
}
