//! Heat exchange across contact pairs.
//!
//! Each slave node of a pair seen by the mechanical contact at the converged
//! state (`NodeContact`, the SAME gap and pressure that gave the forces)
//! exchanges the heat `Q = h A (T_master - T_slave)`, where `A` is the
//! node's tributary area (`contact::tributary`, as for the forces) and
//! - closed contact: `h = h(p)` ([`Conductance`]: `h0 + h1 p^n` or a table);
//! - open contact within `prof`: `h = k_gap / max(g, g_min)` (gas conduction
//!   across the gap), 0 when `k_gap = 0`.
//!
//! `T_master` is the tool's prescribed temperature against a rigid tool
//! (a planar curve tool or a solid model's surface tool), or
//! `(1 - xi) T_m1 + xi T_m2` on a deformable master segment
//! (node-to-segment): the element is then the 3-node conductance
//! `h A w w^T`, `w = [1, -(1 - xi), -xi]`, which conserves heat exactly
//! (what leaves the slave enters the master).
//!
//! Quadratic slave faces against a rigid tool (tri6 / quad8 / quad9 bodies
//! and 3-node edges, tet10 / hex20 / hex27 faces) have no usable nodal
//! areas (`int N_a dA` is 0 at a tri6 corner, negative at a quad8 one), so
//! their exchange is integrated at the faces' points instead
//! ([`super::contact_faces`]): one element per point, `h(p_g) w_g` with the
//! shape values `N_a(xi_g)` as weights.

use crate::contact::{ContactStatus, NodeContact};
use crate::model::thermal::ContactThermal;

/// Conductance `h` of one contact node (power / area / temperature).
pub fn node_conductance<const D: usize>(settings: &ContactThermal, c: &NodeContact<D>) -> f64 {
    match c.status {
        ContactStatus::Closed => settings.conductance.at(c.pressure),
        ContactStatus::Open => {
            if settings.gap_conductivity > 0.0 {
                settings.gap_conductivity / c.gap.max(settings.gap_min)
            } else {
                0.0
            }
        }
    }
}

/// The other side of a contact node's heat exchange.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ThermalMaster {
    /// A rigid tool at a prescribed temperature.
    Tool(f64),
    /// A deformable master segment `m1 -> m2` at parameter `xi`.
    Segment {
        /// Global node numbers of the segment ends.
        nodes: [usize; 2],
        /// Projection parameter (0 at `m1`).
        xi: f64,
    },
}

/// Most nodes of a conductance element (a quad9 face's integration point).
pub const MAX_ELEMENT_NODES: usize = 9;

/// Conductance element of one contact node (or of one integration point of
/// a quadratic slave face): nodes and weights of the temperature jump
/// `T_master - T_slave = -(w . T)`, and the prescribed part (tool
/// temperature).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ConductanceElement {
    /// `h A` (power / temperature).
    pub ha: f64,
    /// Slave node, then the master segment's nodes if any (a face point:
    /// the face's nodes).
    pub nodes: [usize; MAX_ELEMENT_NODES],
    /// Number of nodes used (1 against a tool, 3 on a segment, the face's
    /// node count at a face point).
    pub count: usize,
    /// Weights `w` (slave +1, master nodes -(1 - xi), -xi; a face point:
    /// the shape values `N_a` of its face there).
    pub weights: [f64; MAX_ELEMENT_NODES],
    /// Tool temperature (rigid master), else 0.
    pub tool_temperature: f64,
}

impl ConductanceElement {
    /// The element of slave node `node` with `h A = ha` against `master`.
    pub fn new(node: usize, ha: f64, master: ThermalMaster) -> Self {
        match master {
            ThermalMaster::Tool(t) => Self::on_nodes(ha, &[node], &[1.0], t),
            ThermalMaster::Segment { nodes, xi } => Self::on_nodes(
                ha,
                &[node, nodes[0], nodes[1]],
                &[1.0, -(1.0 - xi), -xi],
                0.0,
            ),
        }
    }

    /// The element `h A = ha` on `nodes` with the weights `weights` against
    /// the prescribed `tool_temperature` (a face point against a tool: the
    /// face's nodes and their shape values at the point); nodes beyond
    /// [`MAX_ELEMENT_NODES`] are dropped (no facet has more).
    pub fn on_nodes(ha: f64, nodes: &[usize], weights: &[f64], tool_temperature: f64) -> Self {
        let count = nodes.len().min(weights.len()).min(MAX_ELEMENT_NODES);
        let mut e = ConductanceElement {
            ha,
            nodes: [0; MAX_ELEMENT_NODES],
            count,
            weights: [0.0; MAX_ELEMENT_NODES],
            tool_temperature,
        };
        e.nodes[..count].copy_from_slice(&nodes[..count]);
        e.weights[..count].copy_from_slice(&weights[..count]);
        e
    }

    /// Heat flowing from the master side into the slave node (power) at
    /// nodal temperatures `temperature`.
    pub fn heat_into_slave(&self, temperature: &[f64]) -> f64 {
        let mut jump = self.tool_temperature;
        for k in 0..self.count {
            jump -= self.weights[k] * temperature[self.nodes[k]];
        }
        self.ha * jump
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::thermal::Conductance;

    fn contact(status: ContactStatus, gap: f64, pressure: f64) -> NodeContact {
        NodeContact {
            node: 0,
            gap,
            normal: [0.0, 1.0],
            force: [0.0, 0.0],
            stiffness: [[0.0; 2]; 2],
            pressure,
            status,
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    #[test]
    fn conductance_closed_depends_on_pressure_open_on_gap() {
        let s = ContactThermal {
            conductance: Conductance::Power {
                h0: 10.0,
                h1: 2.0,
                n: 0.5,
            },
            gap_conductivity: 0.03,
            gap_min: 1e-3,
            friction_split: 0.5,
            tool_temperature: None,
        };
        let h = node_conductance(&s, &contact(ContactStatus::Closed, -1e-6, 100.0));
        assert!((h - 30.0).abs() < 1e-12);
        let h = node_conductance(&s, &contact(ContactStatus::Open, 0.01, 0.0));
        assert!((h - 3.0).abs() < 1e-12);
        let h = node_conductance(&s, &contact(ContactStatus::Open, 1e-6, 0.0));
        assert!((h - 30.0).abs() < 1e-12);
    }

    #[test]
    fn segment_element_conserves_heat() {
        let e = ConductanceElement::new(
            0,
            2.0,
            ThermalMaster::Segment {
                nodes: [1, 2],
                xi: 0.25,
            },
        );
        let t = [10.0, 30.0, 50.0];
        // T_master = 0.75 * 30 + 0.25 * 50 = 35
        assert!((e.heat_into_slave(&t) - 50.0).abs() < 1e-12);
        let w: f64 = e.weights.iter().sum();
        assert!(w.abs() < 1e-15);
    }
}
