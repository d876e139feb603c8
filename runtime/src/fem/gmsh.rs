//! Gmsh MSH 4.1 files (ASCII and binary) of 8-node quadrilaterals, read into a [`Mesh`] whose
//! boundary sets are the file's physical groups.
//!
//! What is read: `$MeshFormat`, `$PhysicalNames`, `$Entities`, `$Nodes`, `$Elements`; every
//! other section is skipped. The elements of the mesh are the 8-node quadrilaterals
//! (Gmsh type 16, `Mesh.SecondOrderIncomplete = 1`) of every surface; their node order (corners
//! counter-clockwise, then the mid-sides of edges 0–1, 1–2, 2–3, 3–0) is [`super::Quad8`]'s. A
//! physical group of dimension 1 becomes an edge set of the 3-node lines (type 8, `[end, end,
//! middle]`, the order [`Mesh::insert_edge_set`] takes) of its curves; one of dimension 0 a
//! point set of the nodes of its points (type 15). Nodes no quadrilateral uses are dropped;
//! the others are numbered in the order of the file.
//!
//! Checked, with errors naming the element (by its tag in the file) or the group: element types
//! other than these three, an element with a zero or negative Jacobian anywhere (inverted, or
//! degenerate) at its nodes or its 3 × 3 Gauss points, a group whose nodes are not nodes of the
//! quadrilaterals, a mesh of several unconnected parts. The reader does not need Gmsh.
//!
//! Why not the `mshio` crate: it parses `$Entities`, `$Nodes` and `$Elements` but not
//! `$PhysicalNames`, which are the boundary names here, and brings a parser-combinator
//! dependency for what is a few counted loops.

use super::element::{ElementKind, QUAD8_NODES, Quad8};
use super::mesh::{Mesh, MeshError};
use std::collections::{BTreeMap, HashMap};

/// Gmsh element type of the 8-node quadrilateral.
pub const GMSH_QUAD8: i32 = 16;
/// Gmsh element type of the 3-node line.
pub const GMSH_LINE3: i32 = 8;
/// Gmsh element type of the point.
pub const GMSH_POINT: i32 = 15;

/// Errors reading a Gmsh file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GmshError {
    /// The bytes are not an MSH 4.1 file as this reader understands it.
    #[error("Gmsh file: {0}")]
    Format(String),
    /// An element type that is not a Q8 quadrilateral, a 3-node line or a point.
    #[error(
        "Gmsh file: element {tag} is of type {element_type} ({name}); only 8-node quadrilaterals (type 16, second order incomplete), 3-node lines (type 8) on boundaries and points (type 15) are supported"
    )]
    UnsupportedElement {
        /// The element's tag in the file.
        tag: u64,
        /// Its Gmsh type.
        element_type: i32,
        /// What that type is.
        name: &'static str,
    },
    /// An element whose Jacobian is not positive somewhere.
    #[error(
        "Gmsh file: element {tag} is {what} (det J = {jacobian:.3e} at reference point ({xi}, {eta})); its corners must run counter-clockwise (`Reverse Surface` in the .geo flips them)"
    )]
    BadElement {
        /// The element's tag in the file.
        tag: u64,
        /// `inverted` or `degenerate`.
        what: &'static str,
        /// The Jacobian found.
        jacobian: f64,
        /// Reference coordinates where it was found.
        xi: f64,
        /// Reference coordinates where it was found.
        eta: f64,
    },
    /// A physical group with elements of a dimension this reader does not use, or whose
    /// nodes are not on the quadrilaterals.
    #[error("Gmsh file: physical group `{group}`: {message}")]
    Group {
        /// The group's name.
        group: String,
        /// What is wrong.
        message: String,
    },
    /// The quadrilaterals form several unconnected parts.
    #[error(
        "Gmsh file: the mesh has {parts} unconnected parts (element {first} and element {other} share no path of elements); a membrane must be one piece"
    )]
    Unconnected {
        /// Number of parts.
        parts: usize,
        /// An element of the first part (file tag).
        first: u64,
        /// An element of another part (file tag).
        other: u64,
    },
    /// The mesh failed [`Mesh`]'s own checks.
    #[error(transparent)]
    Mesh(#[from] MeshError),
}

