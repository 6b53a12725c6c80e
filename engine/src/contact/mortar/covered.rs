//! The dual basis over the covered part of a 3D slave facet (tri3 / quad4;
//! Popp, Wohlmuth, Gee & Wall, SIAM J. Sci. Comput. 34 (2012) B421, §3.2
//! and Popp et al., CMAME 264 (2013) 67, "Improved robustness and
//! consistency of 3D contact algorithms based on a dual mortar approach",
//! §3: the dual functions of a partially integrated slave element are
//! biorthogonal over the part actually integrated).
//!
//! [`super::facets`] builds the dual functions `psi_j = sum_k A_jk N_k` of
//! a slave facet from its whole mass matrix (`A = D_e M_e^-1`): where the
//! master covers only part of the facet, `int_cov psi_j N_k` is no longer
//! diagonal and the nodal area `A_j = sum_k D_jk` can be negative (the
//! ironing die's end: `A_j = -0.165 T_j`, a node "closed" at a positive
//! gap). Here, per slave facet, from the facet pairs the search kept (its
//! integration cells): `M_cov = int_cov N N^T`, `d_j = int_cov N_j` and
//! the coefficients `A_cov = diag(d) M_cov^-1`, so that `int_cov psi_j N_k
//! = delta_jk d_j`: `D` diagonal and positive on what is integrated. The
//! pairs were integrated with `A` (full facet), so `D_p = A M_cov,p`
//! and the change of basis is `X_cov,p = T X_p`, `T = A_cov A^-1 =
//! diag(d) (sum_p D_p)^-1`, applied to `D`, `M` and the weighted gaps of
//! every pair of the facet: no second integration. `T` depends on every
//! master facet that covers the slave one, so the transformed integrals
//! are dual numbers over the slave facet's nodes and all those master
//! nodes ([`Part`], sizes [`Covered`]); the linearization is exact.
//!
//! A facet covered to within [`FULL`] of its area keeps the full-facet
//! basis bit for bit (the patch tests); `sum_p D_p` near singular (a
//! covered sliver, pivot below [`PIVOT`]) or more than
//! [`MAX_MASTER_NODES`] master nodes keep it too (counted in [`Outcome`]).

use super::ad::Ad;
use super::facets::Ad24;
use super::{FacetPiece, UNUSED};

/// Most distinct master nodes over the pairs of one slave facet handled
/// (the largest [`Covered`] size).
pub(super) const MAX_MASTER_NODES: usize = 64;

/// A slave facet whose pairs' clip polygons sum to at least `1 - FULL` of
/// its projected area is fully covered: the full-facet dual basis.
pub(super) const FULL: f64 = 1e-9;

/// Smallest pivot of `sum_p D_p` (partial pivoting), relative to its
/// largest entry, for the covered-part basis.
pub(super) const PIVOT: f64 = 1e-12;

/// The integrals of one facet pair in the covered-part basis, dual numbers
/// over `vars` (3 components each: the slave facet's 4 slots, a tri3's
/// fourth [`UNUSED`], then the master nodes of every pair of the facet).
#[derive(Debug, Clone)]
pub(super) struct Part<const G: usize> {
    pub vars: Vec<usize>,
    pub d: [[Ad<G>; 4]; 4],
    pub m: [[Ad<G>; 4]; 4],
    pub gap: [Ad<G>; 4],
    pub normal: [Ad<G>; 3],
}

/// A [`Part`] of the size its facet's master nodes need (`G = 12 + 3 K`,
/// `K` master nodes at most 8, 16, 32, 64).
#[derive(Debug, Clone)]
pub(super) enum Covered {
    G36(Box<Part<36>>),
    G60(Box<Part<60>>),
    G108(Box<Part<108>>),
    G204(Box<Part<204>>),
}

/// What [`cover`] did with the slave facets: fully covered (unchanged),
/// partly covered (covered-part basis), left with the full-facet basis
/// (singular `sum_p D_p` or too many master nodes).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Outcome {
    pub full: usize,
    pub partial: usize,
    pub kept: usize,
}

/// The slave facet's slots of a piece.
fn slave_slots(vars: &[usize; 8]) -> [usize; 4] {
    [vars[0], vars[1], vars[2], vars[3]]
}

