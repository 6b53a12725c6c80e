//! The catalogue of verification cases run by `ctc verify`.
//!
//! Tolerances are relative errors per refinement level (level 0 first).
//! They are set from the measured errors (quoted next to each case) with a
//! margin, and the finest default level of the Hertz cases carries the
//! issue requirement: a and p0 within 2 %. The contact force must balance
//! the reactions to the Newton tolerance at every level; the patch tests
//! are exact to round-off.

use crate::analytical::lame::{EndCondition, ThickCylinder};
use crate::analytical::patch::{PatchKind, PenaltyPatch};
use crate::case::{Case, Check, Quantity, Reference};
use crate::profile::Abscissa;

/// Force balance tolerance: the residual is converged to 1e-10 relative.
const BALANCE: f64 = 1e-7;

/// Patch tests are exact: round-off and Newton tolerance only.
const EXACT: f64 = 1e-7;

/// All cases, in report order.
pub fn all() -> Vec<Case> {
    vec![
        hertz_cylinder(),
        rigid_cylinder(),
        hertz_sphere(),
        lame_plane_strain(),
        lame_axisymmetric(),
        patch_plane_strain(),
        patch_axisymmetric(),
        hertz_two_cylinders(),
        hertz_two_cylinders_mortar(),
        hertz_two_spheres_mortar(),
        hertz_two_cylinders_nts_nonmatching(),
        hertz_two_cylinders_nts_smoothed(),
        hertz_two_spheres_nts_smoothed(),
        hertz_two_cylinders_nts_lagrange(),
    ]
}

/// Hertz contact checks shared by the three Hertz cases: per-level
/// tolerances on a (both estimators), p0 and the L2 error of p(x), the
/// force balance, and optionally a minimum observed rate of the L2 error.
fn hertz_checks(
    a: &[f64],
    a_moment: &[f64],
    p0: &[f64],
    l2: &[f64],
    l2_rate: Option<f64>,
) -> Vec<Check> {
    let mut l2 = Check::new(Quantity::PressureL2, l2);
    l2.min_rate = l2_rate;
    vec![
        Check::new(Quantity::HalfWidth, a),
        Check::new(Quantity::HalfWidthMoment, a_moment),
        Check::new(Quantity::PeakPressure, p0),
        Check::new(Quantity::ContactForce, &[BALANCE]),
        l2,
    ]
}

/// Elastic quarter cylinder on a rigid plane.
pub fn hertz_cylinder() -> Case {
    Case {
        name: "hertz_cylinder",
        title: "Hertz: elastic cylinder on a rigid plane, plane strain (quarter model)",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3",
        deck: "hertz_cylinder.ctc",
        tags: &[
            "contact",
            "hertz",
            "penalty",
            "plane_strain",
            "closed_form",
            "rate",
        ],
        levels: 4,
        reference: Reference::HertzCylinder {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
            axis: 0.0,
            half_model: true,
            abscissa: Abscissa::Reference,
        },
        // Measured (levels 0-3): a 1.2e-2 9.4e-3 4.1e-3 2.3e-3; a (moment)
        // 2.5e-2 1.0e-2 3.2e-3 1.5e-3; p0 2.5e-2 1.4e-2 6.8e-3 3.3e-3;
        // L2 8.5e-2 4.6e-2 2.4e-2 1.2e-2 (rate ~0.9).
        checks: hertz_checks(
            &[0.05, 0.03, 0.02, 0.02],
            &[0.06, 0.03, 0.02, 0.02],
            &[0.05, 0.03, 0.02, 0.02],
            &[0.15, 0.08, 0.05, 0.03],
            Some(0.7),
        ),
    }
}

/// Two identical elastic quarter cylinders pressed together (node-to-segment
/// contact between deformable bodies, non-matching arcs).
pub fn hertz_two_cylinders() -> Case {
    Case {
        name: "hertz_two_cylinders",
        title:
            "Hertz: two elastic cylinders, node-to-segment contact, plane strain (quarter models)",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3 (E*, R combined)",
        deck: "hertz_two_cylinders.ctc",
        tags: &[
            "contact",
            "hertz",
            "node_to_segment",
            "penalty",
            "plane_strain",
            "closed_form",
            "rate",
        ],
        levels: 3,
        // identical cylinders: a and p0 of one cylinder (E, nu, R) on a
        // rigid plane under the same load
        reference: Reference::HertzCylinder {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
            axis: 0.0,
            half_model: true,
            abscissa: Abscissa::Reference,
        },
        // Measured (levels 0-2): a 1.3e-2 1.0e-2 4.7e-3; a (moment) 2.6e-2
        // 1.1e-2 3.6e-3; p0 2.6e-2 1.4e-2 7.3e-3; L2 8.5e-2 4.6e-2 2.4e-2
        // (rate ~0.9). With non-matching arcs (gradings 0.02 / 0.03) a and
        // L2 still converge but p0 plateaus at ~8 %: the single-pass
        // patch-test defect at the axis node.
        checks: hertz_checks(
            &[0.03, 0.02, 0.01],
            &[0.04, 0.02, 0.01],
            &[0.04, 0.02, 0.012],
            &[0.12, 0.07, 0.04],
            Some(0.7),
        ),
    }
}

