//! VERIFICATION-CASES case 7 at kernel level: penalty scaling with the mesh.
//!
//! Slave nodes on a rigid floor, loaded by the consistent nodal forces of a
//! uniform pressure p (computed here independently by Gauss quadrature of
//! `p N_a` along the edges, times thickness or `2 pi r`), each node brought
//! to equilibrium with its contact force by Newton iterations that use the
//! contact force and tangent of `evaluate_pair`.
//! - area penalty k (pressure per unit gap): gap = -p / k at every node, for
//!   every mesh (uniform, graded, axisymmetric with a node on the axis);
//! - nodal penalty alpha (force per unit gap): gap = -p A_node / alpha, so
//!   halving h halves the gap, and halving alpha with h restores it.

mod support;

use ctc_engine::contact::{evaluate_pair, PairState};
use ctc_engine::model::{AnalysisKind, ContactMethod, ToolGeometry, ToolMotion};
use std::f64::consts::PI;
use support::contact::{area, nodal, surface_model};

/// Consistent nodal loads of a uniform pressure `p` on the edges
/// (2-point Gauss: exact for the linear x linear axisymmetric integrand).
fn pressure_loads(
    kind: AnalysisKind,
    thickness: f64,
    nodes: &[[f64; 2]],
    edges: &[[usize; 2]],
    p: f64,
) -> Vec<f64> {
    let mut f = vec![0.0; nodes.len()];
    let g = 0.5 / 3f64.sqrt();
    for &[a, b] in edges {
        let (pa, pb) = (nodes[a], nodes[b]);
        let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        for s in [0.5 - g, 0.5 + g] {
            let r = pa[0] + s * (pb[0] - pa[0]);
            let w = match kind {
                AnalysisKind::Axisymmetric => 2.0 * PI * r,
                _ => thickness,
            };
            f[a] += 0.5 * len * p * (1.0 - s) * w;
            f[b] += 0.5 * len * p * s * w;
        }
    }
    f
}

/// Equilibrium gaps of every node under the pressure loads.
fn equilibrium_gaps(
    kind: AnalysisKind,
    thickness: f64,
    xs: &[f64],
    method: ContactMethod,
    p: f64,
) -> Vec<f64> {
    let nodes: Vec<[f64; 2]> = xs.iter().map(|&x| [x, 0.0]).collect();
    // Body above the floor: edges walk in +x (body on the left).
    let edges: Vec<[usize; 2]> = (0..xs.len() - 1).map(|i| [i, i + 1]).collect();
    let load = pressure_loads(kind, thickness, &nodes, &edges, p);
    let model = surface_model(
        kind,
        thickness,
        nodes.clone(),
        edges,
        ToolGeometry::Plane {
            point: [0.0, 0.0],
            normal: [0.0, 1.0],
        },
        ToolMotion::fixed(),
        method,
        Some(1.0),
    );
    let mut state = PairState::new(&model, 0);
    let mut x: Vec<[f64; 2]> = nodes.iter().map(|p| [p[0], -1e-9]).collect();
    for _ in 0..5 {
        let out = evaluate_pair(&model, 0, &x, 0.0, &mut state);
        assert_eq!(out.len(), xs.len());
        for c in &out {
            // Residual (external + contact) along y; Newton: y += R / K.
            let r = -load[c.node] + c.force[1];
            x[c.node][1] += r / c.stiffness[1][1];
        }
    }
    let out = evaluate_pair(&model, 0, &x, 0.0, &mut state);
    for c in &out {
        let r = -load[c.node] + c.force[1];
        assert!(
            r.abs() <= 1e-10 * load[c.node].abs().max(1e-300),
            "residual {r:e}"
        );
    }
    out.iter().map(|c| c.gap).collect()
}

fn uniform(n: usize, x0: f64, x1: f64) -> Vec<f64> {
    (0..=n)
        .map(|i| x0 + (x1 - x0) * i as f64 / n as f64)
        .collect()
}

fn graded(n: usize, x0: f64, x1: f64, ratio: f64) -> Vec<f64> {
    let w: Vec<f64> = (0..n).map(|i| ratio.powi(i as i32)).collect();
    let total: f64 = w.iter().sum();
    let mut xs = vec![x0];
    for wi in w {
        let last = *xs.last().unwrap();
        xs.push(last + (x1 - x0) * wi / total);
    }
    xs
}

