//! Coulomb friction on Nagata patches (3D node-to-facet, `smoothing =
//! nagata`; issue 18): the law of [`super::friction_facet`] on the
//! smoothed master, "one normal everywhere".
//!
//! The slave node `x_s` projects on the Nagata patch of facet `k` at `xi`
//! ([`super::nagata::project`]); the patch's unit normal `n` there gives
//! the gap (as in the frictionless element) and the tangent plane `P = I -
//! n ⊗ n` of the friction. The stick point is a material point of the
//! master, stored as in the faceted element (facet `k_a` and its
//! parameters `xi_a`, [`super::friction::FrictionState::anchor`]), whose
//! current position is the point at `xi_a` of the Nagata patch of facet
//! `k_a` (current nodes, current nodal normals): the slip is measured on
//! the smoothed surface, continuous across facet edges (neighbouring
//! patches share their edge curves). After a slip the stick point is the
//! closest point of the patch of `k` to `x_a + delta`. First touch,
//! augmented-Lagrangian base, the cone tie and the cycling guard's hold
//! are those of [`super::friction_facet::apply_on`].
//!
//! Forces: `t` on the slave, and at the foot the reaction distributed as
//! the Nagata element distributes the normal force, `-(dx(xi)/dY)^T t`
//! over `Y = [x_a, n_a]` of the patch (`xi` held): `-N_a t` on the patch
//! nodes plus the edge corrections' share on the nodes and the nodal
//! normals, which the chain rule `n_a(X)` spreads over the facets around
//! the patch nodes. The stick point's patch gets none (it only places the
//! stick point). A rigid translation of every node leaves `x(xi) - x_s`
//! and the normals unchanged, a rotation turns the patch with them: the
//! forces sum to zero and their moment is `(x_s - x(xi)) x t = g n x t`.
//!
//! Tangent: the law over the 51 variables `[x_s, x_a, n_a (patch k), y_b,
//! m_b (patch k_a)]` in dual numbers ([`Ad`]`<51>`) through one Newton
//! step of the closest-point equations at the converged foot (the
//! implicit `dxi/dY`, as [`super::nagata::differentiate`]), then the chain
//! rule to the coordinates: `K = -(P^T dF/dY P + sum_a F_(n_a) . d^2 n_a
//! / dX^2)` with `P = dY/dX` (the nodal normals' Jacobians and the closed
//! form of their second derivatives, [`super::nagata::normal_chain`]).
//! Not symmetric.

use super::friction::{FrictionStatus, NodeFriction};
use super::friction_facet::{coulomb, FacetContact, FacetFriction, Master};
use super::mortar::ad::Ad;
use super::nagata::{self, normal_chain, patch_data, reaction, Patch, Ring};
use super::node_to_facet::{cross, dot, newton_step, FacetSurface};

/// Variables of the law: the slave, the contact patch's 4 nodes and 4
/// nodal normals, the stick point's patch's 4 nodes and 4 nodal normals.
pub const NF: usize = 51;

type B = Ad<NF>;

/// Friction on a Nagata element over global nodes.
#[derive(Debug, Clone, PartialEq)]
pub struct PatchFriction {
    /// Status, force, gaps, slip and work.
    pub friction: NodeFriction<3>,
    /// Global nodes: the slave first, then the others sorted (the nodes of
    /// the facets around both patches' nodes).
    pub nodes: Vec<usize>,
    /// Forces over `nodes` (local dof `3 a + c`).
    pub forces: Vec<f64>,
    /// `-d forces / dX`, row-major.
    pub tangent: Vec<f64>,
    /// The stick point's parameters on the contact facet's patch after a
    /// slip, `None` in stick.
    pub moved: Option<[f64; 2]>,
    /// The stick point's current position after the return map.
    pub point: [f64; 3],
}

/// The law over `Y`: the Coulomb state and the forces over `[x_s, x_a,
/// n_a]` of the contact patch (the first 27 variables), as dual numbers.
struct PatchLaw {
    law: super::friction_facet::Coulomb<NF>,
    forces: [B; 27],
    moved: Option<[f64; 2]>,
}