fn format_error(message: impl Into<String>) -> GmshError {
    GmshError::Format(message.into())
}

/// Name of a Gmsh element type, for messages.
fn element_type_name(element_type: i32) -> &'static str {
    match element_type {
        1 => "2-node line",
        2 => "3-node triangle",
        3 => "4-node quadrangle",
        4 => "4-node tetrahedron",
        5 => "8-node hexahedron",
        8 => "3-node line",
        9 => "6-node triangle",
        10 => "9-node quadrangle",
        15 => "point",
        16 => "8-node quadrangle",
        _ => "see the Gmsh manual",
    }
}

/// Nodes of an element of a supported type.
fn nodes_per_element(tag: u64, element_type: i32) -> Result<usize, GmshError> {
    match element_type {
        GMSH_QUAD8 => Ok(8),
        GMSH_LINE3 => Ok(3),
        GMSH_POINT => Ok(1),
        _ => Err(GmshError::UnsupportedElement {
            tag,
            element_type,
            name: element_type_name(element_type),
        }),
    }
}

/// A cursor over the file: whitespace-separated tokens in ASCII sections, little-endian
/// values in the binary sections of a binary file (MSH 4.1 writes the same sequence of values
/// either way).
struct Cursor<'a> {
    bytes: &'a [u8],
    position: usize,
    binary: bool,
}

impl<'a> Cursor<'a> {
    fn skip_space(&mut self) {
        while self.position < self.bytes.len() && self.bytes[self.position].is_ascii_whitespace() {
            self.position += 1;
        }
    }

    /// The next whitespace-separated token (ASCII).
    fn token(&mut self) -> Result<&'a str, GmshError> {
        self.skip_space();
        let start = self.position;
        while self.position < self.bytes.len() && !self.bytes[self.position].is_ascii_whitespace() {
            self.position += 1;
        }
        if start == self.position {
            return Err(format_error("unexpected end of file"));
        }
        std::str::from_utf8(&self.bytes[start..self.position])
            .map_err(|_| format_error(format!("non-text bytes at offset {start}")))
    }

    /// The rest of the current line (ASCII), without its end.
    fn line(&mut self) -> Result<&'a str, GmshError> {
        let start = self.position;
        while self.position < self.bytes.len() && self.bytes[self.position] != b'\n' {
            self.position += 1;
        }
        let line = std::str::from_utf8(&self.bytes[start..self.position])
            .map_err(|_| format_error(format!("non-text bytes at offset {start}")))?;
        self.position = (self.position + 1).min(self.bytes.len());
        Ok(line.trim_end_matches('\r'))
    }

    fn raw<const N: usize>(&mut self) -> Result<[u8; N], GmshError> {
        let end = self.position + N;
        let slice = self
            .bytes
            .get(self.position..end)
            .ok_or_else(|| format_error("unexpected end of binary data"))?;
        self.position = end;
        Ok(slice.try_into().expect("slice of N bytes"))
    }

    fn parse<T: std::str::FromStr>(&mut self, what: &str) -> Result<T, GmshError> {
        let token = self.token()?;
        token
            .parse()
            .map_err(|_| format_error(format!("expected {what}, got `{token}`")))
    }

    /// An `int` (4 bytes in binary).
    fn int(&mut self) -> Result<i32, GmshError> {
        if self.binary {
            Ok(i32::from_le_bytes(self.raw()?))
        } else {
            self.parse("an integer")
        }
    }

    /// A `size_t` (8 bytes in binary).
    fn size(&mut self) -> Result<u64, GmshError> {
        if self.binary {
            Ok(u64::from_le_bytes(self.raw()?))
        } else {
            self.parse("a non-negative integer")
        }
    }

    /// A `double`.
    fn double(&mut self) -> Result<f64, GmshError> {
        if self.binary {
            Ok(f64::from_le_bytes(self.raw()?))
        } else {
            self.parse("a number")
        }
    }

    /// A count read as `size_t`, bounded by what the remaining bytes can hold (so that a
    /// corrupt count cannot ask for an enormous allocation).
    fn count(&mut self, bytes_each: usize) -> Result<usize, GmshError> {
        let count = self.size()?;
        let remaining = (self.bytes.len() - self.position) as u64;
        if count.saturating_mul(bytes_each.max(1) as u64) > remaining.saturating_mul(8) {
            return Err(format_error(format!(
                "count {count} is larger than the file can hold"
            )));
        }
        Ok(count as usize)
    }

    /// Expects the line `$End<name>` next.
    fn end_section(&mut self, name: &str) -> Result<(), GmshError> {
        self.skip_space();
        let line = self.line()?;
        if line.trim() != format!("$End{name}") {
            return Err(format_error(format!(
                "expected `$End{name}`, found `{}`",
                line.chars().take(40).collect::<String>()
            )));
        }
        Ok(())
    }
}

