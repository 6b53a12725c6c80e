//! Broad phase of the contact search: a hashed bucket grid over the boxes
//! of the master entities (segments), rebuilt when the geometry moves.
//!
//! A query returns the entities whose box, inflated by `radius` (the search
//! window `prof`), contains the point: the narrow phase (projection) then
//! only runs on those.
//!
//! The grid is unbounded and *hashed*: cell `(i, j)` (in 3D `(i, j, k)`)
//! of side `cell` goes to bucket `morton(i, j) mod B` (see [`bucket`]), with `B` a power of two
//! about the number of (box, cell) registrations. Memory and build time are therefore `O(n)`
//! whatever the shape of the surface (a ring of `n` segments would need
//! `O(n^2)` cells in a dense grid over its bounding box). Two cells sharing
//! a bucket only cost a few extra box tests, never a wrong answer: every
//! entry is checked against its box. The cell size is the larger of the
//! mean box extent and the expected query radius, so a box covers O(1)
//! cells, a cell holds O(1) boxes of a surface mesh of even size and a
//! query visits O(1) cells: building is `O(n)` and a query `O(1)` (plus the
//! sort of its few hits).
//!
//! Boxes covering more than [`MAX_COVER`] cells (one huge box among small
//! ones, or an infinite one) are kept in a separate list tested by every
//! query. A query whose window covers more cells than there are entities
//! tests every box (brute force is cheaper then).
//!
//! The grid is generic over the dimension `D` (`BroadPhase` without a
//! parameter is the planar one): master segments in 2D, master facets of
//! node-to-facet contact in 3D ([`super::node_to_facet`]).
//!
//! [`BroadPhase::rebuild`] reuses the storage of the previous build, so the
//! per-iteration rebuild of a moving surface does not allocate once the
//! sizes have settled.

use crate::geom::Aabb;

/// Hashed uniform grid of entity boxes.
#[derive(Debug, Clone)]
pub struct BroadPhase<const D: usize = 2> {
    /// Grid origin (lower corner of the boxes' bounds).
    origin: [f64; D],
    /// Cell size (same along every axis), > 0.
    cell: f64,
    /// Bucket count minus one (bucket count is a power of two).
    mask: usize,
    /// Start of each bucket's entries in `entries` (`mask + 2` values).
    start: Vec<u32>,
    /// Entity indices grouped by bucket, ascending within a bucket.
    entries: Vec<u32>,
    /// Entities whose box covers too many cells (tested by every query).
    oversize: Vec<usize>,
    /// The boxes the grid was built from.
    boxes: Vec<Aabb<D>>,
}

impl<const D: usize> Default for BroadPhase<D> {
    fn default() -> Self {
        BroadPhase {
            origin: [0.0; D],
            cell: 0.0,
            mask: 0,
            start: Vec::new(),
            entries: Vec::new(),
            oversize: Vec::new(),
            boxes: Vec::new(),
        }
    }
}

/// Largest number of cells a box is registered in; bigger boxes go to the
/// oversize list.
pub const MAX_COVER: i64 = 64;

/// Bucket of cell `(i, j)`: its Morton (Z-order) code, bits of `i` and `j`
/// interleaved, modulo `B`. Cells close to each other in any direction get
/// close buckets, so a query reads a few nearby runs of `start` and a
/// surface searched (or rebuilt) in its own order walks the arrays almost
/// sequentially (a random hash costs a cache miss per cell at 10^5
/// segments). Cells farther apart than `sqrt(B)` cells may share a bucket:
/// a few extra box tests, never a wrong answer.
#[inline]
fn bucket<const D: usize>(cell: [i64; D], mask: usize) -> usize {
    crate::geom::morton::encode(cell) as usize & mask
}

/// Calls `f` on every cell of the range `lo ..= hi` (first axis fastest).
#[inline]
fn for_each_cell<const D: usize>(lo: [i64; D], hi: [i64; D], mut f: impl FnMut([i64; D])) {
    let mut c = lo;
    loop {
        f(c);
        let mut axis = 0;
        loop {
            if axis == D {
                return;
            }
            if c[axis] < hi[axis] {
                c[axis] += 1;
                break;
            }
            c[axis] = lo[axis];
            axis += 1;
        }
    }
}

impl<const D: usize> BroadPhase<D> {
    /// Builds the grid over `boxes` (an empty list gives an empty grid).
    pub fn build(boxes: &[Aabb<D>]) -> Self {
        let mut grid = BroadPhase::default();
        grid.rebuild(boxes, 0.0);
        grid
    }