/// The reference of the two-cylinder cases.
fn two_cylinders_reference() -> Reference {
    Reference::HertzCylinder {
        young: 1e3,
        poisson: 0.3,
        radius: 1.0,
        pair: 0,
        axis: 0.0,
        half_model: true,
        abscissa: Abscissa::Reference,
    }
}

/// Two identical elastic quarter cylinders on non-matching arcs, mortar
/// segment-to-segment contact.
pub fn hertz_two_cylinders_mortar() -> Case {
    Case {
        name: "hertz_two_cylinders_mortar",
        title: "Hertz: two elastic cylinders, non-matching arcs, mortar contact, plane strain",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3 (E*, R combined)",
        deck: "hertz_two_cylinders_mortar.ctc",
        tags: &[
            "contact",
            "hertz",
            "mortar",
            "two_bodies",
            "penalty",
            "plane_strain",
            "closed_form",
            "rate",
        ],
        levels: 3,
        reference: two_cylinders_reference(),
        // Measured (levels 0-2, dual multipliers, pressure per reference
        // area): a 1.9e-2 1.4e-2 5.9e-3; a (moment) 2.6e-2 1.0e-2 3.6e-3;
        // p0 3.1e-2 1.7e-2 9.4e-3 (rate 0.85); L2 8.4e-2 4.5e-2 2.3e-2
        // (rate 0.9). Level 3 (`--max-level 3`, 17,556 dofs, 20 s dev):
        // a (moment) 1.8e-3, p0 5.3e-3, L2 1.1e-2. Standard multipliers on
        // the same meshes gave p0 21 % / 3.1 % / 1.5 %, L2 24 % / 9.4 % /
        // 4.6 %; the pressure per current area (the slave surface
        // contracts ~2 % under p0 = 42 with E = 1e3) gave p0 +2.4 % at
        // every level (a plateau against Hertz's profile in reference
        // coordinates). The finest default level carries issue 18's 2 %.
        checks: hertz_checks(
            &[0.03, 0.02, 0.01],
            &[0.04, 0.015, 0.006],
            &[0.045, 0.025, 0.02],
            &[0.12, 0.065, 0.035],
            Some(0.7),
        ),
    }
}

/// Two identical elastic spheres (axisymmetric) on non-matching arcs,
/// mortar segment-to-segment contact with dual multipliers.
pub fn hertz_two_spheres_mortar() -> Case {
    Case {
        name: "hertz_two_spheres_mortar",
        title: "Hertz: two elastic spheres, non-matching arcs, mortar contact, axisymmetric",
        source: "VERIFICATION-CASES.md §2; Johnson, Contact Mechanics §4.2 (E*, R combined)",
        deck: "hertz_two_spheres_mortar.ctc",
        tags: &[
            "contact",
            "hertz",
            "mortar",
            "two_bodies",
            "penalty",
            "axisymmetric",
            "closed_form",
        ],
        levels: 3,
        // identical spheres: a and p0 of one sphere (E, nu, R) on a rigid
        // plane under the same load
        reference: Reference::HertzSphere {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
        },
        // Measured (levels 0-2): a 2.8e-2 4.9e-3 5.2e-4; a (moment) 1.8e-2
        // 1.2e-2 2.3e-3; p0 6.7e-3 5.4e-3 1.9e-3; L2 9.3e-2 3.5e-2 1.5e-2
        // (rates 1.4, 1.1); 2.6 s dev for the three levels
        checks: hertz_checks(
            &[0.04, 0.01, 0.005],
            &[0.03, 0.02, 0.005],
            &[0.015, 0.01, 0.005],
            &[0.14, 0.05, 0.025],
            Some(0.8),
        ),
    }
}