#[test]
fn contact_penalty_area_gap_equals_p_over_k_mesh_independent() {
    let (p, k) = (3.0e2, 1.0e6);
    let mut worst = 0.0f64;
    for (kind, xs) in [
        (AnalysisKind::PlaneStrain, uniform(4, -1.0, 1.0)),
        (AnalysisKind::PlaneStrain, uniform(32, -1.0, 1.0)),
        (AnalysisKind::PlaneStrain, graded(17, -1.0, 1.0, 1.3)),
        (AnalysisKind::PlaneStress, graded(9, 0.0, 3.0, 0.7)),
        (AnalysisKind::Axisymmetric, uniform(10, 0.0, 1.0)),
        (AnalysisKind::Axisymmetric, graded(13, 0.0, 2.0, 1.4)),
        (AnalysisKind::Axisymmetric, graded(6, 0.5, 1.5, 0.6)),
    ] {
        let gaps = equilibrium_gaps(kind, 2.5, &xs, area(k), p);
        for g in gaps {
            worst = worst.max((g + p / k).abs() / (p / k));
        }
    }
    println!("area penalty: worst relative deviation of the gap from -p/k: {worst:.2e}");
    assert!(worst < 1e-12, "{worst:e}");
}

#[test]
fn contact_penalty_nodal_gap_scales_with_h() {
    let (p, alpha, t) = (3.0e2, 1.0e6, 2.5);
    let coarse = equilibrium_gaps(
        AnalysisKind::PlaneStrain,
        t,
        &uniform(8, -1.0, 1.0),
        nodal(alpha),
        p,
    );
    let fine = equilibrium_gaps(
        AnalysisKind::PlaneStrain,
        t,
        &uniform(16, -1.0, 1.0),
        nodal(alpha),
        p,
    );
    let fine_half_alpha = equilibrium_gaps(
        AnalysisKind::PlaneStrain,
        t,
        &uniform(16, -1.0, 1.0),
        nodal(alpha / 2.0),
        p,
    );
    // Interior node gap = -p h t / alpha.
    let h = 0.25;
    let (gc, gf, gh) = (coarse[4], fine[8], fine_half_alpha[8]);
    println!(
        "nodal penalty: gap h={h}: {gc:.6e}, h/2: {gf:.6e} (ratio {:.6}), h/2 with alpha/2: {gh:.6e}",
        gf / gc
    );
    assert!((gc + p * h * t / alpha).abs() < 1e-12 * gc.abs());
    assert!((gf / gc - 0.5).abs() < 1e-12);
    assert!((gh / gc - 1.0).abs() < 1e-12);
    // End nodes carry half the tributary length: half the gap.
    assert!((coarse[0] / gc - 0.5).abs() < 1e-12);
}

#[test]
fn contact_tributary_areas_plane_and_axisymmetric() {
    let nodes = vec![[0.0, 0.0], [1.0, 0.0], [3.0, 0.0]];
    let edges = vec![[0, 1], [1, 2]];
    let plane = ToolGeometry::Plane {
        point: [0.0, 0.0],
        normal: [0.0, 1.0],
    };
    let m = surface_model(
        AnalysisKind::PlaneStrain,
        2.0,
        nodes.clone(),
        edges.clone(),
        plane.clone(),
        ToolMotion::fixed(),
        area(1.0),
        None,
    );
    assert_eq!(PairState::new(&m, 0).tributary, vec![1.0, 3.0, 2.0]);
    let m = surface_model(
        AnalysisKind::Axisymmetric,
        2.0,
        nodes,
        edges,
        plane,
        ToolMotion::fixed(),
        area(1.0),
        None,
    );
    let a = PairState::new(&m, 0).tributary;
    // Exact: integral of N_a 2 pi r over each edge; the axis node keeps a
    // non-zero area; the sum is the disc area pi * 3^2.
    let expected = [
        2.0 * PI * (0.0 + 1.0) / 6.0,
        2.0 * PI * (2.0 / 6.0 + 2.0 * (2.0 + 3.0) / 6.0),
        2.0 * PI * 2.0 * (1.0 + 6.0) / 6.0,
    ];
    for (got, exp) in a.iter().zip(expected) {
        assert!((got - exp).abs() < 1e-12, "{got} vs {exp}");
    }
    assert!((a.iter().sum::<f64>() - 9.0 * PI).abs() < 1e-12);
    // Default prof: the largest slave edge (2.0).
    assert_eq!(PairState::new(&m, 0).prof, 2.0);
}
