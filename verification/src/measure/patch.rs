//! Contact patch test quantities: uniform pressure, uniform gap `-p/k`,
//! linear displacement, uniform stress, force balance.

use super::{max_cell_edge, relative_error, total_reaction, Measured, Value};
use crate::analytical::patch::PenaltyPatch;
use crate::capture::FinalState;
use crate::case::Quantity;
use crate::profile::ContactProfile;
use ctc_engine::element::recovery::{blocks_of, cell_states};
use ctc_engine::element::Section;
use ctc_engine::model::Model;

/// Measures the deviations from the uniform state.
pub fn measure(model: &Model, state: &FinalState, patch: &PenaltyPatch, pair: usize) -> Result<Measured, String> {
    let profile = ContactProfile::extract(model, state, pair, patch.x0)?;
    if profile.points.is_empty() {
        return Err("the contact surface has no node".into());
    }
    let (p, g) = (patch.pressure(), patch.gap());
    let mut values = Vec::new();

    // Pressure and gap of every slave node, as reported by the engine.
    let (mut pe, mut pw) = (0.0, p);
    let (mut ge, mut gw) = (0.0, g);
    for q in &profile.points {
        let e = (q.pressure - p).abs() / p;
        if e >= pe {
            (pe, pw) = (e, q.pressure);
        }
        let gap = q.gap.unwrap_or(f64::INFINITY);
        let e = (gap - g).abs() / g.abs();
        if e >= ge {
            (ge, gw) = (e, gap);
        }
    }
    values.push(Value {
        quantity: Quantity::PatchPressure,
        reference: Some(p),
        computed: pw,
        error: pe,
    });
    values.push(Value {
        quantity: Quantity::PatchGap,
        reference: Some(g),
        computed: gw,
        error: ge,
    });

    // Displacement of every node.
    let mut de = 0.0;
    for (x, u) in model.mesh.nodes.iter().zip(&state.displacement) {
        let ex = patch.displacement(x[0], x[1]);
        let d = ((u[0] - ex[0]).powi(2) + (u[1] - ex[1]).powi(2)).sqrt();
        de = f64::max(de, d / patch.top_displacement);
    }
    values.push(Value {
        quantity: Quantity::PatchDisplacement,
        reference: None,
        computed: de,
        error: de,
    });

    // sigma_yy at every integration point.
    let section = Section::new(&model.analysis);
    let (mut se, mut sw) = (0.0, patch.sigma_yy());
    for block in blocks_of(model)? {
        for c in block.cells.clone() {
            let states = cell_states(&model.mesh, c, &state.displacement, &section, &block).map_err(|e| e.to_string())?;
            for s in states {
                let e = (s.stress[1] - patch.sigma_yy()).abs() / p;
                if e >= se {
                    (se, sw) = (e, s.stress[1]);
                }
            }
        }
    }
    values.push(Value {
        quantity: Quantity::PatchStress,
        reference: Some(patch.sigma_yy()),
        computed: sw,
        error: se,
    });

    let reaction = total_reaction(state);
    values.push(Value {
        quantity: Quantity::ContactForce,
        reference: Some(-reaction[1]),
        computed: profile.force[1],
        error: relative_error(profile.force[1], -reaction[1]),
    });
    Ok(Measured {
        values,
        h: max_cell_edge(model),
        profile: None,
    })
}