/// The patch nodes / normals of a facet at the current coordinates.
type PatchData = ([[f64; 3]; 4], [[f64; 3]; 4]);

fn law_on_patches(
    law: &FacetFriction,
    xs: [f64; 3],
    ((xp, np), count): (PatchData, usize),
    xi: [f64; 2],
    ((xa, na), count_a): (PatchData, usize),
    xi_a: [f64; 2],
) -> Option<PatchLaw> {
    let var = |p: [f64; 3], k: usize| -> [B; 3] { std::array::from_fn(|c| B::var(p[c], k + c)) };
    let xs_d = var(xs, 0);
    let patch = Patch::new(
        std::array::from_fn(|a| var(xp[a], 3 + 3 * a)),
        std::array::from_fn(|a| var(np[a], 15 + 3 * a)),
        count,
    );
    let (r, j) = nagata::system(xs_d, &patch, xi.map(B::cst));
    let step = newton_step(r, j)?;
    let xi_d = [B::cst(xi[0]) + step[0], B::cst(xi[1]) + step[1]];
    let (x, t, _) = patch.at(xi_d);
    let m = cross(t[0], t[1]);
    let len = dot(m, m).sqrt();
    if len.v.is_nan() || len.v <= 0.0 {
        return None;
    }
    let n = m.map(|v| v / len);
    let cl = coulomb(law, xs_d, x, n, B::cst(1.0), || {
        // the stick point: the material point xi_a of its facet's patch
        let anchor = Patch::new(
            std::array::from_fn(|a| var(xa[a], 27 + 3 * a)),
            std::array::from_fn(|a| var(na[a], 39 + 3 * a)),
            count_a,
        );
        anchor.at(xi_a.map(B::cst)).0
    });
    let mut forces = [B::cst(0.0); 27];
    forces[..3].copy_from_slice(&cl.t);
    forces[3..].copy_from_slice(&reaction(&patch, xi_d, cl.t));
    let moved = (cl.status == FrictionStatus::Slip && !law.held).then(|| {
        let pf = Patch::new(xp, np, count);
        nagata::project(cl.point, &pf, Some(xi)).unwrap_or(xi)
    });
    Some(PatchLaw {
        law: cl,
        forces,
        moved,
    })
}