/// Sets `covered` on the pieces of every partly covered slave facet
/// (pieces of one slave facet are contiguous, as
/// [`super::face_pairs`] lists them).
pub(super) fn cover(pieces: &mut [FacetPiece]) -> Outcome {
    let mut out = Outcome::default();
    let mut start = 0;
    while start < pieces.len() {
        let key = slave_slots(&pieces[start].vars);
        let mut end = start + 1;
        while end < pieces.len() && slave_slots(&pieces[end].vars) == key {
            end += 1;
        }
        let group = &mut pieces[start..end];
        let covered: f64 = group.iter().map(|p| p.seg.area).sum();
        if covered >= (1.0 - FULL) * group[0].seg.slave_area {
            out.full += 1;
        } else if cover_group(group) {
            out.partial += 1;
        } else {
            out.kept += 1;
        }
        start = end;
    }
    out
}

/// The covered-part basis on one slave facet's pieces; false (pieces
/// unchanged) when `sum_p D_p` is near singular or the master nodes are
/// too many.
fn cover_group(group: &mut [FacetPiece]) -> bool {
    let mut masters: Vec<usize> = group
        .iter()
        .flat_map(|p| p.vars[4..].iter().copied())
        .filter(|&n| n != UNUSED)
        .collect();
    masters.sort_unstable();
    masters.dedup();
    macro_rules! parts {
        ($g:literal, $variant:ident) => {
            match transform::<$g>(group, &masters) {
                Some(parts) => {
                    for (p, part) in group.iter_mut().zip(parts) {
                        p.covered = Some(Covered::$variant(Box::new(part)));
                    }
                    true
                }
                None => false,
            }
        };
    }
    match masters.len() {
        0..=8 => parts!(36, G36),
        9..=16 => parts!(60, G60),
        17..=32 => parts!(108, G108),
        33..=MAX_MASTER_NODES => parts!(204, G204),
        _ => false,
    }
}

/// `x` (over a pair's 24 coordinates) over the group's variables (`map`:
/// pair coordinate -> group coordinate, `usize::MAX` for none).
fn lift<const G: usize>(x: &Ad24, map: &[usize; 24]) -> Ad<G> {
    let mut d = [0.0; G];
    for (k, &v) in x.d.iter().enumerate() {
        if let Some(slot) = d.get_mut(map[k]) {
            *slot += v;
        }
    }
    Ad { v: x.v, d }
}

/// The covered-part integrals of every pair of one slave facet.
#[allow(clippy::needless_range_loop)]
fn transform<const G: usize>(group: &[FacetPiece], masters: &[usize]) -> Option<Vec<Part<G>>> {
    let ns = group[0].seg.ns;
    let z = Ad::<G>::cst(0.0);
    let mut vars: Vec<usize> = group[0].vars[..4].to_vec();
    vars.extend_from_slice(masters);
    let maps: Vec<[usize; 24]> = group
        .iter()
        .map(|p| {
            std::array::from_fn(|k| {
                if k < 12 {
                    return k;
                }
                let node = p.vars[4 + (k - 12) / 3];
                match masters.binary_search(&node) {
                    Ok(q) if node != UNUSED => 12 + 3 * q + k % 3,
                    _ => usize::MAX,
                }
            })
        })
        .collect();
    let mut sum = [[z; 4]; 4];
    let mut lumped = [z; 4];
    for (p, map) in group.iter().zip(&maps) {
        for j in 0..ns {
            lumped[j] += lift(&p.seg.lumped[j], map);
            for k in 0..ns {
                sum[j][k] += lift(&p.seg.d[j][k], map);
            }
        }
    }
    let inv = invert(&sum, ns)?;
    let mut t = [[z; 4]; 4];
    for j in 0..ns {
        for q in 0..ns {
            t[j][q] = lumped[j] * inv[j][q];
        }
    }
    let parts = group
        .iter()
        .zip(&maps)
        .map(|(p, map)| {
            let s = &p.seg;
            let mut part = Part {
                vars: vars.clone(),
                d: [[z; 4]; 4],
                m: [[z; 4]; 4],
                gap: [z; 4],
                normal: s.normal.map(|v| lift(&v, map)),
            };
            let d: Vec<[Ad<G>; 4]> = (0..ns)
                .map(|q| std::array::from_fn(|k| lift(&s.d[q][k], map)))
                .collect();
            let m: Vec<[Ad<G>; 4]> = (0..ns)
                .map(|q| std::array::from_fn(|l| lift(&s.m[q][l], map)))
                .collect();
            let gap: Vec<Ad<G>> = (0..ns).map(|q| lift(&s.gap[q], map)).collect();
            for j in 0..ns {
                for q in 0..ns {
                    let tq = t[j][q];
                    for k in 0..ns {
                        part.d[j][k] += tq * d[q][k];
                    }
                    for l in 0..s.nm {
                        part.m[j][l] += tq * m[q][l];
                    }
                    part.gap[j] += tq * gap[q];
                }
            }
            part
        })
        .collect();
    Some(parts)
}

