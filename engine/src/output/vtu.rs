//! VTK XML unstructured grid (`.vtu`) of one increment: binary (appended
//! raw, zlib) by default, ASCII with `output { format = ascii }` (the
//! storage is [`super::encode`]; [`super::vtu_read`] reads either back).
//!
//! Points are the reference coordinates (z = 0 for planar models);
//! ParaView's "Warp By Vector" on `displacement` shows the deformed shape.
//! Point data, as requested: `displacement` (3 components, z = 0 when
//! planar), `stress` and `strain` (planar: 4 components named xx, yy, zz,
//! xy; zz is the hoop component for axisymmetric runs; solid: 6 components
//! xx, yy, zz, xy, xz, yz; strain shear is engineering; finite-strain
//! bodies: Cauchy stress and logarithmic strain), `von_mises`,
//! `equivalent_plastic_strain` (with stress/strain/von_mises when a body is
//! plastic: converged integration-point values, nodal averages), `reaction` (3 components), `contact_gap`, `contact_pressure`,
//! `contact_status` (-1 not a slave node, 0 open or out of reach, 1 closed;
//! the gap is 0 where no contact was evaluated); with friction also
//! `friction_force` (tangential force; 3D: its magnitude, and the vector
//! `friction_traction`), `friction_slip` (slip increment; 3D: its length),
//! `friction_status` (0 frictionless, 1 stick, 2 slip) and
//! `friction_dissipation` (work of the increment); dynamic runs:
//! `velocity`, `acceleration` (3 components, when requested); `thickness`
//! with `output { thickness = (a, b) }` ([`super::thickness`]). Cell data: `body` index,
//! and with the same names as the point data `stress`, `strain`,
//! `von_mises`, `equivalent_plastic_strain`: the volume-weighted mean of
//! each cell's integration points (element values, not smoothed; the von
//! Mises mean is of the points' von Mises stresses).
//! Field data: `TIME` and `CYCLE` (the increment number).

use super::encode::{fmt_f64, Arrays, Encoding};
use crate::contact::{ContactStatus, NodeContact};
use crate::element::recovery::NodalFields;
use crate::mesh::CellKind;
use crate::model::{AnalysisKind, Field, Model};
use std::fmt::Write;

/// What one VTU file shows (a model of dimension `D`).
#[derive(Debug)]
pub struct VtuData<'a, const D: usize = 2> {
    /// The model (mesh, bodies, contact pairs).
    pub model: &'a Model<D>,
    /// Step name, for the header comment.
    pub step: &'a str,
    /// Increment number.
    pub increment: usize,
    /// Time.
    pub time: f64,
    /// Fields to write.
    pub fields: &'a [Field],
    /// Nodal displacements.
    pub displacement: &'a [[f64; D]],
    /// Nodal reactions.
    pub reaction: &'a [[f64; D]],
    /// Contact evaluation per pair.
    pub contact: &'a [Vec<NodeContact<D>>],
    /// Recovered stress/strain (required when a stress/strain field is requested).
    pub nodal: Option<&'a NodalFields>,
    /// Nodal temperatures (thermal scenes only; written whenever present).
    pub temperature: Option<&'a [f64]>,
    /// Nodal sheet thickness (`output { thickness = (a, b) }`; written
    /// whenever present, [`super::thickness`]).
    pub thickness: Option<&'a [f64]>,
    /// Velocity per dof `node D + c` (written when requested and present).
    pub velocity: Option<&'a [f64]>,
    /// Acceleration per dof (written when requested and present).
    pub acceleration: Option<&'a [f64]>,
    /// How the arrays are stored.
    pub encoding: Encoding,
    /// A piece of a parallel file (`None`: the whole mesh): these global
    /// cells (increasing) and the nodes they use, with the point data
    /// `node` and the cell data `cell` giving their global numbers
    /// ([`pvtu`] lists the pieces).
    pub piece: Option<&'a [usize]>,
}

/// The nodes and cells of a piece, and the local number of each node.
struct Selection {
    /// Global nodes of the piece, increasing.
    nodes: Vec<usize>,
    /// Global cells of the piece, increasing.
    cells: Vec<usize>,
    /// Local number of each global node (`usize::MAX`: not in the piece).
    local: Vec<usize>,
}

