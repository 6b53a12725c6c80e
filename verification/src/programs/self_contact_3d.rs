//! Self contact in 3D, node-to-facet (`contact ring.inner -> ring.inner`
//! in a `3d` analysis; `ctc_engine::contact::node_to_facet`), tags `3d`,
//! `contact`, `self_contact`.
//!
//! `self_contact_3d` — the thick elastic ring of
//! `examples/ring_self_contact.ctc` (Neo-Hookean E = 1000, nu = 0.3,
//! finite strain, inner radius 0.25, outer 1) as one layer of hex8
//! (`extrude` of the same annulus, length 0.25) held in plane strain (uz =
//! 0 everywhere), squeezed between two clamped caps (the top cap moves
//! down 0.9) until its hole collapses and the hole's faces touch:
//!
//! ```text
//!          top cap: uy = -0.9
//!            ___====___
//!          /     __     \        the hole's faces (ring.inner) are
//!         |    (____)    |  ->   slave and master: the upper half of
//!          \___      ___/        the hole touches the lower half
//!              ====
//!          bottom cap fixed
//! ```
//!
//! Self contact (seed slides, "Contact between two deformable bodies /
//! self contact"): each node against the surface's facets except its own
//! patch (its facets and the facets sharing a node with them), only the
//! facets whose outward normal opposes its own, both directions at once
//! with half the tributary areas (penalty, area stiffness k = 1e5).
//! Checks, at the end of the squeeze:
//!
//! - equilibrium of the self-contact forces: the forces of every closed
//!   node's element (slave and facet nodes) sum to zero, and so does their
//!   moment about the origin, relative to the total normal force (round-off);
//! - the penalty gap: `|g| = p_pass / k` at every closed node, `p_pass =
//!   f_n / (A / 2)` the node's own (per-direction) force over its half
//!   tributary area, to round-off;
//! - the reported pressure is the interface pressure (the total contact
//!   force on each node over its full area, averaged with the facing
//!   side's at the foot: `ctc_engine::contact::interface_pressures`): max
//!   relative deviation from `k |g|` 0.22 at level 0 (the rim of the
//!   contact zone, where a node's neighbours are open) and 5.9e-3 at level
//!   1 (`ctc verify self_contact_3d --max-level 1`); its uniformity on
//!   non-matching meshes is `ctc verify contact_patch_self`;
//! - no closed node against its own patch or a facet facing its way;
//! - the element tangent against central finite differences of the forces
//!   (the assembled couplings of the pair at the final state);
//! - the squeeze force per unit length against the plane-strain ring of
//!   the same in-plane mesh (node-to-segment self contact, half areas in
//!   both directions, the same k). With uz = 0 the hex8 ring is the
//!   plane-strain ring, each facet's edge at z = 0 its segment.
//!
//! Level 0 (the default): 3 x 32 cells (radial, circumferential), 12
//! increments; level 1: 6 x 64 (the example's 2D mesh).

use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::node_to_facet::{excluded_facets, FacetSurface};
use ctc_engine::contact::surface::{evaluate_pair, SurfacePair};
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{run, IncrementView, Observer, RunSummary};

/// Length of the extruded ring (one layer).
const LENGTH: f64 = 0.25;
/// Area penalty of the 3D pair (the 2D pair gets half of it).
const K: f64 = 1e5;
/// Displacement of the top cap.
const SQUEEZE: f64 = 0.9;

const NAMES: [&str; 7] = [
    "squeeze force per unit length: 3D / plane-strain ring (node-to-segment) - 1",
    "self-contact forces: |sum f| / sum R_N",
    "self-contact moments: |sum x ^ f| / (R_outer sum R_N)",
    "penalty gap: max | |g| k / p_pass - 1 | over the closed nodes",
    "closed nodes against their own patch or a facet facing their way",
    "tangent: max relative error against finite differences of the forces",
    "interface pressure: max | p / (k |g|) - 1 | over the closed nodes",
];

/// The ring's mesh at `level`: radial and circumferential divisions.
fn divisions(level: usize) -> (usize, usize) {
    (3 << level, 32 << level)
}