/// Everything read from a file before it becomes a [`Mesh`].
#[derive(Default)]
struct FileContents {
    /// `(dimension, physical tag)` → name.
    physical_names: BTreeMap<(i32, i32), String>,
    /// `(dimension, entity tag)` → its physical tags.
    entity_groups: HashMap<(i32, i32), Vec<i32>>,
    /// Node tag → coordinates.
    nodes: HashMap<u64, [f64; 2]>,
    /// Node tags in file order.
    node_order: Vec<u64>,
    /// Q8 elements: (element tag, node tags).
    quads: Vec<(u64, [u64; 8])>,
    /// Lines: (entity tag, node tags).
    lines: Vec<(i32, [u64; 3])>,
    /// Points: (entity tag, node tag).
    points: Vec<(i32, u64)>,
}

/// Reads an MSH 4.1 file's bytes (ASCII or binary) into a Q8 [`Mesh`] with the physical groups
/// as boundary sets (module documentation).
pub fn read_msh(bytes: &[u8]) -> Result<Mesh, GmshError> {
    let mut cursor = Cursor {
        bytes,
        position: 0,
        binary: false,
    };
    let mut contents = FileContents::default();
    let mut format_seen = false;
    loop {
        cursor.skip_space();
        if cursor.position >= bytes.len() {
            break;
        }
        let header = cursor.line()?.trim().to_string();
        let Some(name) = header.strip_prefix('$') else {
            return Err(format_error(format!(
                "expected a section (`$Name`), found `{}`",
                header.chars().take(40).collect::<String>()
            )));
        };
        match name {
            "MeshFormat" => {
                read_format(&mut cursor)?;
                format_seen = true;
            }
            _ if !format_seen => {
                return Err(format_error("the file does not start with `$MeshFormat`"));
            }
            "PhysicalNames" => read_physical_names(&mut cursor, &mut contents)?,
            "Entities" => read_entities(&mut cursor, &mut contents)?,
            "Nodes" => read_nodes(&mut cursor, &mut contents)?,
            "Elements" => read_elements(&mut cursor, &mut contents)?,
            other => skip_section(&mut cursor, other)?,
        }
        if name != "MeshFormat" {
            cursor.end_section(name)?;
        }
    }
    if !format_seen {
        return Err(format_error("no `$MeshFormat` section: not a Gmsh file"));
    }
    build_mesh(contents)
}