    /// Rebuilds the grid over `boxes`, reusing the storage of the previous
    /// build. `radius` is the query radius expected (the search window);
    /// the cell size is at least that, so a query visits at most 3 cells
    /// along each axis.
    pub fn rebuild(&mut self, boxes: &[Aabb<D>], radius: f64) {
        self.boxes.clear();
        self.boxes.extend_from_slice(boxes);
        self.entries.clear();
        self.oversize.clear();
        let mut bounds = Aabb {
            min: [f64::INFINITY; D],
            max: [f64::NEG_INFINITY; D],
        };
        let mut extent = 0.0;
        let mut finite = 0usize;
        for b in boxes {
            if b.is_finite() {
                bounds.include(b.min);
                bounds.include(b.max);
                extent += (0..D).map(|k| b.max[k] - b.min[k]).fold(0.0, f64::max);
                finite += 1;
            }
        }
        self.origin = if finite > 0 { bounds.min } else { [0.0; D] };
        let span = if finite > 0 {
            (0..D)
                .map(|k| bounds.max[k] - bounds.min[k])
                .fold(0.0, f64::max)
        } else {
            0.0
        };
        let radius = if radius.is_finite() {
            radius.max(0.0)
        } else {
            0.0
        };
        self.cell = (extent / finite.max(1) as f64)
            .max(radius)
            .max(span * 1e-9)
            .max(f64::MIN_POSITIVE);
        // count registrations to size the table; indices are stored as u32
        // (beyond 2^26 boxes, every box is tested by every query)
        let small = boxes.len() < u32::MAX as usize / MAX_COVER as usize;
        let mut registrations = 0usize;
        for b in boxes {
            if let Some(n) = self.cover_count(b) {
                registrations += n;
            }
        }
        // about one registration per bucket: small tables stay in cache
        let buckets = registrations.max(8).next_power_of_two();
        self.mask = buckets - 1;
        self.start.clear();
        self.start.resize(buckets + 1, 0);
        // counting sort of (bucket, entity) pairs, fill pointers kept in
        // `start` itself (no second table)
        for (e, b) in boxes.iter().enumerate() {
            match self.cover(b).filter(|_| small) {
                Some((lo, hi)) => {
                    let (start, mask) = (&mut self.start, self.mask);
                    for_each_cell(lo, hi, |c| start[bucket(c, mask) + 1] += 1);
                }
                None => self.oversize.push(e),
            }
        }
        for k in 0..buckets {
            self.start[k + 1] += self.start[k];
        }
        self.entries.resize(self.start[buckets] as usize, 0);
        for (e, b) in boxes.iter().enumerate() {
            if let Some((lo, hi)) = self.cover(b).filter(|_| small) {
                let (start, entries, mask) = (&mut self.start, &mut self.entries, self.mask);
                for_each_cell(lo, hi, |cell| {
                    let c = bucket(cell, mask);
                    entries[start[c] as usize] = e as u32;
                    start[c] += 1;
                });
            }
        }
        // start[c] now holds the end of bucket c = the start of c + 1
        for c in (0..buckets).rev() {
            self.start[c + 1] = self.start[c];
        }
        self.start[0] = 0;
    }

    /// Cell index of coordinate `v` along an axis of origin `o`.
    #[inline]
    fn index(&self, v: f64, o: f64) -> i64 {
        // floor without the libm call (finite inputs; the cast saturates
        // for absurd ratios)
        let q = (v - o) / self.cell;
        let k = q as i64;
        if q < k as f64 {
            k.saturating_sub(1)
        } else {
            k
        }
    }

    /// Cell range of a box and its number of cells (saturating), or `None`
    /// if the box is not finite.
    fn cells(&self, b: &Aabb<D>) -> Option<([i64; D], [i64; D], i64)> {
        if !b.is_finite() {
            return None;
        }
        let lo: [i64; D] = std::array::from_fn(|k| self.index(b.min[k], self.origin[k]));
        let hi: [i64; D] = std::array::from_fn(|k| self.index(b.max[k], self.origin[k]));
        let mut count: i64 = 1;
        for k in 0..D {
            let n = hi[k].saturating_sub(lo[k]).saturating_add(1);
            if n <= 0 {
                return None;
            }
            count = count.saturating_mul(n);
        }
        Some((lo, hi, count))
    }

    /// Cell range of a box, or `None` if it is not finite or covers more
    /// than [`MAX_COVER`] cells.
    fn cover(&self, b: &Aabb<D>) -> Option<([i64; D], [i64; D])> {
        self.cells(b)
            .filter(|c| c.2 <= MAX_COVER)
            .map(|(lo, hi, _)| (lo, hi))
    }

    /// Number of cells box `b` is registered in (`None`: oversize).
    fn cover_count(&self, b: &Aabb<D>) -> Option<usize> {
        self.cover(b)
            .map(|(lo, hi)| (0..D).map(|k| (hi[k] - lo[k] + 1) as usize).product())
    }

