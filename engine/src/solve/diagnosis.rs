//! Contact health of a failed increment, turned into a likely cause and a
//! remedy: nodes whose contact status flipped between Newton iterations
//! (chattering) and the ratio of the penalty stiffness to the element
//! stiffness at the contact nodes (a ratio far above ~1e4 makes the
//! tangent ill-conditioned and the open/closed decision of a node flip on
//! round-off-sized gaps).

use crate::contact::{ContactStatus, NodeContact};
use std::collections::{BTreeMap, BTreeSet};

/// Penalty-to-element stiffness ratio above which the penalty is named as
/// the likely cause.
pub const RATIO_TOO_HIGH: f64 = 1e5;
/// Ratio suggested as the remedy (penetration ~1e-3 of the local elastic
/// deflection, well-conditioned tangent).
pub const RATIO_SUGGESTED: f64 = 1e3;
/// Nodes listed in a message.
const LISTED: usize = 8;

/// Counts contact status flips per node between consecutive Newton
/// iterations, over the failed attempts since the last converged increment.
#[derive(Debug, Clone, Default)]
pub struct FlipTracker {
    /// Closed nodes at the previous iteration of the current attempt.
    prev: Option<BTreeSet<usize>>,
    /// Flips per node.
    flips: BTreeMap<usize, usize>,
}

impl FlipTracker {
    /// A new attempt starts (from the converged state).
    pub fn start_attempt(&mut self) {
        self.prev = None;
    }

    /// An increment converged: forget everything.
    pub fn clear(&mut self) {
        self.prev = None;
        self.flips.clear();
    }

    /// Records the statuses of one iteration.
    pub fn record(&mut self, contact: &[Vec<NodeContact>]) {
        let closed: BTreeSet<usize> = contact
            .iter()
            .flatten()
            .filter(|c| c.status == ContactStatus::Closed)
            .map(|c| c.node)
            .collect();
        if let Some(prev) = &self.prev {
            for n in prev.symmetric_difference(&closed) {
                *self.flips.entry(*n).or_default() += 1;
            }
        }
        self.prev = Some(closed);
    }

    /// Nodes that flipped at least twice (node, flips), most flips first.
    pub fn chattering(&self) -> Vec<(usize, usize)> {
        let mut v: Vec<(usize, usize)> = self
            .flips
            .iter()
            .filter(|(_, f)| **f >= 2)
            .map(|(n, f)| (*n, *f))
            .collect();
        v.sort_by(|a, b| b.1.cmp(&a.1).then(a.0.cmp(&b.0)));
        v
    }
}

/// The stiffest penalty relative to the element stiffness.
#[derive(Debug, Clone, PartialEq)]
pub struct PenaltyRatio {
    /// `alpha_eff / K_elem`: nodal penalty coefficient over the element
    /// stiffness diagonal at the node.
    pub ratio: f64,
    /// Node where the ratio is largest.
    pub node: usize,
    /// Contact pair name.
    pub pair: String,
    /// The pair's penalty value as given in the deck.
    pub stiffness: f64,
}

/// Likely cause and remedy from the contact health, or `None` when the
/// contact does not explain the failure.
pub fn contact_cause(
    ratio: Option<&PenaltyRatio>,
    flips: &FlipTracker,
) -> Option<(String, String)> {
    let chatter = flips.chattering();
    let nodes = |v: &[(usize, usize)]| {
        let list: Vec<String> = v
            .iter()
            .take(LISTED)
            .map(|(n, f)| format!("{n} ({f}x)"))
            .collect();
        let more = v.len().saturating_sub(LISTED);
        if more > 0 {
            format!("[{}, and {more} more]", list.join(", "))
        } else {
            format!("[{}]", list.join(", "))
        }
    };
    let chatter_text = if chatter.is_empty() {
        "no node changed contact status back and forth".to_string()
    } else {
        format!(
            "contact status chattering on nodes {} (status flips in the failed iterations)",
            nodes(&chatter)
        )
    };
    match ratio {
        Some(r) if r.ratio > RATIO_TOO_HIGH => {
            let suggested = r.stiffness * RATIO_SUGGESTED / r.ratio;
            Some((
                format!(
                    "penalty too high for this mesh: alpha_eff / element stiffness ~ {:.0e} \
                     (pair `{}`, node {}); {chatter_text}",
                    r.ratio, r.pair, r.node
                ),
                format!(
                    "try stiffness <= {suggested:.1e} for pair `{}` (alpha_eff / element \
                     stiffness ~ {RATIO_SUGGESTED:.0e}), or `method = augmented_lagrange {{ penalty \
                     = {suggested:.1e} }}` / `method = lagrange` for an exact contact condition",
                    r.pair
                ),
            ))
        }
        _ if !chatter.is_empty() => Some((
            format!(
                "{chatter_text}: the contact zone does not settle within the increment{}",
                ratio.map_or(String::new(), |r| format!(
                    " (alpha_eff / element stiffness ~ {:.0e}, pair `{}`)",
                    r.ratio, r.pair
                ))
            ),
            "use more `increments` (smaller contact changes per increment), or \
             `method = augmented_lagrange` for this pair"
                .into(),
        )),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn nc(node: usize, closed: bool) -> NodeContact {
        NodeContact {
            node,
            gap: if closed { -1e-9 } else { 1e-9 },
            normal: [0.0, 1.0],
            force: [0.0; 2],
            stiffness: [[0.0; 2]; 2],
            pressure: 0.0,
            status: if closed {
                ContactStatus::Closed
            } else {
                ContactStatus::Open
            },
            entity: 0,
            master: None,
            friction: Default::default(),
        }
    }

    #[test]
    fn chattering_nodes_are_counted_per_attempt_and_ranked() {
        let mut t = FlipTracker::default();
        t.start_attempt();
        t.record(&[vec![nc(1, true), nc(2, false)]]);
        t.record(&[vec![nc(1, true), nc(2, true)]]);
        t.record(&[vec![nc(1, true), nc(2, false)]]);
        t.record(&[vec![nc(1, false), nc(2, true)]]);
        // a new attempt does not count a flip against the last iteration
        t.start_attempt();
        t.record(&[vec![nc(1, true)]]);
        assert_eq!(t.chattering(), vec![(2, 3)]);
        t.clear();
        assert!(t.chattering().is_empty());
    }

    #[test]
    fn penalty_1e6_times_element_stiffness_is_named_with_a_remedy() {
        let mut t = FlipTracker::default();
        t.record(&[vec![nc(7, true)]]);
        t.record(&[vec![nc(7, false)]]);
        t.record(&[vec![nc(7, true)]]);
        let r = PenaltyRatio {
            ratio: 2e6,
            node: 7,
            pair: "top-punch".into(),
            stiffness: 2.5e10,
        };
        let (cause, remedy) = contact_cause(Some(&r), &t).unwrap();
        assert!(
            cause.starts_with("penalty too high for this mesh"),
            "{cause}"
        );
        assert!(
            cause.contains("~ 2e6") && cause.contains("7 (2x)"),
            "{cause}"
        );
        assert!(remedy.contains("stiffness <= 1.2e7"), "{remedy}");
        assert!(remedy.contains("augmented_lagrange"));
        // a moderate penalty without chattering does not explain a failure
        let soft = PenaltyRatio { ratio: 10.0, ..r };
        assert!(contact_cause(Some(&soft), &FlipTracker::default()).is_none());
    }
}
