//! Nested dissection ordering of a symmetric sparsity pattern, by level
//! structures (George 1973; George and Liu, *Computer Solution of Large
//! Sparse Positive Definite Systems*, 1981, ch. 8).
//!
//! A connected part of the graph is cut by one level of the breadth-first
//! level structure rooted at a pseudo-peripheral vertex (the level with the
//! fewest vertices among those that leave at least a third of the part on
//! each side); both sides are ordered first, recursively, and the separator
//! last. Parts below [`LEAF`] vertices keep their breadth-first order.
//!
//! On 3D meshes the separators are planes of nodes, so the factor fill
//! grows like `n^(4/3)` instead of the faster growth of minimum degree
//! orderings on large 3D grids; on 2D meshes minimum degree is usually as
//! good or better. The direct solver computes both symbolic factorizations
//! of a large pattern and keeps the one with the smaller factor
//! (`direct.rs`). Everything here is deterministic: ties are broken by the
//! vertex number.

use super::pattern::SparsePattern;

/// Parts smaller than this are not dissected further.
pub const LEAF: usize = 96;

/// A nested dissection permutation of `pattern`: `order[k]` is the vertex
/// eliminated `k`-th (faer's forward array).
pub fn nested_dissection(pattern: &SparsePattern) -> Vec<usize> {
    let n = pattern.n;
    // part id of every vertex still to be ordered; ordered vertices get
    // `DONE`
    const DONE: usize = usize::MAX;
    let mut part = vec![0usize; n];
    let mut next_part = 1usize;
    // explicit stack of (part id, a vertex of it, its size); a part popped
    // is split into its connected components first
    let mut order = vec![usize::MAX; n];
    let mut head = 0usize;
    let mut queue = Vec::with_capacity(n);
    let mut seen = Marks::new(n);
    // depth-first over tasks: a part's two halves are ordered completely,
    // then its separator (the recursion as an explicit stack)
    enum Task {
        /// Order the part with this id and these vertices.
        Part(usize, Vec<usize>),
        /// Emit these separator vertices (after both halves are done).
        Emit(Vec<usize>),
    }
    let all: Vec<usize> = (0..n).collect();
    let mut tasks = vec![Task::Part(0, all)];
    while let Some(task) = tasks.pop() {
        match task {
            Task::Emit(sep) => {
                for v in sep {
                    order[head] = v;
                    part[v] = DONE;
                    head += 1;
                }
            }
            Task::Part(id, vertices) => {
                if vertices.len() <= LEAF {
                    // breadth-first order inside the leaf
                    let bfs = bfs_order(pattern, &part, id, &vertices, &mut queue, &mut seen);
                    for v in bfs {
                        order[head] = v;
                        part[v] = DONE;
                        head += 1;
                    }
                    continue;
                }
                // connected components of the part
                let components = components(pattern, &mut part, id, &vertices, &mut next_part);
                if components.len() > 1 {
                    // ordered one after the other (reverse push: the first
                    // component first)
                    for (cid, verts) in components.into_iter().rev() {
                        tasks.push(Task::Part(cid, verts));
                    }
                    continue;
                }
                let (cid, verts) = components.into_iter().next().expect("one component");
                let Some((left, sep, right)) =
                    split(pattern, &part, cid, &verts, &mut queue, &mut seen)
                else {
                    let bfs = bfs_order(pattern, &part, cid, &verts, &mut queue, &mut seen);
                    for v in bfs {
                        order[head] = v;
                        part[v] = DONE;
                        head += 1;
                    }
                    continue;
                };
                let (lid, rid) = (next_part, next_part + 1);
                next_part += 2;
                for &v in &left {
                    part[v] = lid;
                }
                for &v in &right {
                    part[v] = rid;
                }
                for &v in &sep {
                    part[v] = DONE - 1; // separated, not yet placed
                }
                tasks.push(Task::Emit(sep));
                tasks.push(Task::Part(rid, right));
                tasks.push(Task::Part(lid, left));
            }
        }
    }
    debug_assert_eq!(head, n);
    order
}

/// A set of vertices cleared in O(1) (a stamp per vertex).
struct Marks {
    /// Stamp of each vertex; marked when equal to `now`.
    stamp: Vec<u32>,
    /// The current stamp.
    now: u32,
}

