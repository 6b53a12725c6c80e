//! Polar-structured disc sector with a triangle hub and 2:1 coarsening
//! towards the centre, shared by the half- and quarter-disc generators.
//!
//! Ring `n` (the arc) carries every graded arc angle. Going inwards, ring
//! `i` keeps the angles of ring `i + 1` except where two neighbouring
//! divisions are thinner than the radial spacing: those two are merged into
//! one (the middle node is dropped), when the merged division stays no wider
//! than `sqrt(2)` times the radial spacing below the ring. Rays stay
//! straight and radial, so arc grading keeps elements square near the arc
//! without sending needle-thin elements into the centre, and the innermost
//! ring is a fan of near-equilateral triangles instead of slivers.
//!
//! A merge turns the cell between the rings into a pentagon, cut into three
//! triangles (`Tri3`) or one quad and one triangle (`Quad4`). Quad diagonals
//! and transition cuts are mirrored about the `mirror` angle, so a
//! symmetric grading gives a mirror-symmetric mesh.

use super::common::{polar_point, push_quad};
use crate::mesh::{Cell, CellKind, Mesh};

/// Merge two divisions when the merged one is at most this times the radial
/// spacing: merging then improves the aspect ratio of the cells below.
const MERGE_LIMIT: f64 = std::f64::consts::SQRT_2;

/// Input of [`build`].
pub struct Sector {
    /// Centre of the circle.
    pub center: [f64; 2],
    /// Ring radii `r_1 < ... < r_n`, `r_n` = the disc radius (r_0 = 0 is the
    /// centre node).
    pub radii: Vec<f64>,
    /// Arc node angles in degrees, strictly increasing, at least 2.
    pub angles: Vec<f64>,
    /// Mirror angle (degrees): cells below it and above it use mirrored
    /// diagonals. At the first angle / last angle it also makes the merge
    /// pairing start from the opposite end; strictly inside it makes the
    /// pairing symmetric when the arc divisions are.
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

/// Which arc divisions to merge at one ring: returns the kept positions of
/// the outer ring (always both ends; never two neighbouring drops).
fn merge_pattern(widths: &[f64], mergeable: impl Fn(usize) -> bool, start: Start) -> Vec<bool> {
    let m = widths.len();
    let mut keep = vec![true; m + 1];
    // greedy over the divisions index range [lo, hi) in the given direction;
    // pair (j, j + 1) drops node j + 1.
    let greedy = |keep: &mut Vec<bool>, order: &mut dyn Iterator<Item = usize>| {
        let mut skip = false;
        for j in order {
            if skip {
                skip = false;
                continue;
            }
            if mergeable(j) {
                keep[j + 1] = false;
                skip = true;
            }
        }
    };
    match start {
        Start::Low => greedy(&mut keep, &mut (0..m.saturating_sub(1))),
        Start::High => greedy(&mut keep, &mut (0..m.saturating_sub(1)).rev()),
        Start::Mirror => {
            let scale = widths.iter().cloned().fold(0.0, f64::max);
            let symmetric = (0..m).all(|j| (widths[j] - widths[m - 1 - j]).abs() <= 1e-9 * scale);
            if !symmetric {
                greedy(&mut keep, &mut (0..m.saturating_sub(1)));
            } else {
                let half = m / 2;
                // pairs entirely inside the lower half, mirrored
                greedy(&mut keep, &mut (0..half.saturating_sub(1)));
                for k in 1..half {
                    if !keep[k] {
                        keep[m - k] = false;
                    }
                }
                // the two divisions around the middle node, if both are free
                if m % 2 == 0 && m >= 2 && keep[half - 1] && mergeable(half - 1) {
                    keep[half] = false;
                }
            }
        }
    }
    keep
}

/// Where the merge pairing starts.
#[derive(Clone, Copy)]
enum Start {
    Low,
    High,
    Mirror,
}

/// Builds the sector mesh.
pub fn build(s: &Sector) -> SectorMesh {
    let n = s.radii.len();
    let m = s.angles.len() - 1;
    let first = s.angles[0];
    let last = s.angles[m];
    let start = if s.mirror <= first {
        Start::High
    } else if s.mirror >= last {
        Start::Low
    } else {
        Start::Mirror
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
        let keep = merge_pattern(
            &widths,
            |j| r * (widths[j] + widths[j + 1]) <= MERGE_LIMIT * h,
            start,
        );
        if std::env::var("DISC_DEBUG").is_ok() && widths.len() >= 6 {
            let mm = widths.len();
            eprintln!("ring {i} r {r:.4} h {h:.4} m {mm} mid widths {:?} keep {:?}", &widths[mm/2-3..mm/2+3], &keep[mm/2-3..mm/2+4]);
        }
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
            debug_assert_eq!(outer_idx[o], inner_idx[k]);
            let span = if outer_idx[o + 1] == inner_idx[k + 1] {
                1
            } else {
                2
            };
            let mid = 0.5 * (s.angles[inner_idx[k]] + s.angles[inner_idx[k + 1]]);
            let low_side = mid < s.mirror;
            let (p, q) = (inner[k], inner[k + 1]);
            if span == 1 {
                let (a, b) = (outer[o], outer[o + 1]);
                push_quad(&mut mesh.cells, s.kind, [p, a, b, q], low_side);
            } else {
                let (a, b, c) = (outer[o], outer[o + 1], outer[o + 2]);
                match s.kind {
                    CellKind::Tri3 => {
                        mesh.cells.push(Cell::tri(p, a, b));
                        mesh.cells.push(Cell::tri(p, b, q));
                        mesh.cells.push(Cell::tri(q, b, c));
                    }
                    CellKind::Quad4 if low_side => {
                        mesh.cells.push(Cell::tri(p, a, b));
                        mesh.cells.push(Cell::quad(p, b, c, q));
                    }
                    CellKind::Quad4 => {
                        mesh.cells.push(Cell::quad(p, a, b, q));
                        mesh.cells.push(Cell::tri(q, b, c));
                    }
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

#[cfg(test)]
mod scratch_tests {
    use super::*;
    #[test]
    fn scratch_pattern() {
        let w = vec![0.3, 0.2, 0.1, 0.05, 0.05, 0.1, 0.2, 0.3];
        let keep = merge_pattern(&w, |j| w[j] + w[j + 1] <= 0.11, Start::Mirror);
        println!("{keep:?}");
    }
}
