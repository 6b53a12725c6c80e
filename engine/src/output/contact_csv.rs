//! `contact_<pair>_<increment>.csv`: the slave nodes of a contact pair along
//! the surface (sorted by current x, then y): node, current x, y, gap,
//! pressure, status (0 open or out of reach, 1 closed), force of the tool on
//! the node (x, y; axisymmetric: totals over 2*pi). The gap is empty where
//! the node is out of the search reach (`prof`).
//!
//! Deformable masters (node-to-segment) add the columns `master_1`,
//! `master_2` (the segment's end nodes) and `xi` (projection parameter, 0
//! at `master_1`), and list the master surface's nodes too when they act as
//! slaves (double-pass strategies). Pairs with friction have four more
//! columns (after those): tangential force (along `t = (n_y, -n_x)`), slip
//! increment, friction status (0 frictionless, 1 stick, 2 slip) and the
//! frictional work of the increment.

use super::encode::Shortest as N;
use crate::contact::{ContactStatus, NodeContact};
use crate::model::Model;
use std::fmt::Write;

/// The CSV text of pair `pair`.
pub fn contact_csv(
    model: &Model,
    pair: usize,
    displacement: &[[f64; 2]],
    contact: &[NodeContact],
) -> String {
    let surface = matches!(
        model.contacts[pair].master,
        crate::model::ContactMaster::Surface { .. }
    );
    let slaves;
    let nodes = if surface {
        slaves = crate::contact::node_to_segment::slave_nodes(model, pair);
        &slaves
    } else {
        &model.contacts[pair].nodes
    };
    let mut rows: Vec<(usize, [f64; 2], Option<&NodeContact>)> = nodes
        .iter()
        .map(|&n| {
            let x0 = model.mesh.nodes[n];
            let u = displacement[n];
            (
                n,
                [x0[0] + u[0], x0[1] + u[1]],
                contact.iter().find(|c| c.node == n),
            )
        })
        .collect();
    rows.sort_by(|a, b| a.1[0].total_cmp(&b.1[0]).then(a.1[1].total_cmp(&b.1[1])));
    let friction = model.contacts[pair].friction.is_some();
    let mut s = String::from("node,x,y,gap,pressure,status,force_x,force_y");
    if surface {
        s.push_str(",master_1,master_2,xi");
    }
    s.push_str(if friction {
        ",tangential_force,slip,friction_status,dissipation\n"
    } else {
        "\n"
    });
    for (n, x, c) in rows {
        match c {
            Some(c) => {
                let st = match c.status {
                    ContactStatus::Open => 0,
                    ContactStatus::Closed => 1,
                };
                let _ = write!(
                    s,
                    "{n},{},{},{},{},{st},{},{}",
                    N(x[0]),
                    N(x[1]),
                    N(c.gap),
                    N(c.pressure),
                    N(c.force[0]),
                    N(c.force[1])
                );
                match (&c.master, surface) {
                    (Some(m), _) => {
                        let _ = write!(s, ",{},{},{}", m.nodes[0], m.nodes[1], N(m.xi));
                    }
                    (None, true) => s.push_str(",,,"),
                    (None, false) => {}
                }
                if friction {
                    let f = &c.friction;
                    let _ = write!(
                        s,
                        ",{},{},{},{}",
                        N(f.tangential_force),
                        N(f.slip),
                        crate::contact::friction::status_code(f.status),
                        N(f.dissipation)
                    );
                }
                s.push('\n');
            }
            None => {
                let _ = write!(s, "{n},{},{},,0,0,0,0", N(x[0]), N(x[1]));
                if surface {
                    s.push_str(",,,");
                }
                s.push_str(if friction { ",0,0,0,0\n" } else { "\n" });
            }
        }
    }
    s
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::mesh::{Cell, Mesh};
    use crate::model::*;

    pub(crate) fn model_with_pair() -> Model {
        crate::testkit::ModelBuilder::plane_strain()
            .elastic("m", 1.0, 0.3)
            .body(
                "b",
                Mesh::new(
                    vec![[2.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.0, 1.0]],
                    vec![Cell::tri(1, 2, 3), Cell::tri(2, 0, 3)],
                ),
                "m",
            )
            .tool(
                "t",
                ToolGeometry::Plane {
                    point: [0.0, 0.0],
                    normal: [0.0, 1.0],
                },
                ToolMotion::fixed(),
            )
            .contact_tool(
                "p",
                "b",
                vec![[1, 2], [2, 0]],
                "t",
                ContactMethod::Penalty {
                    kind: PenaltyKind::Nodal,
                    stiffness: 1.0,
                },
            )
            .build()
    }

    pub(crate) fn contact(node: usize, gap: f64, closed: bool) -> NodeContact {
        NodeContact {
            node,
            gap,
            normal: [0.0, 1.0],
            force: [0.0, if closed { -gap * 10.0 } else { 0.0 }],
            stiffness: [[0.0; 2]; 2],
            pressure: if closed { -gap * 5.0 } else { 0.0 },
            status: if closed {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    #[test]
    fn contact_csv_sorted_along_surface_with_far_nodes_blank() {
        let m = model_with_pair();
        // node 2 moves right past node 0: current x order is 1, 0, 2
        let u = vec![[0.0, 0.0], [0.0, 0.0], [1.5, -0.1], [0.0, 0.0]];
        let list = vec![contact(2, -0.1, true), contact(0, 0.2, false)];
        let csv = contact_csv(&m, 0, &u, &list);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "node,x,y,gap,pressure,status,force_x,force_y");
        assert_eq!(lines[1], "1,0,0,,0,0,0,0");
        assert_eq!(lines[2], "0,2,0,0.2,0,0,0,0");
        assert_eq!(lines[3], "2,2.5,-0.1,-0.1,0.5,1,0,1");
        assert_eq!(lines.len(), 4);
        // tiny numbers in exponent form, not hundreds of digits
        let list = vec![contact(2, -3.5940786e-300, true)];
        let csv = contact_csv(&m, 0, &u, &list);
        assert!(csv.contains(",-3.5940786e-300,"), "{csv}");
    }
}
