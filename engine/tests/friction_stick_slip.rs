//! VERIFICATION-CASES case 4, plain stick/slip: a block pressed on a rigid
//! plane with `N` and pulled tangentially with `Q` sticks for `Q < mu N` and
//! slides for `Q > mu N`; the work dissipated by friction is `mu N x slip`.

mod support;

use ctc_engine::contact::friction::FrictionStatus;
use ctc_engine::model::{ContactMethod, LagrangeFormulation};
use support::friction::{count, solve, Block, Drive};

const MU: f64 = 0.3;
const N: f64 = 100.0;

#[test]
fn pulled_block_sticks_below_mu_n() {
    let q = 0.9 * MU * N;
    let mut b = Block::new(0.0, MU, Drive::Force(q));
    // nu = 0: pressing does not spread the base (no slip at the edges)
    b.poisson = 0.0;
    let (rec, _) = solve(&b).unwrap_or_else(|e| panic!("{e}"));
    let last = rec.rows.last().unwrap();
    assert_eq!(
        count(&last.contact, FrictionStatus::Stick),
        last.contact.len()
    );
    let rt: f64 = last
        .contact
        .iter()
        .map(|c| c.friction.tangential_force)
        .sum();
    // t = (n_y, -n_x) = (1, 0): the friction force holds the pull
    assert!((rt + q).abs() < 1e-8 * q, "sum R_T = {rt}, Q = {q}");
    let dissipated: f64 = rec.rows.iter().map(|r| r.dissipation).sum();
    assert_eq!(dissipated, 0.0);
}

#[test]
fn pulled_block_slides_above_mu_n() {
    // force control: above mu N there is no equilibrium (the block slides
    // away): the run stops with a diagnosis instead of a wrong answer
    let b = Block::new(0.0, MU, Drive::Force(1.1 * MU * N));
    let err = solve(&b).err().expect("no static equilibrium above mu N");
    assert!(err.contains("push"), "{err}");
}

/// Displacement-driven pull `d` (drive `drive`): the pull force plateaus at
/// `mu N` once all base nodes slide, and over the increments of steady
/// sliding the dissipated work is `mu N` times the slip of the base.
/// Returns (plateau error, sliding-phase energy error, whole-run energy
/// error against `mu N (u_base - u_elastic)`, meaningful when every node
/// starts slipping at once).
fn pulled_block_energy(
    method: ContactMethod,
    squeeze: Option<f64>,
    drive: Drive,
) -> (f64, f64, f64) {
    let mut b = Block::new(0.0, MU, drive);
    b.method = method;
    b.squeeze = squeeze;
    b.increments = 10;
    b.poisson = 0.0;
    let (rec, _) = solve(&b).unwrap_or_else(|e| panic!("{e}"));
    let last = rec.rows.last().unwrap();
    let all_slip =
        |r: &support::friction::Row| count(&r.contact, FrictionStatus::Slip) == r.contact.len();
    assert!(all_slip(last));
    let n = match squeeze {
        Some(_) => -last.lift,
        None => N,
    };
    let plateau_err = (last.push - MU * n).abs() / (MU * n);
    // steady sliding: from the first increment after which every increment slides
    let k0 = (0..rec.rows.len())
        .rev()
        .take_while(|&k| all_slip(&rec.rows[k]))
        .last()
        .unwrap();
    let slip = last.bottom_ux - rec.rows[k0].bottom_ux;
    let sliding: f64 = rec.rows[k0 + 1..].iter().map(|r| r.dissipation).sum();
    let sliding_err = (sliding - MU * n * slip).abs() / (MU * n * slip);
    // whole run: slip = base displacement minus the elastic tangential gap
    let c = &last.contact[0];
    let total_slip = last.bottom_ux - (c.friction.tangential_gap - c.friction.slip);
    let dissipated: f64 = rec.rows.iter().map(|r| r.dissipation).sum();
    let total_err = (dissipated - MU * n * total_slip).abs() / (MU * n * total_slip);
    println!(
        "{drive:?}: N = {n:.6}, Q/(mu N) - 1 = {plateau_err:.1e}; steady sliding over {} \
         increments: work {sliding:.9e} vs mu N slip {:.9e}: rel. error {sliding_err:.1e}; \
         whole run: {dissipated:.9e} vs {:.9e}: {total_err:.1e}",
        rec.rows.len() - 1 - k0,
        MU * n * slip,
        MU * n * total_slip
    );
    (plateau_err, sliding_err, total_err)
}

#[test]
fn pulled_block_friction_work_is_mu_n_slip() {
    let penalty = ContactMethod::Penalty {
        kind: ctc_engine::model::PenaltyKind::Area,
        stiffness: 1e7,
    };
    // rigid translation of the block: every base node starts slipping at once
    let (p, e, t) = pulled_block_energy(penalty.clone(), None, Drive::AllNodes(0.01));
    assert!(
        p < 1e-8 && e < 1e-8 && t < 1e-8,
        "plateau {p}, energy {e}, {t}"
    );
    // the base nodes free (Lagrange needs free tangential dofs at the contact)
    for (method, squeeze) in [
        (penalty, None),
        (
            ContactMethod::Lagrange {
                formulation: LagrangeFormulation::Single,
            },
            Some(1e-3),
        ),
    ] {
        let (p, e, _) = pulled_block_energy(method, squeeze, Drive::AboveBase(0.01));
        assert!(p < 1e-8 && e < 1e-8, "plateau {p}, energy {e}");
    }
}