    /// Entities whose box inflated by `radius` contains `p`, ascending and
    /// without duplicates, written to `out` (cleared first).
    pub fn query(&self, p: [f64; D], radius: f64, out: &mut Vec<usize>) {
        out.clear();
        self.query_append(p, radius, out);
    }

    /// Like [`BroadPhase::query`] but appends to `out`: the appended part is
    /// ascending and without duplicates (what `out` held before is kept and
    /// not looked at).
    pub fn query_append(&self, p: [f64; D], radius: f64, out: &mut Vec<usize>) {
        let base = out.len();
        if self.boxes.is_empty() || !p.iter().all(|v| v.is_finite()) {
            return;
        }
        let r = if radius.is_nan() {
            0.0
        } else {
            radius.max(0.0)
        };
        let window = Aabb {
            min: p.map(|v| v - r),
            max: p.map(|v| v + r),
        };
        // visit the window's cells unless there are more of them than boxes
        let limit = (self.boxes.len() as i64).max(MAX_COVER);
        match self.cells(&window).filter(|c| c.2 <= limit) {
            Some((lo, hi, _)) => {
                for_each_cell(lo, hi, |cell| {
                    let c = bucket(cell, self.mask);
                    let run = self.start[c] as usize..self.start[c + 1] as usize;
                    for &e in &self.entries[run] {
                        if self.boxes[e as usize].contains_within(p, r) {
                            out.push(e as usize);
                        }
                    }
                });
                for &e in &self.oversize {
                    if self.boxes[e].contains_within(p, r) {
                        out.push(e);
                    }
                }
            }
            None => {
                for (e, b) in self.boxes.iter().enumerate() {
                    if b.contains_within(p, r) {
                        out.push(e);
                    }
                }
            }
        }
        let tail = &mut out[base..];
        tail.sort_unstable();
        let mut kept = base;
        for k in base..out.len() {
            if kept == base || out[k] != out[kept - 1] {
                out[kept] = out[k];
                kept += 1;
            }
        }
        out.truncate(kept);
    }

    /// Number of entities.
    pub fn len(&self) -> usize {
        self.boxes.len()
    }

    /// True if the grid holds no entity.
    pub fn is_empty(&self) -> bool {
        self.boxes.is_empty()
    }