/// The inverse of the leading `n x n` block of `a` (Gauss-Jordan with
/// partial pivoting on the values); `None` for a pivot below [`PIVOT`]
/// of the largest entry.
fn invert<const G: usize>(a: &[[Ad<G>; 4]; 4], n: usize) -> Option<[[Ad<G>; 4]; 4]> {
    let mut a = *a;
    let mut inv = [[Ad::<G>::cst(0.0); 4]; 4];
    for (j, row) in inv.iter_mut().enumerate().take(n) {
        row[j] = Ad::cst(1.0);
    }
    let scale = (0..n)
        .flat_map(|j| (0..n).map(move |k| (j, k)))
        .map(|(j, k)| a[j][k].v.abs())
        .fold(0.0, f64::max);
    for c in 0..n {
        let p = (c..n).max_by(|&r, &s| a[r][c].v.abs().total_cmp(&a[s][c].v.abs()))?;
        let size = a[p][c].v.abs();
        if size.is_nan() || size <= PIVOT * scale {
            return None;
        }
        a.swap(p, c);
        inv.swap(p, c);
        let pivot = a[c][c];
        for k in 0..n {
            a[c][k] = a[c][k] / pivot;
            inv[c][k] = inv[c][k] / pivot;
        }
        for r in 0..n {
            if r == c {
                continue;
            }
            let f = a[r][c];
            for k in 0..n {
                a[r][k] = a[r][k] - f * a[c][k];
                inv[r][k] = inv[r][k] - f * inv[c][k];
            }
        }
    }
    Some(inv)
}

#[cfg(test)]
mod tests {
    use super::super::facets::{facet_pair, Basis};
    use super::*;

    /// Slave: the unit square at `z = 0` (nodes 0..4, outward `+z`);
    /// master: two quads over `x in [-0.5, 0.4]`, `y in [-0.5, 0.5]` and
    /// `[0.5, 1.5]` (nodes 4..10), on the plane `z = 0.05 + 0.02 x + 0.03
    /// y`, facing down: 40 % of the slave facet covered.
    fn nodes() -> Vec<[f64; 3]> {
        let mut x = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        for y in [-0.5, 0.5, 1.5] {
            for xm in [-0.5, 0.4] {
                x.push([xm, y, 0.05 + 0.02 * xm + 0.03 * y]);
            }
        }
        x
    }

    const SLAVE: [usize; 4] = [0, 1, 2, 3];
    const MASTERS: [[usize; 4]; 2] = [[4, 6, 7, 5], [6, 8, 9, 7]];

    /// The facet pairs at `x`, before and after [`cover`].
    fn pieces(x: &[[f64; 3]]) -> (Vec<FacetPiece>, Outcome) {
        let sx: Vec<[f64; 3]> = SLAVE.iter().map(|&n| x[n]).collect();
        let mut out = Vec::new();
        for (k, mf) in MASTERS.iter().enumerate() {
            let mx: Vec<[f64; 3]> = mf.iter().map(|&n| x[n]).collect();
            let seg = facet_pair(&sx, &mx, Basis::Dual).unwrap();
            let mut vars = [UNUSED; 8];
            vars[..4].copy_from_slice(&SLAVE);
            vars[4..].copy_from_slice(mf);
            out.push(FacetPiece {
                vars,
                master: k,
                seg,
                covered: None,
            });
        }
        let outcome = cover(&mut out);
        (out, outcome)
    }

    fn part(p: &FacetPiece) -> &Part<36> {
        match &p.covered {
            Some(Covered::G36(p)) => p,
            other => panic!("expected a 36-direction part, got {other:?}"),
        }
    }

