//! Mass redistribution at contact boundaries for implicit dynamics
//! (Khenous, Laborde & Renard 2008, "Mass redistribution method for
//! finite element contact problems in elastodynamics", Eur. J. Mech.
//! A/Solids 27:918; Hager, Hüeber & Wohlmuth 2008, "A stable energy
//! conserving approach for frictional contact problems based on
//! quadrature formulas", IJNME 73:205).
//!
//! A node on a contact surface that carries mass bounces: the unilateral
//! constraint switches within a time increment, the implicit integrator
//! sees an impulse it cannot represent, and the contact does positive
//! work (chatter, energy growth). With no mass on the contact nodes the
//! semi-discrete problem is a well-posed differential system (its
//! solution is Lipschitz in time), the contact nodes follow the
//! constraint quasi-statically, and the trapezoidal rule conserves the
//! energy of an impact up to the penalty spring's.
//!
//! Each cell with nodes on a contact surface gets the lumped mass of its
//! consistent matrix (row sums, HRZ where needed) with the contact nodes'
//! masses moved to its other nodes in proportion to their own: the cell's
//! mass is unchanged, so is the kinetic energy and momentum of every rigid
//! translation; the centre of mass moves inward by at most a cell, a
//! perturbation confined to one layer of cells that vanishes with the mesh
//! size. Cells away from contact keep the chosen mass (consistent or
//! lumped). A cell whose nodes are all on contact surfaces (a one-cell
//! layer in contact on both sides) keeps its lumped mass and is counted.

use crate::element::kernel::lump;
use crate::model::{ContactMaster, Model, SurfaceShape, TimeFunction, ToolGeometry};
use ctc_geom::analytic::Analytic;

/// Replaces the `nn x nn` cell mass `m` (row-major) by its lumped mass
/// with the masses of the nodes flagged `massless` moved to the others in
/// proportion to their own. Returns false (and leaves the lumped mass)
/// when every node is flagged or the other nodes carry no mass.
pub fn redistribute(m: &mut [f64], nn: usize, massless: &[bool]) -> bool {
    lump(m, nn);
    let total: f64 = (0..nn).map(|a| m[a * nn + a]).sum();
    let kept: f64 = (0..nn)
        .filter(|&a| !massless[a])
        .map(|a| m[a * nn + a])
        .sum();
    if kept <= 0.0 {
        return false;
    }
    let scale = total / kept;
    for a in 0..nn {
        let d = &mut m[a * nn + a];
        *d = if massless[a] { 0.0 } else { *d * scale };
    }
    true
}

/// The lumped diagonal of `nn x nn` cell mass `m` (row-major) and the
/// mass [`redistribute`] moves from node `a` to node `b`, `moved[a * nn +
/// b]` (zero unless `a` is flagged and `b` is not).
pub fn moved_mass(m: &[f64], nn: usize, massless: &[bool]) -> Vec<f64> {
    let mut lumped = m.to_vec();
    lump(&mut lumped, nn);
    let kept: f64 = (0..nn)
        .filter(|&a| !massless[a])
        .map(|a| lumped[a * nn + a])
        .sum();
    let mut moved = vec![0.0; nn * nn];
    if kept <= 0.0 {
        return moved;
    }
    for a in (0..nn).filter(|&a| massless[a]) {
        for b in (0..nn).filter(|&b| !massless[b]) {
            moved[a * nn + b] = lumped[a * nn + a] * lumped[b * nn + b] / kept;
        }
    }
    moved
}

/// The unit normal of `master` when it is a rigid plane that does not
/// rotate and whose normal is a coordinate axis (`contact_mass = normal`
/// keeps the tangential mass of its contact nodes: with an axis normal,
/// the massless direction is one dof, so the initial acceleration and the
/// mass matrix stay well posed on the others); `None` otherwise.
pub fn axis_plane_normal<const D: usize>(
    model: &Model<D>,
    master: &ContactMaster,
) -> Option<[f64; D]> {
    let &ContactMaster::Tool(i) = master else {
        return None;
    };
    let still = |f: &TimeFunction| *f == TimeFunction::Constant(0.0);
    let n: Vec<f64> = if D == 2 {
        let t = model.tools.get(i)?;
        let ToolGeometry::Plane { normal, .. } = t.geometry else {
            return None;
        };
        if !still(&t.motion.rotation) {
            return None;
        }
        normal.to_vec()
    } else {
        let t = model.surfaces.get(i)?;
        let SurfaceShape::Analytic(Analytic::Plane(p)) = &t.geometry else {
            return None;
        };
        if !still(&t.motion.rotation) {
            return None;
        }
        vec![p.normal.x, p.normal.y, p.normal.z]
    };
    let len = n.iter().map(|x| x * x).sum::<f64>().sqrt();
    let axis = n
        .iter()
        .filter(|x| (x.abs() / len - 1.0).abs() < 1e-12)
        .count()
        == 1
        && n.iter().filter(|x| **x == 0.0).count() == D - 1;
    let mut out = [0.0; D];
    for (o, x) in out.iter_mut().zip(&n) {
        *o = (x / len).round();
    }
    axis.then_some(out)
}

