//! gmsh `.msh` reader (ASCII formats 2.2 and 4.1).
//!
//! What is read:
//! - `$MeshFormat`: versions 2, 2.0, 2.1, 2.2 and 4.1, ASCII only (a binary
//!   file is a clear error);
//! - `$PhysicalNames`, `$Entities` (4.1: physical groups of each entity),
//!   `$Nodes` (4.1 blocks, any tags), `$Elements`;
//! - other sections (`$NodeData`, `$Periodic`, `$Comments`, ...) are skipped.
//!
//! How it becomes a [`Mesh`]:
//! - cells are the triangles (type 2) and quadrangles (type 3) of every
//!   surface, re-oriented counter-clockwise when the file has them
//!   clockwise; duplicates (MSH 2 repeats elements once per physical group)
//!   are dropped;
//! - nodes are those used by cells, numbered densely in file order (gmsh
//!   tags need not be contiguous; geometry points off the mesh, like a circle
//!   centre, are dropped); z is ignored (the mesh is taken as planar);
//! - physical groups become sets named from `$PhysicalNames`, else
//!   `physical_<tag>`: dimension 1 -> an edge set (each line oriented like
//!   the boundary edge of its cell, body on the left) and a node set;
//!   dimension 0 -> a node set; dimension 2 -> the node set of its cells.
//!   A dimension-1 group made only of interior lines (shared by two cells)
//!   gives a node set only; one mixing boundary and interior lines is an
//!   error. Groups of different dimensions sharing a name given in
//!   `$PhysicalNames` are merged; unnamed groups of different dimensions
//!   with the same tag (both `physical_<tag>`) are an error asking for names;
//! - points (type 15) and lines (types 1 and 8) only feed the sets; planar
//!   meshes read the second-order tri6 (9), quad8 (16) and quad9 (10) in
//!   gmsh's node order (the engine's), midside nodes where gmsh put them
//!   (on the curved geometry); 3D elements are errors in planar meshes,
//!   orders above 2 everywhere. Solid meshes also read
//!   the second-order tet10 (11), hex20 (17) and hex27 (12) with their
//!   facets (8, 9, 10, 16), gmsh's node order mapped to the engine's
//!   (`crate::element::reference`).
//!
//! Every malformed input gives a [`MeshError`] with the 1-based line.

mod assemble;
mod cursor;
mod raw;
mod solid;
mod tags;
mod v2;
mod v41;

use super::Mesh;
use crate::mesh::MeshError;
use cursor::Cursor;
use raw::RawMesh;

/// Supported format families.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Version {
    V2,
    V41,
}

/// Parses the text of a `.msh` file. Physical groups of dimension 1 become
/// edge sets (and node sets), of dimension 0 node sets; cells are the 2D
/// triangles and quadrangles. Errors carry the 1-based line number.
pub fn parse(text: &str) -> Result<Mesh, MeshError> {
    let (raw, eof) = read_raw(text, false)?;
    assemble::assemble(raw, eof)
}

/// Parses the text of a `.msh` file as a solid (3D) mesh: cells are the
/// tetrahedra (type 4) and hexahedra (type 5), re-oriented to a positive
/// volume; physical groups of dimension 2 become face sets (each triangle
/// or quadrangle matched to the cell face it lies on, in that cell's
/// outward order; a group with a face interior to the mesh is an error)
/// with their node sets, of dimension 3 the node set of their cells, of
/// dimension 0 or 1 node sets. Errors carry the 1-based line number.
pub fn parse_solid(text: &str) -> Result<Mesh<3>, MeshError> {
    let (raw, eof) = read_raw(text, true)?;
    solid::assemble(raw, eof)
}

/// Like [`parse_bytes`] for a solid mesh ([`parse_solid`]).
pub fn parse_solid_bytes(bytes: &[u8]) -> Result<Mesh<3>, MeshError> {
    let text = utf8(bytes)?;
    parse_solid(text)
}