impl Marks {
    fn new(n: usize) -> Self {
        Marks {
            stamp: vec![0; n],
            now: 1,
        }
    }
    /// Empties the set.
    fn clear(&mut self) {
        self.now = self.now.wrapping_add(1);
        if self.now == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.now = 1;
        }
    }
    /// Marks `v`; whether it was unmarked.
    fn insert(&mut self, v: usize) -> bool {
        let fresh = self.stamp[v] != self.now;
        self.stamp[v] = self.now;
        fresh
    }
}

/// Neighbours of `v` in the pattern (the diagonal skipped).
fn neighbours(pattern: &SparsePattern, v: usize) -> impl Iterator<Item = usize> + '_ {
    pattern.row_idx[pattern.col_ptr[v]..pattern.col_ptr[v + 1]]
        .iter()
        .copied()
        .filter(move |&w| w != v)
}

/// Breadth-first order of the vertices of part `id` (all components, each
/// from its smallest vertex).
fn bfs_order(
    pattern: &SparsePattern,
    part: &[usize],
    id: usize,
    vertices: &[usize],
    queue: &mut Vec<usize>,
    seen: &mut Marks,
) -> Vec<usize> {
    seen.clear();
    let mut out = Vec::with_capacity(vertices.len());
    let mut sorted = vertices.to_vec();
    sorted.sort_unstable();
    for &s in &sorted {
        if !seen.insert(s) {
            continue;
        }
        queue.clear();
        queue.push(s);
        let mut i = 0;
        while i < queue.len() {
            let v = queue[i];
            i += 1;
            out.push(v);
            for w in neighbours(pattern, v) {
                if part[w] == id && seen.insert(w) {
                    queue.push(w);
                }
            }
        }
    }
    out
}

/// Splits part `id` into connected components, each with a new part id
/// (a single component keeps `id`).
fn components(
    pattern: &SparsePattern,
    part: &mut [usize],
    id: usize,
    vertices: &[usize],
    next_part: &mut usize,
) -> Vec<(usize, Vec<usize>)> {
    let mut sorted = vertices.to_vec();
    sorted.sort_unstable();
    // label with fresh ids as we go; vertices still carrying `id` are
    // unvisited
    let mut out = Vec::new();
    for &s in &sorted {
        if part[s] != id {
            continue;
        }
        let cid = *next_part;
        *next_part += 1;
        part[s] = cid;
        let mut verts = vec![s];
        let mut i = 0;
        while i < verts.len() {
            let v = verts[i];
            i += 1;
            for w in neighbours(pattern, v) {
                if part[w] == id {
                    part[w] = cid;
                    verts.push(w);
                }
            }
        }
        out.push((cid, verts));
    }
    out
}

/// Breadth-first levels of part `id` from `root`: the vertices in visiting
/// order and the start of each level in it.
fn levels(
    pattern: &SparsePattern,
    part: &[usize],
    id: usize,
    root: usize,
    queue: &mut Vec<usize>,
    seen: &mut Marks,
) -> Vec<usize> {
    seen.clear();
    queue.clear();
    queue.push(root);
    seen.insert(root);
    // level l is queue[starts[l]..starts[l + 1]]
    let mut starts = vec![0];
    let mut begin = 0;
    loop {
        let end = queue.len();
        for i in begin..end {
            let v = queue[i];
            for w in neighbours(pattern, v) {
                if part[w] == id && seen.insert(w) {
                    queue.push(w);
                }
            }
        }
        starts.push(end);
        if queue.len() == end {
            break;
        }
        begin = end;
    }
    starts
}