/// The same deck with node-to-segment contact (guarded, not improved).
pub fn hertz_two_cylinders_nts_nonmatching() -> Case {
    Case {
        name: "hertz_two_cylinders_nts_nonmatching",
        title: "Hertz: two elastic cylinders, non-matching arcs, node-to-segment (single pass)",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3 (E*, R combined)",
        deck: "hertz_two_cylinders_nts_nonmatching.ctc",
        tags: &[
            "contact",
            "hertz",
            "node_to_segment",
            "penalty",
            "plane_strain",
            "closed_form",
        ],
        levels: 3,
        reference: two_cylinders_reference(),
        // Measured (levels 0-2): a 4.0e-2 2.5e-2 1.0e-2; a (moment) 2.7e-2
        // 1.0e-2 3.7e-3; p0 8.9e-2 8.5e-2 8.4e-2 (the plateau, low); L2
        // 8.6e-2 4.8e-2 2.7e-2
        checks: hertz_checks(
            &[0.05, 0.03, 0.015],
            &[0.04, 0.015, 0.006],
            &[0.11, 0.1, 0.1],
            &[0.11, 0.06, 0.035],
            None,
        ),
    }
}

/// The same deck, node-to-segment modified double pass with nodal normal
/// smoothing (the interface pressure of `contact::interface_pressures`).
pub fn hertz_two_cylinders_nts_smoothed() -> Case {
    Case {
        name: "hertz_two_cylinders_nts_smoothed",
        title: "Hertz: two elastic cylinders, non-matching arcs, node-to-segment modified double \
                pass, nodal normal smoothing",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3 (E*, R combined)",
        deck: "hertz_two_cylinders_nts_smoothed.ctc",
        tags: &[
            "contact",
            "hertz",
            "node_to_segment",
            "smoothing",
            "penalty",
            "plane_strain",
            "closed_form",
        ],
        levels: 3,
        reference: two_cylinders_reference(),
        // Measured (`ctc verify hertz_two_cylinders_nts_smoothed --max-level
        // 2`, release): a 1.6e-1 2.1e-2 3.9e-2 (the last top node closed:
        // the edge within one cell, 0.0067 = 8.8 % of a at level 2, no
        // rate); a (moment) 4.3e-2 1.2e-2 4.2e-3; p0 3.5e-2 2.1e-2 1.7e-2
        // (high; rates 0.73, 0.33); L2 8.9e-2 4.6e-2 2.5e-2 (rates 0.94,
        // 0.91); Newton 26 / 28 / 35.
        //
        // Why not the double pass (`strategy = double_pass`, this deck until
        // issue 18's fix): it swaps the sides at every converged increment,
        // so the last (5th) increment is a single pass with the top arc as
        // slave, bit for bit; p0 8.85e-2 8.45e-2 8.34e-2 low, a plateau.
        // Level 2 (`ctc run` of the deck, contact CSV of the last
        // increment): slave pressures -8.3 % at the axis, +1.9 / +3.2 /
        // +2.1 / -4.9 % on the next nodes: the node-to-segment patch-test
        // defect (a slave node's force lands on the master nodes by the
        // shape functions at its foot, not by the master's tributary
        // areas: the top axis node projects onto the bottom axis node,
        // whose nodal traction is +12 %, so it sinks and the axis gap, k g,
        // is 11 % short). The modified double pass carries half the load
        // by each pass; its per-pass pressure oscillates the same way
        // (-14 % at the axis), but the nodal traction of each node (its
        // total contact force as slave and master over its full area) is
        // smooth: -1.3 % .. +1.8 % off Hertz on both arcs except the top
        // axis node, +4.7 % (the two axis nodes coincide, so their gaps
        // are equal and their loads split by area); averaged with the
        // other arc's tractions at the foot point (the reported pressure)
        // +1.7 % at the axis, within 1 % elsewhere.
        checks: hertz_checks(
            &[0.2, 0.03, 0.05],
            &[0.05, 0.015, 0.006],
            &[0.04, 0.025, 0.02],
            &[0.1, 0.055, 0.03],
            Some(0.7),
        ),
    }
}

