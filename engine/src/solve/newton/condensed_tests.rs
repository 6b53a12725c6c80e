//! The condensed dual-mortar system (`lagrange { formulation = condensed
//! }`, [`crate::solve::linalg::condensed`]) against finite differences of
//! the residual and the gaps, on a curved mortar interface.
//!
//! ```text
//!   top  [0,1]x[1,2], 3 x 2 quads, bottom bulged down (u_y = -0.02 + 0.04 (x - 1/2)^2)
//!   ---- slave top.bottom -> master base.top (mortar, Lagrange) ----
//!   base [0,1]x[0,1], 4 x 2 quads, top bent (u_y = 0.01 sin(pi x))
//! ```
//!
//! Source of the check: the condensed matrix `A = Q K + S G` is the
//! saddle point's Newton matrix with the multipliers eliminated (Popp, Gee
//! & Wall, IJNME 79 (2009) 1354, §4.3): along a displacement direction
//! `v` with the multipliers moved by the recovery `dlambda = -Y v` (`Y =
//! W^-1 P^T K`), the residual changes by `Q K v` and the gaps by `-G v`,
//! so `A v = d r - S d g` (central differences at a state with active
//! nodes and positive multipliers).

use super::Newton;
use crate::mesh::generate::{generate, Grading, MeshSpec};
use crate::mesh::{CellKind, Mesh};
use crate::model::{ContactFormulation, ContactMethod, LagrangeFormulation, Model};
use crate::solve::dofs::Dof;
use crate::solve::linalg::condensed::CondensedSolver;
use crate::testkit::{ramp, ModelBuilder};

fn block(origin: [f64; 2], nx: usize) -> Mesh {
    generate(&MeshSpec::Rectangle {
        origin,
        size: [1.0, 1.0],
        divisions: [nx, 2],
        grading: [Grading::Uniform, Grading::Uniform],
        kind: CellKind::Quad4,
    })
    .expect("rectangle")
}

fn model() -> Model {
    let b = ModelBuilder::plane_strain()
        .elastic("soft", 1e3, 0.3)
        .body("base", block([0.0, 0.0], 4), "soft")
        .body("top", block([0.0, 1.0], 3), "soft");
    let slave = b.edge_set("top.bottom");
    let master = b.edge_set("base.top");
    let (base_bottom, base_left) = (b.node_set("base.bottom"), b.node_set("base.left"));
    let (top_left, top_top) = (b.node_set("top.left"), b.node_set("top.top"));
    b.fix(base_bottom, 1)
        .fix(base_left, 0)
        .fix(top_left, 0)
        .displace(top_top, 1, ramp(0.0, 1.0, -0.02))
        .contact_surface(
            "top.bottom -> base.top",
            ("top", slave),
            ("base", master),
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Condensed,
            },
        )
        .formulation_of_pair(ContactFormulation::Mortar)
        .step("press", 1.0, 1)
        .build()
}

/// The residual on the free dofs and the constraint gaps at `u` and the
/// pair's multipliers `lambda`.
fn residual(n: &mut Newton<'_>, u: &[[f64; 2]], lambda: &[f64]) -> (Vec<f64>, Vec<f64>) {
    n.u.copy_from_slice(u);
    n.contacts.pairs[0].active.fill(true);
    n.contacts.pairs[0].multiplier.copy_from_slice(lambda);
    n.evaluate(1.0, true).expect("evaluation");
    (n.r_free.clone(), n.contacts.constraints.gap.clone())
}

