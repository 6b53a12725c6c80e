//! A bounding-volume hierarchy over boxes (median split along the longest
//! axis) with a nearest-object query.

use crate::{Aabb, Vec3};

/// One node: a box and either two children or a range of leaves.
#[derive(Debug, Clone, PartialEq)]
struct Node {
    /// Box of everything below.
    bbox: Aabb,
    /// Children (internal node) or `usize::MAX`.
    left: usize,
    /// Second child.
    right: usize,
    /// Range in `order` (leaf).
    start: usize,
    /// End of the range (leaf).
    end: usize,
}

/// The hierarchy.
#[derive(Debug, Clone, PartialEq)]
pub struct Bvh {
    /// Nodes, root first.
    nodes: Vec<Node>,
    /// Object indices in leaf order.
    order: Vec<usize>,
}

/// Objects per leaf.
const LEAF: usize = 4;

impl Bvh {
    /// Builds the hierarchy over the objects' boxes.
    pub fn new(boxes: &[Aabb]) -> Self {
        let mut b = Bvh {
            nodes: Vec::new(),
            order: (0..boxes.len()).collect(),
        };
        if !boxes.is_empty() {
            b.build(boxes, 0, boxes.len());
        }
        b
    }

    /// Box of everything.
    pub fn bounds(&self) -> Aabb {
        self.nodes.first().map_or(Aabb::empty(), |n| n.bbox)
    }

    fn build(&mut self, boxes: &[Aabb], start: usize, end: usize) -> usize {
        let bbox = self.order[start..end]
            .iter()
            .fold(Aabb::empty(), |b, &i| b.union(&boxes[i]));
        let id = self.nodes.len();
        self.nodes.push(Node {
            bbox,
            left: usize::MAX,
            right: usize::MAX,
            start,
            end,
        });
        if end - start > LEAF {
            let ext = bbox.max - bbox.min;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = (start + end) / 2;
            let centre = |i: usize| boxes[i].min[axis] + boxes[i].max[axis];
            self.order[start..end]
                .select_nth_unstable_by(mid - start, |&a, &b| centre(a).total_cmp(&centre(b)));
            let l = self.build(boxes, start, mid);
            let r = self.build(boxes, mid, end);
            self.nodes[id].left = l;
            self.nodes[id].right = r;
        }
        id
    }

    /// The object minimising `dist2(object)` (a squared distance that is at
    /// least the squared distance from `x` to the object's box); ties keep
    /// the lowest index. Returns the object and what `f` returned for it.
    pub fn nearest<T, R>(&self, x: &Vec3, f: impl Fn(usize) -> (T, R)) -> Option<(usize, T, R)>
    where
        T: HasDistance,
    {
        let mut best: Option<(usize, T, R)> = None;
        let mut stack = vec![0usize];
        if self.nodes.is_empty() {
            return None;
        }
        while let Some(n) = stack.pop() {
            let node = &self.nodes[n];
            let lb = node.bbox.distance(x).powi(2);
            if let Some((_, b, _)) = &best {
                if lb > b.distance2() {
                    continue;
                }
            }
            if node.left == usize::MAX {
                for &o in &self.order[node.start..node.end] {
                    let (t, r) = f(o);
                    let replace = match &best {
                        None => true,
                        Some((bo, b, _)) => {
                            t.distance2() < b.distance2()
                                || (t.distance2() == b.distance2() && o < *bo)
                        }
                    };
                    if replace {
                        best = Some((o, t, r));
                    }
                }
            } else {
                // Visit the nearer child first.
                let (l, r) = (node.left, node.right);
                let (dl, dr) = (
                    self.nodes[l].bbox.distance(x),
                    self.nodes[r].bbox.distance(x),
                );
                if dl <= dr {
                    stack.push(r);
                    stack.push(l);
                } else {
                    stack.push(l);
                    stack.push(r);
                }
            }
        }
        best
    }
}

/// Something with a squared distance.
pub trait HasDistance {
    /// The squared distance.
    fn distance2(&self) -> f64;
}

impl HasDistance for super::TriangleFoot {
    fn distance2(&self) -> f64 {
        self.distance2
    }
}
