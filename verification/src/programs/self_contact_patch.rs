//! `contact_patch_self` — the contact patch test (Taylor & Papadopoulos,
//! IJNME 31 (1991) 2205; VERIFICATION-CASES.md case 3) run as **self
//! contact**: the two blocks of the two-body patch test are one body (one
//! gmsh mesh with two disconnected blocks, written by this program), and
//! the interface is one surface `s`, slave and master of itself (`contact
//! b.s -> b.s`): each node is pressed against the facing block's facets
//! (node-to-segment in 2D, node-to-facet in 3D), both directions at once
//! with half the tributary areas (the modified double pass of a two-body
//! pair, which is what self contact is at an interface).
//!
//! ```text
//!   2D (plane strain, E = 2e6, nu = 0)    3D (E = 1000, nu = 0.3)
//!   upper [0,1] x [1,2], 3 quads across   upper [0,1]^2 x [0.5,1], 3 x 3 hex8
//!   ---- s: both faces of y = 1 ----      ---- s: both faces of z = 0.5 ----
//!   lower [0,1] x [0,1], 4 quads across   lower [0,1]^2 x [0,0.5], 4 x 4 hex8
//!   top pushed down by d, bottom on rollers, x = 0 (and y = 0) symmetric
//! ```
//!
//! Exact state: uniform uniaxial stress `-p` in both blocks, `p = (d - g0)
//! / (H / E + 1 / k)` (`H` the total height, `g0 = d / 100` the initial gap
//! between the blocks, `k` the area penalty: each node's
//! own force gives `k |g|` over half its area, the two directions together
//! `k |g|` over its full area).
//!
//! Measured: the largest deviation of the **reported** pressure of the
//! closed nodes from `p` (the interface pressure: each node's total force
//! as slave and as master over its full area, averaged with the facing
//! side's at its foot, `ctc_engine::contact::interface_pressures`), the
//! total force through the stack (the bottom reaction against `p` times
//! the area), and, not judged, the same deviation of the per-direction
//! pressure `f_n / (A / 2)` that self contact reported before (the
//! node-to-segment defect: the share each direction carries at a node
//! depends on where the other side's nodes project). Before this case the
//! reported pressure of a 2D self-contact pair was that per-direction
//! pressure over the *full* area, half the interface pressure (2D self
//! contact had full areas in both directions: twice the interface
//! stiffness of the deck's `k`; now half areas, as in 3D).
//!
//! Measured (`ctc verify contact_patch_self`, 0.1 s debug; the tolerances
//! are these figures rounded up): reported pressure 2.95e-4 (2D) /
//! 1.57e-3 (3D: the modified double pass of `contact_patch_ntf_3d` gives
//! the same 1.57e-3), total force 6.5e-6 / 8.0e-5; the per-direction
//! pressure 0.32 / 0.35 from uniform (what self contact reported before,
//! in 2D over the full area: about half of `p`).
//!
//! **Frictional slide** (`Setup::slide_deck`, Coulomb `mu = 0.1`): the
//! bottom clamped, the top pressed down by `d` (2 increments), then moved
//! along x by 0.05 (2D) / 0.01 (3D) with its height held (4 increments):
//! past the stick limit, every closed node slips, and the upper block
//! overhangs the lower one's edge (20 % / 4 % of a lower facet). Exact:
//! `|T_i| = mu R_N,i` at every closed node (the return map), and the
//! upper block in equilibrium: its top reaction equals minus the contact
//! forces on it (its slave nodes' forces minus the lower block's, whose
//! reactions act on the upper block's facets). Measured (`ctc verify
//! contact_patch_self`, debug, 0.8 s for the four runs): Coulomb 4.5e-14
//! (2D) / 4.4e-16 (3D), no closed node sticking, equilibrium 4.4e-13 /
//! 1.2e-12. Before the free-edge rule of `FacetSurface::closest` the 3D
//! slide stopped at 4 % overhang (the nodes past the edge were paired
//! with an interior edge a facet away, gap -0.256), and 3D self contact
//! with friction was refused.
//!
//! **Lagrange multipliers** (`method = lagrange`, the same patch, exact
//! `p = (d - g0) / (H / E)`): every interface node is constrained in both
//! directions, and the rows of coincident nodes (the blocks' edges) repeat
//! each other; they are dropped (`ctc_engine::contact::redundancy`; before,
//! self contact with Lagrange multipliers was refused in 3D and singular
//! in 2D). Measured (`ctc verify contact_patch_self`, debug): reported
//! pressure 2.0e-15 (2D) / 2.4e-14 (3D), total force 6.7e-16 / 2.9e-15.