/// `$MeshFormat`: version 4.1, file type, data size 8; in a binary file the integer 1 that
/// tells the byte order.
fn read_format(cursor: &mut Cursor) -> Result<(), GmshError> {
    let line = cursor.line()?.to_string();
    let fields: Vec<&str> = line.split_whitespace().collect();
    let [version, file_type, data_size] = fields[..] else {
        return Err(format_error(format!("bad `$MeshFormat` line `{line}`")));
    };
    if version != "4.1" {
        return Err(format_error(format!(
            "MSH version {version}; only 4.1 is read (Gmsh: `Mesh.MshFileVersion = 4.1;`)"
        )));
    }
    if data_size != "8" {
        return Err(format_error(format!(
            "data size {data_size}; only 8-byte size_t is read"
        )));
    }
    cursor.binary = match file_type {
        "0" => false,
        "1" => true,
        other => return Err(format_error(format!("unknown file type {other}"))),
    };
    if cursor.binary {
        let one = i32::from_le_bytes(cursor.raw()?);
        if one != 1 {
            return Err(format_error(
                "binary file of another byte order (big-endian) is not read",
            ));
        }
    }
    let binary = cursor.binary;
    cursor.binary = false;
    cursor.end_section("MeshFormat")?;
    cursor.binary = binary;
    Ok(())
}

/// `$PhysicalNames` (ASCII in binary files too).
fn read_physical_names(cursor: &mut Cursor, contents: &mut FileContents) -> Result<(), GmshError> {
    let binary = std::mem::replace(&mut cursor.binary, false);
    let count: usize = cursor.parse("the number of physical names")?;
    for _ in 0..count {
        let dimension: i32 = cursor.parse("a dimension")?;
        let tag: i32 = cursor.parse("a physical tag")?;
        cursor.skip_space();
        let rest = cursor.line()?;
        let name = rest.trim().trim_matches('"').to_string();
        contents.physical_names.insert((dimension, tag), name);
    }
    cursor.binary = binary;
    Ok(())
}

/// `$Entities`: the physical tags of every point, curve and surface.
fn read_entities(cursor: &mut Cursor, contents: &mut FileContents) -> Result<(), GmshError> {
    let counts = [
        cursor.size()?,
        cursor.size()?,
        cursor.size()?,
        cursor.size()?,
    ];
    for (dimension, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let tag = cursor.int()?;
            let bounds = if dimension == 0 { 3 } else { 6 };
            for _ in 0..bounds {
                cursor.double()?;
            }
            let physical_count = cursor.count(4)?;
            let physicals = (0..physical_count)
                .map(|_| cursor.int())
                .collect::<Result<Vec<_>, _>>()?;
            if dimension > 0 {
                let bounding = cursor.count(4)?;
                for _ in 0..bounding {
                    cursor.int()?;
                }
            }
            contents
                .entity_groups
                .insert((dimension as i32, tag), physicals);
        }
    }
    Ok(())
}

/// `$Nodes`: per entity block, the tags then the coordinates ($`Z`$ must be 0).
fn read_nodes(cursor: &mut Cursor, contents: &mut FileContents) -> Result<(), GmshError> {
    let blocks = cursor.count(20)?;
    let _total = cursor.size()?;
    let _min_tag = cursor.size()?;
    let _max_tag = cursor.size()?;
    for _ in 0..blocks {
        let _dimension = cursor.int()?;
        let _entity = cursor.int()?;
        let parametric = cursor.int()?;
        let count = cursor.count(32)?;
        if parametric != 0 {
            return Err(format_error(
                "parametric node coordinates are not read (save without `Mesh.SaveParametric`)",
            ));
        }
        let tags = (0..count)
            .map(|_| cursor.size())
            .collect::<Result<Vec<_>, _>>()?;
        for tag in tags {
            let [x, y, z] = [cursor.double()?, cursor.double()?, cursor.double()?];
            if z != 0.0 {
                return Err(format_error(format!(
                    "node {tag} has Z = {z}; a membrane mesh lies in the plane Z = 0"
                )));
            }
            if contents.nodes.insert(tag, [x, y]).is_some() {
                return Err(format_error(format!("node {tag} is defined twice")));
            }
            contents.node_order.push(tag);
        }
    }
    Ok(())
}