impl Selection {
    fn of<const D: usize>(m: &Model<D>, cells: Option<&[usize]>) -> Option<Selection> {
        let cells = cells?;
        let nn = m.mesh.nodes.len();
        let mut used = vec![false; nn];
        let cells: Vec<usize> = cells
            .iter()
            .copied()
            .filter(|&c| c < m.mesh.cells.len())
            .collect();
        for &c in &cells {
            for &n in m.mesh.cells.nodes(c) {
                used[n] = true;
            }
        }
        let nodes: Vec<usize> = (0..nn).filter(|&n| used[n]).collect();
        let mut local = vec![usize::MAX; nn];
        for (i, &n) in nodes.iter().enumerate() {
            local[n] = i;
        }
        Some(Selection {
            nodes,
            cells,
            local,
        })
    }
}

/// The point values (`comps` per node, all nodes) of the piece's nodes.
fn pick<T: Copy>(
    sel: Option<&Selection>,
    comps: usize,
    values: impl IntoIterator<Item = T>,
) -> Vec<T> {
    restrict(sel.map(|s| &s.nodes[..]), comps, values)
}

/// The cell values (`comps` per cell, all cells) of the piece's cells.
fn pick_cells<T: Copy>(
    sel: Option<&Selection>,
    comps: usize,
    values: impl IntoIterator<Item = T>,
) -> Vec<T> {
    restrict(sel.map(|s| &s.cells[..]), comps, values)
}

/// The values (`comps` per entity, all entities) of the listed entities
/// (all of them without a list).
fn restrict<T: Copy>(
    entities: Option<&[usize]>,
    comps: usize,
    values: impl IntoIterator<Item = T>,
) -> Vec<T> {
    let all: Vec<T> = values.into_iter().collect();
    match entities {
        None => all,
        Some(list) => {
            let k = comps.max(1);
            list.iter()
                .flat_map(|&e| all[k * e..k * (e + 1)].iter().copied())
                .collect()
        }
    }
}

const TENSOR_NAMES: &str =
    " ComponentName0=\"xx\" ComponentName1=\"yy\" ComponentName2=\"zz\" ComponentName3=\"xy\"";

/// Component names of the 6-component (solid) tensors, in the engine's
/// Voigt order.
const TENSOR_NAMES_3D: &str = " ComponentName0=\"xx\" ComponentName1=\"yy\" \
     ComponentName2=\"zz\" ComponentName3=\"xy\" ComponentName4=\"xz\" ComponentName5=\"yz\"";

/// `[v_x, v_y, v_z]` of a nodal vector (z = 0 in 2D).
fn xyz<const D: usize>(v: &[f64; D]) -> [f64; 3] {
    std::array::from_fn(|k| if k < D { v[k] } else { 0.0 })
}

/// The VTK cell type of `kind` (quadratic cells: the engine's node order
/// is VTK's).
fn vtk_type(kind: CellKind) -> u8 {
    match kind {
        CellKind::Tri3 => 5,
        CellKind::Quad4 => 9,
        CellKind::Tet4 => 10,
        CellKind::Hex8 => 12,
        CellKind::Tri6 => 22,
        CellKind::Quad8 | CellKind::Quad8R => 23,
        CellKind::Quad9 => 28,
        CellKind::Tet10 => 24,
        CellKind::Hex20 | CellKind::Hex20R => 25,
        CellKind::Hex27 => 29,
    }
}

/// Indentation of a data array.
const IN: &str = "        ";

