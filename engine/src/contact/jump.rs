//! Nodes that move farther than the search window in one increment.
//!
//! The search only creates contact elements within `prof` of the master
//! (plus the memory entity). A node whose motion *relative to the master*
//! during one increment is larger than `prof` in the normal direction may
//! have crossed the master between two evaluations (a tool jumping past a
//! thin surface, or a node ending deeper than `prof` with no memory): the
//! contact would be missed silently. This module finds such nodes after an
//! increment so the run can warn about them.
//!
//! Rule, per slave node, with `d` its displacement relative to the master
//! over the increment (rigid tool: the node mapped into the tool's
//! reference frame at the start and at the end; deformable master: the
//! node's displacement minus that of its closest master point):
//! 1. `|d| > prof` (it moved farther than the window), and
//! 2. the master is within `|d|` of the node's end position (otherwise the
//!    straight path never came near the master: a tool approaching from
//!    far away is not reported), and
//! 3. `|d . n| > prof`, `n` the master normal at the closest point (a
//!    node sliding along the master, however fast, is still found by the
//!    window and is not reported).

use super::geometry::ToolShape;
use super::motion::Placement;
use super::search;
use super::segment_search::SurfaceSearch;
use super::vec2::{dot, norm, sub};
use crate::model::{LocalSearch, Model};

/// A slave node that moved farther than the window relative to the master.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jump {
    /// Global node number.
    pub node: usize,
    /// Length of its displacement relative to the master over the increment.
    pub distance: f64,
    /// Normal component of that displacement (absolute value).
    pub normal: f64,
}

/// Jumps of the slave nodes of a rigid-tool pair between the state
/// `(x0, t0)` (start of the increment: current coordinates of all nodes and
/// time) and `(x1, t1)` (end). `prof` is the pair's window. Ascending node
/// order.
pub fn tool_jumps(
    model: &Model,
    pair: usize,
    shape: &ToolShape,
    prof: f64,
    (x0, t0): (&[[f64; 2]], f64),
    (x1, t1): (&[[f64; 2]], f64),
) -> Vec<Jump> {
    let mut out = Vec::new();
    let Some(cp) = model.contacts.get(pair) else {
        return out;
    };
    let Some(tool) = cp.master.tool().and_then(|t| model.tools.get(t)) else {
        return out;
    };
    let (p0, p1) = (
        Placement::at(&tool.motion, t0),
        Placement::at(&tool.motion, t1),
    );
    for &node in &cp.nodes {
        let (Some(&a), Some(&b)) = (x0.get(node), x1.get(node)) else {
            continue;
        };
        let (r0, r1) = (p0.to_reference(a), p1.to_reference(b));
        let d = sub(r1, r0);
        let distance = norm(d);
        if !exceeds(distance, prof) {
            continue;
        }
        let mut tests = 0;
        let reach = distance * (1.0 + 1e-12);
        let Some(found) = search::closest_with(
            shape,
            r1,
            reach,
            None,
            None,
            LocalSearch::Memory,
            &mut tests,
        ) else {
            continue;
        };
        if found.projection.gap.abs() > reach {
            continue;
        }
        let normal = dot(d, found.projection.normal).abs();
        if normal > prof {
            out.push(Jump {
                node,
                distance,
                normal,
            });
        }
    }
    out
}

/// Jumps of `slaves` (global node numbers) against a deformable master
/// surface between coordinates `x0` (start of the increment) and `x1`
/// (end). `search` must be updated at `x1`; its window is the `prof` of
/// the rule. The segments of a slave node itself are left out (self
/// contact). `scratch` is reused for the candidate lists.
pub fn surface_jumps(
    search: &SurfaceSearch,
    slaves: &[usize],
    x0: &[[f64; 2]],
    x1: &[[f64; 2]],
    scratch: &mut Vec<usize>,
) -> Vec<Jump> {
    let prof = search.prof();
    let mut out = Vec::new();
    let mut exclude = Vec::new();
    for &node in slaves {
        let (Some(&a), Some(&b)) = (x0.get(node), x1.get(node)) else {
            continue;
        };
        let moved = sub(b, a);
        if !exceeds(norm(moved), prof) {
            continue;
        }
        exclude.clear();
        exclude.extend(search.segments_of_node(node));
        // closest master point within the node's own travel
        let reach = norm(moved) * (1.0 + 1e-12);
        search.candidates_within(b, reach, None, &exclude, scratch);
        let best = scratch
            .iter()
            .filter_map(|&e| search.project(e, b))
            .filter(|h| h.distance <= reach)
            .min_by(|p, q| {
                p.distance
                    .total_cmp(&q.distance)
                    .then(p.segment.cmp(&q.segment))
            });
        let Some(hit) = best else {
            continue;
        };
        let [m1, m2] = search.edges()[hit.segment];
        let (Some(&m1a), Some(&m1b), Some(&m2a), Some(&m2b)) =
            (x0.get(m1), x1.get(m1), x0.get(m2), x1.get(m2))
        else {
            continue;
        };
        // relative displacement: node minus the master point under it
        let xi = hit.xi;
        let master = [
            (1.0 - xi) * (m1b[0] - m1a[0]) + xi * (m2b[0] - m2a[0]),
            (1.0 - xi) * (m1b[1] - m1a[1]) + xi * (m2b[1] - m2a[1]),
        ];
        let d = sub(moved, master);
        let distance = norm(d);
        if !exceeds(distance, prof) {
            continue;
        }
        // outward normal of the segment (body on the left of m1 -> m2)
        let t = sub(m2b, m1b);
        let len = norm(t);
        if !exceeds(len, 0.0) {
            continue;
        }
        let n = [t[1] / len, -t[0] / len];
        let normal = dot(d, n).abs();
        if normal > prof && hit.distance <= distance * (1.0 + 1e-12) {
            out.push(Jump {
                node,
                distance,
                normal,
            });
        }
    }
    out
}