/// `$Elements`: Q8 quadrilaterals, 3-node lines and points, by entity block.
fn read_elements(cursor: &mut Cursor, contents: &mut FileContents) -> Result<(), GmshError> {
    let blocks = cursor.count(20)?;
    let _total = cursor.size()?;
    let _min_tag = cursor.size()?;
    let _max_tag = cursor.size()?;
    for _ in 0..blocks {
        let _dimension = cursor.int()?;
        let entity = cursor.int()?;
        let element_type = cursor.int()?;
        let count = cursor.count(16)?;
        for index in 0..count {
            let tag = cursor.size()?;
            let per_element = nodes_per_element(tag, element_type)?;
            let mut nodes = [0u64; 8];
            for node in nodes.iter_mut().take(per_element) {
                *node = cursor.size()?;
            }
            match element_type {
                GMSH_QUAD8 => contents.quads.push((tag, nodes)),
                GMSH_LINE3 => contents
                    .lines
                    .push((entity, [nodes[0], nodes[1], nodes[2]])),
                _ => contents.points.push((entity, nodes[0])),
            }
            let _ = index;
        }
    }
    Ok(())
}

/// Skips a section this reader does not use, up to its `$End` line.
fn skip_section(cursor: &mut Cursor, name: &str) -> Result<(), GmshError> {
    let end = format!("\n$End{name}");
    let rest = &cursor.bytes[cursor.position.saturating_sub(1)..];
    let found = rest
        .windows(end.len())
        .position(|window| window == end.as_bytes())
        .ok_or_else(|| format_error(format!("section `${name}` has no `$End{name}`")))?;
    cursor.position = cursor.position.saturating_sub(1) + found + 1;
    Ok(())
}

/// Numbers the nodes of the quadrilaterals, checks the elements and the parts, and names the
/// physical groups.
fn build_mesh(contents: FileContents) -> Result<Mesh, GmshError> {
    if contents.quads.is_empty() {
        return Err(format_error(
            "no 8-node quadrilaterals (type 16): mesh with `Mesh.RecombineAll = 1; Mesh.ElementOrder = 2; Mesh.SecondOrderIncomplete = 1;`",
        ));
    }
    let mut index: HashMap<u64, usize> = HashMap::new();
    for (tag, nodes) in &contents.quads {
        for node in nodes {
            if !contents.nodes.contains_key(node) {
                return Err(format_error(format!(
                    "element {tag} refers to node {node}, which `$Nodes` does not define"
                )));
            }
            let next = index.len();
            index.entry(*node).or_insert(next);
        }
    }
    // Number in file order, not in order of first use.
    let mut used: Vec<u64> = contents
        .node_order
        .iter()
        .copied()
        .filter(|tag| index.contains_key(tag))
        .collect();
    used.dedup();
    let index: HashMap<u64, usize> = used.iter().enumerate().map(|(i, &t)| (t, i)).collect();
    let nodes: Vec<[f64; 2]> = used.iter().map(|tag| contents.nodes[tag]).collect();
    let connectivity: Vec<usize> = contents
        .quads
        .iter()
        .flat_map(|(_, element)| element.iter().map(|tag| index[tag]))
        .collect();
    let mut mesh = Mesh::new(ElementKind::Quad8, nodes, connectivity)?;
    let tags: Vec<u64> = contents.quads.iter().map(|(tag, _)| *tag).collect();
    check_elements(&mesh, &tags)?;
    check_connected(&mesh, &tags)?;
    name_groups(&mut mesh, &contents, &index)?;
    Ok(mesh)
}

/// Reference points where the Jacobian of every element must be positive: the 8 nodes and
/// the 3 × 3 Gauss points.
fn check_points() -> Vec<[f64; 2]> {
    let gauss = (0.6f64).sqrt();
    let mut points: Vec<[f64; 2]> = super::element::QUAD8_REFERENCE_NODES.to_vec();
    for xi in [-gauss, 0.0, gauss] {
        for eta in [-gauss, 0.0, gauss] {
            points.push([xi, eta]);
        }
    }
    points
}

