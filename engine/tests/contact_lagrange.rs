//! Lagrange multipliers and augmented Lagrangian against rigid tools, in
//! the full solver (seed slides, "Part II – Lagrange multipliers",
//! "Variants – Augmented Lagrangian"), on coarse versions of
//! examples/hertz_cylinder.ctc (flat floor) and
//! examples/cylinder_on_block.ctc (curved tool). Each test prints the
//! Newton residual sequences (`cargo test -- --nocapture`).
//!
//! Reference: Hertz line contact, a = sqrt(4 P R / (pi E*)),
//! p0 = 2 P / (pi a) (VERIFICATION-CASES.md case 1), and the exact
//! constraint g = 0 of the Lagrange solution.

mod support;

use support::lagrange::*;

fn max_abs(v: &[[f64; 2]]) -> f64 {
    v.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()))
}

fn max_diff(a: &[[f64; 2]], b: &[[f64; 2]]) -> f64 {
    a.iter()
        .flatten()
        .zip(b.iter().flatten())
        .fold(0.0f64, |m, (x, y)| m.max((x - y).abs()))
}

#[test]
fn hertz_cylinder_lagrange_has_zero_penetration_and_hertz_pressure() {
    let depth = 0.08;
    let (summary, rec) = solve(
        "hertz lagrange",
        &hertz_disc(lagrange(false), 16, 48, depth, 4),
    );
    assert!(summary.completed);
    for r in &rec.increments {
        // exact constraint: no penetration beyond round-off
        assert!(
            r.max_penetration(0) <= 1e-12 * depth,
            "t={} penetration {:e}",
            r.time,
            r.max_penetration(0)
        );
        // contact force balances the reaction on the flat edge
        let f = r.contact_force(0);
        assert!(
            (f[1] + r.total_reaction()[1]).abs() <= 1e-8 * f[1].abs(),
            "t={}: contact {:?} reaction {:?}",
            r.time,
            f,
            r.total_reaction()
        );
        // lambda >= 0 on every closed node, pressure = force / tributary area
        for c in r.closed(0) {
            assert!(c.force[1] >= 0.0 && c.pressure >= 0.0, "{c:?}");
        }
    }
    let last = rec.increments.last().unwrap();
    let p = last.contact_force(0)[1];
    let p0_fe = last
        .closed(0)
        .iter()
        .map(|c| c.pressure)
        .fold(0.0, f64::max);
    let p0 = hertz_p0(p, HERTZ_R, HERTZ_E);
    let err = (p0_fe - p0).abs() / p0;
    println!("hertz lagrange: P = {p:.5}, p0 FE = {p0_fe:.5}, Hertz p0 = {p0:.5}, error {err:.3}");
    assert!(err < 0.1, "p0 error {err}");
    // symbolic factorization of the saddle-point system reused while the
    // active set is unchanged
    println!(
        "saddle factorizations: {} symbolic, {} numeric",
        summary.saddle_symbolic_factorizations, summary.saddle_factorizations
    );
    assert!(summary.saddle_symbolic_factorizations >= 1);
    assert!(summary.saddle_symbolic_factorizations < summary.saddle_factorizations);
    // the active-set loop ran: nodes introduced in the first increment
    // (none are active at the start)
    assert!(summary.increments[0].contact_iterations >= 1);
}

#[test]
fn hertz_cylinder_single_and_doubled_formulations_agree_to_1e_10() {
    let (_, single) = solve(
        "hertz single",
        &hertz_disc(lagrange(false), 12, 32, 0.08, 3),
    );
    let (_, doubled) = solve(
        "hertz doubled",
        &hertz_disc(lagrange(true), 12, 32, 0.08, 3),
    );
    assert_eq!(single.increments.len(), doubled.increments.len());
    for (a, b) in single.increments.iter().zip(&doubled.increments) {
        let du = max_diff(&a.displacement, &b.displacement) / max_abs(&a.displacement);
        let fa = a.contact_force(0);
        let fb = b.contact_force(0);
        let df = (fa[1] - fb[1]).abs() / fa[1].abs();
        let dl = a.contact[0]
            .iter()
            .zip(&b.contact[0])
            .map(|(x, y)| (x.force[1] - y.force[1]).abs())
            .fold(0.0, f64::max)
            / fa[1].abs();
        println!(
            "t={}: |du|/|u| = {du:.1e}, |dP|/P = {df:.1e}, max |dlambda|/P = {dl:.1e}",
            a.time
        );
        assert!(
            du <= 1e-10 && df <= 1e-10 && dl <= 1e-10,
            "{du:e} {df:e} {dl:e}"
        );
        assert_eq!(a.closed(0).len(), b.closed(0).len());
    }
}

#[test]
fn cylinder_on_block_lagrange_exact_and_quadratic_on_a_curved_tool() {
    let depth = 0.02;
    let (summary, rec) = solve(
        "cylinder lagrange",
        &cylinder_on_block(lagrange(false), 32, 16, depth, 4),
    );
    assert!(summary.completed);
    for (r, inc) in rec.increments.iter().zip(&summary.increments) {
        assert!(
            r.max_penetration(0) <= 1e-12 * depth,
            "{:e}",
            r.max_penetration(0)
        );
        let f = r.contact_force(0);
        assert!(
            (f[1] + r.total_reaction()[1]).abs() <= 1e-8 * f[1].abs(),
            "{f:?} {:?}",
            r.total_reaction()
        );
        // the curvature term keeps Newton quadratic: each Newton loop
        // reaches 1e-10 from ~1e-4 in at most two more iterations
        assert!(
            inc.iterations <= 3 * (inc.contact_iterations + 1),
            "{} iterations for {} loops",
            inc.iterations,
            inc.contact_iterations + 1
        );
    }
}