/// Flags of the nodes of every contact surface of the pairs (`slave`
/// node lists and the deformable masters' node lists), `n` nodes.
pub fn contact_nodes<'a>(n: usize, lists: impl IntoIterator<Item = &'a [usize]>) -> Vec<bool> {
    let mut flags = vec![false; n];
    for list in lists {
        for &node in list {
            if let Some(f) = flags.get_mut(node) {
                *f = true;
            }
        }
    }
    flags
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A quad4 cell of mass 4 (consistent mass of a unit square, rho = 4):
    /// the contact edge's nodes 0 and 1 lose their mass to nodes 2 and 3.
    #[test]
    fn contact_nodes_lose_their_mass_and_the_cell_keeps_its_total() {
        let mut m = vec![0.0; 16];
        let base = [4.0, 2.0, 1.0, 2.0];
        for a in 0..4 {
            for b in 0..4 {
                // circulant consistent mass of a square, rho A = 4: / 9
                m[a * 4 + b] = base[(b + 4 - a) % 4] * 4.0 / 36.0;
            }
        }
        assert!(redistribute(&mut m, 4, &[true, true, false, false]));
        let diag: Vec<f64> = (0..4).map(|a| m[a * 4 + a]).collect();
        assert_eq!(diag[0], 0.0);
        assert_eq!(diag[1], 0.0);
        assert!((diag[2] - 2.0).abs() < 1e-14 && (diag[3] - 2.0).abs() < 1e-14);
        assert!((diag.iter().sum::<f64>() - 4.0).abs() < 1e-14);
        let off: f64 = (0..16).filter(|k| k % 5 != 0).map(|k| m[k].abs()).sum();
        assert_eq!(off, 0.0);
    }

    /// The mass moved from each contact node to each other node is what
    /// `redistribute` adds to the latter (`contact_mass = normal` gives it
    /// back tangentially): nodes 0, 1 (1 each) to nodes 2, 3 (1 each).
    #[test]
    fn moved_mass_is_what_redistribution_adds() {
        let mut m = vec![0.0; 16];
        let base = [4.0, 2.0, 1.0, 2.0];
        for a in 0..4 {
            for b in 0..4 {
                m[a * 4 + b] = base[(b + 4 - a) % 4] * 4.0 / 36.0;
            }
        }
        let flags = [true, true, false, false];
        let moved = moved_mass(&m, 4, &flags);
        let mut r = m.clone();
        assert!(redistribute(&mut r, 4, &flags));
        for b in 2..4 {
            let gained: f64 = (0..4).map(|a| moved[a * 4 + b]).sum();
            assert!((1.0 + gained - r[b * 4 + b]).abs() < 1e-14, "{moved:?}");
        }
        for a in 0..2 {
            let lost: f64 = (0..4).map(|b| moved[a * 4 + b]).sum();
            assert!((lost - 1.0).abs() < 1e-14, "{moved:?}");
        }
        assert!(moved[2 * 4 + 3] == 0.0 && moved[1] == 0.0);
    }

    #[test]
    fn a_cell_with_every_node_in_contact_keeps_its_lumped_mass() {
        let mut m = vec![1.0, 0.5, 0.5, 1.0];
        assert!(!redistribute(&mut m, 2, &[true, true]));
        assert_eq!(m, vec![1.5, 0.0, 0.0, 1.5]);
    }

    #[test]
    fn contact_node_flags_ignore_out_of_range_nodes() {
        let a = [0usize, 2];
        let b = [2usize, 7];
        assert_eq!(
            contact_nodes(4, [&a[..], &b[..]]),
            vec![true, false, true, false]
        );
    }
}