/// Every element has a positive Jacobian at [`check_points`], relative to its size.
fn check_elements(mesh: &Mesh, tags: &[u64]) -> Result<(), GmshError> {
    let points = check_points();
    for (e, &tag) in tags.iter().enumerate() {
        let x = mesh.element_coordinates(e);
        let corners = &x[..4];
        let area = 0.5
            * ((corners[2][0] - corners[0][0]) * (corners[3][1] - corners[1][1])
                - (corners[3][0] - corners[1][0]) * (corners[2][1] - corners[0][1]));
        for &[xi, eta] in &points {
            let gradients = Quad8::shape_reference_gradients(xi, eta);
            let mut j = [[0.0; 2]; 2];
            for a in 0..QUAD8_NODES {
                for (row, coordinate) in j.iter_mut().zip(x[a]) {
                    row[0] += coordinate * gradients[a][0];
                    row[1] += coordinate * gradients[a][1];
                }
            }
            let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
            // det J of the reference square (area 4) is area/4 for a parallelogram.
            if det <= 1e-8 * area.abs() / 4.0 {
                return Err(GmshError::BadElement {
                    tag,
                    what: if det < 0.0 { "inverted" } else { "degenerate" },
                    jacobian: det,
                    xi,
                    eta,
                });
            }
        }
    }
    Ok(())
}

/// One piece: the elements connected through shared nodes form a single component.
fn check_connected(mesh: &Mesh, tags: &[u64]) -> Result<(), GmshError> {
    let count = mesh.element_count();
    let mut node_elements: Vec<Vec<usize>> = vec![Vec::new(); mesh.nodes.len()];
    for (e, element) in mesh.elements().enumerate() {
        for &n in element {
            node_elements[n].push(e);
        }
    }
    let mut part = vec![usize::MAX; count];
    let mut parts = 0;
    let mut first_of_part = Vec::new();
    for seed in 0..count {
        if part[seed] != usize::MAX {
            continue;
        }
        first_of_part.push(seed);
        part[seed] = parts;
        let mut stack = vec![seed];
        while let Some(e) = stack.pop() {
            for &n in mesh.element_nodes(e) {
                for &neighbour in &node_elements[n] {
                    if part[neighbour] == usize::MAX {
                        part[neighbour] = parts;
                        stack.push(neighbour);
                    }
                }
            }
        }
        parts += 1;
    }
    if parts > 1 {
        return Err(GmshError::Unconnected {
            parts,
            first: tags[first_of_part[0]],
            other: tags[first_of_part[1]],
        });
    }
    Ok(())
}

/// Edge sets from the physical groups of dimension 1, point sets from those of dimension 0.
fn name_groups(
    mesh: &mut Mesh,
    contents: &FileContents,
    index: &HashMap<u64, usize>,
) -> Result<(), GmshError> {
    let node = |group: &str, tag: u64| {
        index.get(&tag).copied().ok_or_else(|| GmshError::Group {
            group: group.to_string(),
            message: format!("node {tag} is not a node of the quadrilaterals"),
        })
    };
    let groups_of = |dimension: i32, entity: i32| {
        contents
            .entity_groups
            .get(&(dimension, entity))
            .into_iter()
            .flatten()
            .filter_map(move |physical| contents.physical_names.get(&(dimension, *physical)))
    };
    let mut edges: BTreeMap<String, Vec<[usize; 3]>> = BTreeMap::new();
    for (entity, line) in &contents.lines {
        for group in groups_of(1, *entity) {
            let segment = [
                node(group, line[0])?,
                node(group, line[1])?,
                node(group, line[2])?,
            ];
            edges.entry(group.clone()).or_default().push(segment);
        }
    }
    let mut points: BTreeMap<String, Vec<usize>> = BTreeMap::new();
    for (entity, tag) in &contents.points {
        for group in groups_of(0, *entity) {
            points
                .entry(group.clone())
                .or_default()
                .push(node(group, *tag)?);
        }
    }
    for (name, segments) in edges {
        mesh.insert_edge_set(&name, segments)?;
    }
    for (name, mut nodes) in points {
        nodes.sort_unstable();
        nodes.dedup();
        mesh.insert_point_set(&name, nodes)?;
    }
    Ok(())
}
