//! Element colours and the shared output the elements of one colour add into.

use crate::fem::mesh::Mesh;
use crate::scalar::Scalar;

/// Where one element adds its contributions during [`super::Assembler`]'s colour loop.
///
/// A raw view of the output shared by the elements of one colour. Sound because elements of one
/// colour share no node, hence no dof and no matrix entry: each entry is written by at most one
/// element of the colour being processed, and colours are processed one after the other.
pub(super) struct ElementSink<S> {
    pub(super) data: *mut S,
    pub(super) len: usize,
}

impl<S> Clone for ElementSink<S> {
    fn clone(&self) -> Self {
        ElementSink {
            data: self.data,
            len: self.len,
        }
    }
}

// SAFETY: see the type's documentation: concurrent elements write disjoint entries.
unsafe impl<S: Send> Send for ElementSink<S> {}
unsafe impl<S: Send> Sync for ElementSink<S> {}

impl<S: Scalar> ElementSink<S> {
    #[inline(always)]
    pub(super) fn add(&mut self, index: usize, value: S) {
        assert!(index < self.len, "assembly index out of range");
        // SAFETY: in bounds (checked), and no other element of the running colour writes
        // `index` (elements of one colour share no dof).
        unsafe {
            let entry = self.data.add(index);
            *entry = *entry + value;
        }
    }
}

/// Greedy colouring of the elements (in element order, smallest free colour) such that no two
/// elements of a colour share a node. Deterministic; a structured Q8 mesh gets 4 colours, a
/// line mesh 2.
pub fn colour_elements(mesh: &Mesh) -> Vec<Vec<usize>> {
    let mut elements_of_node: Vec<Vec<usize>> = vec![Vec::new(); mesh.nodes.len()];
    for (e, nodes) in mesh.elements().enumerate() {
        for &n in nodes.iter() {
            elements_of_node[n].push(e);
        }
    }
    let mut colour_of = vec![usize::MAX; mesh.element_count()];
    let mut colours: Vec<Vec<usize>> = Vec::new();
    let mut taken = Vec::new();
    for (e, nodes) in mesh.elements().enumerate() {
        taken.clear();
        for &n in nodes.iter() {
            for &other in &elements_of_node[n] {
                if colour_of[other] != usize::MAX {
                    taken.push(colour_of[other]);
                }
            }
        }
        let colour = (0..)
            .find(|c| !taken.contains(c))
            .expect("a free colour exists");
        if colour == colours.len() {
            colours.push(Vec::new());
        }
        colours[colour].push(e);
        colour_of[e] = colour;
    }
    colours
}
