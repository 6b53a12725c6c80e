//! Tests of the 3D mortar penalty rows' load-stiffness cap
//! ([`super::LOAD_STIFFNESS_CAP`]) and hold ([`super::HOLD_BAND`]) on a
//! small pair: a slave grid of 2 x 2 quads (0.8 wide, over `[0.2, 1.8]^2`,
//! facing -z) over a master grid of 2 x 2 unit quads (facing +z), area
//! penalty 1000, interface meshes non-matching.
//!
//! ```text
//!      slave  +---+---+   z = zs (bottom of the upper body, normal -z)
//!           +---+---+---+ z = 0  (top of the lower body, normal +z)
//!          master
//! ```

use crate::contact::surface::{evaluate_pair, SurfacePair};
use crate::contact::ContactStatus;
use crate::mesh::Facet;
use crate::model::{
    ContactMaster, ContactMethod, ContactPair, ContactStrategy, Model, PenaltyKind,
};

/// Master nodes `0..9` (3 x 3 at z = 0), slave nodes `9..18` (3 x 3 at `z
/// = zs`).
fn model(zs: f64) -> Model<3> {
    let mut nodes: Vec<[f64; 3]> = (0..9)
        .map(|n| [(n % 3) as f64, (n / 3) as f64, 0.0])
        .collect();
    nodes.extend((0..9).map(|n| [0.2 + 0.8 * (n % 3) as f64, 0.2 + 0.8 * (n / 3) as f64, zs]));
    let mesh = crate::mesh::Mesh::new(nodes, vec![]);
    let mut m = crate::testkit::ModelBuilder::solid()
        .elastic("m", 1.0, 0.3)
        .body("b", mesh, "m")
        .build();
    let quads = |base: usize, up: bool| -> Vec<Facet> {
        (0..4)
            .map(|k| {
                let (i, j) = (k % 2, k / 2);
                let id = |a: usize, b: usize| base + a + 3 * b;
                if up {
                    Facet::new(&[id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)])
                } else {
                    Facet::new(&[id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)])
                }
            })
            .collect()
    };
    m.contacts.push(ContactPair {
        name: "slave -> master".into(),
        body: 0,
        edges: vec![],
        faces: quads(9, false),
        nodes: (9..18).collect(),
        master: ContactMaster::Surface {
            body: 0,
            edges: vec![],
            faces: quads(0, true),
            nodes: (0..9).collect(),
        },
        strategy: ContactStrategy::SinglePass,
        search: Default::default(),
        formulation: crate::model::ContactFormulation::Mortar,
        smoothing: Default::default(),
        method: ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1000.0,
        },
        prof: Some(0.5),
        friction: None,
        local_penalty: Vec::new(),
    });
    m
}

/// The pair's forces and `K v` at `x` from the couplings of `state`'s
/// last evaluation.
fn scatter(state: &SurfacePair, n: usize, v: &[[f64; 3]]) -> (Vec<f64>, Vec<f64>) {
    let pair = state.deformable.as_ref().expect("a deformable pair");
    pair.forces_and_tangent_times(n, v)
}

/// A pressed, tilted and jittered configuration of [`model`] (the slave
/// grid `depth` into the master, tilted by 0.01 across x) and a
/// direction, both seeded.
fn pressed(m: &Model<3>, depth: f64) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let mut seed: u64 = 0x2545_f491_4f6c_dd1d;
    let mut rnd = move || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let x: Vec<[f64; 3]> = m
        .mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(k, p)| {
            let dz = if k >= 9 { -depth + 0.01 * p[0] } else { 0.0 };
            [
                p[0] + 0.01 * rnd(),
                p[1] + 0.01 * rnd(),
                p[2] + dz + 0.001 * rnd(),
            ]
        })
        .collect();
    let v = x.iter().map(|_| [rnd(), rnd(), rnd()]).collect();
    (x, v)
}

/// `max |K v - FD| / max |K v|` at `x` of the pair evaluated at `first`
/// (the increment's first evaluation: it sets the cap), then at `x`.
fn fd_error(m: &Model<3>, first: &[[f64; 3]], x: &[[f64; 3]], v: &[[f64; 3]]) -> f64 {
    let n = x.len();
    let at = |y: &[[f64; 3]]| {
        let mut state = SurfacePair::new(m, 0);
        let _ = evaluate_pair(m, 0, first, 0.0, &mut state);
        let (res, _) = evaluate_pair(m, 0, y, 0.0, &mut state);
        let closed = res
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .count();
        (scatter(&state, n, v), closed)
    };
    let ((_, kv), closed) = at(x);
    assert_eq!(closed, 9, "every slave node closed");
    let h = 1e-7;
    let shift = |s: f64| -> Vec<[f64; 3]> {
        x.iter()
            .zip(v)
            .map(|(p, d)| std::array::from_fn(|c| p[c] + s * h * d[c]))
            .collect()
    };
    let (((fp, _), cp), ((fm, _), cm)) = (at(&shift(1.0)), at(&shift(-1.0)));
    assert!(cp == closed && cm == closed, "the contact set changed");
    let scale = kv.iter().fold(1e-300f64, |a, b| a.max(b.abs()));
    (0..kv.len())
        .map(|k| (-(fp[k] - fm[k]) / (2.0 * h) - kv[k]).abs() / scale)
        .fold(0.0, f64::max)
}

