//! The Gmsh MSH 4.1 reader: the shipped meshes of the example 1 rectangle (ASCII and binary,
//! made by Gmsh 4.15 from `examples/meshes/example1_rectangle.geo`) hold the nodes, elements
//! and boundary sets of the built-in 32 × 16 mesh; hostile files (unsupported element types,
//! inverted and degenerate elements, unconnected parts, truncated or foreign files) are errors
//! that name the element or what is wrong, never a panic.

use std::collections::BTreeSet;
use std::path::PathBuf;

use wrinkle_runtime::fem::Mesh;
use wrinkle_runtime::fem::gmsh::{GmshError, read_msh};

fn shipped(name: &str) -> Vec<u8> {
    let path: PathBuf = [env!("CARGO_MANIFEST_DIR"), "..", "examples", "meshes", name]
        .iter()
        .collect();
    std::fs::read(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// A node position to 1e-9 mm (`make_meshes.py` snaps the file's nodes onto the grid, which
/// Gmsh's transfinite interpolation misses by up to 1.3e-9 mm).
fn key(position: [f64; 2]) -> (i64, i64) {
    let round = |x: f64| (x * 1e9).round() as i64;
    (round(position[0]), round(position[1]))
}

/// Node positions, for set comparison.
fn positions(mesh: &Mesh, nodes: impl IntoIterator<Item = usize>) -> BTreeSet<(i64, i64)> {
    nodes.into_iter().map(|n| key(mesh.nodes[n])).collect()
}

/// Elements as sets of their node positions in order, for comparison across numberings.
fn elements(mesh: &Mesh) -> BTreeSet<Vec<(i64, i64)>> {
    mesh.elements()
        .map(|element| {
            element
                .iter()
                .map(|&n| key(mesh.nodes[n]))
                .collect::<Vec<_>>()
        })
        .map(|mut corners| {
            // The same element may start at another corner: rotate to the smallest corner.
            let start = (0..4).min_by_key(|&k| corners[k]).unwrap();
            corners[..4].rotate_left(start);
            corners[4..].rotate_left(start);
            corners
        })
        .collect()
}

#[test]
fn example1_rectangle_file_is_the_built_in_mesh() {
    let built_in = Mesh::rectangle(400.0, 200.0, 32, 16, 1.0).unwrap();
    for file in ["example1_rectangle.msh", "example1_rectangle_binary.msh"] {
        let mesh = read_msh(&shipped(file)).unwrap();
        assert_eq!(mesh.nodes.len(), built_in.nodes.len(), "{file}");
        assert_eq!(
            positions(&mesh, 0..mesh.nodes.len()),
            positions(&built_in, 0..built_in.nodes.len()),
            "{file}: node positions"
        );
        assert_eq!(elements(&mesh), elements(&built_in), "{file}: elements");
        for name in ["left", "right", "bottom", "top", "centre", "right_middle"] {
            assert_eq!(
                positions(&mesh, mesh.boundary_nodes(name).unwrap()),
                positions(&built_in, built_in.boundary_nodes(name).unwrap()),
                "{file}: boundary `{name}`"
            );
        }
        assert_eq!(mesh.edges["left"].len(), 16);
        assert!(mesh.grid.is_none());
    }
}

/// An ASCII MSH 4.1 file of `columns` unit Q8 squares in a row, with the edge `left` (a 3-node
/// line) and the point `corner`; `edit` may change the elements' type and nodes.
fn strip_file(columns: usize, edit: impl Fn(&mut i32, &mut Vec<[usize; 8]>)) -> String {
    // Node grid: x = 0, ½, 1, … (2·columns + 1 columns of positions), y = 0, ½, 1; no
    // element centres. Tag = 1 + index in this list.
    let mut nodes = Vec::new();
    let mut tag_of = std::collections::HashMap::new();
    for j in 0..3 {
        for i in 0..=2 * columns {
            if j == 1 && i % 2 == 1 {
                continue;
            }
            tag_of.insert((i, j), nodes.len() + 1);
            nodes.push([0.5 * i as f64, 0.5 * j as f64]);
        }
    }
    let mut quads: Vec<[usize; 8]> = (0..columns)
        .map(|c| {
            let i = 2 * c;
            [
                tag_of[&(i, 0)],
                tag_of[&(i + 2, 0)],
                tag_of[&(i + 2, 2)],
                tag_of[&(i, 2)],
                tag_of[&(i + 1, 0)],
                tag_of[&(i + 2, 1)],
                tag_of[&(i + 1, 2)],
                tag_of[&(i, 1)],
            ]
        })
        .collect();
    let mut quad_type = 16;
    edit(&mut quad_type, &mut quads);
    let per = if quad_type == 16 { 8 } else { 4 };
    let mut text = String::from(
        "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n0 2 \"corner\"\n1 1 \"left\"\n$EndPhysicalNames\n",
    );
    text +=
        "$Entities\n1 1 1 0\n1 0 0 0 1 2\n1 0 0 0 0 1 0 1 1 0\n1 0 0 0 9 1 0 0 0\n$EndEntities\n";
    text += &format!("$Nodes\n1 {0} 1 {0}\n2 1 0 {0}\n", nodes.len());
    for k in 0..nodes.len() {
        text += &format!("{}\n", k + 1);
    }
    for [x, y] in &nodes {
        text += &format!("{x} {y} 0\n");
    }
    text += "$EndNodes\n";
    let total = quads.len() + 2;
    text += &format!(
        "$Elements\n3 {total} 1 {total}\n0 1 15 1\n{} {}\n",
        1,
        tag_of[&(0, 0)]
    );
    text += &format!(
        "1 1 8 1\n2 {} {} {}\n",
        tag_of[&(0, 0)],
        tag_of[&(0, 2)],
        tag_of[&(0, 1)]
    );
    text += &format!("2 1 {quad_type} {}\n", quads.len());
    for (k, quad) in quads.iter().enumerate() {
        let listed: Vec<String> = quad[..per].iter().map(|t| t.to_string()).collect();
        text += &format!("{} {}\n", k + 3, listed.join(" "));
    }
    text += "$EndElements\n";
    text
}

#[test]
fn a_small_ascii_file_gives_its_elements_and_groups() {
    let mesh = read_msh(strip_file(3, |_, _| {}).as_bytes()).unwrap();
    assert_eq!(mesh.element_count(), 3);
    assert_eq!(mesh.nodes.len(), 7 * 2 + 4);
    assert_eq!(mesh.edges["left"].len(), 1);
    assert_eq!(mesh.points["corner"], vec![0]);
    // An unknown section is skipped.
    let with_extra = strip_file(2, |_, _| {}).replace(
        "$Entities",
        "$Comments\nanything $ here\n$EndComments\n$Entities",
    );
    assert_eq!(read_msh(with_extra.as_bytes()).unwrap().element_count(), 2);
}

#[test]
fn unsupported_element_types_are_named() {
    let file = strip_file(2, |kind, _| *kind = 3);
    let error = read_msh(file.as_bytes()).unwrap_err();
    assert!(
        matches!(
            error,
            GmshError::UnsupportedElement {
                tag: 3,
                element_type: 3,
                ..
            }
        ),
        "{error}"
    );
    assert!(error.to_string().contains("4-node quadrangle"), "{error}");
}

#[test]
fn inverted_and_degenerate_elements_are_named() {
    // Element 4 (the second quadrilateral) listed clockwise.
    let inverted = strip_file(2, |_, quads| {
        let q = quads[1];
        quads[1] = [q[0], q[3], q[2], q[1], q[7], q[6], q[5], q[4]];
    });
    let error = read_msh(inverted.as_bytes()).unwrap_err();
    assert!(
        matches!(
            error,
            GmshError::BadElement {
                tag: 4,
                what: "inverted",
                ..
            }
        ),
        "{error}"
    );
    // Element 3 collapsed: two corners on one node.
    let degenerate = strip_file(2, |_, quads| quads[0][1] = quads[0][0]);
    let error = read_msh(degenerate.as_bytes()).unwrap_err();
    assert!(
        matches!(error, GmshError::BadElement { tag: 3, .. }),
        "{error}"
    );
}

#[test]
fn unconnected_parts_are_refused() {
    // Drop the middle one of three elements: the first and the last share no node.
    let file = strip_file(3, |_, quads| {
        quads.remove(1);
    });
    let error = read_msh(file.as_bytes()).unwrap_err();
    assert!(
        matches!(
            error,
            GmshError::Unconnected {
                parts: 2,
                first: 3,
                other: 4
            }
        ),
        "{error}"
    );
}

#[test]
fn foreign_or_truncated_files_are_errors_not_panics() {
    let good = strip_file(2, |_, _| {});
    let cases: Vec<(String, &str)> = vec![
        (String::new(), "no `$MeshFormat`"),
        ("hello\n".into(), "expected a section"),
        (good.replace("4.1 0 8", "2.2 0 8"), "only 4.1 is read"),
        (good[..good.len() / 2].to_string(), ""),
        (good.replace("$EndNodes", "$EndNode"), "$EndNodes"),
        (
            good.replace("$Nodes\n1 ", "$Nodes\n99999999999999 "),
            "larger than the file",
        ),
        (good.replace("0.5 0 0", "0.5 0 1"), "Z = 1"),
    ];
    for (text, expected) in cases {
        match read_msh(text.as_bytes()) {
            Ok(_) => panic!("accepted: {}", text.chars().take(60).collect::<String>()),
            Err(error) => assert!(
                error.to_string().contains(expected),
                "{error} (expected `{expected}`)"
            ),
        }
    }
    // Every prefix of a binary file is an error, never a panic.
    let binary = shipped("example1_rectangle_binary.msh");
    for cut in (0..binary.len()).step_by(997) {
        assert!(read_msh(&binary[..cut]).is_err(), "prefix of {cut} bytes");
    }
}