/// The VTU file's bytes.
pub fn vtu<const D: usize>(d: &VtuData<'_, D>) -> Vec<u8> {
    let m = d.model;
    // planar: xx yy zz xy; solid: all six
    let (tensor_comps, tensor_names) = if D == 3 {
        (6, TENSOR_NAMES_3D)
    } else {
        (4, TENSOR_NAMES)
    };
    let nn = m.mesh.nodes.len();
    let sel = Selection::of(m, d.piece);
    let sel = sel.as_ref();
    let mut s = String::with_capacity(4096);
    let mut a = Arrays::new(d.encoding);
    s.push_str("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(
        s,
        "<!-- ctc results: step `{}`, increment {}, time {}. Stress/strain components {} \
         (engineering shear strain). -->",
        d.step.replace("--", "- -"),
        d.increment,
        fmt_f64(d.time),
        if D == 3 {
            "xx, yy, zz, xy, xz, yz"
        } else {
            "xx, yy, zz, xy"
        }
    );
    if m.analysis.kind == AnalysisKind::Axisymmetric {
        let _ = writeln!(s, "<!-- {} -->", crate::solve::AXISYMMETRIC_NOTE);
    }
    if let Some(u) = &m.output.units {
        let _ = writeln!(
            s,
            "<!-- units {}: length {}, force {}, stress {}, time {}, temperature {}, energy {} -->",
            u.system, u.length, u.force, u.stress, u.time, u.temperature, u.energy
        );
    }
    let _ = writeln!(
        s,
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\"{}>\n  <UnstructuredGrid>",
        a.compressor_attribute()
    );
    s.push_str("    <FieldData>\n");
    a.array(
        &mut s,
        "      ",
        "TIME",
        0,
        " NumberOfTuples=\"1\"",
        [d.time],
    );
    a.array(
        &mut s,
        "      ",
        "CYCLE",
        0,
        " NumberOfTuples=\"1\"",
        [d.increment as i64],
    );
    s.push_str("    </FieldData>\n");
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
        sel.map_or(nn, |p| p.nodes.len()),
        sel.map_or(m.mesh.cells.len(), |p| p.cells.len())
    );
    let has = |f: Field| d.fields.contains(&f);
    if has(Field::Displacement) {
        s.push_str("      <PointData Vectors=\"displacement\">\n");
    } else {
        s.push_str("      <PointData>\n");
    }
    if has(Field::Displacement) {
        a.array(
            &mut s,
            IN,
            "displacement",
            3,
            "",
            pick(sel, 3, d.displacement.iter().flat_map(xyz)),
        );
    }
    if let Some(t) = d.temperature {
        a.array(
            &mut s,
            IN,
            "temperature",
            1,
            "",
            pick(sel, 1, t.iter().copied()),
        );
    }
    if let Some(t) = d.thickness.filter(|t| t.len() == nn) {
        a.array(
            &mut s,
            IN,
            "thickness",
            1,
            "",
            pick(sel, 1, t.iter().copied()),
        );
    }
    for (field, name, values) in [
        (Field::Velocity, "velocity", d.velocity),
        (Field::Acceleration, "acceleration", d.acceleration),
    ] {
        if let Some(v) = values.filter(|v| has(field) && v.len() == nn * D) {
            a.array(
                &mut s,
                IN,
                name,
                3,
                "",
                pick(
                    sel,
                    3,
                    v.chunks_exact(D).flat_map(|c| {
                        std::array::from_fn::<f64, 3, _>(|k| c.get(k).copied().unwrap_or(0.0))
                    }),
                ),
            );
        }
    }
    if let Some(nodal) = d.nodal {
        if has(Field::Stress) {
            a.array(
                &mut s,
                IN,
                "stress",
                tensor_comps,
                tensor_names,
                pick(
                    sel,
                    tensor_comps,
                    nodal
                        .stress
                        .iter()
                        .flat_map(|v| v[..tensor_comps].iter().copied()),
                ),
            );
        }
        if has(Field::Strain) {
            a.array(
                &mut s,
                IN,
                "strain",
                tensor_comps,
                tensor_names,
                pick(
                    sel,
                    tensor_comps,
                    nodal
                        .strain
                        .iter()
                        .flat_map(|v| v[..tensor_comps].iter().copied()),
                ),
            );
        }
        if has(Field::VonMises) {
            a.array(
                &mut s,
                IN,
                "von_mises",
                1,
                "",
                pick(sel, 1, nodal.von_mises.iter().copied()),
            );
        }
        // written whenever a body is plastic and stresses are requested
        if !nodal.equivalent_plastic_strain.is_empty()
            && (has(Field::Stress) || has(Field::VonMises) || has(Field::Strain))
        {
            a.array(
                &mut s,
                IN,
                "equivalent_plastic_strain",
                1,
                "",
                pick(sel, 1, nodal.equivalent_plastic_strain.iter().copied()),
            );
        }
    }
    if has(Field::Reaction) {
        a.array(
            &mut s,
            IN,
            "reaction",
            3,
            "",
            pick(sel, 3, d.reaction.iter().flat_map(xyz)),
        );
    }
    if has(Field::Contact) {
        let mut gap = vec![0.0f64; nn];
        let mut pressure = vec![0.0f64; nn];
        let mut status = vec![-1i32; nn];
        let mut best = vec![f64::INFINITY; nn];
        for pair in &m.contacts {
            for &n in &pair.nodes {
                status[n] = status[n].max(0);
            }
        }
        for list in d.contact {
            for c in list {
                if c.gap < best[c.node] {
                    best[c.node] = c.gap;
                    gap[c.node] = c.gap;
                    pressure[c.node] = c.pressure;
                    status[c.node] = match c.status {
                        ContactStatus::Open => 0,
                        ContactStatus::Closed => 1,
                    };
                }
            }
        }
        a.array(&mut s, IN, "contact_gap", 1, "", pick(sel, 1, gap));
        a.array(
            &mut s,
            IN,
            "contact_pressure",
            1,
            "",
            pick(sel, 1, pressure),
        );
        a.array(&mut s, IN, "contact_status", 1, "", pick(sel, 1, status));
        if m.contacts.iter().any(|c| c.friction.is_some()) {
            let f = crate::contact::friction::nodal_fields(nn, d.contact);
            a.array(&mut s, IN, "friction_force", 1, "", pick(sel, 1, f.force));
            if D == 3 {
                a.array(
                    &mut s,
                    IN,
                    "friction_traction",
                    3,
                    "",
                    pick(sel, 3, f.traction.iter().flatten().copied()),
                );
            }
            a.array(&mut s, IN, "friction_slip", 1, "", pick(sel, 1, f.slip));
            a.array(&mut s, IN, "friction_status", 1, "", pick(sel, 1, f.status));
            a.array(
                &mut s,
                IN,
                "friction_dissipation",
                1,
                "",
                pick(sel, 1, f.dissipation),
            );
        }
    }
    if let Some(sel) = sel {
        // the global node numbers: the pieces' union is the whole mesh
        a.array(
            &mut s,
            IN,
            "node",
            1,
            "",
            sel.nodes.iter().map(|&n| n as i64),
        );
    }
    s.push_str("      </PointData>\n      <CellData>\n");
    let mut body = vec![-1i32; m.mesh.cells.len()];
    for (b, bd) in m.bodies.iter().enumerate() {
        for c in bd.cells.clone() {
            if let Some(x) = body.get_mut(c) {
                *x = b as i32;
            }
        }
    }
    a.array(&mut s, IN, "body", 1, "", pick_cells(sel, 1, body));
    if let Some(sel) = sel {
        a.array(
            &mut s,
            IN,
            "cell",
            1,
            "",
            sel.cells.iter().map(|&c| c as i64),
        );
    }
    if let Some(cells) = d.nodal.map(|n| &n.cells) {
        if has(Field::Stress) {
            a.array(
                &mut s,
                IN,
                "stress",
                tensor_comps,
                tensor_names,
                pick_cells(
                    sel,
                    tensor_comps,
                    cells
                        .stress
                        .iter()
                        .flat_map(|v| v[..tensor_comps].iter().copied()),
                ),
            );
        }
        if has(Field::Strain) {
            a.array(
                &mut s,
                IN,
                "strain",
                tensor_comps,
                tensor_names,
                pick_cells(
                    sel,
                    tensor_comps,
                    cells
                        .strain
                        .iter()
                        .flat_map(|v| v[..tensor_comps].iter().copied()),
                ),
            );
        }
        if has(Field::VonMises) {
            a.array(
                &mut s,
                IN,
                "von_mises",
                1,
                "",
                pick_cells(sel, 1, cells.von_mises.iter().copied()),
            );
        }
        if !cells.equivalent_plastic_strain.is_empty()
            && (has(Field::Stress) || has(Field::VonMises) || has(Field::Strain))
        {
            a.array(
                &mut s,
                IN,
                "equivalent_plastic_strain",
                1,
                "",
                pick_cells(sel, 1, cells.equivalent_plastic_strain.iter().copied()),
            );
        }
    }
    s.push_str("      </CellData>\n      <Points>\n");
    a.array(
        &mut s,
        IN,
        "coordinates",
        3,
        "",
        pick(sel, 3, m.mesh.nodes.iter().flat_map(xyz)),
    );
    s.push_str("      </Points>\n      <Cells>\n");
    let cells: Vec<usize> = match sel {
        Some(sel) => sel.cells.clone(),
        None => (0..m.mesh.cells.len()).collect(),
    };
    let local = |n: usize| sel.map_or(n, |p| p.local[n]) as i64;
    a.array(
        &mut s,
        IN,
        "connectivity",
        1,
        "",
        cells
            .iter()
            .flat_map(|&c| m.mesh.cells.nodes(c).iter().map(|&n| local(n))),
    );
    a.array(
        &mut s,
        IN,
        "offsets",
        1,
        "",
        cells.iter().scan(0i64, |o, &c| {
            *o += m.mesh.cells.kind(c).node_count() as i64;
            Some(*o)
        }),
    );
    a.array(
        &mut s,
        IN,
        "types",
        1,
        "",
        cells.iter().map(|&c| vtk_type(m.mesh.cells.kind(c))),
    );
    s.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n");
    a.finish(s)
}