/// First contact (issue 18): two meshes that touch at the start have
/// nodal gaps of round-off, here a penetration of 1e-15 (a force of
/// round-off on every slave node at the increment's first evaluation).
/// That is no pressure: no load-stiffness cap from it, and the tangent at
/// a pressed iterate (0.02 deep, tilted: the load-stiffness term `p
/// dB/dx` matters) is the exact derivative of the forces (central
/// differences). Before, the cap was twice that round-off pressure, the
/// term was dropped, and `K v` departed from the differences by 1e-3 of
/// its size (`examples/contact_blocks_mortar_3d.ctc`: increment 1 in 6
/// iterations instead of 4). A committed state that carries a real
/// pressure (1e-4 deep) keeps the cap: the same iterate's tangent then
/// departs from the differences.
#[test]
fn a_first_contact_of_round_off_pressure_gets_the_exact_tangent() {
    let m = model(-1e-15);
    let (x, v) = pressed(&m, 0.02);
    let start = m.mesh.nodes.clone();
    let exact = fd_error(&m, &start, &x, &v);
    println!("round-off start: {exact:.2e}");
    assert!(exact < 1e-6, "{exact:.2e}");
    let pressed_start = model(-1e-4).mesh.nodes;
    let capped = fd_error(&m, &pressed_start, &x, &v);
    println!("start 1e-4 deep: {capped:.2e}");
    assert!(capped > 1e-5, "{capped:.2e}");
}

/// The hold ([`super::HOLD_BAND`]): a Newton loop starts
/// (`guard_start`) at a state pressed 0.01 (every slave node closed with
/// a force), and its first iterate lifts the slave grid 1e-3 above the
/// master (within the band, 5e-2 of `sqrt(T)` = 0.02..0.04): every node
/// keeps the closed branch of the penalty law, the tensile force `-alpha
/// g` (the slave grid pulled down by 1000 x 1e-3 x its covered area
/// 2.56) and its tangent, reported open, and the iterate cannot be a
/// converged one (`guard_consistent`). Lifted 0.1 (past the band): no
/// coupling. The hold lasts one iterate: accepted there (no node carried
/// a compressive force), the next evaluation at 1e-3 holds none; nor
/// does a new Newton loop's first evaluation.
#[test]
fn a_node_closed_at_the_last_iterate_and_open_within_the_band_keeps_the_closed_branch() {
    let m = model(0.0);
    let n = m.mesh.nodes.len();
    let lift = |dz: f64| -> Vec<[f64; 3]> {
        m.mesh
            .nodes
            .iter()
            .enumerate()
            .map(|(k, p)| [p[0], p[1], p[2] + if k >= 9 { dz } else { 0.0 }])
            .collect()
    };
    let down: Vec<[f64; 3]> = (0..n)
        .map(|k| [0.0, 0.0, -f64::from(u8::from(k >= 9))])
        .collect();
    let start = |state: &mut SurfacePair| {
        state.deformable.as_mut().expect("deformable").guard_start();
        let (res, _) = evaluate_pair(&m, 0, &lift(-0.01), 0.0, state);
        let forced = res.iter().filter(|c| c.pressure > 0.0).count();
        assert_eq!(forced, 9, "the start presses every slave node");
    };
    // (couplings, z force on the slave nodes, K v along z on them for v
    // = -z on them, closed statuses, consistent)
    let at = |state: &mut SurfacePair, dz: f64| {
        let (res, _) = evaluate_pair(&m, 0, &lift(dz), 0.0, state);
        let closed = res
            .iter()
            .filter(|c| c.status == ContactStatus::Closed)
            .count();
        let (f, kv) = scatter(state, n, &down);
        let slaves = state.slaves.clone();
        let fp = state.deformable.as_mut().expect("deformable");
        let consistent = fp.guard_consistent(&slaves, &res);
        let fz: f64 = (9..18).map(|k| f[3 * k + 2]).sum();
        let kz: f64 = (9..18).map(|k| kv[3 * k + 2]).sum();
        (fp.couplings.len(), fz, kz, closed, consistent)
    };
    let mut state = SurfacePair::new(&m, 0);
    start(&mut state);
    let (couplings, fz, kz, closed, consistent) = at(&mut state, 1e-3);
    println!("held: {couplings} couplings, f_z {fz:.4e}, K v {kz:.4e}, {closed} closed");
    assert_eq!((couplings, closed, consistent), (9, 0, false));
    assert!((fz + 2.56).abs() < 1e-9, "{fz}");
    assert!((kz.abs() - 2560.0).abs() < 1e-6, "{kz}");
    // past the band
    let mut state = SurfacePair::new(&m, 0);
    start(&mut state);
    let (couplings, _, _, _, consistent) = at(&mut state, 0.1);
    assert_eq!((couplings, consistent), (0, true));
    // one iterate only: accepted held, the next evaluation holds none
    let mut state = SurfacePair::new(&m, 0);
    start(&mut state);
    assert_eq!(at(&mut state, 1e-3).0, 9);
    state
        .deformable
        .as_mut()
        .expect("deformable")
        .accept_iterate();
    assert_eq!(at(&mut state, 1e-3).0, 0);
    // a new Newton loop's first evaluation holds none
    state.deformable.as_mut().expect("deformable").guard_start();
    assert_eq!(at(&mut state, 1e-3).0, 0);
}