use super::error;
use crate::case::{Check, Quantity};
use crate::registry::{CaseKind, ProgramCase, ProgramLevel, VerifyCase};
use ctc_engine::contact::{ContactStatus, NodeContact};
use ctc_engine::model::{AnyModel, Model};
use ctc_engine::solve::{run, IncrementView, Observer};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

const NAMES: [&str; 6] = [
    "2D reported pressure: max |p_i / p - 1|",
    "2D total force: |R / (p A) - 1|",
    "2D per-direction pressure f_n / (A / 2): max |p_i / p - 1| (not judged)",
    "3D reported pressure: max |p_i / p - 1|",
    "3D total force: |R / (p A) - 1|",
    "3D per-direction pressure f_n / (A / 2): max |p_i / p - 1| (not judged)",
];

/// The figures of the frictional slide, per dimension.
const SLIDE_NAMES: [&str; 6] = [
    "2D slide: max ||T_i| / (mu R_N,i) - 1| over the closed nodes",
    "2D slide: closed nodes sticking",
    "2D slide: |top reaction + contact force on the upper block| / |reaction|",
    "3D slide: max ||T_i| / (mu R_N,i) - 1| over the closed nodes",
    "3D slide: closed nodes sticking",
    "3D slide: |top reaction + contact force on the upper block| / |reaction|",
];

/// The figures of the Lagrange-multiplier run, per dimension.
const LAGRANGE_NAMES: [&str; 4] = [
    "2D Lagrange: reported pressure max |p_i / p - 1|",
    "2D Lagrange: total force |R / (p A) - 1|",
    "3D Lagrange: reported pressure max |p_i / p - 1|",
    "3D Lagrange: total force |R / (p A) - 1|",
];

/// Coulomb's coefficient of the frictional slide.
const MU: f64 = 0.1;

/// Nodes of a structured block of `n` cells per in-plane axis and `layers`
/// cells through its height, from `z0` to `z0 + height` along the last
/// axis, numbered from `first` (x fastest, then y, then the height axis).
fn block_nodes(dim: usize, n: usize, layers: usize, z0: f64, height: f64) -> Vec<[f64; 3]> {
    let mut out = Vec::new();
    let h = |k: usize| z0 + height * k as f64 / layers as f64;
    let s = |i: usize| i as f64 / n as f64;
    if dim == 2 {
        for k in 0..=layers {
            for i in 0..=n {
                out.push([s(i), h(k), 0.0]);
            }
        }
    } else {
        for k in 0..=layers {
            for j in 0..=n {
                for i in 0..=n {
                    out.push([s(i), s(j), h(k)]);
                }
            }
        }
    }
    out
}