/// The axisymmetric twin of `hertz_two_cylinders_nts_smoothed`: the deck of
/// `hertz_two_spheres_mortar` with node-to-segment contact, modified double
/// pass and nodal normal smoothing.
pub fn hertz_two_spheres_nts_smoothed() -> Case {
    Case {
        name: "hertz_two_spheres_nts_smoothed",
        title: "Hertz: two elastic spheres, non-matching arcs, node-to-segment modified double \
                pass, nodal normal smoothing, axisymmetric",
        source: "VERIFICATION-CASES.md §2; Johnson, Contact Mechanics §4.2 (E*, R combined)",
        deck: "hertz_two_spheres_nts_smoothed.ctc",
        tags: &[
            "contact",
            "hertz",
            "node_to_segment",
            "smoothing",
            "two_bodies",
            "penalty",
            "axisymmetric",
            "closed_form",
        ],
        levels: 3,
        reference: Reference::HertzSphere {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
        },
        // Measured (`ctc verify hertz_two_spheres_nts_smoothed --max-level
        // 2 -j 1`, debug, 1.4 s CPU for the three levels): a 1.5e-1 3.0e-2
        // 2.6e-3 (the last closed node: the edge within one cell, as for
        // the cylinders); a (moment) 3.2e-2 1.4e-2 2.8e-3 (rates 1.18,
        // 2.11); p0 4.2e-3 1.1e-2 1.1e-2 (high, no rate: a plateau at +1.1
        // %); L2 9.9e-2 4.0e-2 1.6e-2 (rates 1.30, 1.20); Newton 26 / 32 /
        // 42 (40 before the axis nodes' nodal normals were mirrored,
        // `ctc_engine::contact::symmetry`: they now project exactly onto
        // each other, the force along the axis, and p0 did not move, the
        // axis node's pressure 50.66816 -> 50.66813 at level 2: the
        // plateau is not the normal's). Where the plateau is (level 2,
        // `ctc run` of the deck refined to radial 32, circumferential 64,
        // the contact CSV of the last increment): the two axis nodes
        // coincide and carry the reported
        // peak, +1.1 % over Hertz (the cylinders' +1.7 %: equal gaps, loads
        // split by area); every other interface pressure of the first 12
        // is within -1.0 % .. -0.2 % of Hertz's at its radius. Issue 18's 2
        // % at the finest level holds.
        checks: hertz_checks(
            &[0.2, 0.04, 0.01],
            &[0.04, 0.02, 0.005],
            &[0.01, 0.015, 0.015],
            &[0.12, 0.05, 0.02],
            Some(1.0),
        ),
    }
}

/// The smoothed modified-double-pass deck with Lagrange multipliers:
/// two curved deformable bodies with exact enforcement (issue 18, the
/// redundant rows of the two passes dropped, `contact::redundancy`).
pub fn hertz_two_cylinders_nts_lagrange() -> Case {
    Case {
        name: "hertz_two_cylinders_nts_lagrange",
        title: "Hertz: two elastic cylinders, non-matching arcs, node-to-segment modified double \
                pass, nodal normal smoothing, Lagrange multipliers",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3 (E*, R combined)",
        deck: "hertz_two_cylinders_nts_lagrange.ctc",
        tags: &[
            "contact",
            "hertz",
            "node_to_segment",
            "smoothing",
            "lagrange",
            "plane_strain",
            "closed_form",
        ],
        levels: 3,
        reference: two_cylinders_reference(),
        // Measured (`ctc verify hertz_two_cylinders_nts --max-level 2 -j 1`,
        // debug): a 1.7e-1 2.1e-2 4.2e-2 (the last closed node decides, as
        // with the penalty); a (moment) 4.3e-2 1.3e-2 4.3e-3; p0 3.7e-2
        // 1.6e-2 8.4e-3 (the penalty deck: 3.5e-2 2.1e-2 1.7e-2; rates 1.22,
        // 0.90); L2 8.8e-2 4.6e-2 2.5e-2 (rates 0.92, 0.91); force balance
        // 4.4e-13. Newton iterations 62 / 228 / 181 against the penalty's
        // 26 / 28 / 35 with the active-set loop around Newton (7 / 12 / 18
        // Newton loops of 3-5 iterations in the first increment); with the
        // semi-smooth active set inside Newton (`contact::semismooth`, same
        // command) **29 / 47 / 70**, the same a, p0, L2 to 3 digits, force
        // balance 4.7e-13 / 7.4e-14 / 2.8e-13 (15 s at level 2, was 54). One
        // row dropped per evaluation (the two axis nodes coincide;
        // `CTC_LOG=debug`).
        checks: hertz_checks(
            &[0.2, 0.03, 0.05],
            &[0.05, 0.015, 0.006],
            &[0.045, 0.02, 0.011],
            &[0.1, 0.055, 0.03],
            Some(0.7),
        ),
    }
}