/// The annulus of both decks.
fn annulus(level: usize) -> String {
    let (r, c) = divisions(level);
    format!(
        "annulus {{ center = (0, 0)  inner = 0.25  outer = 1  radial = {r}  \
         circumferential = {c}  element = quad4 }}"
    )
}

/// The 3D deck of `level`.
pub fn deck_3d(level: usize) -> String {
    format!(
        "analysis {{ dimension = 3d }}\n\
         material rubber {{ neo_hookean {{ E = 1e3  nu = 0.3 }} }}\n\
         body ring {{\n  mesh = extrude {{ base = {}  length = {LENGTH}  layers = 1 }}\n  \
         material = rubber\n  kinematics = finite\n}}\n\
         contact ring.inner -> ring.inner {{ method = penalty {{ kind = area  stiffness = {K:e} }} }}\n\
         fix ring.all {{ uz }}\n\
         fix ring.nodes(box((-0.3, -1.1, -1), (0.3, -0.95, 1))) {{ ux uy }}\n\
         displace ring.nodes(box((-0.3, 0.95, -1), (0.3, 1.1, 1))) {{ ux = 0  uy = ramp(0, -{SQUEEZE}) }}\n\
         step squeeze {{\n  time = 0 .. 1\n  increments = 12\n  newton {{ tol = 1e-9  max_iter = 25 }}\n}}\n",
        annulus(level)
    )
}

/// The plane-strain deck of `level` (the same in-plane mesh and penalty:
/// node-to-segment self contact has half areas in both directions, as 3D).
fn deck_2d(level: usize) -> String {
    format!(
        "analysis {{ dimension = plane_strain }}\n\
         material rubber {{ neo_hookean {{ E = 1e3  nu = 0.3 }} }}\n\
         body ring {{\n  mesh = {}\n  material = rubber\n  kinematics = finite\n}}\n\
         contact ring.inner -> ring.inner {{ method = penalty {{ kind = area  stiffness = {:e} }} }}\n\
         fix ring.nodes(box((-0.3, -1.1), (0.3, -0.95))) {{ ux uy }}\n\
         displace ring.nodes(box((-0.3, 0.95), (0.3, 1.1))) {{ ux = 0  uy = ramp(0, -{SQUEEZE}) }}\n\
         step squeeze {{\n  time = 0 .. 1\n  increments = 12\n  newton {{ tol = 1e-9  max_iter = 25 }}\n}}\n",
        annulus(level),
        K
    )
}

/// The last converged state of a run: the top cap's force along y, the
/// contact entries of the first pair and the displacements.
struct Last<const D: usize> {
    top: f64,
    contact: Vec<NodeContact<D>>,
    displacement: Vec<[f64; D]>,
}

impl<const D: usize> Default for Last<D> {
    fn default() -> Self {
        Last {
            top: 0.0,
            contact: Vec::new(),
            displacement: Vec::new(),
        }
    }
}

impl<const D: usize> Observer<D> for Last<D> {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        // the top cap: the nodes with y >= 0.95 in the reference frame
        self.top = v
            .model
            .mesh
            .nodes
            .iter()
            .zip(v.reaction)
            .filter(|(p, _)| p[1] >= 0.95 && p[0].abs() <= 0.3)
            .map(|(_, r)| r[1])
            .sum();
        self.contact = v.contact.first().cloned().unwrap_or_default();
        self.displacement = v.displacement.to_vec();
        Ok(())
    }
}

fn compile(name: &str, text: String) -> Result<AnyModel, String> {
    let src = ctc_lang::Source::new(name, text);
    ctc_lang::compile_any(&src).map_err(|d| d.render(&src))
}

fn solve<const D: usize>(model: &Model<D>) -> Result<(Last<D>, RunSummary), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    let mut last = Last::default();
    let summary = run(model, &mut last).map_err(|e| e.message)?;
    if !summary.completed {
        return Err("the squeeze did not complete".into());
    }
    Ok((last, summary))
}