/// The gmsh 2.2 text of the two blocks: `lower` cells across the lower
/// block, `upper` across the upper; the physical group `s` holds the lower
/// block's top and the upper block's bottom (lines in 2D, quadrangles in
/// 3D), the group `block` the cells; the upper block starts `gap` above the
/// lower one (a mesh may not have coincident nodes).
fn mesh(dim: usize, lower: usize, upper: usize, height: f64, gap: f64) -> String {
    let layers = 2;
    let blocks = [
        (lower, block_nodes(dim, lower, layers, 0.0, height)),
        (upper, block_nodes(dim, upper, layers, height + gap, height)),
    ];
    let mut nodes = String::new();
    let mut cells: Vec<(usize, Vec<usize>)> = Vec::new();
    let mut faces: Vec<(usize, Vec<usize>)> = Vec::new();
    let mut offset = 0;
    let mut count = 0;
    for (b, (n, xs)) in blocks.iter().enumerate() {
        for p in xs {
            count += 1;
            let _ = writeln!(nodes, "{count} {} {} {}", p[0], p[1], p[2]);
        }
        let id = |i: usize, j: usize, k: usize| {
            offset
                + 1
                + if dim == 2 {
                    k * (n + 1) + i
                } else {
                    (k * (n + 1) + j) * (n + 1) + i
                }
        };
        // the interface layer: the lower block's top, the upper's bottom
        let face_k = if b == 0 { layers } else { 0 };
        if dim == 2 {
            for k in 0..layers {
                for i in 0..*n {
                    let c = vec![
                        id(i, 0, k),
                        id(i + 1, 0, k),
                        id(i + 1, 0, k + 1),
                        id(i, 0, k + 1),
                    ];
                    cells.push((3, c));
                }
            }
            for i in 0..*n {
                faces.push((1, vec![id(i, 0, face_k), id(i + 1, 0, face_k)]));
            }
        } else {
            for k in 0..layers {
                for j in 0..*n {
                    for i in 0..*n {
                        let c = vec![
                            id(i, j, k),
                            id(i + 1, j, k),
                            id(i + 1, j + 1, k),
                            id(i, j + 1, k),
                            id(i, j, k + 1),
                            id(i + 1, j, k + 1),
                            id(i + 1, j + 1, k + 1),
                            id(i, j + 1, k + 1),
                        ];
                        cells.push((5, c));
                    }
                }
            }
            for j in 0..*n {
                for i in 0..*n {
                    let f = vec![
                        id(i, j, face_k),
                        id(i + 1, j, face_k),
                        id(i + 1, j + 1, face_k),
                        id(i, j + 1, face_k),
                    ];
                    faces.push((3, f));
                }
            }
        }
        offset += xs.len();
    }
    let (face_dim, cell_dim) = if dim == 2 { (1, 2) } else { (2, 3) };
    let mut text = format!(
        "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n{face_dim} 1 \"s\"\n\
         {cell_dim} 2 \"block\"\n$EndPhysicalNames\n$Nodes\n{count}\n{nodes}$EndNodes\n\
         $Elements\n{}\n",
        faces.len() + cells.len()
    );
    // element lines `id type 2 physical elementary nodes..`: the faces in
    // group 1 (`s`), the cells in group 2 (`block`)
    let groups = faces
        .iter()
        .map(|f| (1, f))
        .chain(cells.iter().map(|c| (2, c)));
    for (e, (group, (gmsh_type, nodes))) in groups.enumerate() {
        let list: Vec<String> = nodes.iter().map(ToString::to_string).collect();
        let _ = writeln!(
            text,
            "{} {gmsh_type} 2 {group} {group} {}",
            e + 1,
            list.join(" ")
        );
    }
    text.push_str("$EndElements\n");
    text
}

/// Problem data of a dimension: Young's modulus, Poisson's ratio, the
/// height of one block, the top's displacement and the area penalty.
struct Setup {
    dim: usize,
    e: f64,
    nu: f64,
    height: f64,
    d: f64,
    k: f64,
    /// The top's displacement along x in the frictional slide (past the
    /// stick limit: in 2D the blocks shear by `mu p H / G = 0.02` before
    /// the interface slips, in 3D by `2.6e-3`; the upper block then
    /// overhangs the lower one's edge by 20 % (2D) and 4 % (3D) of a
    /// lower facet: the contact search past a free edge).
    slide: f64,
}

