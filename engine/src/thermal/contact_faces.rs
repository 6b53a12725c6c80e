//! Thermal contact of quadratic slave faces against a rigid tool (issue
//! 23): the 3-node edges of tri6 / quad8 / quad9 bodies (plane and
//! axisymmetric) and the tri6 / quad8 / quad9 faces of tet10 / hex20 /
//! hex27 bodies.
//!
//! The nodal exchange of the linear faces ([`super::contact`]), `h_a A_a
//! (T_tool - T_a)` with `A_a = int N_a dA`, has no meaning here: `A_a` is
//! 0 at the corners of a tri6 face and -1/12 of the face at those of a
//! quad8 one, so a corner would exchange no heat, or heat against the
//! temperature difference. The flux `q = h(p) (T_tool - T)` is integrated
//! over the slave faces instead, at the points of the mechanical contact's
//! rule ([`FacetRule`], reference configuration: the faces' mass rules,
//! exact for `N_a N_b` on flat faces):
//!
//! `Q_a = sum_g w_g N_a(xi_g) h_g (T_tool - sum_b N_b(xi_g) T_b)`,
//!
//! one [`ConductanceElement`] per point (`h A = h_g w_g`, weights the shape
//! values), so the heat solver assembles the conductance matrix `H_ab =
//! sum_g w_g h_g N_a N_b` (positive semi-definite whatever the signs of
//! `int N_a dA`; `h` times the face's mass matrix for a uniform `h`) and
//! the load `sum_g w_g h_g T_tool N_a`. `H = -dQ/dT` is the exact tangent
//! of the heat in the temperatures (the exchange is linear in `T`).
//!
//! `h_g` at a point comes from the converged contact state of the slave
//! nodes (`NodeContact`, what the mechanics reports; the coupling is
//! staggered, so `p` and `g` are data of the heat solve): the pressure
//! `p_g = sum_a N_a p_a` of the reported nodal pressures (for the
//! face-integrated contact the L2 projection of the points' pressures, so
//! a uniform pressure is met exactly; a node not reported counts 0): closed
//! where `p_g > 0`, `h_g = h(p_g)`; else the gas conductance `k_gap /
//! max(g_g, g_min)` with `g_g = sum_a N_a g_a` when every node of the face
//! reports its gap (within `prof`), 0 otherwise.

use super::contact::ConductanceElement;
use crate::contact::face_integrated::{body_is_quadratic, FacetRule};
use crate::contact::NodeContact;
use crate::model::thermal::ContactThermal;
use crate::model::{AnalysisKind, Model};
use std::collections::BTreeMap;

/// The slave facets and integration points of pair `pair` when its heat
/// exchange is integrated over the faces: a pair against a rigid tool whose
/// slave body has quadratic cells (the rule of
/// `contact::face_integrated`, reference configuration); `None` otherwise
/// (the nodal exchange of [`super::contact`]).
pub fn pair_rule<const D: usize>(model: &Model<D>, pair: usize) -> Option<FacetRule> {
    let cp = model.contacts.get(pair)?;
    cp.master.tool()?;
    if !body_is_quadratic(model, cp.body) {
        return None;
    }
    let nodes = &model.mesh.nodes;
    if D == 2 {
        // the 3-node edges [a, b, m] (`Mesh::edge_facet`)
        let midsides = model.mesh.planar_midsides();
        let facets = cp
            .edges
            .iter()
            .map(|&[a, b]| match midsides.get(&(a.min(b), a.max(b))) {
                Some(&m) => vec![a, b, m],
                None => vec![a, b],
            })
            .collect();
        let planar: Vec<[f64; 2]> = nodes.iter().map(|x| [x[0], x[1]]).collect();
        Some(FacetRule::planar(
            &planar,
            facets,
            model.analysis.kind == AnalysisKind::Axisymmetric,
            model.analysis.thickness,
        ))
    } else {
        let solid: Vec<[f64; 3]> = nodes.iter().map(|x| [x[0], x[1], x[2]]).collect();
        let facets = cp.faces.iter().map(|f| f.nodes().to_vec()).collect();
        Some(FacetRule::solid(&solid, facets))
    }
}

/// The contact state of one slave node as the heat exchange sees it:
/// `(pressure, gap)`.
pub type NodeState = (f64, f64);

