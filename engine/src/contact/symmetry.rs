//! Symmetry planes and the axis of a smoothed master surface (issue 18):
//! which coordinates the nodal normals of `smoothing = nodal` (2D,
//! [`super::smoothing`]) and `smoothing = nagata` (3D, [`super::nagata`])
//! drop at a node of the surface's rim.
//!
//! A half, quarter or octant model holds the part of a symmetric whole on
//! one side of its symmetry planes. The nodal normal of a master node is a
//! mean over the segments (facets) around it, and at a node on a symmetry
//! plane the mirrored half of them is not in the model: the mean of one
//! side tilts off the whole's by half a segment (facet) angle, and the
//! pole of an octant (on two planes) by a whole one. By symmetry the
//! whole's nodal normal lies in the plane: its component along the
//! plane's normal `e_k` is removed and the rest renormalized, `n = P m /
//! |P m|`, `P = I - sum_k e_k e_k^T` over the planes through the node.
//! `P` is constant, so the derivatives of the normal are the projected
//! ones (the same formulas with `m`, `dm/dX` projected).
//!
//! The rule is automatic, from the model (search geometry only: the
//! enforcement does not change):
//! - a symmetry plane of a body is a coordinate plane `x_k = c` at the
//!   body's least or largest `x_k` whose nodes (at least `D`, spanning the
//!   plane) all have `u_k` held at zero by the deck's fixities, the rule
//!   of the mass redistribution's centre
//!   ([`crate::solve::contact_mass::symmetry_planes`]): rollers;
//! - a master node is on it when it lies on the plane (within 1e-9 of the
//!   body's size) at a free end (2D) or free edge (3D) of the contact
//!   surface, and not every component of its displacement is held (a
//!   clamped face is no mirror);
//! - in an axisymmetric model (2D) a free end at `r = 0` drops its radial
//!   component, whatever the fixities (the axis is a line of symmetry);
//! - a node on as many planes as there are coordinates keeps its normal
//!   (nothing would be left).

use crate::model::{AnalysisKind, Model};
use crate::solve::contact_mass::{held_at_zero, symmetry_planes};

/// The coordinates removed from the nodal normal of each of `nodes`
/// (nodes of a contact surface of body `body` at the surface's free ends
/// or edges), the rule of the module: `mask[k]` drops `x_k`.
pub fn masks<const D: usize>(model: &Model<D>, body: usize, nodes: &[usize]) -> Vec<[bool; D]> {
    let mut out = vec![[false; D]; nodes.len()];
    let Some(b) = model.bodies.get(body) else {
        return out;
    };
    let x = &model.mesh.nodes;
    let Some(body_nodes) = x.get(b.nodes.clone()) else {
        return out;
    };
    let mut lo = [f64::INFINITY; D];
    let mut hi = [f64::NEG_INFINITY; D];
    for p in body_nodes {
        for k in 0..D {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let size = (0..D).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>().sqrt();
    if !(size > 0.0 && size.is_finite()) {
        return out;
    }
    let held = held_at_zero(model);
    let planes = symmetry_planes(x, b.nodes.clone(), &held, size);
    let axisymmetric = D == 2 && model.analysis.kind == AnalysisKind::Axisymmetric;
    for (mask, &n) in out.iter_mut().zip(nodes) {
        let Some(p) = x.get(n) else { continue };
        let clamped = held.get(n).is_some_and(|h| h.iter().all(|&v| v));
        if !clamped {
            for &(k, c) in &planes {
                if (p[k] - c).abs() <= 1e-9 * size {
                    mask[k] = true;
                }
            }
        }
        if axisymmetric && p[0].abs() <= 1e-9 * size {
            mask[0] = true;
        }
        if mask.iter().all(|&m| m) {
            *mask = [false; D];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::grid::grid;
    use crate::testkit::ModelBuilder;

    /// A 4 x 2 grid on `[0, 2] x [0, 1]` (nodes `j * 5 + i`): rollers on
    /// the whole left side (`u_x`) and bottom (`u_y`) make both planes
    /// symmetry planes; the top-left node drops `x`, the bottom-right one
    /// `y`, the corner held both ways keeps its normal, the others too.
    #[test]
    fn rollers_on_a_whole_face_mirror_and_a_lone_fixity_does_not() {
        let mesh = || grid(4, 2, [0.0, 0.0], [2.0, 1.0], 0.0, 1, false);
        let m = ModelBuilder::plane_strain()
            .elastic("s", 1.0, 0.3)
            .body("b", mesh(), "s")
            .fix([0, 5, 10], 0)
            .fix([0, 1, 2, 3, 4], 1)
            .build();
        let got = masks(&m, 0, &[10, 4, 0, 14, 7]);
        assert_eq!(
            got,
            vec![
                [true, false],
                [false, true],
                [false, false],
                [false, false],
                [false, false]
            ]
        );
        // the left side held at one node only: no plane
        let m = ModelBuilder::plane_strain()
            .elastic("s", 1.0, 0.3)
            .body("b", mesh(), "s")
            .fix([5], 0)
            .fix([0, 1, 2, 3, 4], 1)
            .build();
        assert_eq!(masks(&m, 0, &[10, 5]), vec![[false, false]; 2]);
        // a prescribed nonzero value is no roller
        let m = ModelBuilder::plane_strain()
            .elastic("s", 1.0, 0.3)
            .body("b", mesh(), "s")
            .displace([0, 5, 10], 0, crate::model::TimeFunction::Constant(0.1))
            .build();
        assert_eq!(masks(&m, 0, &[10]), vec![[false, false]]);
        // axisymmetric: the axis r = 0 without any fixity
        let m = ModelBuilder::axisymmetric()
            .elastic("s", 1.0, 0.3)
            .body("b", mesh(), "s")
            .build();
        assert_eq!(masks(&m, 0, &[10, 14]), vec![[true, false], [false, false]]);
    }
}