#[test]
fn condensed_matrix_is_the_derivative_along_the_recovered_multipliers() {
    let m = model();
    let mut n = Newton::new(&m).unwrap();
    // a curved state: the top's bottom bulged into the bent base (the
    // base's 5 x 3 nodes first, then the top's 4 x 3)
    let base_nodes = 15;
    let u: Vec<[f64; 2]> = m
        .mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            if k >= base_nodes {
                [2e-3 * p[0], -0.02 + 0.04 * (p[0] - 0.5).powi(2)]
            } else {
                let bend = (std::f64::consts::PI * p[0]).sin();
                [-1e-3 * p[0] * p[1], 0.01 * bend * p[1]]
            }
        })
        .collect();
    assert_eq!(m.mesh.nodes.len(), base_nodes + 12);
    assert!(
        m.mesh.nodes[base_nodes][1] >= 1.0,
        "the top block's nodes last"
    );
    let slaves = n.contacts.pairs[0].active.len();
    n.contacts.pairs[0].active.fill(true);
    let lambda: Vec<f64> = (0..slaves).map(|i| 5.0 + i as f64).collect();
    residual(&mut n, &u, &lambda);
    residual(&mut n, &u, &lambda); // the pattern grown at the first
    let c = n.contacts.constraints.clone();
    assert_eq!(c.len(), slaves, "every slave node active");
    assert!(!c.symmetric, "mortar rows differ from their columns");
    let pattern = n.scatter.pattern.clone();
    let values = n.values.clone();
    let mut q = CondensedSolver::new();
    q.factorize(&pattern, &values, &c).unwrap();
    // D diagonal but on the last slave segment, which the master covers in
    // part (the top slid 3e-3 farther than the base): one block of 2
    assert_eq!((q.fallbacks, q.largest_block), (0, 2));
    let nf = pattern.n;
    // a direction over the free dofs
    let v: Vec<f64> = (0..nf)
        .map(|f| 1e-3 * ((f as f64 * 1.37).sin() + 0.3))
        .collect();
    let dl = q.recovery(&v);
    let av = q.apply(&v);
    // central differences: the error is round-off above truncation here
    // (measured 4.4e-9 at h = 1e-5, 2.3e-8 at 1e-6, 2.8e-7 at 1e-7)
    let h = 1e-5;
    let mut shifted = |sign: f64| {
        let mut us = u.clone();
        for (node, up) in us.iter_mut().enumerate() {
            for (comp, x) in up.iter_mut().enumerate() {
                if let Dof::Free(f) = n.dofs.dofs[n.dofs.dof(node, comp)] {
                    *x += sign * h * v[f];
                }
            }
        }
        let mut ls = lambda.clone();
        for (k, &(_, i)) in c.owner.iter().enumerate() {
            ls[i] += sign * h * dl[k];
        }
        residual(&mut n, &us, &ls)
    };
    let (rp, gp) = shifted(1.0);
    let (rm, gm) = shifted(-1.0);
    let dr: Vec<f64> = rp
        .iter()
        .zip(&rm)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect();
    let dg: Vec<f64> = gp
        .iter()
        .zip(&gm)
        .map(|(a, b)| (a - b) / (2.0 * h))
        .collect();
    let fd = q.subtract_scaled_pivots(&dr, &dg);
    let scale = av.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    let err = av
        .iter()
        .zip(&fd)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / scale;
    println!("condensed tangent vs FD: {err:.2e} (|A v| {scale:.3e})");
    assert!(err < 1e-7, "condensed tangent vs FD: {err:.2e}");
    // the recovered multipliers keep each active slave node in balance
    // along its multiplier's direction: P^T d r = 0
    let unbalance = c
        .pivots
        .iter()
        .map(|p| p.iter().map(|&(i, w)| w * dr[i]).sum::<f64>().abs())
        .fold(0.0, f64::max)
        / scale;
    println!("P^T d r / |A v|: {unbalance:.2e}");
    // symmetry: the mortar tangent K itself is unsymmetric (`-lambda d(B /
    // A) / dx`), and the condensed matrix more so
    let k_asym = crate::solve::linalg::condensed::asymmetry(&pattern, &values[..pattern.nnz()]);
    println!(
        "|K - K^T| / |K| {k_asym:.2e}, |A - A^T| / |A| {:.2e}",
        q.asymmetry()
    );
    assert!(q.asymmetry() > 1e-3, "the condensed matrix is unsymmetric");
    assert!(unbalance < 1e-7, "P^T dr = {unbalance:.2e}");
}