/// The sections of a `.msh` text and its last line.
fn read_raw(text: &str, solid: bool) -> Result<(RawMesh, usize), MeshError> {
    let mut c = Cursor::new(text);
    let version = header(&mut c)?;
    let mut raw = RawMesh {
        solid,
        ..Default::default()
    };
    let mut entities = v41::EntityPhysicals::new();
    while let Some((tok, line)) = c.next_token() {
        let Some(name) = tok.strip_prefix('$') else {
            return Err(MeshError::at_line(
                line,
                format!(
                    "expected a section header such as $Nodes, found '{}'",
                    tok.chars().take(40).collect::<String>()
                ),
            ));
        };
        match name {
            "MeshFormat" => return Err(MeshError::at_line(line, "a second $MeshFormat section")),
            "PhysicalNames" => {
                c.section = "$PhysicalNames";
                physical_names(&mut c, &mut raw)?;
            }
            "Entities" if version == Version::V41 => {
                c.section = "$Entities";
                entities = v41::entities(&mut c)?;
            }
            "Nodes" | "Elements" => {
                let seen = if name == "Nodes" {
                    &mut raw.has_nodes
                } else {
                    &mut raw.has_elements
                };
                if *seen {
                    return Err(MeshError::at_line(
                        line,
                        format!("a second ${name} section (partitioned files are not supported)"),
                    ));
                }
                *seen = true;
                c.section = if name == "Nodes" {
                    "$Nodes"
                } else {
                    "$Elements"
                };
                match (name, version) {
                    ("Nodes", Version::V2) => v2::nodes(&mut c, &mut raw)?,
                    ("Nodes", Version::V41) => v41::nodes(&mut c, &mut raw)?,
                    (_, Version::V2) => v2::elements(&mut c, &mut raw)?,
                    (_, Version::V41) => v41::elements(&mut c, &mut raw, &entities)?,
                }
            }
            n if n.starts_with("End") => {
                return Err(MeshError::at_line(
                    line,
                    format!("{tok} without its opening section"),
                ))
            }
            _ => skip(&mut c, name, line)?,
        }
    }
    Ok((raw, c.line()))
}

/// Parses a `.msh` file's bytes: like [`parse`], but recognises binary
/// files before requiring UTF-8 text, and reports invalid bytes by line.
pub fn parse_bytes(bytes: &[u8]) -> Result<Mesh, MeshError> {
    parse(utf8(bytes)?)
}

/// The text of a `.msh` file, or why it is not text.
fn utf8(bytes: &[u8]) -> Result<&str, MeshError> {
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text),
        Err(e) => {
            let valid = &bytes[..e.valid_up_to()];
            // a binary file has a readable header: let `header` explain
            if let Ok(head) = std::str::from_utf8(valid) {
                let mut c = Cursor::new(head);
                if let Err(err) = header(&mut c) {
                    if err.message.contains("binary") {
                        return Err(err);
                    }
                }
            }
            let line = 1 + valid.iter().filter(|&&b| b == b'\n').count();
            Err(MeshError::at_line(
                line,
                "the file is not valid UTF-8 text: is it a binary .msh? (ctc reads ASCII .msh only)",
            ))
        }
    }
}

/// Reads and parses a `.msh` file; I/O errors name the path.
pub fn read(path: &std::path::Path) -> Result<Mesh, MeshError> {
    let bytes = std::fs::read(path)
        .map_err(|e| MeshError::new(format!("cannot read {}: {e}", path.display())))?;
    parse_bytes(&bytes)
}

/// Reads `$MeshFormat` .. `$EndMeshFormat`.
fn header(c: &mut Cursor) -> Result<Version, MeshError> {
    match c.next_token() {
        Some(("$MeshFormat", _)) => {}
        Some((tok, line)) => {
            return Err(MeshError::at_line(
                line,
                format!(
                    "not a gmsh mesh in format 2.2 or 4.1: the file must start with $MeshFormat, found '{}'",
                    tok.chars().take(40).collect::<String>()
                ),
            ))
        }
        None => return Err(MeshError::at_line(1, "the mesh file is empty")),
    }
    c.section = "$MeshFormat";
    let (v, line) = c.token("the format version")?;
    let version = match v {
        "2" | "2.0" | "2.1" | "2.2" => Version::V2,
        "4.1" => Version::V41,
        "4" | "4.0" => {
            return Err(MeshError::at_line(
                line,
                "MSH format 4.0 is not supported: save as 4.1 or 2.2 (gmsh -format msh41)",
            ))
        }
        _ => {
            return Err(MeshError::at_line(
                line,
                format!(
                    "unsupported MSH format version '{}': ctc reads 2.2 and 4.1",
                    v.chars().take(20).collect::<String>()
                ),
            ))
        }
    };
    let file_type = c.usize("the file type (0 = ASCII, 1 = binary)")?;
    if file_type != 0 {
        return Err(c.error(
            "binary .msh files are not supported: save the mesh as ASCII \
             (gmsh: Mesh.Binary = 0, or File > Export with 'Save all' unchecked and ASCII)",
        ));
    }
    c.usize("the data size")?;
    c.end("MeshFormat")?;
    Ok(version)
}