#[test]
fn cylinder_on_block_augmented_lagrangian_below_tolerance_and_agrees_with_lagrange() {
    let depth = 0.02;
    let tol = 1e-7;
    let (_, lag) = solve(
        "cylinder lagrange",
        &cylinder_on_block(lagrange(false), 32, 16, depth, 2),
    );
    let p_lag = lag.increments.last().unwrap().contact_force(0)[1];
    for newton in [false, true] {
        let label = if newton { "AL newton" } else { "AL converged" };
        let (summary, al) = solve(
            label,
            &cylinder_on_block(augmented(2e4, tol, newton), 32, 16, depth, 2),
        );
        assert!(summary.completed);
        for (r, inc) in al.increments.iter().zip(&summary.increments) {
            assert!(
                r.max_penetration(0) < tol,
                "{label}: {:e}",
                r.max_penetration(0)
            );
            assert!((inc.max_penetration - r.max_penetration(0)).abs() < 1e-15);
            // Uzawa iterations were needed (alpha alone would penetrate ~ p / alpha)
            assert!(
                inc.contact_iterations >= 2,
                "{label}: {}",
                inc.contact_iterations
            );
            let f = r.contact_force(0);
            assert!((f[1] + r.total_reaction()[1]).abs() <= 1e-8 * f[1].abs());
        }
        let last = al.increments.last().unwrap();
        let p = last.contact_force(0)[1];
        let du = max_diff(
            &last.displacement,
            &lag.increments.last().unwrap().displacement,
        ) / depth;
        println!("{label}: P = {p:.6} vs Lagrange {p_lag:.6}; max |u_AL - u_L| / depth = {du:.1e}");
        // penetration below 1e-7 = 5e-6 of the indentation: the solutions agree
        assert!((p - p_lag).abs() <= 1e-4 * p_lag.abs(), "{p} vs {p_lag}");
        assert!(du <= 1e-4, "{du}");
    }
}

#[test]
fn cylinder_on_block_penalty_penetrates_p_over_k_where_lagrange_does_not() {
    let depth = 0.02;
    let (_, lag) = solve(
        "cylinder lagrange",
        &cylinder_on_block(lagrange(false), 32, 16, depth, 2),
    );
    let p_max = lag
        .increments
        .last()
        .unwrap()
        .closed(0)
        .iter()
        .map(|c| c.pressure)
        .fold(0.0, f64::max);
    for k in [2e4, 2e5] {
        let (_, pen) = solve(
            "cylinder penalty",
            &cylinder_on_block(penalty(k), 32, 16, depth, 2),
        );
        let g = pen.increments.last().unwrap().max_penetration(0);
        let ratio = g / (p_max / k);
        println!("penalty k = {k:e}: max penetration {g:.3e}, p_max(Lagrange) / k = {:.3e}, ratio {ratio:.3}", p_max / k);
        assert!((0.8..1.1).contains(&ratio), "k={k}: ratio {ratio}");
    }
}

#[test]
fn hertz_cylinder_augmented_lagrangian_and_penalty_against_lagrange() {
    let depth = 0.08;
    let tol = 1e-6;
    let (_, lag) = solve(
        "hertz lagrange",
        &hertz_disc(lagrange(false), 12, 32, depth, 2),
    );
    let l = lag.increments.last().unwrap();
    let p_lag = l.contact_force(0)[1];
    let p0_lag = l.closed(0).iter().map(|c| c.pressure).fold(0.0, f64::max);
    for newton in [false, true] {
        let (summary, al) = solve(
            "hertz AL",
            &hertz_disc(augmented(2e3, tol, newton), 12, 32, depth, 2),
        );
        for (r, inc) in al.increments.iter().zip(&summary.increments) {
            assert!(r.max_penetration(0) < tol, "{:e}", r.max_penetration(0));
            assert!(inc.contact_iterations >= 1);
            let f = r.contact_force(0);
            assert!((f[1] + r.total_reaction()[1]).abs() <= 1e-8 * f[1].abs());
        }
        let p = al.increments.last().unwrap().contact_force(0)[1];
        println!("hertz AL (newton update: {newton}): P = {p:.7} vs Lagrange {p_lag:.7}");
        // penetration < 1e-6 = 1.25e-5 of the indentation
        assert!((p - p_lag).abs() <= 1e-4 * p_lag, "{p} vs {p_lag}");
    }
    // penalty: penetration ~ p / k, and softer than Lagrange
    let k = 2e4;
    let (_, pen) = solve("hertz penalty", &hertz_disc(penalty(k), 12, 32, depth, 2));
    let last = pen.increments.last().unwrap();
    let ratio = last.max_penetration(0) / (p0_lag / k);
    println!("hertz penalty k = {k:e}: penetration / (p0 / k) = {ratio:.3}");
    assert!((0.8..1.1).contains(&ratio), "{ratio}");
    assert!(last.contact_force(0)[1] < p_lag);
}