/// Left part, separator and right part of the connected part `id`, or
/// `None` when no level separates it with both sides non-empty.
fn split(
    pattern: &SparsePattern,
    part: &[usize],
    id: usize,
    vertices: &[usize],
    queue: &mut Vec<usize>,
    seen: &mut Marks,
) -> Option<(Vec<usize>, Vec<usize>, Vec<usize>)> {
    let size = vertices.len();
    // pseudo-peripheral root: repeat BFS from a vertex of the last level
    // (smallest number) while the depth grows
    let mut root = *vertices.iter().min().expect("non-empty part");
    let mut starts = levels(pattern, part, id, root, queue, seen);
    for _ in 0..8 {
        let last = &queue[starts[starts.len() - 2]..];
        let candidate = *last.iter().min().expect("non-empty level");
        let again = levels(pattern, part, id, candidate, queue, seen);
        if again.len() > starts.len() {
            root = candidate;
            starts = again;
        } else {
            // restore the queue of the kept root
            starts = levels(pattern, part, id, root, queue, seen);
            break;
        }
    }
    let depth = starts.len() - 1;
    if depth < 3 {
        return None;
    }
    // the smallest level leaving at least a third on each side; else the
    // median level
    let mut best: Option<(usize, usize)> = None;
    let mut median = None;
    for l in 1..depth - 1 {
        let before = starts[l];
        let after = size - starts[l + 1];
        let width = starts[l + 1] - starts[l];
        if median.is_none() && starts[l + 1] * 2 >= size {
            median = Some(l);
        }
        if 3 * before >= size && 3 * after >= size && best.is_none_or(|(_, w)| width < w) {
            best = Some((l, width));
        }
    }
    let l = best.map(|(l, _)| l).or(median)?;
    let left = queue[..starts[l]].to_vec();
    let sep = queue[starts[l]..starts[l + 1]].to_vec();
    let right = queue[starts[l + 1]..].to_vec();
    if left.is_empty() || right.is_empty() {
        return None;
    }
    Some((left, sep, right))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The pattern of the 5-point Laplacian on an `m x m` grid (both
    /// triangles and the diagonal).
    fn grid(m: usize) -> SparsePattern {
        let n = m * m;
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        for j in 0..n {
            let (x, y) = (j % m, j / m);
            let mut rows = vec![j];
            if x > 0 {
                rows.push(j - 1);
            }
            if x + 1 < m {
                rows.push(j + 1);
            }
            if y > 0 {
                rows.push(j - m);
            }
            if y + 1 < m {
                rows.push(j + m);
            }
            rows.sort_unstable();
            row_idx.extend(rows);
            col_ptr.push(row_idx.len());
        }
        SparsePattern {
            n,
            col_ptr,
            row_idx,
        }
    }

    #[test]
    fn nested_dissection_is_a_permutation_and_orders_a_separator_last() {
        let p = grid(40);
        let order = nested_dissection(&p);
        let mut seen = vec![false; p.n];
        for &v in &order {
            assert!(!seen[v], "vertex {v} twice");
            seen[v] = true;
        }
        assert!(seen.iter().all(|&s| s));
        // the last vertices are a separator of about one grid line: the
        // grid without them falls into at least two components
        let m = 40;
        let sep: std::collections::HashSet<usize> = order[p.n - m..].iter().copied().collect();
        let rest: Vec<usize> = (0..p.n).filter(|v| !sep.contains(v)).collect();
        let mut part = vec![usize::MAX; p.n];
        for &v in &rest {
            part[v] = 0;
        }
        let mut next = 1;
        let parts = components(&p, &mut part, 0, &rest, &mut next);
        assert!(parts.len() >= 2, "{} components", parts.len());
        // deterministic
        assert_eq!(order, nested_dissection(&p));
    }

    #[test]
    fn disconnected_parts_are_ordered_each_whole() {
        // two grids side by side, not connected
        let a = grid(12);
        let n = 2 * a.n;
        let mut col_ptr = a.col_ptr.clone();
        let mut row_idx = a.row_idx.clone();
        for j in 0..a.n {
            let rows = &a.row_idx[a.col_ptr[j]..a.col_ptr[j + 1]];
            row_idx.extend(rows.iter().map(|r| r + a.n));
            col_ptr.push(row_idx.len());
        }
        let p = SparsePattern {
            n,
            col_ptr,
            row_idx,
        };
        let order = nested_dissection(&p);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n).collect::<Vec<_>>());
        // the first component is ordered completely before the second
        let first_of_second = order.iter().position(|&v| v >= a.n).unwrap();
        assert!(order[first_of_second..].iter().all(|&v| v >= a.n));
    }
}