/// Rigid circle tool pushed into an elastic block.
pub fn rigid_cylinder() -> Case {
    Case {
        name: "rigid_cylinder_block",
        title: "Hertz: rigid cylinder tool pushed into an elastic block, plane strain (half model)",
        source: "VERIFICATION-CASES.md §1; Johnson, Contact Mechanics §4.3",
        deck: "rigid_cylinder_block.ctc",
        tags: &["contact", "hertz", "penalty", "plane_strain", "closed_form"],
        levels: 4,
        reference: Reference::HertzCylinder {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
            axis: 0.0,
            half_model: true,
            abscissa: Abscissa::Current,
        },
        // Measured (levels 0-3): a 9.5e-2 4.3e-3 2.5e-2 4.3e-3 (the edge is
        // located within one element: a/h = 2.4 at level 0, 17 at level 3);
        // a (moment) 6.1e-2 7.7e-3 1.2e-2 7.6e-3; p0 8.6e-3 7.9e-3 6.1e-3
        // 7.3e-3; L2 6.2e-2 6.3e-2 1.9e-2 2.0e-2. p0 and L2 level off at
        // ~0.7 % and ~2 %: the exact-geometry gap of the circle tool on a
        // small-strain body differs from linear Hertz at the order of the
        // contact strain (the floor halves with the load).
        checks: hertz_checks(
            &[0.20, 0.05, 0.05, 0.02],
            &[0.10, 0.03, 0.03, 0.02],
            &[0.03, 0.02, 0.02, 0.02],
            &[0.12, 0.10, 0.04, 0.04],
            None,
        ),
    }
}

/// Elastic sphere on a rigid plane, axisymmetric.
pub fn hertz_sphere() -> Case {
    Case {
        name: "hertz_sphere",
        title: "Hertz: elastic sphere on a rigid plane, axisymmetric",
        source: "VERIFICATION-CASES.md §2; Johnson, Contact Mechanics §4.2",
        deck: "hertz_sphere.ctc",
        tags: &[
            "contact",
            "hertz",
            "penalty",
            "axisymmetric",
            "closed_form",
            "rate",
        ],
        levels: 4,
        reference: Reference::HertzSphere {
            young: 1e3,
            poisson: 0.3,
            radius: 1.0,
            pair: 0,
        },
        // Measured (levels 0-3): a 2.8e-2 7.4e-3 6.0e-3 7.9e-3; a (moment)
        // 1.7e-2 9.9e-3 2.5e-3 2.3e-4; p0 1.1e-2 8.1e-3 3.3e-4 2.8e-3;
        // L2 9.5e-2 3.9e-2 1.5e-2 6.4e-3 (rate 1.25).
        checks: hertz_checks(
            &[0.06, 0.03, 0.02, 0.02],
            &[0.05, 0.03, 0.02, 0.02],
            &[0.04, 0.03, 0.02, 0.02],
            &[0.15, 0.08, 0.04, 0.02],
            Some(0.7),
        ),
    }
}

/// The Lamé cylinder of both Lamé decks.
fn pipe(ends: EndCondition) -> ThickCylinder {
    ThickCylinder {
        inner: 1.0,
        outer: 2.0,
        pressure: 100.0,
        young: 210e3,
        poisson: 0.3,
        ends,
    }
}

/// Quarter ring, plane strain.
pub fn lame_plane_strain() -> Case {
    Case {
        name: "lame_plane_strain",
        title: "Lamé: thick cylinder under internal pressure, plane strain (quarter ring)",
        source: "Timoshenko & Goodier, Theory of Elasticity §33",
        deck: "lame_plane_strain.ctc",
        tags: &["elasticity", "lame", "plane_strain", "closed_form", "rate"],
        levels: 4,
        reference: Reference::Lame {
            cylinder: pipe(EndCondition::PlaneStrain),
            center: [0.0, 0.0],
            axisymmetric: false,
        },
        // Measured (levels 0-3): u_r 1.3e-2 3.3e-3 8.3e-4 2.1e-4 (rate 2.0);
        // s_tt 6.3e-2 3.6e-2 2.0e-2 1.0e-2 (rate 0.94).
        checks: vec![
            Check::new(Quantity::InnerDisplacement, &[0.03, 0.01, 0.003, 0.001]).with_min_rate(1.5),
            Check::new(Quantity::HoopStress, &[0.1, 0.06, 0.035, 0.02]).with_min_rate(0.8),
        ],
    }
}