/// The friction law on the Nagata element of slave node `slave` at `xs`
/// on the patch of `facet` (its global nodes; `rings[a]` the facets around
/// its node `a` and its symmetry planes) at the converged foot `xi`, with the stick point `xi_a`
/// on the patch of `anchor` (`anchor_rings`), at coordinates `x`. `None`
/// for a degenerate patch.
#[allow(clippy::too_many_arguments)]
pub fn respond(
    law: &FacetFriction,
    slave: usize,
    xs: [f64; 3],
    facet: &[usize],
    rings: &[Ring<'_>],
    xi: [f64; 2],
    anchor: &[usize],
    anchor_rings: &[Ring<'_>],
    xi_a: [f64; 2],
    x: &[[f64; 3]],
) -> Option<PatchFriction> {
    let (count, count_a) = (facet.len(), anchor.len());
    let contact = patch_data(facet, rings, x)?;
    let stick = patch_data(anchor, anchor_rings, x)?;
    let pl = law_on_patches(law, xs, (contact, count), xi, (stick, count_a), xi_a)?;
    // global nodes: the slave, then every node of both patches' rings
    let nodes = nagata::element_nodes(
        slave,
        rings
            .iter()
            .chain(anchor_rings)
            .flat_map(|r| r.facets.iter())
            .flat_map(|f| f.iter().copied())
            .chain(facet.iter().copied())
            .chain(anchor.iter().copied()),
    );
    let nn = nodes.len();
    let nd = 3 * nn;
    let at = |node: usize| nagata::local_index(&nodes, node);
    // P = dY/dX (nd x 51): coordinates directly, normals through J_a
    let mut pm = vec![[0.0; NF]; nd];
    for (c, row) in pm.iter_mut().enumerate().take(3) {
        row[c] = 1.0;
    }
    for (a, &k) in facet.iter().enumerate() {
        for c in 0..3 {
            pm[3 * at(k) + c][3 + 3 * a + c] += 1.0;
        }
    }
    for (a, &k) in anchor.iter().enumerate() {
        for c in 0..3 {
            pm[3 * at(k) + c][27 + 3 * a + c] += 1.0;
        }
    }
    // -F_(n_a) . d^2 n_a / dX^2 (the contact patch's normals carry
    // forces; the stick point's patch only places the point)
    let mut tangent = vec![0.0; nd * nd];
    for (a, ring) in rings.iter().enumerate().take(count) {
        let lam: [f64; 3] = std::array::from_fn(|c| -pl.forces[15 + 3 * a + c].v);
        let j = normal_chain(ring, x, &at, nn, lam, &mut tangent);
        for (col, jc) in j.iter().enumerate() {
            for i in 0..3 {
                pm[col][15 + 3 * a + i] += jc[i];
            }
        }
    }
    for (a, ring) in anchor_rings.iter().enumerate().take(count_a) {
        let j = normal_chain(ring, x, &at, nn, [0.0; 3], &mut tangent);
        for (col, jc) in j.iter().enumerate() {
            for i in 0..3 {
                pm[col][39 + 3 * a + i] += jc[i];
            }
        }
    }
    // the Y slots in use
    let used: Vec<usize> = (0..NF)
        .filter(|&k| {
            k < 3 + 3 * count
                || (15..15 + 3 * count).contains(&k)
                || (27..27 + 3 * count_a).contains(&k)
                || (39..39 + 3 * count_a).contains(&k)
        })
        .collect();
    let rows: Vec<usize> = used.iter().copied().filter(|&k| k < 27).collect();
    let mut forces = vec![0.0; nd];
    for (f, p) in forces.iter_mut().zip(&pm) {
        *f = rows.iter().map(|&k| p[k] * pl.forces[k].v).sum();
    }
    // (dF/dY) P: 27 x nd, then P^T (dF/dY P)
    let mut fp = vec![[0.0; 27]; nd];
    for (col, pc) in pm.iter().enumerate() {
        for &k in &rows {
            fp[col][k] = used.iter().map(|&l| pl.forces[k].d[l] * pc[l]).sum();
        }
    }
    for row in 0..nd {
        for col in 0..nd {
            tangent[row * nd + col] -= rows.iter().map(|&k| pm[row][k] * fp[col][k]).sum::<f64>();
        }
    }
    Some(PatchFriction {
        friction: pl.law.friction(),
        nodes,
        forces,
        tangent,
        moved: pl.moved,
        point: pl.law.point,
    })
}

/// The Nagata patches of a master surface at the current coordinates `x`,
/// as the friction's [`Master`].
pub struct Patches<'a> {
    /// The master surface.
    pub surface: &'a FacetSurface,
    /// Current coordinates.
    pub x: &'a [[f64; 3]],
    /// The slave node (global).
    pub slave: usize,
}

impl Patches<'_> {
    fn rings(&self, k: usize) -> Vec<Ring<'_>> {
        self.surface.faces[k]
            .nodes()
            .iter()
            .map(|&m| self.surface.nagata_ring(m))
            .collect()
    }

    fn patch(&self, k: usize) -> Option<Patch<f64>> {
        nagata::patch_of(self.surface.faces[k].nodes(), &self.rings(k), self.x)
    }
}

