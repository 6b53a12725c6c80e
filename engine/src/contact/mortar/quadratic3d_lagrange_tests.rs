//! Lagrange rows of 3D mortar on quadratic faces (tri6 / quad8 / quad9,
//! [`super::quadratic3d`]): the constraint row of every slave node
//! (corners and midside nodes) is the full derivative of its nodal gap
//! `g~_j / A_j` and the tangent minus the derivative of its force
//! `lambda B_j / A_j`, both against central differences of the assembled
//! row ([`super::row_quadratic`], [`super::Row::close_lagrange`]).

use super::{quadratic3d, row_quadratic, Coupling, QuadPiece, UNUSED};
use crate::element::reference::{quad9::Quad9, tri6::Tri6, ReferenceCell};

/// The parent coordinates of node `a` of a face of `nn` nodes.
fn parent(nn: usize, a: usize) -> [f64; 2] {
    if nn == 6 {
        <Tri6 as ReferenceCell<2, 6>>::NODES[a]
    } else {
        <Quad9 as ReferenceCell<2, 9>>::NODES[a]
    }
}

/// A slave face over `[0, 1]^2` (the unit triangle for tri6) at `z = bend
/// (x^2 + y^2)`, outward `+z`, then a master face of size `size` at `(ox,
/// oy)` turned by `rot`, at `z = gap + bend (x^2 + y^2)`, facing down;
/// every node moved by up to `jitter` (seeded).
fn pair(ns: usize, nm: usize, bend: f64, gap: f64, jitter: f64, seed: u64) -> Vec<[f64; 3]> {
    let mut state = seed;
    let mut rnd = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut x = Vec::new();
    for a in 0..ns {
        let [r, s] = parent(ns, a);
        let (px, py) = if ns == 6 {
            (r, s)
        } else {
            (0.5 * (1.0 + r), 0.5 * (1.0 + s))
        };
        x.push([px, py, bend * (px * px + py * py)]);
    }
    let (ox, oy, size, rot) = (0.3, -0.15, 0.9, 0.4);
    for a in 0..nm {
        let [r, s] = parent(nm, a);
        let (u, v) = if nm == 6 {
            (s, r)
        } else {
            (0.5 * (1.0 + s), 0.5 * (1.0 + r))
        };
        let (c, sn) = (f64::cos(rot), f64::sin(rot));
        let (px, py) = (ox + size * (c * u - sn * v), oy + size * (sn * u + c * v));
        x.push([px, py, gap + bend * (px * px + py * py)]);
    }
    for p in &mut x {
        for v in p.iter_mut() {
            *v += jitter * rnd();
        }
    }
    x
}

/// The Lagrange rows of the slave nodes of the face pair `x` (slave nodes
/// `0..ns`, master nodes after them, every node a row node) with
/// multiplier `lambda`: per slave node its covered area, nodal gap and
/// coupling, `None` for a node whose covered area is below `1e-3`; `None`
/// when the faces do not overlap.
#[allow(clippy::type_complexity)]
fn lagrange_rows(
    x: &[[f64; 3]],
    ns: usize,
    lambda: f64,
) -> Option<Vec<Option<(f64, f64, Coupling)>>> {
    let seg = quadratic3d::face_pair(&x[..ns], &x[ns..])?;
    let nm = x.len() - ns;
    let mut vars = [UNUSED; 2 * quadratic3d::MAX_NODES];
    for (k, v) in vars.iter_mut().take(ns).enumerate() {
        *v = k;
    }
    for l in 0..nm {
        vars[quadratic3d::MAX_NODES + l] = ns + l;
    }
    let pieces = [QuadPiece {
        vars,
        master: 0,
        seg,
    }];
    let nodes: Vec<usize> = (0..x.len()).collect();
    Some(
        (0..ns)
            .map(|j| {
                let row = row_quadratic(&pieces, &[(0, j)], &nodes);
                (row.area >= 1e-3).then(|| {
                    let (_, c) = row.close_lagrange(j, lambda);
                    (row.area, row.g / row.area, c)
                })
            })
            .collect(),
    )
}