const SETUPS: [Setup; 2] = [
    Setup {
        dim: 2,
        e: 2e6,
        nu: 0.0,
        height: 1.0,
        d: 0.1,
        k: 1e10,
        slide: 0.05,
    },
    Setup {
        dim: 3,
        e: 1000.0,
        nu: 0.3,
        height: 0.5,
        d: 0.01,
        k: 1e6,
        slide: 0.01,
    },
];

impl Setup {
    /// The initial gap between the blocks (`d / 100`).
    fn gap(&self) -> f64 {
        self.d / 100.0
    }

    /// The exact pressure `(d - g0) / (H / E + 1 / k)`.
    fn pressure(&self) -> f64 {
        (self.d - self.gap()) / (2.0 * self.height / self.e + 1.0 / self.k)
    }

    /// The same setup with Lagrange multipliers (`k` infinite).
    fn lagrange(&self) -> Setup {
        Setup {
            k: f64::INFINITY,
            ..*self
        }
    }

    /// The patch deck with Lagrange multipliers instead of the penalty.
    fn lagrange_deck(&self) -> String {
        let d = self.deck();
        let penalty = format!(
            "method = penalty {{ kind = area  stiffness = {:e} }}",
            self.k
        );
        d.replace(&penalty, "method = lagrange")
    }

    fn deck(&self) -> String {
        let top = 2.0 * self.height + self.gap();
        let (analysis, sym, bottom, top_set, dof) = if self.dim == 2 {
            (
                "plane_strain",
                "fix b.nodes(x = 0) { ux }\n".to_string(),
                "fix b.nodes(y = 0) { uy }\n",
                format!("b.nodes(y = {top})"),
                "uy",
            )
        } else {
            (
                "3d",
                "fix b.nodes(x = 0) { ux }\nfix b.nodes(y = 0) { uy }\n".to_string(),
                "fix b.nodes(z = 0) { uz }\n",
                format!("b.nodes(z = {top})"),
                "uz",
            )
        };
        format!(
            "analysis {{ dimension = {analysis} }}\n\
             material soft {{ elastic {{ E = {:e}  nu = {} }} }}\n\
             body b {{\n  mesh = file \"patch.msh\"\n  material = soft\n}}\n\
             contact b.s -> b.s {{ method = penalty {{ kind = area  stiffness = {:e} }} }}\n\
             {sym}{bottom}displace {top_set} {{ {dof} = ramp(0, -{}) }}\n\
             step press {{\n  time = 0 .. 1\n  increments = 2\n  newton {{ tol = 1e-10 }}\n}}\n",
            self.e, self.nu, self.k, self.d
        )
    }

    /// The frictional slide: the bottom clamped, the top pressed down by
    /// `d` (as [`Setup::deck`]) then moved by `slide` along x with the
    /// height held, Coulomb friction `MU` on the self-contact surface.
    fn slide_deck(&self) -> String {
        let top = 2.0 * self.height + self.gap();
        let (analysis, bottom, top_set, dof, held) = if self.dim == 2 {
            (
                "plane_strain",
                "fix b.nodes(y = 0) { ux uy }\n",
                format!("b.nodes(y = {top})"),
                "uy",
                "",
            )
        } else {
            (
                "3d",
                "fix b.nodes(z = 0) { ux uy uz }\n",
                format!("b.nodes(z = {top})"),
                "uz",
                "  uy = 0",
            )
        };
        format!(
            "analysis {{ dimension = {analysis} }}\n\
             material soft {{ elastic {{ E = {:e}  nu = {} }} }}\n\
             body b {{\n  mesh = file \"patch.msh\"\n  material = soft\n}}\n\
             contact b.s -> b.s {{\n  method = penalty {{ kind = area  stiffness = {:e} }}\n  \
             friction = coulomb {{ mu = {MU} }}\n}}\n\
             {bottom}displace {top_set} {{\n  {dof} = table((0, 0), (1, -{d}), (2, -{d}))\n  \
             ux = table((0, 0), (1, 0), (2, {slide})){held}\n}}\n\
             step press {{\n  time = 0 .. 1\n  increments = 2\n  newton {{ tol = 1e-10 }}\n}}\n\
             step slide {{\n  time = 1 .. 2\n  increments = 4\n  newton {{ tol = 1e-10 }}\n}}\n",
            self.e,
            self.nu,
            self.k,
            d = self.d,
            slide = self.slide,
        )
    }
}

