//! Polar-structured disc sector with a triangle hub and coarsening towards
//! the centre, shared by the half- and quarter-disc generators.
//!
//! Ring `n` (the arc) carries every graded arc angle, and so does ring
//! `n - 1` (the layer along the arc, where contact happens, has one regular
//! cell per arc division). Going further inwards, ring `i` keeps the angles
//! of ring `i + 1` except where neighbouring divisions
//! are thinner than the radial spacing: those are merged by pairs (the node
//! between them is dropped), thinnest first, when the merged division stays
//! no wider than [`MERGE_LIMIT`] times the radial spacing below the ring. Rays stay
//! straight and radial, so an arc grading keeps elements square near the
//! arc without sending needle-thin elements into the centre, and the
//! innermost ring is a fan of reasonable triangles instead of slivers.
//!
//! A pair merge turns the cell between the rings into a pentagon, cut into
//! three triangles (`Tri3`) or one quad and one triangle (`Quad4`). With the
//! pole in the middle of a symmetric arc (half disc) the matching is done on
//! one half and mirrored: the pole ray is kept, or with an odd count the
//! middle division may merge with both its neighbours (a hexagon: two
//! triangles and a quad). Quad diagonals and
//! transition cuts are mirrored about the `mirror` angle, so a symmetric
//! grading gives a mirror-symmetric mesh.

use super::common::{divisions, finite_point, node_budget, polar_point, positive, push_quad};
use super::Grading;
use crate::mesh::{Cell, CellKind, Mesh, MeshError};

/// Merge divisions when the merged one is at most this times the radial
/// spacing below the ring. Merging improves the aspect ratio of the cells
/// below up to sqrt(2); the margin keeps uniform polar meshes free of
/// transitions until their cells are about 1.7 times thinner than deep
/// (each transition costs a triangle in a quad mesh).
pub const MERGE_LIMIT: f64 = 1.2;

/// Input of [`build`].
pub struct Sector {
    /// Centre of the circle.
    pub center: [f64; 2],
    /// Ring radii `r_1 < ... < r_n`, `r_n` = the disc radius (r_0 = 0 is the
    /// centre node).
    pub radii: Vec<f64>,
    /// Arc node angles in degrees, strictly increasing, at least 2.
    pub angles: Vec<f64>,
    /// Mirror angle (degrees), where the pole is: at the first angle, at the
    /// last one, or in between (half disc). Cells below and above it use
    /// mirrored diagonals.
    pub mirror: f64,
    /// Tri3 or Quad4.
    pub kind: CellKind,
}

/// Output of [`build`]: the mesh (no sets yet) and its node numbering.
pub struct SectorMesh {
    /// Nodes and cells.
    pub mesh: Mesh,
    /// Node number of the centre.
    pub center: usize,
    /// `rings[i - 1]` = node numbers of ring `i`, by increasing angle; the
    /// last ring is the arc.
    pub rings: Vec<Vec<usize>>,
}

/// Where the pole (the finest, contact end of the arc) sits among the ring
/// divisions: it sets the tie-breaking order of the merge matching.
#[derive(Clone, Copy, PartialEq, Debug)]
enum Pole {
    /// At the first angle.
    Low,
    /// At the last angle.
    High,
    /// In the middle: matching is done on the lower half and mirrored.
    Middle,
}

/// Pairs neighbouring free divisions of `range`, thinnest first: each free
/// division is merged with its thinner free neighbour when `mergeable`
/// allows it. Widths equal to 1e-9 relative count as ties, broken towards
/// the pole (`pole_high`: the high end). Pair (j, j + 1) drops node j + 1.
fn match_range(
    widths: &[f64],
    range: std::ops::Range<usize>,
    pole_high: bool,
    mergeable: &dyn Fn(usize, usize) -> bool,
    paired: &mut [bool],
    keep: &mut [bool],
) {
    let (lo, hi) = (range.start, range.end);
    if hi <= lo + 1 {
        return;
    }
    let scale = widths[lo..hi].iter().cloned().fold(0.0, f64::max);
    let q = |w: f64| (w / scale * 1e9).round() as i64;
    let toward_pole = |j: usize| if pole_high { usize::MAX - j } else { j };
    let mut order: Vec<usize> = (lo..hi).collect();
    order.sort_by_key(|&j| (q(widths[j]), toward_pole(j)));
    for j in order {
        if paired[j] {
            continue;
        }
        let left = (j > lo && !paired[j - 1]).then(|| j - 1);
        let right = (j + 1 < hi && !paired[j + 1]).then(|| j + 1);
        let other = match (left, right) {
            (Some(l), Some(r)) => {
                let (wl, wr) = (q(widths[l]), q(widths[r]));
                if wl < wr || (wl == wr && !pole_high) {
                    l
                } else {
                    r
                }
            }
            (Some(l), None) => l,
            (None, Some(r)) => r,
            (None, None) => continue,
        };
        let (a, b) = (j.min(other), j.max(other));
        if mergeable(a, b) {
            paired[a] = true;
            paired[b] = true;
            keep[b] = false;
        }
    }
}

