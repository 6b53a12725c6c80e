//! Contact patch test quantities: uniform pressure, uniform gap `-p/k`,
//! linear displacement, uniform stress, force balance.

use super::{max_cell_edge, relative_error, total_reaction, Measured, Value};
use crate::analytical::patch::PenaltyPatch;
use crate::capture::FinalState;
use crate::case::Quantity;
use crate::profile::{Abscissa, ContactProfile};
use ctc_engine::element::recovery::{blocks_of, cell_states};
use ctc_engine::element::Section;
use ctc_engine::model::Model;

/// Measures the deviations from the uniform state.
pub fn measure(
    model: &Model,
    state: &FinalState,
    patch: &PenaltyPatch,
    pair: usize,
) -> Result<Measured, String> {
    let profile = ContactProfile::extract(model, state, pair, patch.x0, Abscissa::Reference)?;
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
            let states = cell_states(&model.mesh, c, &state.displacement, &section, &block)
                .map_err(|e| e.to_string())?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::patch::PatchKind;
    use crate::measure::test_model::one_body;
    use ctc_engine::contact::tributary::tributary_areas;
    use ctc_engine::contact::{ContactStatus, NodeContact};
    use ctc_engine::mesh::generate::{generate, Grading, MeshSpec};
    use ctc_engine::mesh::CellKind;
    use ctc_engine::model::*;

    /// A graded patch model with the exact state filled in as the engine
    /// would report it.
    fn exact(kind: PatchKind, poisson: f64) -> (Model, FinalState, PenaltyPatch) {
        let analysis = match kind {
            PatchKind::PlaneStrain => AnalysisKind::PlaneStrain,
            PatchKind::PlaneStress => AnalysisKind::PlaneStress,
            PatchKind::Axisymmetric => AnalysisKind::Axisymmetric,
        };
        let mesh = generate(&MeshSpec::Rectangle {
            origin: [0.0, 0.0],
            size: [1.0, 1.0],
            divisions: [5, 3],
            grading: [
                Grading::Geometric { ratio: 4.0 },
                Grading::Geometric { ratio: 0.3 },
            ],
            kind: CellKind::Tri3,
        })
        .unwrap();
        let mut model = one_body(mesh, analysis, 2e6, poisson);
        let edges = model.mesh.edge_sets["b.bottom"].clone();
        let mut nodes: Vec<usize> = edges.iter().flatten().copied().collect();
        nodes.sort_unstable();
        nodes.dedup();
        model.tools.push(RigidTool {
            name: "floor".into(),
            geometry: ToolGeometry::Plane {
                point: [0.0, 0.0],
                normal: [0.0, 1.0],
            },
            motion: ToolMotion::fixed(),
            free_rotation: None,
        });
        model.contacts.push(ContactPair {
            name: "b.bottom -> floor".into(),
            body: 0,
            edges,
            faces: Vec::new(),
            nodes: nodes.clone(),
            master: ctc_engine::model::ContactMaster::Tool(0),
            strategy: Default::default(),
            search: Default::default(),
            formulation: Default::default(),
            smoothing: Default::default(),
            method: ContactMethod::Penalty {
                kind: PenaltyKind::Area,
                stiffness: 1e9,
            },
            prof: None,
            friction: None,
            local_penalty: Vec::new(),
        });
        let patch = PenaltyPatch {
            kind,
            young: 2e6,
            poisson,
            height: 1.0,
            top_displacement: 0.05,
            penalty: 1e9,
            x0: 0.0,
            y0: 0.0,
        };
        let area = tributary_areas(&model, 0);
        let contact = nodes
            .iter()
            .zip(&area)
            .map(|(&n, &a)| NodeContact {
                node: n,
                gap: patch.gap(),
                normal: [0.0, 1.0],
                force: [0.0, patch.pressure() * a],
                stiffness: [[0.0; 2]; 2],
                pressure: patch.pressure(),
                status: ContactStatus::Closed,
                entity: 0,
                master: None,
                friction: Default::default(),
            })
            .collect::<Vec<_>>();
        let total: f64 = contact.iter().map(|c| c.force[1]).sum();
        let top = &model.mesh.node_sets["b.top"];
        let mut reaction = vec![[0.0; 2]; model.mesh.nodes.len()];
        for &n in top {
            reaction[n][1] = -total / top.len() as f64;
        }
        let displacement = model
            .mesh
            .nodes
            .iter()
            .map(|p| patch.displacement(p[0], p[1]))
            .collect();
        let state = FinalState {
            displacement,
            reaction,
            contact: vec![contact],
            ..FinalState::default()
        };
        (model, state, patch)
    }

    /// The exact state measures zero deviation for every quantity (this
    /// also checks the closed form against the engine's elastic law).
    #[test]
    fn patch_test_exact_state_measures_round_off() {
        for (kind, nu) in [
            (PatchKind::PlaneStrain, 0.0),
            (PatchKind::PlaneStrain, 0.3),
            (PatchKind::Axisymmetric, 0.3),
        ] {
            let (model, state, patch) = exact(kind, nu);
            let m = measure(&model, &state, &patch, 0).unwrap();
            for v in &m.values {
                assert!(
                    v.error < 1e-9,
                    "{kind:?} nu={nu}: {} error {}",
                    v.quantity,
                    v.error
                );
            }
        }
    }

    /// One node off by 1 % in pressure is caught.
    #[test]
    fn patch_test_detects_non_uniform_pressure() {
        let (model, mut state, patch) = exact(PatchKind::PlaneStrain, 0.0);
        state.contact[0][2].pressure *= 1.01;
        let m = measure(&model, &state, &patch, 0).unwrap();
        let p = m
            .values
            .iter()
            .find(|v| v.quantity == Quantity::PatchPressure)
            .unwrap();
        assert!((p.error - 0.01).abs() < 1e-9, "{}", p.error);
    }
}