    /// Box of entity `e` as given to the last build.
    pub fn bounding_box(&self, e: usize) -> Aabb<D> {
        self.boxes[e]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn segment_boxes(n: usize) -> Vec<Aabb<2>> {
        // a wavy open polyline of n segments
        let pts: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let x = i as f64 / n as f64;
                [x, 0.1 * (7.0 * x).sin()]
            })
            .collect();
        pts.windows(2).map(Aabb::around).collect()
    }

    fn brute(boxes: &[Aabb<2>], p: [f64; 2], r: f64) -> Vec<usize> {
        (0..boxes.len())
            .filter(|&e| boxes[e].contains_within(p, r))
            .collect()
    }

    #[test]
    fn query_matches_brute_force() {
        let boxes = segment_boxes(200);
        let grid: BroadPhase = BroadPhase::build(&boxes);
        let mut out = Vec::new();
        for k in 0..500 {
            let p = [
                -0.1 + 1.2 * ((k * 37 % 500) as f64 / 500.0),
                -0.2 + 0.4 * ((k * 91 % 500) as f64 / 500.0),
            ];
            let r = 0.003 * (k % 7) as f64;
            grid.query(p, r, &mut out);
            assert_eq!(out, brute(&boxes, p, r), "point {p:?} radius {r}");
        }
    }

    #[test]
    fn ring_surface_uses_linear_storage() {
        // a ring of 20000 segments: a dense grid over its bounding box would
        // need ~4e7 cells; the hashed grid stays O(n)
        let n = 20_000;
        let pts: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / n as f64;
                [a.cos(), a.sin()]
            })
            .collect();
        let boxes: Vec<Aabb<2>> = pts.windows(2).map(Aabb::around).collect();
        let grid: BroadPhase = BroadPhase::build(&boxes);
        assert!(grid.start.len() <= 8 * 4 * n + 2, "{}", grid.start.len());
        let mut out = Vec::new();
        for k in 0..200 {
            let a = 0.0314 * k as f64;
            let rad = 1.0 + 1e-4 * ((k % 5) as f64 - 2.0);
            let p = [rad * a.cos(), rad * a.sin()];
            grid.query(p, 2e-4, &mut out);
            assert_eq!(out, brute(&boxes, p, 2e-4));
            assert!(out.len() <= 8, "{} hits", out.len());
        }
    }

    #[test]
    fn oversize_infinite_and_huge_radius() {
        let mut boxes = segment_boxes(50);
        boxes.push(Aabb::around(&[[-5.0, -5.0], [5.0, 5.0]])); // huge
        boxes.push(Aabb::<2>::everything()); // infinite
        let mut grid = BroadPhase::default();
        grid.rebuild(&boxes, 0.01);
        let mut out = Vec::new();
        for (p, r) in [([0.5, 0.0], 0.01), ([0.3, 0.05], 10.0), ([9.0, 9.0], 1.0)] {
            grid.query(p, r, &mut out);
            assert_eq!(out, brute(&boxes, p, r));
        }
    }

    #[test]
    fn only_unbounded_boxes() {
        // a plane tool: one infinite box, no finite one to size the cells
        let grid = BroadPhase::build(&[Aabb::<2>::everything()]);
        let mut out = Vec::new();
        for p in [[0.0, 0.0], [-1e300, 1e300], [3.0, -7.0]] {
            grid.query(p, 0.1, &mut out);
            assert_eq!(out, vec![0]);
        }
    }

    #[test]
    fn query_append_keeps_prefix() {
        let boxes = segment_boxes(20);
        let grid: BroadPhase = BroadPhase::build(&boxes);
        let mut out = vec![99, 3];
        grid.query_append([0.5, 0.1 * 3.5f64.sin()], 0.02, &mut out);
        assert_eq!(&out[..2], &[99, 3]);
        assert_eq!(
            &out[2..],
            &brute(&boxes, [0.5, 0.1 * 3.5f64.sin()], 0.02)[..]
        );
    }

    #[test]
    fn rebuild_reuses_storage() {
        let boxes = segment_boxes(300);
        let mut grid = BroadPhase::default();
        grid.rebuild(&boxes, 0.0);
        let caps = (
            grid.start.capacity(),
            grid.entries.capacity(),
            grid.boxes.capacity(),
        );
        let ptrs = (
            grid.start.as_ptr(),
            grid.entries.as_ptr(),
            grid.boxes.as_ptr(),
        );
        let moved: Vec<Aabb<2>> = boxes
            .iter()
            .map(|b| Aabb {
                min: [b.min[0] + 1e-4, b.min[1]],
                max: [b.max[0] + 1e-4, b.max[1]],
            })
            .collect();
        grid.rebuild(&moved, 0.0);
        assert_eq!(
            (
                grid.start.capacity(),
                grid.entries.capacity(),
                grid.boxes.capacity()
            ),
            caps
        );
        assert_eq!(
            (
                grid.start.as_ptr(),
                grid.entries.as_ptr(),
                grid.boxes.as_ptr()
            ),
            ptrs
        );
        let mut out = Vec::new();
        grid.query([0.5, 0.0], 0.05, &mut out);
        assert_eq!(out, brute(&moved, [0.5, 0.0], 0.05));
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
        one.query([1.0, 1.0], f64::NAN, &mut out);
        assert_eq!(out, vec![0]);
        one.query([1.0, 1.0], f64::INFINITY, &mut out);
        assert_eq!(out, vec![0]);
    }

    proptest! {
        #[test]
        fn random_boxes_in_3d_match_brute_force(
            raw in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0, 0.0f64..0.3, 0.0f64..0.3, 0.0f64..0.3), 0..80),
            queries in proptest::collection::vec((-1.5f64..1.5, -1.5f64..1.5, -1.5f64..1.5, 0.0f64..0.5), 1..20),
            hint in 0.0f64..0.5,
        ) {
            let boxes: Vec<Aabb<3>> = raw
                .iter()
                .map(|&(x, y, z, w, h, d)| Aabb { min: [x, y, z], max: [x + w, y + h, z + d] })
                .collect();
            let mut grid = BroadPhase::<3>::default();
            grid.rebuild(&boxes, hint);
            let mut out = Vec::new();
            for &(x, y, z, r) in &queries {
                grid.query([x, y, z], r, &mut out);
                let brute: Vec<usize> = (0..boxes.len())
                    .filter(|&e| boxes[e].contains_within([x, y, z], r))
                    .collect();
                prop_assert_eq!(&out, &brute);
            }
        }

        #[test]
        fn random_boxes_match_brute_force(
            raw in proptest::collection::vec((-1.0f64..1.0, -1.0f64..1.0, 0.0f64..0.3, 0.0f64..0.3), 0..80),
            queries in proptest::collection::vec((-1.5f64..1.5, -1.5f64..1.5, 0.0f64..0.5), 1..20),
            hint in 0.0f64..0.5,
        ) {
            let boxes: Vec<Aabb<2>> = raw
                .iter()
                .map(|&(x, y, w, h)| Aabb { min: [x, y], max: [x + w, y + h] })
                .collect();
            let mut grid = BroadPhase::default();
            grid.rebuild(&boxes, hint);
            let mut out = Vec::new();
            for &(x, y, r) in &queries {
                grid.query([x, y], r, &mut out);
                prop_assert_eq!(&out, &brute(&boxes, [x, y], r));
            }
        }
    }
}