/// The conductance at a point of a face with shape values `shape`, from the
/// states of the face's nodes (`None`: the node is not reported): see the
/// module doc.
pub fn point_conductance(
    settings: &ContactThermal,
    shape: &[f64],
    states: &[Option<NodeState>],
) -> f64 {
    let p: f64 = shape
        .iter()
        .zip(states)
        .map(|(n, s)| n * s.map_or(0.0, |s| s.0))
        .sum();
    if p > 0.0 {
        return settings.conductance.at(p);
    }
    if settings.gap_conductivity <= 0.0 || states.iter().any(Option::is_none) {
        return 0.0;
    }
    let g: f64 = shape
        .iter()
        .zip(states)
        .map(|(n, s)| n * s.map_or(0.0, |s| s.1))
        .sum();
    settings.gap_conductivity / g.max(settings.gap_min)
}

/// The conductance elements of a pair with the face rule `rule` against a
/// tool at `tool_temperature`, from the converged state `contact` of its
/// slave nodes: one element per integration point with `h w > 0`, in the
/// rule's order.
pub fn face_elements<const D: usize>(
    rule: &FacetRule,
    settings: &ContactThermal,
    contact: &[NodeContact<D>],
    tool_temperature: f64,
) -> Vec<ConductanceElement> {
    let states: BTreeMap<usize, NodeState> = contact
        .iter()
        .map(|c| (c.node, (c.pressure, c.gap)))
        .collect();
    let mut out = Vec::new();
    for point in &rule.points {
        let facet = &rule.facets[point.facet];
        let face_states: Vec<Option<NodeState>> =
            facet.iter().map(|n| states.get(n).copied()).collect();
        let ha = point_conductance(settings, &point.shape, &face_states) * point.weight;
        if ha > 0.0 {
            out.push(ConductanceElement::on_nodes(
                ha,
                facet,
                &point.shape,
                tool_temperature,
            ));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::ContactStatus;
    use crate::model::thermal::Conductance;

    fn settings() -> ContactThermal {
        ContactThermal {
            conductance: Conductance::Power {
                h0: 3.0,
                h1: 0.5,
                n: 0.5,
            },
            gap_conductivity: 0.0,
            gap_min: 1e-3,
            friction_split: 0.5,
            tool_temperature: None,
        }
    }

    fn node(node: usize, pressure: f64, gap: f64) -> NodeContact<3> {
        NodeContact {
            node,
            gap,
            normal: [0.0, 0.0, 1.0],
            force: [0.0; 3],
            stiffness: [[0.0; 3]; 3],
            pressure,
            status: if pressure > 0.0 {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    /// A curved quad8 / quad9 / tri6 face in the reference configuration:
    /// corners and midsides of a patch of `z = 0.1 (x^2 - y^2)` (nodes 0..).
    fn curved_face(kind: usize) -> (Vec<[f64; 3]>, Vec<usize>) {
        let xy: Vec<[f64; 2]> = match kind {
            6 => vec![
                [0.0, 0.0],
                [2.0, 0.0],
                [0.0, 1.5],
                [1.0, 0.0],
                [1.0, 0.75],
                [0.0, 0.75],
            ],
            _ => {
                let mut v = vec![
                    [0.0, 0.0],
                    [2.0, 0.0],
                    [2.0, 1.5],
                    [0.0, 1.5],
                    [1.0, 0.0],
                    [2.0, 0.75],
                    [1.0, 1.5],
                    [0.0, 0.75],
                ];
                if kind == 9 {
                    v.push([1.0, 0.75]);
                }
                v
            }
        };
        let nodes = xy
            .iter()
            .map(|p| [p[0], p[1], 0.1 * (p[0] * p[0] - p[1] * p[1])])
            .collect();
        (nodes, (0..xy.len()).collect())
    }

    /// The heat `Q_a` into each node of the elements at temperatures `t`.
    fn heat(elements: &[ConductanceElement], t: &[f64]) -> Vec<f64> {
        let mut q = vec![0.0; t.len()];
        for e in elements {
            let jump = e.heat_into_slave(t) / e.ha;
            for k in 0..e.count {
                q[e.nodes[k]] += e.ha * e.weights[k] * jump;
            }
        }
        q
    }

    #[test]
    fn uniform_pressure_gives_h_times_the_face_mass_matrix_and_its_exact_tangent() {
        let s = settings();
        let (p, t_tool) = (64.0, 20.0);
        let h = 3.0 + 0.5 * 8.0;
        for kind in [6, 8, 9] {
            let (nodes, face) = curved_face(kind);
            let rule = FacetRule::solid(&nodes, vec![face.clone()]);
            let contact: Vec<NodeContact<3>> = face.iter().map(|&n| node(n, p, -1e-6)).collect();
            let elements = face_elements(&rule, &s, &contact, t_tool);
            // the conductance matrix the solver assembles: sum ha w w^T
            let nn = face.len();
            let mut matrix = vec![vec![0.0; nn]; nn];
            for e in &elements {
                for i in 0..e.count {
                    for j in 0..e.count {
                        matrix[e.nodes[i]][e.nodes[j]] += e.ha * e.weights[i] * e.weights[j];
                    }
                }
            }
            // against h times the face's mass matrix by the boundary code
            // (a separate quadrature loop, `solve::loads::face_points`)
            let mut mass = vec![vec![0.0; nn]; nn];
            crate::solve::loads::face_points(&nodes, &face, true, |w, n, an| {
                let da = w * (an[0] * an[0] + an[1] * an[1] + an[2] * an[2]).sqrt();
                for a in 0..nn {
                    for b in 0..nn {
                        mass[a][b] += n[a] * n[b] * da;
                    }
                }
            });
            for a in 0..nn {
                for b in 0..nn {
                    let d = (matrix[a][b] - h * mass[a][b]).abs();
                    assert!(
                        d < 1e-12,
                        "{kind}: {a} {b}: {} vs {}",
                        matrix[a][b],
                        h * mass[a][b]
                    );
                }
            }
            // uniform T: total heat h A (T_tool - T); the corner shares are
            // the consistent ones (negative on quad8, zero on tri6)
            let t = vec![50.0; nn];
            let q = heat(&elements, &t);
            let area: f64 = mass.iter().flatten().sum();
            let total: f64 = q.iter().sum();
            assert!((total - h * area * (t_tool - 50.0)).abs() < 1e-10 * total.abs());
            if kind == 8 {
                assert!(q[0] > 0.0, "quad8 corner share against the flux: {}", q[0]);
            }
            // the tangent -dQ/dT is the assembled matrix: central
            // differences at a non-uniform temperature (Q is linear in T,
            // so they agree to round-off)
            let t: Vec<f64> = (0..nn).map(|a| 30.0 + 7.0 * a as f64).collect();
            for b in 0..nn {
                let (mut up, mut down) = (t.clone(), t.clone());
                up[b] += 1e-3;
                down[b] -= 1e-3;
                let (qu, qd) = (heat(&elements, &up), heat(&elements, &down));
                for a in 0..nn {
                    let fd = -(qu[a] - qd[a]) / 2e-3;
                    assert!(
                        (fd - matrix[a][b]).abs() < 1e-9 * (1.0 + matrix[a][b].abs()),
                        "{kind}: d Q_{a} / d T_{b}: {fd} vs {}",
                        matrix[a][b]
                    );
                }
            }
        }
    }

    #[test]
    fn point_conductance_follows_the_interpolated_pressure_and_gap() {
        let mut s = settings();
        let shape = [0.25, 0.25, 0.5];
        // closed: h(p) at p = sum N_a p_a = 0.25 16 + 0.25 16 + 0.5 64
        let closed = [Some((16.0, 0.0)), Some((16.0, 0.0)), Some((64.0, 0.0))];
        let h = point_conductance(&s, &shape, &closed);
        assert!((h - (3.0 + 0.5 * 40f64.sqrt())).abs() < 1e-12);
        // derivative in a nodal pressure against central differences
        let dh = 0.5 * 0.5 / 40f64.sqrt() * 0.5;
        let at = |p2: f64| point_conductance(&s, &shape, &[closed[0], closed[1], Some((p2, 0.0))]);
        let fd = (at(64.0 + 1e-4) - at(64.0 - 1e-4)) / 2e-4;
        assert!((fd - dh).abs() < 1e-8, "{fd} vs {dh}");
        // open: no gas, nothing; with gas, k / g at the interpolated gap,
        // and nothing when a node of the face is not reported
        let open = [Some((0.0, 0.02)), Some((0.0, 0.02)), Some((0.0, 0.04))];
        assert_eq!(point_conductance(&s, &shape, &open), 0.0);
        s.gap_conductivity = 0.03;
        let h = point_conductance(&s, &shape, &open);
        assert!((h - 0.03 / 0.03).abs() < 1e-12);
        let missing = [Some((0.0, 0.02)), None, Some((0.0, 0.04))];
        assert_eq!(point_conductance(&s, &shape, &missing), 0.0);
        // a pressure that interpolates to <= 0 is open
        let edge = [Some((0.0, -1e-9)), Some((0.0, -1e-9)), Some((0.0, 1e-9))];
        assert!((point_conductance(&s, &shape, &edge) - 0.03 / 1e-3).abs() < 1e-9);
    }
}