impl Master for Patches<'_> {
    type Response = PatchFriction;

    fn frame(&self, c: &FacetContact<'_>) -> Option<([f64; 3], [f64; 3])> {
        let (p, t, _) = self.patch(c.facet)?.at(c.xi);
        let m = [
            t[0][1] * t[1][2] - t[0][2] * t[1][1],
            t[0][2] * t[1][0] - t[0][0] * t[1][2],
            t[0][0] * t[1][1] - t[0][1] * t[1][0],
        ];
        let l = (m[0] * m[0] + m[1] * m[1] + m[2] * m[2]).sqrt();
        (l > 0.0 && l.is_finite()).then(|| (p, m.map(|v| v / l)))
    }

    fn foot_on(&self, c: &FacetContact<'_>, q: [f64; 3]) -> [f64; 2] {
        self.patch(c.facet)
            .and_then(|p| nagata::project(q, &p, Some(c.xi)))
            .unwrap_or(c.xi)
    }

    fn point_on(&self, c: &FacetContact<'_>, k: usize, xi: [f64; 2]) -> [f64; 3] {
        self.patch(k).map_or(c.xs, |p| p.at(xi).0)
    }

    fn respond(
        &self,
        law: &FacetFriction,
        c: &FacetContact<'_>,
        ka: usize,
        xi_a: [f64; 2],
    ) -> Option<PatchFriction> {
        let faces = &self.surface.faces;
        respond(
            law,
            self.slave,
            c.xs,
            faces[c.facet].nodes(),
            &self.rings(c.facet),
            c.xi,
            faces.get(ka)?.nodes(),
            &self.rings(ka),
            xi_a,
            self.x,
        )
    }

    fn outcome(r: &mut PatchFriction) -> (&mut NodeFriction<3>, Option<[f64; 2]>, [f64; 3]) {
        (&mut r.friction, r.moved, r.point)
    }

    fn fade(&self, _: &FacetContact<'_>) -> f64 {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::friction_facet::{self, Projection};
    use crate::contact::nagata::tests::{dome, rings};
    use proptest::prelude::*;

    /// The law of the tests: `alpha_T = 20`, normal stiffness 100, no shift.
    fn plain_law(mu: f64, impact: Option<[f64; 3]>) -> FacetFriction {
        FacetFriction {
            mu,
            alpha_t: 20.0,
            shift: [0.0; 3],
            normal_shift: 0.0,
            normal_stiffness: 100.0,
            fade: [false; 4],
            impact,
            held: false,
        }
    }

    /// The element of slave `s` on the patch of `f` (foot by projection
    /// from the centre), stick point `xi_a` on the patch of `fa`.
    fn element(
        law: &FacetFriction,
        faces: &[Vec<usize>],
        f: &[usize],
        fa: &[usize],
        xi_a: [f64; 2],
        s: usize,
        x: &[[f64; 3]],
    ) -> Option<PatchFriction> {
        let (r, ra) = (rings(faces, f), rings(faces, fa));
        let patch = nagata::patch_of(f, &r, x)?;
        let xi = nagata::project(x[s], &patch, None)?;
        respond(law, s, x[s], f, &r, xi, fa, &ra, xi_a, x)
    }

    /// Largest relative error of the tangent against central differences
    /// of the forces (h = 1e-6) over every coordinate the element touches,
    /// with the force and moment balance checked (`sum f = 0`, `sum x x f
    /// = g n x t`); `None` where the status or the node set changes within
    /// the step.
    fn fd_error(
        law: &FacetFriction,
        faces: &[Vec<usize>],
        f: &[usize],
        fa: &[usize],
        xi_a: [f64; 2],
        s: usize,
        x: &[[f64; 3]],
    ) -> Option<(f64, NodeFriction<3>, f64)> {
        let e = element(law, faces, f, fa, xi_a, s, x)?;
        assert!(
            e.forces.iter().chain(&e.tangent).all(|v| v.is_finite()),
            "{e:?}"
        );
        let nd = e.forces.len();
        // balance
        let r = rings(faces, f);
        let patch = nagata::patch_of(f, &r, x)?;
        let xi = nagata::project(x[s], &patch, None)?;
        let (p, tg, _) = patch.at(xi);
        let m = [
            tg[0][1] * tg[1][2] - tg[0][2] * tg[1][1],
            tg[0][2] * tg[1][0] - tg[0][0] * tg[1][2],
            tg[0][0] * tg[1][1] - tg[0][1] * tg[1][0],
        ];
        let gap = (0..3).map(|c| (x[s][c] - p[c]) * m[c]).sum::<f64>();
        let t = e.friction.traction;
        let lever: [f64; 3] = std::array::from_fn(|c| x[s][c] - p[c]);
        let expect = [
            lever[1] * t[2] - lever[2] * t[1],
            lever[2] * t[0] - lever[0] * t[2],
            lever[0] * t[1] - lever[1] * t[0],
        ];
        let fmax = e.forces.iter().fold(1e-300f64, |a, v| a.max(v.abs()));
        let (mut sum, mut mom) = ([0.0; 3], [0.0; 3]);
        for (a, &n) in e.nodes.iter().enumerate() {
            let (q, y) = (
                [e.forces[3 * a], e.forces[3 * a + 1], e.forces[3 * a + 2]],
                x[n],
            );
            for c in 0..3 {
                sum[c] += q[c];
            }
            mom[0] += y[1] * q[2] - y[2] * q[1];
            mom[1] += y[2] * q[0] - y[0] * q[2];
            mom[2] += y[0] * q[1] - y[1] * q[0];
        }
        for c in 0..3 {
            assert!(sum[c].abs() <= 1e-12 * fmax, "force balance {sum:?}");
            assert!(
                (mom[c] - expect[c]).abs() <= 1e-11 * fmax,
                "moment {mom:?} vs g n x t {expect:?}"
            );
        }
        let kmax = e.tangent.iter().fold(1e-12f64, |a, k| a.max(k.abs()));
        let h = 1e-6;
        let mut err = 0.0f64;
        for col in 0..nd {
            let (node, comp) = (e.nodes[col / 3], col % 3);
            let (mut xp, mut xm) = (x.to_vec(), x.to_vec());
            xp[node][comp] += h;
            xm[node][comp] -= h;
            let ep = element(law, faces, f, fa, xi_a, s, &xp)?;
            let em = element(law, faces, f, fa, xi_a, s, &xm)?;
            let same =
                |o: &PatchFriction| o.nodes == e.nodes && o.friction.status == e.friction.status;
            if !same(&ep) || !same(&em) {
                return None;
            }
            for row in 0..nd {
                let fd = -(ep.forces[row] - em.forces[row]) / (2.0 * h);
                err = err.max((fd - e.tangent[row * nd + col]).abs() / kmax);
            }
        }
        Some((err, e.friction, gap))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// The friction element on a Nagata patch of a dome (tri3 or
        /// quad4) whose nodes are all moved at random: its tangent against
        /// central differences of its forces over every node it touches
        /// (slave, both patches' rings), in stick (`mu` 50), slip (`mu`
        /// 0.02) and at a first touch (the crossing of the path from a
        /// point above the patch), the slave's foot anywhere on the
        /// facet up to its edges, the stick point on the same facet or a
        /// neighbour; plus the balance of the forces and their moment `g n
        /// x t` (`cargo test -p ctc-engine --lib friction_nagata --
        /// --nocapture` prints the errors).
        #[test]
        fn tangent_matches_finite_differences_stick_slip_and_first_touch(
            tri in any::<bool>(),
            mode in 0usize..3,
            neighbour in any::<bool>(),
            moves in proptest::collection::vec(-1.0f64..1.0, 48),
            slave in (-0.48f64..0.48, -0.48f64..0.48, -0.05f64..-0.01),
            anchor in (-0.4f64..0.4, -0.4f64..0.4),
        ) {
            let mut seed = 11u64;
            let (mut x, faces) = dome(3, tri, 0.0, &mut seed);
            for (p, m) in x.iter_mut().zip(moves.chunks(3)) {
                for c in 0..3 {
                    p[c] += 0.02 * m[c];
                }
            }
            let (k, ka) = match (tri, neighbour) {
                (false, false) => (4, 4),
                (false, true) => (4, 5),
                (true, false) => (8, 8),
                (true, true) => (8, 9),
            };
            let f = faces[k].clone();
            let fa = faces[ka].clone();
            // the slave over the facet: bilinear / barycentric placement
            let corner = |a: usize| x[f[a]];
            let place: [f64; 3] = if tri {
                let (u, v) = (0.5 + slave.0, 0.5 + slave.1);
                let (u, v) = if u + v > 1.0 { (1.0 - v, 1.0 - u) } else { (u, v) };
                std::array::from_fn(|c| {
                    (1.0 - u - v) * corner(0)[c] + u * corner(1)[c] + v * corner(2)[c]
                })
            } else {
                let (u, v) = (0.5 + slave.0, 0.5 + slave.1);
                std::array::from_fn(|c| {
                    (1.0 - u) * (1.0 - v) * corner(0)[c]
                        + u * (1.0 - v) * corner(1)[c]
                        + u * v * corner(2)[c]
                        + (1.0 - u) * v * corner(3)[c]
                })
            };
            let s = x.len();
            x.push([place[0], place[1], place[2] + slave.2]);
            let xi_a = if tri {
                [0.33 + 0.5 * anchor.0.abs() * 0.5, 0.33 - 0.5 * anchor.1.abs() * 0.5]
            } else {
                [anchor.0, anchor.1]
            };
            let impact = (mode == 2).then(|| [place[0] + 0.04, place[1] - 0.03, place[2] + 0.03]);
            let mu = [50.0, 0.02, 0.3][mode];
            let law = plain_law(mu, impact);
            let Some((err, fr, gap)) = fd_error(&law, &faces, &f, &fa, xi_a, s, &x) else {
                return Ok(());
            };
            // the patch may bulge past a slave placed below the chord
            prop_assume!(gap < 0.0);
            let status = fr.status;
            println!("friction_nagata tri {tri} mode {mode}: {status:?}, max rel. FD error {err:.2e}");
            match mode {
                0 => prop_assert_eq!(status, FrictionStatus::Stick, "{:?}", fr),
                1 => prop_assert_eq!(status, FrictionStatus::Slip, "{:?}", fr),
                _ => {}
            }
            prop_assert!(err < 1e-6, "tangent vs FD {err:e}");
        }
    }

    /// On a flat master the Nagata patch is the facet: the friction of the
    /// Nagata element equals the faceted element's (the slave and the
    /// facet nodes' forces to round-off, nothing on the ring nodes), in
    /// stick and in slip, the stick point on the facet and on a
    /// neighbour.
    #[test]
    fn a_flat_patch_gives_the_faceted_friction() {
        let mut seed = 3u64;
        let (mut x, faces) = dome(3, false, 0.0, &mut seed);
        for p in &mut x {
            p[2] = 0.0;
        }
        let s = x.len();
        x.push([0.07, -0.05, -0.01]);
        for (mu, status) in [(5.0, FrictionStatus::Stick), (0.02, FrictionStatus::Slip)] {
            // the stick point 0.026 and 0.113 from the slave
            for (ka, xi_a) in [(4, [0.3, -0.4]), (5, [-0.9, -0.4])] {
                let (f, fa) = (&faces[4], &faces[ka]);
                let law = plain_law(mu, None);
                let e = element(&law, &faces, f, fa, xi_a, s, &x).unwrap();
                assert_eq!(e.friction.status, status, "{:?} {:?}", e.friction, e.point);
                let pts: Vec<[f64; 3]> = f.iter().map(|&n| x[n]).collect();
                let apts: Vec<[f64; 3]> = fa.iter().map(|&n| x[n]).collect();
                let (xi, _) = crate::contact::node_to_facet::foot(x[s], &pts).unwrap();
                let r =
                    friction_facet::respond(&law, x[s], &pts, xi, &apts, xi_a, Projection::FACE)
                        .unwrap();
                assert_eq!(r.friction.status, status);
                let fmax = r.forces.iter().fold(0.0f64, |a, v| a.max(v.abs()));
                assert!(fmax > 1e-3);
                for (a, &n) in e.nodes.iter().enumerate() {
                    let want: [f64; 3] = std::array::from_fn(|c| {
                        if n == s {
                            r.forces[c]
                        } else {
                            f.iter()
                                .position(|&m| m == n)
                                .map_or(0.0, |b| r.forces[3 + 3 * b + c])
                        }
                    });
                    for c in 0..3 {
                        assert!(
                            (e.forces[3 * a + c] - want[c]).abs() <= 1e-13 * fmax,
                            "node {n}: {:?} vs {want:?}",
                            &e.forces[3 * a..3 * a + 3]
                        );
                    }
                }
                let moved = (e.moved, r.moved);
                if let (Some(p), Some(q)) = moved {
                    assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12);
                } else {
                    assert_eq!(moved, (None, None));
                }
            }
        }
    }
}