/// Axisymmetric section, open ends.
pub fn lame_axisymmetric() -> Case {
    Case {
        name: "lame_axisymmetric",
        title: "Lamé: thick cylinder under internal pressure, axisymmetric, open ends",
        source: "Timoshenko & Goodier, Theory of Elasticity §33",
        deck: "lame_axisymmetric.ctc",
        tags: &["elasticity", "lame", "axisymmetric", "closed_form", "rate"],
        levels: 4,
        reference: Reference::Lame {
            cylinder: pipe(EndCondition::OpenEnds),
            center: [0.0, 0.0],
            axisymmetric: true,
        },
        // Measured (levels 0-3): u_r 1.5e-2 4.9e-3 1.5e-3 4.5e-4 (rate
        // 1.75); s_tt 5.8e-2 3.6e-2 2.0e-2 1.1e-2 (0.91); eps_zz 3.0e-2
        // 7.0e-3 1.4e-3 2.7e-4 (2.4).
        checks: vec![
            Check::new(Quantity::InnerDisplacement, &[0.03, 0.01, 0.003, 0.001]).with_min_rate(1.5),
            Check::new(Quantity::HoopStress, &[0.1, 0.06, 0.035, 0.02]).with_min_rate(0.8),
            Check::new(Quantity::AxialStrain, &[0.05, 0.015, 0.003, 0.001]).with_min_rate(1.5),
        ],
    }
}

/// Checks of the patch tests: exact to round-off.
fn patch_checks() -> Vec<Check> {
    vec![
        Check::new(Quantity::PatchPressure, &[EXACT]),
        Check::new(Quantity::PatchGap, &[EXACT]),
        Check::new(Quantity::PatchDisplacement, &[EXACT]),
        Check::new(Quantity::PatchStress, &[EXACT]),
        Check::new(Quantity::ContactForce, &[BALANCE]),
    ]
}

/// The exact state of the plane strain patch deck.
pub fn patch_plane_strain_patch() -> PenaltyPatch {
    PenaltyPatch {
        kind: PatchKind::PlaneStrain,
        young: 2e6,
        poisson: 0.0,
        height: 1.0,
        top_displacement: 0.05,
        penalty: 1e9,
        x0: 0.0,
        y0: 0.0,
    }
}

/// Tri3 block on a plane, plane strain, nu = 0 (the §3 instance).
pub fn patch_plane_strain() -> Case {
    Case {
        name: "patch_plane_strain",
        title: "Contact patch test: block on a rigid plane, area penalty, plane strain tri3",
        source: "VERIFICATION-CASES.md §3, §7",
        deck: "patch_plane_strain.ctc",
        tags: &["contact", "patch", "penalty", "plane_strain", "exact"],
        levels: 2,
        reference: Reference::Patch {
            patch: patch_plane_strain_patch(),
            pair: 0,
        },
        checks: patch_checks(),
    }
}

/// Quad4 cylinder on a plane, axisymmetric, nu = 0.3.
pub fn patch_axisymmetric() -> Case {
    Case {
        name: "patch_axisymmetric",
        title: "Contact patch test: cylinder on a rigid plane, area penalty, axisymmetric quad4",
        source: "VERIFICATION-CASES.md §3, §7",
        deck: "patch_axisymmetric.ctc",
        tags: &["contact", "patch", "penalty", "axisymmetric", "exact"],
        levels: 2,
        reference: Reference::Patch {
            patch: PenaltyPatch {
                kind: PatchKind::Axisymmetric,
                young: 2e6,
                poisson: 0.3,
                height: 1.0,
                top_displacement: 0.05,
                penalty: 1e9,
                x0: 0.0,
                y0: 0.0,
            },
            pair: 0,
        },
        checks: patch_checks(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::deck::DeckFile;
    use std::collections::BTreeSet;
    use std::path::Path;

    /// Every case's deck exists, its markers parse, it defines at least the
    /// default number of levels, and names are unique.
    #[test]
    fn catalogue_decks_exist_and_define_their_levels() {
        let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("cases");
        let mut names = BTreeSet::new();
        for case in all() {
            assert!(names.insert(case.name), "duplicate case {}", case.name);
            let deck = DeckFile::read(&dir.join(case.deck)).unwrap();
            assert!(
                deck.levels() >= case.levels,
                "{}: {} < {}",
                case.name,
                deck.levels(),
                case.levels
            );
            let text = std::fs::read_to_string(dir.join(case.deck)).unwrap();
            assert!(
                text.starts_with("# "),
                "{} must open with a comment",
                case.deck
            );
            assert!(
                text.contains("Run: ctc verify"),
                "{} must say how to run it",
                case.deck
            );
            assert!(!case.checks.is_empty());
        }
    }
}