/// The unit normal of facet `nodes` at coordinates `x` (area vector).
fn facet_normal(nodes: &[usize], x: &[[f64; 3]]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for (a, &i) in nodes.iter().enumerate() {
        let (p, q) = (x[i], x[nodes[(a + 1) % nodes.len()]]);
        m[0] += p[1] * q[2] - p[2] * q[1];
        m[1] += p[2] * q[0] - p[0] * q[2];
        m[2] += p[0] * q[1] - p[1] * q[0];
    }
    m
}

/// Equilibrium of the pair's forces at `x`: `(|sum f|, |sum x ^ f|, sum
/// R_N)` over the couplings, and the largest relative finite-difference
/// error of their tangents (every closed node's element, its nodes
/// perturbed by `1e-7`).
fn balance_and_tangent(model: &Model<3>, x: &[[f64; 3]]) -> Result<(f64, f64, f64, f64), String> {
    let mut state = SurfacePair::new(model, 0);
    let (nodes, _) = evaluate_pair(model, 0, x, 1.0, &mut state);
    let couplings = state
        .deformable
        .as_ref()
        .map(|d| d.couplings.clone())
        .ok_or("the pair is not node-to-facet")?;
    let rn: f64 = nodes
        .iter()
        .filter(|n| n.status == ContactStatus::Closed)
        .map(|n| n.force.iter().map(|f| f * f).sum::<f64>().sqrt())
        .sum();
    let (mut f, mut m) = ([0.0; 3], [0.0; 3]);
    for c in &couplings {
        for (a, &n) in c.nodes.iter().enumerate() {
            let p = x[n];
            let q = [c.force[3 * a], c.force[3 * a + 1], c.force[3 * a + 2]];
            for k in 0..3 {
                f[k] += q[k];
            }
            m[0] += p[1] * q[2] - p[2] * q[1];
            m[1] += p[2] * q[0] - p[0] * q[2];
            m[2] += p[0] * q[1] - p[1] * q[0];
        }
    }
    let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    // tangents: central differences of each coupling's force
    let h = 1e-7;
    let mut worst = 0.0f64;
    for c in &couplings {
        let nd = 3 * c.nodes.len();
        let scale = c.tangent.iter().fold(1e-300, |s: f64, v| s.max(v.abs()));
        for (a, &n) in c.nodes.iter().enumerate() {
            for k in 0..3 {
                let mut forces = [Vec::new(), Vec::new()];
                for (s, sign) in [1.0, -1.0].into_iter().enumerate() {
                    let mut xp = x.to_vec();
                    xp[n][k] += sign * h;
                    let mut st = SurfacePair::new(model, 0);
                    evaluate_pair(model, 0, &xp, 1.0, &mut st);
                    let cp = st
                        .deformable
                        .as_ref()
                        .and_then(|d| d.couplings.iter().find(|o| o.slave == c.slave).cloned())
                        .ok_or("a closed node opened under the perturbation")?;
                    if cp.nodes != c.nodes {
                        return Err("a closed node changed facet under the perturbation".into());
                    }
                    forces[s] = cp.force;
                }
                for (r, (fp, fm)) in forces[0].iter().zip(&forces[1]).enumerate().take(nd) {
                    let fd = -(fp - fm) / (2.0 * h);
                    let an = c.tangent[r * nd + 3 * a + k];
                    worst = worst.max((fd - an).abs() / scale);
                }
            }
        }
    }
    Ok((norm(f), norm(m), rn, worst))
}

