//! Broad phase of the contact search: a uniform bucket grid over the boxes
//! of the master entities (segments), rebuilt when the geometry moves.
//!
//! A query returns the entities whose box, inflated by `radius` (the search
//! window `prof`), contains the point: the narrow phase (projection) then
//! only runs on those. Building is `O(n)` (each box is registered in the
//! cells it covers), a query visits the cells of one inflated point box.
//! The cell size defaults to the mean box extent, so a box covers O(1)
//! cells and a cell holds O(1) boxes for a surface mesh of even size.

use super::aabb::Aabb;

/// Uniform grid of entity boxes.
#[derive(Debug, Clone)]
pub struct BroadPhase {
    /// Lower-left corner of the grid.
    origin: [f64; 2],
    /// Cell size (same in x and y), > 0.
    cell: f64,
    /// Number of cells in x and y.
    dims: [usize; 2],
    /// Start of each cell's entries in `entries` (`dims[0] * dims[1] + 1`).
    start: Vec<usize>,
    /// Entity indices, grouped by cell, ascending within a cell.
    entries: Vec<usize>,
    /// The boxes the grid was built from.
    boxes: Vec<Aabb>,
}

/// Upper bound on the number of grid cells (memory guard for a few huge
/// boxes among many small ones).
const MAX_CELLS: usize = 1 << 22;

impl BroadPhase {
    /// Builds the grid over `boxes` (finite boxes; an empty list gives an
    /// empty grid).
    pub fn build(boxes: &[Aabb]) -> Self {
        let mut bounds = Aabb {
            min: [f64::INFINITY; 2],
            max: [f64::NEG_INFINITY; 2],
        };
        let mut extent = 0.0;
        for b in boxes {
            bounds.include(b.min);
            bounds.include(b.max);
            extent += (b.max[0] - b.min[0]).max(b.max[1] - b.min[1]);
        }
        let finite = boxes
            .iter()
            .all(|b| b.min.iter().chain(&b.max).all(|v| v.is_finite()));
        if boxes.is_empty() || !finite {
            return BroadPhase {
                origin: [0.0; 2],
                cell: 1.0,
                dims: [1, 1],
                start: vec![0, boxes.len()],
                entries: (0..boxes.len()).collect(),
                boxes: boxes.to_vec(),
            };
        }
        let span = (bounds.max[0] - bounds.min[0]).max(bounds.max[1] - bounds.min[1]);
        let mut cell = (extent / boxes.len() as f64)
            .max(span * 1e-9)
            .max(f64::MIN_POSITIVE);
        let dims_for = |cell: f64| {
            [
                ((bounds.max[0] - bounds.min[0]) / cell) as usize + 1,
                ((bounds.max[1] - bounds.min[1]) / cell) as usize + 1,
            ]
        };
        let mut dims = dims_for(cell);
        while dims[0].saturating_mul(dims[1]) > MAX_CELLS {
            cell *= 2.0;
            dims = dims_for(cell);
        }
        let mut grid = BroadPhase {
            origin: bounds.min,
            cell,
            dims,
            start: Vec::new(),
            entries: Vec::new(),
            boxes: boxes.to_vec(),
        };
        // counting sort of (cell, entity) pairs
        let ncell = dims[0] * dims[1];
        let mut count = vec![0usize; ncell + 1];
        for b in boxes {
            let (lo, hi) = grid.cell_range(b.min, b.max);
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    count[i + j * dims[0] + 1] += 1;
                }
            }
        }
        for k in 0..ncell {
            count[k + 1] += count[k];
        }
        let mut fill = count.clone();
        let mut entries = vec![0usize; count[ncell]];
        for (e, b) in boxes.iter().enumerate() {
            let (lo, hi) = grid.cell_range(b.min, b.max);
            for j in lo[1]..=hi[1] {
                for i in lo[0]..=hi[0] {
                    let c = i + j * dims[0];
                    entries[fill[c]] = e;
                    fill[c] += 1;
                }
            }
        }
        grid.start = count;
        grid.entries = entries;
        grid
    }

    /// Cell index range (clamped to the grid) covering the box `[min, max]`.
    fn cell_range(&self, min: [f64; 2], max: [f64; 2]) -> ([usize; 2], [usize; 2]) {
        let idx = |v: f64, o: f64, n: usize| -> usize {
            let k = ((v - o) / self.cell).floor();
            if k.is_nan() || k < 0.0 {
                0
            } else {
                (k as usize).min(n - 1)
            }
        };
        (
            [
                idx(min[0], self.origin[0], self.dims[0]),
                idx(min[1], self.origin[1], self.dims[1]),
            ],
            [
                idx(max[0], self.origin[0], self.dims[0]),
                idx(max[1], self.origin[1], self.dims[1]),
            ],
        )
    }

    /// Entities whose box inflated by `radius` contains `p`, ascending and
    /// without duplicates, written to `out` (cleared first).
    pub fn query(&self, p: [f64; 2], radius: f64, out: &mut Vec<usize>) {
        out.clear();
        if self.boxes.is_empty() || !(p[0].is_finite() && p[1].is_finite()) {
            return;
        }
        let r = radius.max(0.0);
        let (lo, hi) = self.cell_range([p[0] - r, p[1] - r], [p[0] + r, p[1] + r]);
        for j in lo[1]..=hi[1] {
            for i in lo[0]..=hi[0] {
                let c = i + j * self.dims[0];
                for &e in &self.entries[self.start[c]..self.start[c + 1]] {
                    if self.boxes[e].contains_within(p, r) {
                        out.push(e);
                    }
                }
            }
        }
        out.sort_unstable();
        out.dedup();
    }

    /// Number of entities.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True if the grid holds no entity.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn segment_boxes(n: usize) -> Vec<Aabb> {
        // a wavy open polyline of n segments
        let pts: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let x = i as f64 / n as f64;
                [x, 0.1 * (7.0 * x).sin()]
            })
            .collect();
        pts.windows(2).map(Aabb::around).collect()
    }

    #[test]
    fn query_matches_brute_force() {
        let boxes = segment_boxes(200);
        let grid = BroadPhase::build(&boxes);
        let mut out = Vec::new();
        for k in 0..500 {
            let p = [
                -0.1 + 1.2 * ((k * 37 % 500) as f64 / 500.0),
                -0.2 + 0.4 * ((k * 91 % 500) as f64 / 500.0),
            ];
            let r = 0.003 * (k % 7) as f64;
            grid.query(p, r, &mut out);
            let brute: Vec<usize> = (0..boxes.len())
                .filter(|&e| boxes[e].contains_within(p, r))
                .collect();
            assert_eq!(out, brute, "point {p:?} radius {r}");
        }
    }

    #[test]
    fn empty_and_degenerate_inputs_do_not_panic() {
        let mut out = vec![7];
        BroadPhase::build(&[]).query([0.0, 0.0], 1.0, &mut out);
        assert!(out.is_empty());
        let one = BroadPhase::build(&[Aabb::around(&[[1.0, 1.0]])]);
        one.query([1.0, 1.0], 0.0, &mut out);
        assert_eq!(out, vec![0]);
        one.query([f64::NAN, 1.0], 1.0, &mut out);
        assert!(out.is_empty());
    }
}