/// `a > b`, false when either is NaN.
fn exceeds(a: f64, b: f64) -> bool {
    a > b
}

/// One warning line for the jumps of pair `name` in an increment, or
/// `None` if there are none: how many nodes, the largest relative motion
/// and the first node numbers (0-based, as in the contact CSV files and
/// the failure diagnosis).
pub fn warning(
    name: &str,
    increment: usize,
    time: f64,
    prof: f64,
    jumps: &[Jump],
) -> Option<String> {
    let worst = jumps.iter().map(|j| j.normal).fold(0.0, f64::max);
    if jumps.is_empty() {
        return None;
    }
    const SHOWN: usize = 8;
    let mut nodes: Vec<String> = jumps
        .iter()
        .take(SHOWN)
        .map(|j| j.node.to_string())
        .collect();
    if jumps.len() > SHOWN {
        nodes.push(format!("... ({} more)", jumps.len() - SHOWN));
    }
    Some(format!(
        "increment {increment} (t = {time:.4e}): {} slave node(s) of contact `{name}` moved up to \
         {worst:.3e} towards or across the master in one increment, more than the search window \
         prof = {prof:.3e} (nodes {}); contact may have been missed: use smaller increments or a \
         larger prof",
        jumps.len(),
        nodes.join(", ")
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A flat master surface along y = 0 (body below), nodes 0..=4, and a
    /// slave node 5.
    fn flat() -> (SurfaceSearch, Vec<[f64; 2]>) {
        let edges: Vec<[usize; 2]> = (0..4).map(|i| [i + 1, i]).collect();
        let x: Vec<[f64; 2]> = (0..5).map(|i| [i as f64, 0.0]).collect();
        (SurfaceSearch::new(&edges, LocalSearch::Memory), x)
    }

    #[test]
    fn node_crossing_the_surface_is_reported_sliding_is_not() {
        let (mut s, mut x0) = flat();
        x0.push([1.5, 0.3]);
        let mut scratch = Vec::new();
        // crosses the surface: from 0.3 above to 0.2 below
        let mut x1 = x0.clone();
        x1[5] = [1.5, -0.2];
        s.update(&x1, 0.1);
        let j = surface_jumps(&s, &[5], &x0, &x1, &mut scratch);
        assert_eq!(j.len(), 1);
        assert_eq!(j[0].node, 5);
        assert!((j[0].normal - 0.5).abs() < 1e-12);
        // slides 2.0 along the surface at the same height: not reported
        x1[5] = [3.5, 0.3];
        s.update(&x1, 0.1);
        assert!(surface_jumps(&s, &[5], &x0, &x1, &mut scratch).is_empty());
        // moves 0.5 but stays far from the surface: not reported
        x0[5] = [1.5, 3.0];
        x1[5] = [1.5, 2.5];
        assert!(surface_jumps(&s, &[5], &x0, &x1, &mut scratch).is_empty());
        // the surface moves with the node (rigid translation): not reported
        let x0b: Vec<[f64; 2]> = x0.iter().map(|p| [p[0], p[1] - 1.0]).collect();
        let mut x0c = x0b.clone();
        x0c[5] = [1.5, -0.7];
        let mut x1c: Vec<[f64; 2]> = x0c.iter().map(|p| [p[0], p[1] + 1.0]).collect();
        x1c[5][1] = 0.3;
        s.update(&x1c, 0.1);
        assert!(surface_jumps(&s, &[5], &x0c, &x1c, &mut scratch).is_empty());
    }

    #[test]
    fn warning_lists_nodes_and_truncates() {
        assert!(warning("a", 1, 0.0, 0.1, &[]).is_none());
        let jumps: Vec<Jump> = (0..10)
            .map(|k| Jump {
                node: k,
                distance: 1.0,
                normal: 0.5 + k as f64 * 0.01,
            })
            .collect();
        let w = warning("a.top -> die", 3, 1.0, 0.1, &jumps).unwrap();
        assert!(
            w.contains("10 slave node(s) of contact `a.top -> die`"),
            "{w}"
        );
        assert!(
            w.contains("nodes 0, 1, 2, 3, 4, 5, 6, 7, ... (2 more)"),
            "{w}"
        );
        assert!(w.contains("5.900e-1"), "{w}");
    }
}
