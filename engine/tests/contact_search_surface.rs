//! The local search tests on a deformable master surface (node-to-segment):
//! Cast3M's circle test (`search = circle`) finds the same contacts as
//! Metafor's memory test on the non-matching patch interface, with fewer
//! projections, and, having no memory, loses a node pushed deeper than
//! `prof` that the memory test keeps.

mod support;

use ctc_engine::contact::{evaluate_pair, PairState};
use ctc_engine::model::{ContactStrategy, LocalSearch, Model};
use support::nts::*;

fn model(search: LocalSearch) -> Model {
    let mut m = patch(penalty(1e8), ContactStrategy::SinglePass, 4, 3, 1);
    m.contacts[0].search = search;
    m
}

/// Coordinates with the top block lowered by `depth` (penetration).
fn lowered(m: &Model, depth: f64) -> Vec<[f64; 2]> {
    let top = &m.bodies[1].nodes;
    m.mesh
        .nodes
        .iter()
        .enumerate()
        .map(|(i, p)| {
            if top.contains(&i) {
                [p[0], p[1] - depth]
            } else {
                *p
            }
        })
        .collect()
}

#[test]
fn contact_circle_test_on_a_deformable_master_matches_memory() {
    let (mm, mc) = (model(LocalSearch::Memory), model(LocalSearch::Circle));
    let (mut sm, mut sc) = (PairState::new(&mm, 0), PairState::new(&mc, 0));
    let prof = sm.prof;
    assert!(prof > 0.0);
    // cold, then again with memory, at a small penetration
    let x = lowered(&mm, 0.1 * prof);
    for _ in 0..2 {
        let a = evaluate_pair(&mm, 0, &x, 0.0, &mut sm);
        let b = evaluate_pair(&mc, 0, &x, 0.0, &mut sc);
        let key = |v: &[ctc_engine::contact::NodeContact]| {
            v.iter()
                .map(|c| (c.node, c.entity, c.gap))
                .collect::<Vec<_>>()
        };
        assert_eq!(key(&a), key(&b));
        assert_eq!(a.len(), 4, "the 4 slave nodes of the 3-cell top block");
        assert!(
            sc.last_projection_tests <= sm.last_projection_tests,
            "circle {} > memory {}",
            sc.last_projection_tests,
            sm.last_projection_tests
        );
        sm.commit();
        sc.commit();
    }
}

#[test]
fn contact_circle_test_loses_a_node_deeper_than_prof_memory_keeps_it() {
    let (mut mm, mut mc) = (model(LocalSearch::Memory), model(LocalSearch::Circle));
    mm.contacts[0].prof = Some(0.05);
    mc.contacts[0].prof = Some(0.05);
    let (mut sm, mut sc) = (PairState::new(&mm, 0), PairState::new(&mc, 0));
    let prof = sm.prof;
    // touch first (memory set), then go 0.2 deep: beyond the circles of the
    // master segments (L = 0.25: radius sqrt(0.125^2 + 0.05^2) = 0.135) but
    // within the depth node-to-segment accepts (max(prof, L) = 0.25)
    let touch = lowered(&mm, 0.01 * prof);
    evaluate_pair(&mm, 0, &touch, 0.0, &mut sm);
    evaluate_pair(&mc, 0, &touch, 0.0, &mut sc);
    sm.commit();
    sc.commit();
    let deep = lowered(&mm, 0.2);
    let a = evaluate_pair(&mm, 0, &deep, 0.0, &mut sm);
    let b = evaluate_pair(&mc, 0, &deep, 0.0, &mut sc);
    assert_eq!((a.len(), b.len()), (4, 0));
}