/// The last converged increment: the pair's entries and the bottom
/// reaction along the height axis.
struct Last<const D: usize> {
    contact: Vec<NodeContact<D>>,
    bottom: f64,
    /// The reaction summed over the top nodes (the highest ones).
    top: [f64; D],
}

impl<const D: usize> Default for Last<D> {
    fn default() -> Self {
        Self {
            contact: Vec::new(),
            bottom: 0.0,
            top: [0.0; D],
        }
    }
}

impl<const D: usize> Observer<D> for Last<D> {
    fn converged(&mut self, v: &IncrementView<'_, D>) -> Result<(), String> {
        self.contact = v.contact.first().cloned().unwrap_or_default();
        self.bottom = v
            .model
            .mesh
            .nodes
            .iter()
            .zip(v.reaction)
            .filter(|(p, _)| p[D - 1].abs() < 1e-12)
            .map(|(_, r)| r[D - 1])
            .sum();
        let high = v
            .model
            .mesh
            .nodes
            .iter()
            .map(|p| p[D - 1])
            .fold(f64::NEG_INFINITY, f64::max);
        self.top = [0.0; D];
        for (p, r) in v.model.mesh.nodes.iter().zip(v.reaction) {
            if (p[D - 1] - high).abs() < 1e-12 {
                for (t, rk) in self.top.iter_mut().zip(r) {
                    *t += rk;
                }
            }
        }
        Ok(())
    }
}

/// A scratch directory for the mesh and deck of one run.
fn scratch(dim: usize) -> Result<PathBuf, String> {
    let dir = std::env::temp_dir().join(format!(
        "ctc_contact_patch_self_{dim}d_{}",
        std::process::id()
    ));
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: {e}", dir.display()))?;
    Ok(dir)
}

/// Runs `model` (the `what` run of this case) to its end: the last
/// converged increment and the run summary.
fn last_increment<const D: usize>(
    model: &Model<D>,
    what: &str,
) -> Result<(Last<D>, ctc_engine::solve::RunSummary), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    let mut last = Last::<D>::default();
    let summary = run(model, &mut last).map_err(|e| e.message)?;
    if !summary.completed {
        return Err(format!("the {D}D self-contact {what} did not complete"));
    }
    Ok((last, summary))
}

/// Deviations of one model: (reported, total force, per-direction), and
/// its run summary.
fn judge<const D: usize>(
    model: &Model<D>,
    setup: &Setup,
    half_areas: impl Fn(&Model<D>) -> (Vec<usize>, Vec<f64>),
) -> Result<([f64; 3], ctc_engine::solve::RunSummary), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    let (last, summary) = last_increment(model, "patch")?;
    let p = setup.pressure();
    let (slaves, half) = half_areas(model);
    let (mut reported, mut per_direction, mut closed) = (0.0f64, 0.0f64, 0usize);
    for c in last
        .contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
    {
        closed += 1;
        reported = reported.max((c.pressure / p - 1.0).abs());
        let f_n = (0..D).map(|d| c.force[d] * c.normal[d]).sum::<f64>().abs();
        if let Some(&a) = slaves.binary_search(&c.node).ok().and_then(|i| half.get(i)) {
            per_direction = per_direction.max((f_n / a / p - 1.0).abs());
        }
    }
    if closed == 0 {
        return Err(format!("no closed node in the {D}D self-contact patch"));
    }
    let force = (last.bottom.abs() / p - 1.0).abs();
    Ok(([reported, force, per_direction], summary))
}

