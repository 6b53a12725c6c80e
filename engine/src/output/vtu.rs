//! VTK XML unstructured grid (`.vtu`, ASCII) of one increment.
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
//! `friction_force` (tangential force), `friction_slip` (slip increment),
//! `friction_status` (0 frictionless, 1 stick, 2 slip) and
//! `friction_dissipation` (work of the increment). Cell data: `body` index.

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
    pub contact: &'a [Vec<NodeContact>],
    /// Recovered stress/strain (required when a stress/strain field is requested).
    pub nodal: Option<&'a NodalFields>,
    /// Nodal temperatures (thermal scenes only; written whenever present).
    pub temperature: Option<&'a [f64]>,
}

fn array<T: std::fmt::Display>(
    s: &mut String,
    ty: &str,
    name: &str,
    comps: usize,
    extra: &str,
    values: impl Iterator<Item = T>,
) {
    let _ = writeln!(
        s,
        "        <DataArray type=\"{ty}\" Name=\"{name}\" NumberOfComponents=\"{comps}\"{extra} format=\"ascii\">"
    );
    let per_line = 3 * comps.max(1);
    for (i, v) in values.enumerate() {
        if i % per_line == 0 {
            s.push_str(if i == 0 { "          " } else { "\n          " });
        } else {
            s.push(' ');
        }
        let _ = write!(s, "{v}");
    }
    s.push_str("\n        </DataArray>\n");
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

/// The VTU text.
pub fn vtu<const D: usize>(d: &VtuData<'_, D>) -> String {
    let m = d.model;
    // planar: xx yy zz xy; solid: all six
    let (tensor_comps, tensor_names) = if D == 3 {
        (6, TENSOR_NAMES_3D)
    } else {
        (4, TENSOR_NAMES)
    };
    let nn = m.mesh.nodes.len();
    let mut s = String::with_capacity(256 * nn + 1024);
    s.push_str("<?xml version=\"1.0\"?>\n");
    let _ = writeln!(
        s,
        "<!-- ctc results: step `{}`, increment {}, time {}. Stress/strain components {} \
         (engineering shear strain). -->",
        d.step.replace("--", "- -"),
        d.increment,
        d.time,
        if D == 3 {
            "xx, yy, zz, xy, xz, yz"
        } else {
            "xx, yy, zz, xy"
        }
    );
    if m.analysis.kind == AnalysisKind::Axisymmetric {
        let _ = writeln!(s, "<!-- {} -->", crate::solve::AXISYMMETRIC_NOTE);
    }
    s.push_str(
        "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" \
         header_type=\"UInt64\">\n  <UnstructuredGrid>\n",
    );
    let _ = writeln!(
        s,
        "    <FieldData>\n      <DataArray type=\"Float64\" Name=\"TIME\" NumberOfTuples=\"1\" \
         format=\"ascii\">{}</DataArray>\n    </FieldData>",
        d.time
    );
    let _ = writeln!(
        s,
        "    <Piece NumberOfPoints=\"{nn}\" NumberOfCells=\"{}\">",
        m.mesh.cells.len()
    );
    let has = |f: Field| d.fields.contains(&f);
    if has(Field::Displacement) {
        s.push_str("      <PointData Vectors=\"displacement\">\n");
    } else {
        s.push_str("      <PointData>\n");
    }
    if has(Field::Displacement) {
        array(
            &mut s,
            "Float64",
            "displacement",
            3,
            "",
            d.displacement.iter().flat_map(xyz),
        );
    }
    if let Some(t) = d.temperature {
        array(&mut s, "Float64", "temperature", 1, "", t.iter());
    }
    if let Some(nodal) = d.nodal {
        if has(Field::Stress) {
            array(
                &mut s,
                "Float64",
                "stress",
                tensor_comps,
                tensor_names,
                nodal.stress.iter().flat_map(|v| v[..tensor_comps].iter()),
            );
        }
        if has(Field::Strain) {
            array(
                &mut s,
                "Float64",
                "strain",
                tensor_comps,
                tensor_names,
                nodal.strain.iter().flat_map(|v| v[..tensor_comps].iter()),
            );
        }
        if has(Field::VonMises) {
            array(
                &mut s,
                "Float64",
                "von_mises",
                1,
                "",
                nodal.von_mises.iter(),
            );
        }
        // written whenever a body is plastic and stresses are requested
        if !nodal.equivalent_plastic_strain.is_empty()
            && (has(Field::Stress) || has(Field::VonMises) || has(Field::Strain))
        {
            array(
                &mut s,
                "Float64",
                "equivalent_plastic_strain",
                1,
                "",
                nodal.equivalent_plastic_strain.iter(),
            );
        }
    }
    if has(Field::Reaction) {
        array(
            &mut s,
            "Float64",
            "reaction",
            3,
            "",
            d.reaction.iter().flat_map(xyz),
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
        array(&mut s, "Float64", "contact_gap", 1, "", gap.iter());
        array(
            &mut s,
            "Float64",
            "contact_pressure",
            1,
            "",
            pressure.iter(),
        );
        array(&mut s, "Int32", "contact_status", 1, "", status.iter());
        if m.contacts.iter().any(|c| c.friction.is_some()) {
            let f = crate::contact::friction::nodal_fields(nn, d.contact);
            array(&mut s, "Float64", "friction_force", 1, "", f.force.iter());
            array(&mut s, "Float64", "friction_slip", 1, "", f.slip.iter());
            array(&mut s, "Int32", "friction_status", 1, "", f.status.iter());
            array(
                &mut s,
                "Float64",
                "friction_dissipation",
                1,
                "",
                f.dissipation.iter(),
            );
        }
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
    array(&mut s, "Int32", "body", 1, "", body.iter());
    s.push_str("      </CellData>\n      <Points>\n");
    array(
        &mut s,
        "Float64",
        "coordinates",
        3,
        "",
        m.mesh.nodes.iter().flat_map(xyz),
    );
    s.push_str("      </Points>\n      <Cells>\n");
    array(
        &mut s,
        "Int64",
        "connectivity",
        1,
        "",
        m.mesh.cells.iter().flat_map(|c| c.nodes.iter().copied()),
    );
    array(
        &mut s,
        "Int64",
        "offsets",
        1,
        "",
        m.mesh.cells.iter().scan(0usize, |o, c| {
            *o += c.kind.node_count();
            Some(*o)
        }),
    );
    array(
        &mut s,
        "UInt8",
        "types",
        1,
        "",
        m.mesh.cells.iter().map(|c| match c.kind {
            CellKind::Tri3 => 5u8,
            CellKind::Quad4 => 9u8,
            CellKind::Tet4 => 10u8,
            CellKind::Hex8 => 12u8,
        }),
    );
    s.push_str("      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::contact_csv::tests::{contact, model_with_pair};

    fn values_of<'a>(text: &'a str, name: &str) -> Vec<&'a str> {
        let start = text.find(&format!("Name=\"{name}\"")).unwrap();
        let body = &text[start..];
        let open = body.find('>').unwrap() + 1;
        let close = body.find("</DataArray>").unwrap();
        body[open..close].split_whitespace().collect()
    }

    #[test]
    fn vtu_contact_status_gap_pressure_and_cells() {
        let m = model_with_pair();
        let u = vec![[0.0; 2]; 4];
        let r = vec![[0.0; 2]; 4];
        let contacts = vec![vec![contact(2, -0.1, true), contact(0, 0.2, false)]];
        let text = vtu(&VtuData {
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
        });
        // node 3 is not a slave, node 1 is a slave out of reach, 0 open, 2 closed
        assert_eq!(values_of(&text, "contact_status"), ["0", "0", "1", "-1"]);
        assert_eq!(values_of(&text, "contact_gap"), ["0.2", "0", "-0.1", "0"]);
        assert_eq!(values_of(&text, "contact_pressure"), ["0", "0", "0.5", "0"]);
        assert_eq!(
            values_of(&text, "connectivity"),
            ["1", "2", "3", "2", "0", "3"]
        );
        assert_eq!(values_of(&text, "offsets"), ["3", "6"]);
        assert_eq!(values_of(&text, "types"), ["5", "5"]);
        assert_eq!(values_of(&text, "displacement").len(), 12);
        // comments may not contain "--"
        let comment = &text[text.find("<!--").unwrap() + 4..text.find("-->").unwrap()];
        assert!(!comment.contains("--"), "{comment}");
    }
}