    #[test]
    #[allow(clippy::needless_range_loop)]
    fn a_partly_covered_facet_gets_positive_areas_and_a_diagonal_d() {
        let x = nodes();
        let (pieces, outcome) = pieces(&x);
        assert_eq!(
            outcome,
            Outcome {
                full: 0,
                partial: 1,
                kept: 0
            }
        );
        let gap = |p: [f64; 3]| 0.05 + 0.02 * p[0] + 0.03 * p[1];
        for j in 0..4 {
            // the full-facet duals: int_cov psi_j < 0 on the uncovered side
            let old: f64 = pieces
                .iter()
                .map(|p| p.seg.d[j].iter().map(|v| v.v).sum::<f64>())
                .sum();
            let (mut area, mut g, mut d) = (0.0, 0.0, [0.0; 4]);
            for p in &pieces {
                let part = part(p);
                for k in 0..4 {
                    d[k] += part.d[j][k].v;
                }
                area += part.d[j].iter().map(|v| v.v).sum::<f64>();
                g += part.gap[j].v;
            }
            // int_cov N_j over [0, 0.4] x [0, 1]: 0.4 (1 - 0.2) / 2 at
            // x = 0, 0.4 * 0.2 / 2 at x = 1
            let lumped = if x[j][0] == 0.0 { 0.16 } else { 0.04 };
            println!("node {j}: full-facet A_j = {old:+.4}, covered-part A_j = {area:.4}");
            if x[j][0] == 1.0 {
                assert!(old < -0.01, "{old}");
            }
            assert!((area - lumped).abs() < 1e-14, "{area}");
            for (k, v) in d.iter().enumerate() {
                let expected = if k == j { lumped } else { 0.0 };
                assert!((v - expected).abs() < 1e-14, "D_{j}{k} = {v:e}");
            }
            // biorthogonality on the covered part: the nodal gap of a
            // linear gap is its nodal value (the full-facet basis is off)
            assert!(
                (g / area - gap(x[j])).abs() < 1e-13,
                "{} {}",
                g / area,
                gap(x[j])
            );
        }
    }

    #[test]
    fn covered_part_integrals_match_finite_differences() {
        let mut x = nodes();
        // jitter: a warped slave, a master not parallel to it
        for (n, p) in x.iter_mut().enumerate() {
            for (c, v) in p.iter_mut().enumerate() {
                *v += 0.01 * (((7 * n + 3 * c) % 11) as f64 / 11.0 - 0.5);
            }
        }
        let (base, _) = pieces(&x);
        let values = |ps: &[FacetPiece]| -> Vec<f64> {
            let mut v = Vec::new();
            for p in ps {
                let part = part(p);
                v.extend(part.d.iter().flatten().map(|a| a.v));
                v.extend(part.m.iter().flatten().map(|a| a.v));
                v.extend(part.gap.iter().map(|a| a.v));
            }
            v
        };
        let grads = |ps: &[FacetPiece], slot: usize| -> Vec<f64> {
            let mut v = Vec::new();
            for p in ps {
                let part = part(p);
                v.extend(part.d.iter().flatten().map(|a| a.d[slot]));
                v.extend(part.m.iter().flatten().map(|a| a.d[slot]));
                v.extend(part.gap.iter().map(|a| a.d[slot]));
            }
            v
        };
        let vars = part(&base[0]).vars.clone();
        let h = 1e-6;
        let mut worst = 0.0f64;
        for n in 0..x.len() {
            let q = vars.iter().position(|&v| v == n).unwrap();
            for c in 0..3 {
                let mut xp = x.clone();
                let mut xm = x.clone();
                xp[n][c] += h;
                xm[n][c] -= h;
                let (vp, vm) = (values(&pieces(&xp).0), values(&pieces(&xm).0));
                for ((a, b), g) in vp.iter().zip(&vm).zip(grads(&base, 3 * q + c)) {
                    let fd = (a - b) / (2.0 * h);
                    worst = worst.max((fd - g).abs() / (1.0 + fd.abs()));
                }
            }
        }
        println!("covered-part D, M, g~ vs central differences: {worst:.2e}");
        assert!(worst < 1e-7, "{worst:e}");
    }
}