/// Which divisions of a ring to merge going one ring inwards: returns the
/// kept nodes of the outer ring (always both ends). With the pole in the
/// middle of a symmetric ring, the lower half is matched and mirrored: an
/// even ring keeps its middle (pole) node, an odd ring merges its middle
/// division with both neighbours (first, being the thinnest when the pole
/// is refined) or keeps it. `mergeable(j, k)`: may divisions
/// `j..=k` become one.
fn merge_pattern(
    widths: &[f64],
    mergeable: &dyn Fn(usize, usize) -> bool,
    pole: Pole,
) -> Vec<bool> {
    let m = widths.len();
    let mut keep = vec![true; m + 1];
    let mut paired = vec![false; m];
    let scale = widths.iter().cloned().fold(0.0, f64::max);
    let symmetric = (0..m).all(|j| (widths[j] - widths[m - 1 - j]).abs() <= 1e-9 * scale);
    match pole {
        Pole::Low => match_range(widths, 0..m, false, mergeable, &mut paired, &mut keep),
        Pole::High => match_range(widths, 0..m, true, mergeable, &mut paired, &mut keep),
        Pole::Middle if !symmetric => {
            match_range(widths, 0..m, false, mergeable, &mut paired, &mut keep)
        }
        Pole::Middle => {
            let half = m / 2;
            if m >= 3 && !m.is_multiple_of(2) && mergeable(half - 1, half + 1) {
                paired[half - 1] = true;
                keep[half] = false;
                keep[half + 1] = false;
            }
            match_range(widths, 0..half, true, mergeable, &mut paired, &mut keep);
            for k in 1..half {
                if !keep[k] {
                    keep[m - k] = false;
                }
            }
        }
    }
    keep
}

/// Builds the sector mesh.
pub fn build(s: &Sector) -> SectorMesh {
    let n = s.radii.len();
    let m = s.angles.len() - 1;
    let pole = if s.mirror <= s.angles[0] {
        Pole::Low
    } else if s.mirror >= s.angles[m] {
        Pole::High
    } else {
        Pole::Middle
    };

    // ring angle indices (into s.angles), from the arc inwards
    let mut ring_idx: Vec<Vec<usize>> = vec![Vec::new(); n];
    ring_idx[n - 1] = (0..=m).collect();
    for i in (0..n - 1).rev() {
        let outer = &ring_idx[i + 1];
        let r = s.radii[i];
        let h = r - if i == 0 { 0.0 } else { s.radii[i - 1] };
        let widths: Vec<f64> = outer
            .windows(2)
            .map(|w| (s.angles[w[1]] - s.angles[w[0]]).to_radians())
            .collect();
        let mergeable =
            |j: usize, k: usize| r * widths[j..=k].iter().sum::<f64>() <= MERGE_LIMIT * h;
        // the layer at the arc is never a transition: the surface cells
        // (contact) stay regular, one per arc division
        let keep = if i + 2 == n {
            vec![true; widths.len() + 1]
        } else {
            merge_pattern(&widths, &mergeable, pole)
        };
        ring_idx[i] = outer
            .iter()
            .zip(&keep)
            .filter(|(_, &k)| k)
            .map(|(&g, _)| g)
            .collect();
    }

    let mut mesh = Mesh::default();
    mesh.nodes.push(s.center);
    let mut rings: Vec<Vec<usize>> = Vec::with_capacity(n);
    for (i, idx) in ring_idx.iter().enumerate() {
        let r = s.radii[i];
        rings.push(
            idx.iter()
                .map(|&g| {
                    mesh.nodes.push(polar_point(s.center, r, s.angles[g]));
                    mesh.nodes.len() - 1
                })
                .collect(),
        );
    }

    // hub: fan of triangles around the centre
    for w in rings[0].windows(2) {
        mesh.cells.push(Cell::tri(0, w[0], w[1]));
    }
    // layers between ring i (inner) and ring i + 1 (outer)
    for i in 0..n - 1 {
        let (inner_idx, outer_idx) = (&ring_idx[i], &ring_idx[i + 1]);
        let (inner, outer) = (&rings[i], &rings[i + 1]);
        let mut o = 0;
        for k in 0..inner_idx.len() - 1 {
            let span = (o + 1..outer_idx.len())
                .find(|&t| outer_idx[t] == inner_idx[k + 1])
                .expect("inner ring angles are a subset of the outer ones")
                - o;
            let mid = 0.5 * (s.angles[inner_idx[k]] + s.angles[inner_idx[k + 1]]);
            let low_side = mid < s.mirror;
            let (p, q) = (inner[k], inner[k + 1]);
            let a = &outer[o..=o + span];
            match (span, s.kind) {
                (1, _) => push_quad(&mut mesh.cells, s.kind, [p, a[0], a[1], q], low_side),
                (2, CellKind::Tri3) => {
                    mesh.cells.push(Cell::tri(p, a[0], a[1]));
                    mesh.cells.push(Cell::tri(p, a[1], q));
                    mesh.cells.push(Cell::tri(q, a[1], a[2]));
                }
                (2, CellKind::Quad4) if low_side => {
                    mesh.cells.push(Cell::tri(p, a[0], a[1]));
                    mesh.cells.push(Cell::quad(p, a[1], a[2], q));
                }
                (2, CellKind::Quad4) => {
                    mesh.cells.push(Cell::quad(p, a[0], a[1], q));
                    mesh.cells.push(Cell::tri(q, a[1], a[2]));
                }
                _ => {
                    // the symmetric middle merge of three divisions
                    debug_assert_eq!(span, 3);
                    mesh.cells.push(Cell::tri(p, a[0], a[1]));
                    push_quad(&mut mesh.cells, s.kind, [p, a[1], a[2], q], low_side);
                    mesh.cells.push(Cell::tri(q, a[2], a[3]));
                }
            }
            o += span;
        }
    }
    SectorMesh {
        mesh,
        center: 0,
        rings,
    }
}