/// Reads `$PhysicalNames` after its header: `n`, then `dim tag "name"`.
fn physical_names(c: &mut Cursor, raw: &mut RawMesh) -> Result<(), MeshError> {
    let n = c.usize("the number of physical names")?;
    for _ in 0..n {
        let dim = c.usize("the dimension of a physical group")?;
        let line = c.line();
        if dim > 3 {
            return Err(MeshError::at_line(
                line,
                format!("physical group dimension {dim} is not 0, 1, 2 or 3"),
            ));
        }
        let tag = c.i64("a physical tag")?;
        let rest = c.rest_of_line();
        let name = rest
            .strip_prefix('"')
            .and_then(|r| r.strip_suffix('"'))
            .filter(|s| !s.is_empty())
            .ok_or_else(|| {
                MeshError::at_line(
                    line,
                    format!("expected a quoted physical name, found '{rest}'"),
                )
            })?;
        raw.names.insert((dim, tag), name.to_string());
    }
    c.end("PhysicalNames")
}

/// Skips an unknown section up to its `$End<name>`.
fn skip(c: &mut Cursor, name: &str, start: usize) -> Result<(), MeshError> {
    let end = format!("$End{name}");
    while let Some((tok, _)) = c.next_token() {
        if tok == end {
            return Ok(());
        }
    }
    Err(MeshError::at_line(
        start,
        format!("section ${name} is never closed by {end} (is the file truncated?)"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::CellKind;

    const SQUARE_V2: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
$PhysicalNames\n2\n1 1 \"bottom\"\n2 2 \"body\"\n$EndPhysicalNames\n\
$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n\
$Elements\n3\n1 1 2 1 1 1 2\n2 2 2 2 1 1 3 2\n3 2 2 2 1 1 4 3\n$EndElements\n";

    #[test]
    fn unit_square_v2_two_triangles_reoriented_and_sets() {
        let m = parse(SQUARE_V2).unwrap();
        assert_eq!(m.nodes.len(), 4);
        assert_eq!(m.cells.len(), 2);
        // the first triangle was clockwise in the file
        assert_eq!(m.cells.nodes(0), &[0, 1, 2]);
        assert_eq!(m.edge_sets["bottom"], vec![[0, 1]]);
        assert_eq!(m.node_sets["bottom"], vec![0, 1]);
        assert_eq!(m.node_sets["body"], vec![0, 1, 2, 3]);
    }

    /// MSH 2 repeats an element once per physical group: the second
    /// triangle comes three times (twice as in the file, once with its
    /// nodes rotated) and a line twice; the first of each is kept, in
    /// file order, and every group gets its nodes.
    #[test]
    fn repeated_elements_are_one_cell_the_first_in_file_order() {
        let text = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
$PhysicalNames\n3\n1 1 \"bottom\"\n2 2 \"body\"\n2 3 \"upper\"\n$EndPhysicalNames\n\
$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n$EndNodes\n\
$Elements\n7\n1 1 2 1 1 1 2\n2 2 2 2 1 1 3 2\n3 2 2 2 1 1 4 3\n4 2 2 3 1 1 4 3\n\
5 2 2 3 1 3 1 4\n6 1 2 1 1 1 2\n7 2 2 3 1 3 2 1\n$EndElements\n";
        let m = parse(text).unwrap();
        assert_eq!(m.cells.len(), 2);
        assert_eq!(m.cells.nodes(0), &[0, 1, 2]);
        assert_eq!(m.cells.nodes(1), &[0, 2, 3]);
        assert_eq!(m.edge_sets["bottom"], vec![[0, 1]]);
        assert_eq!(m.node_sets["body"], vec![0, 1, 2, 3]);
        assert_eq!(m.node_sets["upper"], vec![0, 1, 2, 3]);
    }

    /// `Mesh::boundary_edges` (a counting sort) against the count of every
    /// edge in a `BTreeMap` (the order it replaced): a grid of quads and
    /// triangles, whole and as a range of its cells.
    #[test]
    fn boundary_edges_are_the_edges_met_once_in_key_order() {
        let mut m = crate::testkit::grid::grid(7, 5, [0.0, 0.0], [1.0, 1.0], 0.1, 3, true);
        let tris = crate::testkit::grid::grid(4, 3, [2.0, 0.0], [1.0, 1.0], 0.0, 1, false);
        let shift = m.nodes.len();
        m.nodes.extend_from_slice(&tris.nodes);
        for c in tris.cells.iter() {
            let n: Vec<usize> = c.nodes.iter().map(|&k| k + shift).collect();
            m.cells.push_nodes(CellKind::Tri3, &[n[0], n[1], n[2]]);
            m.cells.push_nodes(CellKind::Tri3, &[n[0], n[2], n[3]]);
        }
        let reference = |cells: std::ops::Range<usize>| {
            let mut count = std::collections::BTreeMap::new();
            for c in cells {
                let n = m.cells.nodes(c);
                let k = m.cells.kind(c).corner_count();
                for i in 0..k {
                    let (a, b) = (n[i], n[(i + 1) % k]);
                    count.entry((a.min(b), a.max(b))).or_insert((0, [a, b])).0 += 1;
                }
            }
            count
                .into_values()
                .filter(|(k, _)| *k == 1)
                .map(|(_, e)| e)
                .collect::<Vec<_>>()
        };
        let all = 0..m.cells.len();
        for range in [all.clone(), 3..20, 35..all.end, 0..0] {
            let got = m.boundary_edges(range.clone());
            assert_eq!(got, reference(range.clone()), "{range:?}");
        }
        assert!(!m.boundary_edges(all).is_empty());
    }

    /// A clockwise quad8 (top midside node off the chord, as gmsh puts it
    /// on a curved boundary) with a 3-node physical line, and a tri6.
    const QUAD8_V2: &str = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n\
$PhysicalNames\n1\n1 1 \"bottom\"\n$EndPhysicalNames\n\
$Nodes\n10\n1 0 0 0\n2 1 0 0\n3 1 1 0\n4 0 1 0\n5 0.5 0 0\n6 1 0.5 0\n7 0.5 1.1 0\n\
8 0 0.5 0\n9 2 0 0\n10 1.5 0 0\n$EndNodes\n\
$Elements\n3\n1 8 2 1 1 1 2 5\n2 16 2 0 1 1 4 3 2 8 7 6 5\n3 9 2 0 1 2 9 3 10 11 6\n$EndElements\n";

    #[test]
    fn second_order_planar_cells_are_read_reoriented_with_their_midside_nodes() {
        let text = QUAD8_V2
            .replace("$Nodes\n10\n", "$Nodes\n11\n")
            .replace("10 1.5 0 0\n", "10 1.5 0 0\n11 1.5 0.5 0\n");
        let m = parse(&text).unwrap();
        assert_eq!(m.cells.kind(0), CellKind::Quad8);
        assert_eq!(m.cells.kind(1), CellKind::Tri6);
        // reflected: corners 1 2 3 4, midside nodes 5 6 7 8 (tags - 1)
        assert_eq!(m.cells.nodes(0), &[0, 1, 2, 3, 4, 5, 6, 7]);
        assert_eq!(m.nodes[6], [0.5, 1.1]);
        // the triangle 2 9 3 was counter-clockwise already
        assert_eq!(m.cells.nodes(1), &[1, 8, 2, 9, 10, 5]);
        assert_eq!(m.edge_sets["bottom"], vec![[0, 1]]);
        assert_eq!(m.node_sets["bottom"], vec![0, 1, 4]);
        assert!(crate::mesh::validate::check(&m).is_ok());
        assert_eq!(m.boundary_edges(0..2).len(), 5);
    }

    #[test]
    fn binary_header_is_a_clear_error() {
        let e = parse("$MeshFormat\n4.1 1 8\n").unwrap_err();
        assert_eq!(e.line, Some(2));
        assert!(e.message.contains("binary"), "{}", e.message);
        let mut bytes = b"$MeshFormat\n4.1 1 8\n".to_vec();
        bytes.extend_from_slice(&[1, 0, 0, 0, 0xff, 0xfe, b'\n']);
        let e = parse_bytes(&bytes).unwrap_err();
        assert!(e.message.contains("binary"), "{}", e.message);
    }

    #[test]
    fn invalid_utf8_reported_at_its_line() {
        let mut bytes = b"$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n".to_vec();
        bytes.push(0xff);
        let e = parse_bytes(&bytes).unwrap_err();
        assert_eq!(e.line, Some(5));
    }

    #[test]
    fn unknown_sections_skipped_unclosed_reported() {
        let text = SQUARE_V2.replace(
            "$Nodes",
            "$Comments\nanything $Nodes-like goes 1 2\n$EndComments\n$Nodes",
        );
        assert!(parse(&text).is_ok());
        let e = parse("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Foo\n1 2\n").unwrap_err();
        assert_eq!(e.line, Some(4));
        assert!(e.message.contains("$EndFoo"), "{}", e.message);
    }

    #[test]
    fn unsupported_versions_and_non_msh_files() {
        for (text, line, word) in [
            ("$MeshFormat\n4 0 8\n$EndMeshFormat\n", 2, "4.0"),
            ("$MeshFormat\n3.0 0 8\n$EndMeshFormat\n", 2, "3.0"),
            ("$NOD\n1\n1 0 0 0\n$ENDNOD\n", 1, "$MeshFormat"),
            ("", 1, "empty"),
        ] {
            let e = parse(text).unwrap_err();
            assert_eq!(e.line, Some(line), "{text}");
            assert!(e.message.contains(word), "{}", e.message);
        }
    }
}