/// The largest errors over the slave nodes' rows of the constraint row
/// against central differences of the nodal gap and of the tangent
/// against those of the force (step 1e-7), each relative to its row's
/// largest entry, and the number of rows.
fn fd_errors(x: &[[f64; 3]], ns: usize, lambda: f64) -> Option<(f64, f64, usize)> {
    let rows = lagrange_rows(x, ns, lambda)?;
    let h = 1e-7;
    let nd = 3 * x.len();
    let shifted: Vec<_> = (0..nd)
        .map(|col| {
            let at = |dh: f64| {
                let mut y = x.to_vec();
                y[col / 3][col % 3] += dh;
                lagrange_rows(&y, ns, lambda)
            };
            at(h).zip(at(-h))
        })
        .collect::<Option<_>>()?;
    let (mut row_err, mut k_err, mut count) = (0.0f64, 0.0f64, 0);
    for (j, row) in rows.iter().enumerate() {
        let Some((_, _, c)) = row else {
            continue;
        };
        count += 1;
        let row_scale = c.gap_gradient.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        let k_scale = c.tangent.iter().fold(1e-300f64, |m, v| m.max(v.abs()));
        for (col, (p, m)) in shifted.iter().enumerate() {
            let (Some(p), Some(m)) = (&p[j], &m[j]) else {
                return None;
            };
            let fd = (p.1 - m.1) / (2.0 * h);
            row_err = row_err.max((fd - c.gap_gradient[col]).abs() / row_scale);
            for r in 0..nd {
                let fd = -(p.2.force[r] - m.2.force[r]) / (2.0 * h);
                k_err = k_err.max((fd - c.tangent[r * nd + col]).abs() / k_scale);
            }
        }
        assert_eq!(c.force_direction.len(), c.gap_gradient.len());
        for (f, d) in c.force.iter().zip(&c.force_direction) {
            assert!((f - lambda * d).abs() <= 1e-14 * d.abs().max(1.0));
        }
    }
    Some((row_err, k_err, count))
}

#[test]
fn quadratic_lagrange_rows_are_the_full_gap_derivative() {
    // curved, jittered, partly covering master: every slave node's row
    // (corners and midside nodes) over tri6 / quad8 / quad9 pairs;
    // measured (this test, --nocapture): row 2.4e-10 .. 9.3e-10, K 5.6e-9
    // .. 1.3e-8 (the tangent's FD error of the step 1e-7)
    for (ns, nm, seed) in [(8, 8, 11), (6, 9, 12), (9, 6, 13)] {
        let x = pair(ns, nm, 0.15, -0.02, 0.01, seed);
        let (row_err, k_err, rows) = fd_errors(&x, ns, 1.7).expect("a smooth pair");
        println!("slave {ns}, master {nm}: {rows} rows, FD row {row_err:.1e}, K {k_err:.1e}");
        assert!(rows >= ns / 2, "{ns} {nm}: {rows} rows");
        assert!(
            row_err < 1e-6 && k_err < 1e-6,
            "{ns} {nm}: {row_err:e} {k_err:e}"
        );
    }
}

#[test]
fn flat_uniform_gap_makes_the_row_the_force_column_and_the_gap_exact() {
    // flat faces at a uniform gap: the nodal gap of every covered node is
    // the gap (corners included: the dual of the positive-weight basis),
    // and the constraint row equals the force column `B / A` (nothing
    // curves); on a bent pair they differ at first order in the bend
    let differ = |c: &Coupling| {
        c.gap_gradient
            .iter()
            .zip(&c.force_direction)
            .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
    };
    for (ns, nm) in [(8, 8), (6, 9), (9, 6)] {
        let flat = lagrange_rows(&pair(ns, nm, 0.0, -0.02, 0.0, 1), ns, 1.0).unwrap();
        let mut rows = 0;
        for (j, (area, gap, c)) in flat
            .iter()
            .enumerate()
            .filter_map(|(j, r)| Some((j, r.as_ref()?)))
        {
            rows += 1;
            assert!(*area > 0.0);
            assert!((gap + 0.02).abs() < 1e-14, "{ns} {nm} {j}: {gap}");
            assert!(differ(c) < 1e-12, "{ns} {nm} {j}: {:e}", differ(c));
        }
        assert!(rows >= ns / 2, "{ns} {nm}: {rows} rows");
        let bent = lagrange_rows(&pair(ns, nm, 0.15, -0.02, 0.0, 1), ns, 1.0).unwrap();
        let most = bent
            .iter()
            .flatten()
            .map(|(_, _, c)| differ(c))
            .fold(0.0, f64::max);
        assert!(most > 1e-4, "{ns} {nm}: {most:e}");
    }
}