/// The parallel file (`.pvtu`) of the pieces `sources` (file names
/// relative to it): the arrays it declares are those of `piece`, the
/// bytes of one of the pieces written by [`vtu`] (every piece of an
/// increment has the same arrays), read from its XML header.
pub fn pvtu(piece: &[u8], sources: &[String]) -> String {
    let end = piece
        .windows(b"<AppendedData".len())
        .position(|w| w == b"<AppendedData")
        .unwrap_or(piece.len());
    let head = String::from_utf8_lossy(&piece[..end]);
    let mut out = String::from("<?xml version=\"1.0\"?>\n");
    for line in head.lines().filter(|l| l.starts_with("<!--")) {
        out.push_str(line);
        out.push('\n');
    }
    out.push_str(
        "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n",
    );
    let mut inside = false;
    for line in head.lines().map(str::trim) {
        for (open, close, tag) in [
            ("<PointData", "</PointData>", "PPointData"),
            ("<CellData", "</CellData>", "PCellData"),
            ("<Points", "</Points>", "PPoints"),
        ] {
            if let Some(rest) = line.strip_prefix(open) {
                let _ = writeln!(out, "    <{tag}{rest}");
                inside = true;
            } else if line == close {
                let _ = writeln!(out, "    </{tag}>");
                inside = false;
            }
        }
        if let Some(rest) = line.strip_prefix("<DataArray").filter(|_| inside) {
            let attributes = rest.split(" format=").next().unwrap_or(rest);
            let _ = writeln!(out, "      <PDataArray{attributes}/>");
        }
    }
    for source in sources {
        let _ = writeln!(out, "    <Piece Source=\"{source}\"/>");
    }
    out.push_str("  </PUnstructuredGrid>\n</VTKFile>\n");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::contact_csv::tests::{contact, model_with_pair};
    use crate::output::vtu_read::{Section, Vtu};

    fn values_of<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
        let start = text.find(&format!("Name=\"{name}\"")).unwrap();
        let body = &text[start..];
        let open = body.find('>').unwrap() + 1;
        let close = body.find("</DataArray>").unwrap();
        body[open..close].split_whitespace().collect()
    }

    fn piece_file(encoding: Encoding, piece: Option<&[usize]>) -> Vec<u8> {
        let m = model_with_pair();
        let u = vec![[0.0, 0.1], [0.5, -0.25], [1e-300, 0.0], [0.0, 3.0]];
        let r = vec![[0.0; 2]; 4];
        let contacts = vec![vec![contact(2, -0.1, true), contact(0, 0.2, false)]];
        vtu(&VtuData {
            model: &m,
            step: "a--b",
            increment: 3,
            time: 0.5,
            fields: &[Field::Contact, Field::Displacement],
            displacement: &u,
            reaction: &r,
            contact: &contacts,
            nodal: None,
            temperature: None,
            thickness: None,
            velocity: None,
            acceleration: None,
            encoding,
            piece,
        })
    }

    fn file(encoding: Encoding) -> Vec<u8> {
        piece_file(encoding, None)
    }

    #[test]
    fn pieces_join_into_the_whole_file_and_the_pvtu_lists_them() {
        let whole = Vtu::read(&file(Encoding::Binary)).unwrap();
        let a = piece_file(Encoding::Binary, Some(&[1]));
        let b = piece_file(Encoding::Ascii, Some(&[0]));
        let (pa, pb) = (Vtu::read(&a).unwrap(), Vtu::read(&b).unwrap());
        // cell 1 is (2, 0, 3): three points, renumbered
        assert_eq!((pa.points, pa.cells), (3, 1));
        assert_eq!(pa.point("node").unwrap().values, [0.0, 2.0, 3.0]);
        assert_eq!(pa.cell("cell").unwrap().values, [1.0]);
        assert_eq!(
            pa.array(Section::Cells, "connectivity").unwrap().values,
            [1.0, 0.0, 2.0]
        );
        let joined = super::super::vtu_read::join_pieces(&[pa.clone(), pb]).unwrap();
        assert_eq!((joined.points, joined.cells), (whole.points, whole.cells));
        assert_eq!(joined.arrays.len(), whole.arrays.len());
        for (j, w) in joined.arrays.iter().zip(&whole.arrays) {
            assert_eq!((&j.name, j.section), (&w.name, w.section));
            assert_eq!(j.values, w.values, "{}", j.name);
        }
        // a piece alone misses a node: an error, not a panic
        assert!(super::super::vtu_read::join_pieces(&[pa]).is_err());
        let p = pvtu(&a, &["x_p0.vtu".into(), "x_p1.vtu".into()]);
        assert!(p.contains("<PUnstructuredGrid GhostLevel=\"0\">"));
        assert!(p.contains("<PPointData Vectors=\"displacement\">"));
        assert!(p.contains(
            "<PDataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\"/>"
        ));
        assert!(p.contains("<PDataArray type=\"Int64\" Name=\"cell\" NumberOfComponents=\"1\"/>"));
        assert!(p.contains("<PPoints>") && p.contains("</PPoints>"));
        assert!(!p.contains("connectivity"), "cells are not declared");
        assert!(p.contains("<Piece Source=\"x_p1.vtu\"/>"));
        // the ascii piece declares the same arrays
        assert_eq!(p, pvtu(&b, &["x_p0.vtu".into(), "x_p1.vtu".into()]));
    }

    #[test]
    fn vtu_contact_status_gap_pressure_and_cells() {
        let bytes = file(Encoding::Ascii);
        let text = std::str::from_utf8(&bytes).unwrap();
        // node 3 is not a slave, node 1 is a slave out of reach, 0 open, 2 closed
        assert_eq!(values_of(text, "contact_status"), ["0", "0", "1", "-1"]);
        assert_eq!(values_of(text, "contact_gap"), ["0.2", "0", "-0.1", "0"]);
        assert_eq!(values_of(text, "contact_pressure"), ["0", "0", "0.5", "0"]);
        assert_eq!(
            values_of(text, "connectivity"),
            ["1", "2", "3", "2", "0", "3"]
        );
        assert_eq!(values_of(text, "offsets"), ["3", "6"]);
        assert_eq!(values_of(text, "types"), ["5", "5"]);
        // shortest round-trip numbers, exponents for tiny ones
        assert_eq!(
            values_of(text, "displacement"),
            ["0", "0.1", "0", "0.5", "-0.25", "0", "1e-300", "0", "0", "0", "3", "0"]
        );
        // comments may not contain "--"
        let comment = &text[text.find("<!--").unwrap() + 4..text.find("-->").unwrap()];
        assert!(!comment.contains("--"), "{comment}");
    }

    #[test]
    fn binary_and_ascii_files_read_back_the_same() {
        let binary = Vtu::read(&file(Encoding::Binary)).unwrap();
        let ascii = Vtu::read(&file(Encoding::Ascii)).unwrap();
        assert_eq!((binary.points, binary.cells), (4, 2));
        assert_eq!(binary.arrays.len(), ascii.arrays.len());
        for (b, t) in binary.arrays.iter().zip(&ascii.arrays) {
            assert_eq!(
                (b.format.as_str(), t.format.as_str()),
                ("appended", "ascii")
            );
            assert_eq!(
                (&b.name, &b.ty, b.components),
                (&t.name, &t.ty, t.components)
            );
            assert_eq!(b.values, t.values, "{}", b.name);
        }
        assert_eq!(binary.field("TIME").unwrap().values, [0.5]);
        assert_eq!(binary.field("CYCLE").unwrap().values, [3.0]);
        assert_eq!(binary.cell("body").unwrap().values.len(), 2);
        assert_eq!(
            binary.point("displacement").unwrap().values[6..9],
            [1e-300, 0.0, 0.0]
        );
        assert_eq!(
            binary.names(Section::Cells),
            ["connectivity", "offsets", "types"]
        );
        // the XML part names the compressor; the binary data follows it
        let bytes = file(Encoding::Binary);
        let head = &bytes[..bytes
            .windows(13)
            .position(|w| w == b"<AppendedData")
            .unwrap()];
        let head = std::str::from_utf8(head).unwrap();
        assert!(head.contains("compressor=\"vtkZLibDataCompressor\""));
        assert!(bytes.ends_with(b"</AppendedData>\n</VTKFile>\n"));
    }
}