/// Checks the parameters shared by the half and quarter disc generators
/// (`min_circumferential` divisions at least) and returns the ring radii
/// (centre excluded, arc last) and the circumferential grading points in
/// [0, 1].
#[allow(clippy::too_many_arguments)]
pub fn checked_rings(
    name: &str,
    center: [f64; 2],
    radius: f64,
    radial: usize,
    circumferential: usize,
    min_circumferential: usize,
    radial_grading: Grading,
    circumferential_grading: Grading,
) -> Result<(Vec<f64>, Vec<f64>), MeshError> {
    finite_point(name, "center", center)?;
    positive(name, "radius", radius)?;
    divisions(name, "radial", radial, 1)?;
    divisions(
        name,
        "circumferential",
        circumferential,
        min_circumferential,
    )?;
    radial_grading.check(&format!("{name} radial grading"))?;
    circumferential_grading.check(&format!("{name} circumferential grading"))?;
    node_budget(
        name,
        circumferential
            .checked_add(1)
            .and_then(|c| c.checked_mul(radial))
            .and_then(|c| c.checked_add(1)),
    )?;
    let radii = radial_grading.points(radial)[1..]
        .iter()
        .map(|t| radius * t)
        .collect();
    Ok((radii, circumferential_grading.points(circumferential)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(w: &[f64], limit: f64, pole: Pole) -> Vec<bool> {
        merge_pattern(w, &|j, k| w[j..=k].iter().sum::<f64>() <= limit, pole)
    }

    #[test]
    fn merge_pattern_symmetric_pairs_keep_the_pole() {
        let w = [0.3, 0.2, 0.1, 0.05, 0.05, 0.1, 0.2, 0.3];
        // (2, 3) and its mirror (4, 5); the pole node 4 stays
        let keep = kept(&w, 0.31, Pole::Middle);
        assert_eq!(
            keep,
            vec![true, true, true, false, true, false, true, true, true]
        );
    }

    #[test]
    fn merge_pattern_odd_middle_merges_with_both_neighbours() {
        let w = [0.3, 0.1, 0.02, 0.1, 0.3];
        let keep = kept(&w, 0.25, Pole::Middle);
        assert_eq!(keep, vec![true, true, false, false, true, true]);
    }

    #[test]
    fn merge_pattern_thinnest_first_does_not_strand_a_thin_division() {
        // greedy from the left would pair (0, 1) and leave 2 alone
        let w = [0.1, 0.01, 0.01, 0.2];
        let keep = kept(&w, 0.15, Pole::Low);
        assert_eq!(keep, vec![true, true, false, true, true]);
    }

    #[test]
    fn merge_pattern_uniform_pairs_from_the_pole() {
        let w = [0.1; 5];
        assert_eq!(
            kept(&w, 0.25, Pole::High),
            vec![true, true, false, true, false, true]
        );
        assert_eq!(
            kept(&w, 0.25, Pole::Low),
            vec![true, false, true, false, true, true]
        );
    }

    #[test]
    fn merge_pattern_nothing_mergeable_keeps_all() {
        let w = [0.2, 0.2, 0.2];
        assert_eq!(kept(&w, 0.3, Pole::Middle), vec![true; 4]);
    }
}