/// The frictional slide's figures: the largest `||T_i| / (mu R_N,i) - 1|`
/// over the closed nodes, how many of them stick, and the equilibrium of
/// the upper block: its top reaction against the contact forces on it
/// (`sum f_a` over its slave nodes minus `sum f_b` over the lower block's,
/// whose reactions go onto the upper block's facets), relative to the
/// reaction; and the run summary. (The top reaction's own `|F_t| / |F_n|`
/// is not `mu`: the interface tilts by ~1 degree as the blocks shear,
/// measured 0.0776 for mu = 0.1 in 2D.)
fn judge_slide<const D: usize>(
    model: &Model<D>,
    setup: &Setup,
) -> Result<([f64; 3], ctc_engine::solve::RunSummary), String>
where
    nalgebra::Const<D>: ctc_engine::geom::Dimension<D>,
{
    use ctc_engine::contact::friction::FrictionStatus;
    let (last, summary) = last_increment(model, "slide")?;
    let (mut coulomb, mut sticking, mut closed) = (0.0f64, 0usize, 0usize);
    for c in last
        .contact
        .iter()
        .filter(|c| c.status == ContactStatus::Closed)
    {
        closed += 1;
        if c.friction.status != FrictionStatus::Slip {
            sticking += 1;
            continue;
        }
        let t = c.friction.traction;
        let r_n = (0..D)
            .map(|k| (c.force[k] - t[k]) * c.normal[k])
            .sum::<f64>()
            .abs();
        let t_norm = t.iter().map(|v| v * v).sum::<f64>().sqrt();
        coulomb = coulomb.max((t_norm / (MU * r_n) - 1.0).abs());
    }
    if closed == 0 {
        return Err(format!("no closed node in the {D}D self-contact slide"));
    }
    // the contact force on the upper block (above the gap in the
    // reference mesh)
    let middle = setup.height + 0.5 * setup.gap();
    let mut on_upper = last.top;
    for c in &last.contact {
        let upper = model
            .mesh
            .nodes
            .get(c.node)
            .is_some_and(|p| p[D - 1] > middle);
        let sign = if upper { 1.0 } else { -1.0 };
        for (u, f) in on_upper.iter_mut().zip(c.force) {
            *u += sign * f;
        }
    }
    let norm = |v: &[f64; D]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let balance = norm(&on_upper) / norm(&last.top);
    Ok(([coulomb, sticking as f64, balance], summary))
}