fn measure(level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: 1.0 / (32 << level) as f64,
        ..ProgramLevel::default()
    };
    let AnyModel::D3(m3) = compile("self_contact_3d.ctc", deck_3d(level))? else {
        return Err("the 3D deck compiled to a planar model".into());
    };
    let AnyModel::D2(m2) = compile("ring_2d.ctc", deck_2d(level))? else {
        return Err("the 2D deck compiled to a solid model".into());
    };
    let (r3, s3) = solve(&m3)?;
    let (r2, s2) = solve(&m2)?;
    out.add_run(&s3);
    out.add_run(&s2);
    let per_length = r3.top / LENGTH;
    out.values.push(super::value(NAMES[0], per_length, r2.top));
    let x: Vec<[f64; 3]> = m3
        .mesh
        .nodes
        .iter()
        .zip(&r3.displacement)
        .map(|(p, u)| [p[0] + u[0], p[1] + u[1], p[2] + u[2]])
        .collect();
    let (f, m, rn, fd) = balance_and_tangent(&m3, &x)?;
    if rn <= 0.0 {
        return Err("no closed node at the end of the squeeze".into());
    }
    out.values.push(super::error(NAMES[1], f / rn));
    out.values.push(super::error(NAMES[2], m / rn));
    // the penalty gap and the exclusion rules over the run's closed nodes
    let cp = &m3.contacts[0];
    let surface = FacetSurface::new(&cp.faces);
    let slaves = ctc_engine::contact::node_to_facet::slave_nodes(&m3, 0);
    let half = ctc_engine::contact::node_to_facet::areas(&m3, 0, &slaves);
    let (mut gap_err, mut wrong, mut closed) = (0.0f64, 0usize, 0usize);
    let mut interface_err = 0.0f64;
    for n in r3
        .contact
        .iter()
        .filter(|n| n.status == ContactStatus::Closed)
    {
        closed += 1;
        let area = slaves
            .binary_search(&n.node)
            .ok()
            .and_then(|i| half.get(i).copied())
            .unwrap_or(0.0);
        let f_n = (0..3).map(|c| n.force[c] * n.normal[c]).sum::<f64>().abs();
        if area > 0.0 && f_n > 0.0 {
            gap_err = gap_err.max((n.gap.abs() * K * area / f_n - 1.0).abs());
        }
        if n.gap != 0.0 {
            interface_err = interface_err.max((n.pressure / (K * n.gap.abs()) - 1.0).abs());
        }
        let own = excluded_facets(&surface, n.node);
        let facet = surface.faces.get(n.entity).map(|f| f.nodes().to_vec());
        let Some(facet) = facet else {
            wrong += 1;
            continue;
        };
        let mine: Vec<[f64; 3]> = own
            .iter()
            .filter(|&&k| surface.faces[k].nodes().contains(&n.node))
            .map(|&k| facet_normal(surface.faces[k].nodes(), &x))
            .collect();
        let ns: [f64; 3] = std::array::from_fn(|c| mine.iter().map(|v| v[c]).sum());
        let nf = facet_normal(&facet, &x);
        let facing = (0..3).map(|c| ns[c] * nf[c]).sum::<f64>() < 0.0;
        if own.binary_search(&n.entity).is_ok() || !facing {
            wrong += 1;
        }
    }
    if closed == 0 {
        return Err("no closed node in the run's last increment".into());
    }
    out.values.push(super::error(NAMES[3], gap_err));
    out.values.push(super::error(NAMES[4], wrong as f64));
    out.values.push(super::error(NAMES[5], fd));
    out.values.push(super::error(NAMES[6], interface_err));
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "self_contact_3d",
        title: "Self contact in 3D (node-to-facet): a hex8 ring squeezed until its hole closes; contact forces and moments in equilibrium, penalty gap p / k, no contact with the own patch, FD tangent, the plane-strain ring's force",
        source: "seed slides, \"Contact between two deformable bodies / self contact\" (equilibrium of the contact forces, penalty gap p / k); the plane-strain ring of examples/ring_self_contact.ctc (node-to-segment) as reference",
        tags: &["3d", "contact", "self_contact"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(NAMES[0]), &[1e-3, 1e-3]),
            Check::new(Quantity::Named(NAMES[1]), &[1e-12, 1e-12]),
            Check::new(Quantity::Named(NAMES[2]), &[1e-12, 1e-12]),
            Check::new(Quantity::Named(NAMES[3]), &[1e-10, 1e-10]),
            Check::new(Quantity::Named(NAMES[4]), &[0.5, 0.5]),
            Check::new(Quantity::Named(NAMES[5]), &[1e-5, 1e-5]),
            Check::new(Quantity::Named(NAMES[6]), &[0.3, 1e-2]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 2,
            run: measure,
        }),
    }]
}