fn measure(_level: usize) -> Result<ProgramLevel, String> {
    let mut out = ProgramLevel {
        h: f64::NAN,
        ..ProgramLevel::default()
    };
    for (s, setup) in SETUPS.iter().enumerate() {
        let dir = scratch(setup.dim)?;
        let msh = mesh(setup.dim, 4, 3, setup.height, setup.gap());
        std::fs::write(dir.join("patch.msh"), msh).map_err(|e| e.to_string())?;
        let path: &Path = &dir.join("patch.ctc");
        let src = ctc_lang::Source::new(path, setup.deck());
        let model = ctc_lang::compile_any(&src).map_err(|d| d.render(&src));
        let slide_src = ctc_lang::Source::new(path, setup.slide_deck());
        let slide = ctc_lang::compile_any(&slide_src).map_err(|d| d.render(&slide_src));
        let lagrange_src = ctc_lang::Source::new(path, setup.lagrange_deck());
        let lagrange = ctc_lang::compile_any(&lagrange_src).map_err(|d| d.render(&lagrange_src));
        let _ = std::fs::remove_dir_all(&dir);
        let (values, summary) = match model? {
            AnyModel::D2(m) => judge(&m, setup, |m| {
                let slaves = ctc_engine::contact::node_to_segment::slave_nodes(m, 0);
                let half = ctc_engine::contact::node_to_segment::tributary_areas(m, 0, &slaves);
                (slaves, half)
            })?,
            AnyModel::D3(m) => judge(&m, setup, |m| {
                let slaves = ctc_engine::contact::node_to_facet::slave_nodes(m, 0);
                let half = ctc_engine::contact::node_to_facet::areas(m, 0, &slaves);
                (slaves, half)
            })?,
        };
        out.add_run(&summary);
        for (v, name) in values.iter().zip(&NAMES[3 * s..3 * s + 3]) {
            out.values.push(error(name, *v));
        }
        let (values, summary) = match slide? {
            AnyModel::D2(m) => judge_slide(&m, setup)?,
            AnyModel::D3(m) => judge_slide(&m, setup)?,
        };
        out.add_run(&summary);
        for (v, name) in values.iter().zip(&SLIDE_NAMES[3 * s..3 * s + 3]) {
            out.values.push(error(name, *v));
        }
        let exact = setup.lagrange();
        let (values, summary) = match lagrange? {
            AnyModel::D2(m) => judge(&m, &exact, |_| (Vec::new(), Vec::new()))?,
            AnyModel::D3(m) => judge(&m, &exact, |_| (Vec::new(), Vec::new()))?,
        };
        out.add_run(&summary);
        for (v, name) in values.iter().zip(&LAGRANGE_NAMES[2 * s..2 * s + 2]) {
            out.values.push(error(name, *v));
        }
    }
    Ok(out)
}

/// The registry entry.
pub fn cases() -> Vec<VerifyCase> {
    vec![VerifyCase {
        name: "contact_patch_self",
        title: "Contact patch test as self contact (one body, two blocks, 4 | 3 cells across; node-to-segment 2D, node-to-facet 3D): the reported interface pressure uniform, the total force, with the penalty and with Lagrange multipliers; a frictional slide past the edge: |T| = mu R_N, the upper block's equilibrium",
        source: "Taylor & Papadopoulos, IJNME 31 (1991) 2205 (the contact patch test); VERIFICATION-CASES.md case 3; seed slides, \"Contact between two deformable bodies / self contact\"",
        tags: &["contact", "self_contact", "patch", "friction", "3d"],
        levels: 1,
        checks: vec![
            Check::new(Quantity::Named(NAMES[0]), &[1e-3]),
            Check::new(Quantity::Named(NAMES[1]), &[2e-5]),
            Check::new(Quantity::Named(NAMES[2]), &[10.0]),
            Check::new(Quantity::Named(NAMES[3]), &[3e-3]),
            Check::new(Quantity::Named(NAMES[4]), &[2e-4]),
            Check::new(Quantity::Named(NAMES[5]), &[10.0]),
            Check::new(Quantity::Named(SLIDE_NAMES[0]), &[1e-9]),
            Check::new(Quantity::Named(SLIDE_NAMES[1]), &[0.5]),
            Check::new(Quantity::Named(SLIDE_NAMES[2]), &[1e-9]),
            Check::new(Quantity::Named(SLIDE_NAMES[3]), &[1e-9]),
            Check::new(Quantity::Named(SLIDE_NAMES[4]), &[0.5]),
            Check::new(Quantity::Named(SLIDE_NAMES[5]), &[1e-9]),
            Check::new(Quantity::Named(LAGRANGE_NAMES[0]), &[1e-12]),
            Check::new(Quantity::Named(LAGRANGE_NAMES[1]), &[1e-12]),
            Check::new(Quantity::Named(LAGRANGE_NAMES[2]), &[1e-11]),
            Check::new(Quantity::Named(LAGRANGE_NAMES[3]), &[1e-12]),
        ],
        kind: CaseKind::Program(ProgramCase {
            max_levels: 1,
            run: measure,
        }),
    }]
}
