//! Lowering a validated deck into the engine's [`Model`]: meshes built and
//! merged into one globally numbered mesh, set references resolved to node
//! and edge lists, time functions made explicit, tools converted to radians
//! and unit normals, defaults filled in.
//!
//! Lowering runs only on decks without validation errors, but it never
//! panics on a deck validation missed: every lookup that can fail becomes a
//! diagnostic. Problems only visible with the mesh at hand (unreadable mesh
//! files, bad meshes, empty selections, unknown sets of mesh files) are
//! reported here, all of them, not just the first.

//!
//! One file per construct, mirroring [`crate::parse`]: each adds its
//! `impl Lowerer` methods ([`analysis`], [`materials`] for bodies and their
//! materials, [`sets`], [`boundaries`], [`loads`], [`tools`], [`contacts`],
//! [`steps`], [`output`], [`thermal`]); [`mesh`] builds and appends the
//! meshes through the generator registry.

pub mod analysis;
pub mod boundaries;
pub mod contacts;
pub mod discrete;
pub mod loads;
pub mod materials;
pub mod mesh;
pub mod output;
pub mod sets;
pub mod steps;
pub mod thermal;
pub mod tools;
pub mod velocity;

use crate::ast::{self, Deck, Span, Spanned, TimeFn};
use crate::diagnostics::Diagnostic;
use crate::source::Source;
use crate::validate::Need;
use ctc_engine::mesh::Mesh;
use ctc_engine::model::{self as m, AnyModel, Model};
use sets::{resolve, Resolved};
use std::collections::BTreeMap;
use std::ops::Range;

/// Default smallest cutback increment, as a fraction of the initial one.
pub const DEFAULT_MIN_FRACTION: f64 = 1.0 / 1024.0;

/// The analysis time window `[first step start, last step end]` that
/// `ramp(v0, v1)` spans.
pub fn analysis_window(deck: &Deck) -> (f64, f64) {
    let times: Vec<[f64; 2]> = deck
        .steps
        .iter()
        .filter_map(|s| {
            s.time
                .as_ref()
                .map(|t| [t.value[0].value, t.value[1].value])
        })
        .collect();
    match (times.first(), times.last()) {
        (Some(a), Some(b)) => (a[0], b[1]),
        _ => (0.0, 1.0),
    }
}

/// The engine time function for `f` in an analysis spanning `window`.
pub fn time_function(f: &TimeFn, window: (f64, f64)) -> m::TimeFunction {
    match f {
        TimeFn::Number(v) | TimeFn::Constant(v) => m::TimeFunction::Constant(*v),
        TimeFn::Ramp { v0, v1, window: w } => {
            let (t0, t1) = match w {
                Some([a, b]) => (a.value, b.value),
                None => window,
            };
            m::TimeFunction::Ramp {
                t0,
                t1,
                v0: *v0,
                v1: *v1,
            }
        }
        TimeFn::Table(points) => m::TimeFunction::Table(points.iter().map(|p| p.value).collect()),
    }
}

/// Open uniform knot vector for `n` control points of degree `p`.
pub fn open_uniform_knots(n: usize, p: usize) -> Vec<f64> {
    let interior = n.saturating_sub(p + 1);
    let mut k = vec![0.0; p + 1];
    for i in 1..=interior {
        k.push(i as f64 / (interior + 1) as f64);
    }
    k.extend(std::iter::repeat_n(1.0, p + 1));
    k
}

struct Lowerer<'a> {
    deck: &'a Deck,
    src: &'a Source,
    /// Spans of errors found before lowering (parse and validation): items
    /// containing one are skipped, and anything they would have provided
    /// is silently missing.
    prior: Vec<Span>,
    /// Names of deck `set`s that could not be built (already reported):
    /// references to them are skipped silently.
    skipped_sets: Vec<String>,
    diags: Vec<Diagnostic>,
    /// Internal errors (something validation guarantees is missing), kept
    /// apart: they reach the user only when no other error explains them
    /// ([`Lowerer::missing`]).
    internal: Vec<Diagnostic>,
    mesh: Mesh,
    /// The global mesh of a `3d` analysis (`mesh` stays empty then).
    mesh3: Mesh<3>,
    /// Whether the analysis is `3d`.
    solid: bool,
    /// Body name -> global node range.
    body_nodes: BTreeMap<String, Range<usize>>,
    window: (f64, f64),
}

/// Lowers `deck` into a [`Model`]. `prior` are the diagnostics of parsing
/// and validation: when they contain errors, lowering still builds what is
/// unaffected by them (so that, say, a missing mesh file is reported
/// together with a misspelled material), but returns no model.
/// Returns the model if there were no errors at all, and the diagnostics
/// found here.
pub fn lower(
    deck: &Deck,
    src: &Source,
    prior: &[Diagnostic],
) -> (Option<AnyModel>, Vec<Diagnostic>) {
    let prior_errors = prior.iter().any(Diagnostic::is_error);
    // Deck-level errors ("no analysis block") sit at 0..0 and concern no item.
    let prior: Vec<Span> = prior
        .iter()
        .filter(|d| d.is_error() && d.span != Span::new(0, 0))
        .map(|d| d.span)
        .collect();
    let mut l = Lowerer {
        deck,
        src,
        prior,
        skipped_sets: Vec::new(),
        diags: Vec::new(),
        internal: Vec::new(),
        mesh: Mesh::default(),
        mesh3: Mesh::default(),
        solid: deck
            .analysis
            .first()
            .and_then(|a| a.dimension.as_ref())
            .is_some_and(|d| d.value == ast::Dimension::ThreeD),
        body_nodes: BTreeMap::new(),
        window: analysis_window(deck),
    };
    let model = l.run();
    let mut has_errors = prior_errors || l.diags.iter().any(Diagnostic::is_error);
    if !has_errors && !l.internal.is_empty() {
        // nothing else explains the missing piece: a genuine internal error
        l.diags.append(&mut l.internal);
        has_errors = true;
    }
    (model.filter(|_| !has_errors), l.diags)
}

impl Lowerer<'_> {
    /// Whether an earlier error lies inside `span`.
    pub(super) fn has_error_in(&self, span: Span) -> bool {
        self.prior
            .iter()
            .any(|e| e.start >= span.start && e.end <= span.end)
    }

    /// Records that something validation guarantees is missing. Only an
    /// internal error when no other error was found, before lowering or
    /// during it, in any item, before or after this one (otherwise that
    /// error explains it: a contact pair dropped for a misspelled gmsh
    /// group is missing for its `contact_force` history): the decision is
    /// taken once lowering is over ([`lower`]).
    pub(super) fn missing(&mut self, what: &str, span: Span) {
        self.internal.push(Diagnostic::error(
            format!("internal: {what} is missing after validation"),
            span,
            "please report this deck",
        ));
    }

    pub(super) fn tf(&self, f: &Spanned<TimeFn>) -> m::TimeFunction {
        time_function(&f.value, self.window)
    }

    pub(super) fn resolve(&mut self, r: &ast::SetRef, need: Need, user: &str) -> Option<Resolved> {
        let resolved = if self.solid {
            sets::resolve_solid(&self.mesh3, &self.body_nodes, r, need, user)
        } else {
            resolve(&self.mesh, &self.body_nodes, r, need, user)
        };
        match resolved {
            Ok(x) => Some(x),
            Err(d) => {
                let cascade = matches!(&r.kind, ast::SetRefKind::Named(n) if self.skipped_sets.contains(&n.name));
                if !cascade {
                    self.diags.push(d);
                }
                None
            }
        }
    }

    fn run(&mut self) -> Option<AnyModel> {
        let analysis = self.analysis();
        let (bodies, materials) = self.bodies();
        self.sets();
        let constraints = self.constraints();
        let loads = self.loads();
        if self.solid {
            // rigid surface tools, frictionless or Coulomb (penalty, augmented
            // Lagrangian; Lagrange friction refused by validation)
            let surfaces = self.surfaces();
            let names: Vec<&str> = surfaces.iter().map(|t| t.name.as_str()).collect();
            let contacts = self.contacts(&bodies, &materials, &names);
            let steps = self.steps();
            let output = self.output(&contacts);
            let initial_velocities = self.initial_velocities();
            let discrete = self.discrete();
            let rigid_bodies = self.rigid_bodies();
            let (mesh3, body_nodes) = (&self.mesh3, &self.body_nodes);
            let thermal = thermal::lower(
                self.deck,
                |r, need, user| sets::resolve_solid(mesh3, body_nodes, r, need, user),
                &self.body_nodes,
                &bodies,
                &materials,
                &contacts,
                self.window,
                &mut self.diags,
            );
            let mut model = Model {
                analysis: analysis?,
                mesh: std::mem::take(&mut self.mesh3),
                bodies,
                materials,
                constraints,
                loads,
                tools: Vec::new(),
                surfaces,
                contacts,
                steps,
                output,
                thermal,
                initial_velocities,
                discrete,
            };
            for (spec, span) in rigid_bodies {
                if let Err(e) = ctc_engine::solve::rigid_body::make_rigid(&mut model, spec) {
                    self.diags.push(Diagnostic::error(e, span, "rigid_body"));
                }
            }
            return Some(AnyModel::D3(model));
        }
        let (tools, free_tools) = self.tools();
        let names: Vec<&str> = tools.iter().map(|t| t.name.as_str()).collect();
        let contacts = self.contacts(&bodies, &materials, &names);
        let steps = self.steps();
        let output = self.output(&contacts);
        let initial_velocities = self.initial_velocities();
        let discrete = self.discrete();
        let rigid_bodies = self.rigid_bodies();
        let (mesh, body_nodes) = (&self.mesh, &self.body_nodes);
        let thermal = thermal::lower(
            self.deck,
            |r, need, user| resolve(mesh, body_nodes, r, need, user),
            &self.body_nodes,
            &bodies,
            &materials,
            &contacts,
            self.window,
            &mut self.diags,
        );
        let mut model = Model {
            analysis: analysis?,
            mesh: std::mem::take(&mut self.mesh),
            bodies,
            materials,
            constraints,
            loads,
            tools,
            surfaces: Vec::new(),
            contacts,
            steps,
            output,
            thermal,
            initial_velocities,
            discrete,
        };
        for f in free_tools {
            if let Err(e) = ctc_engine::solve::free_tool::make_free(&mut model, f.tool, f.moment) {
                self.diags
                    .push(Diagnostic::error(e, f.span, "rotation = free"));
            }
        }
        for (spec, span) in rigid_bodies {
            if let Err(e) = ctc_engine::solve::rigid_body::make_rigid(&mut model, spec) {
                self.diags.push(Diagnostic::error(e, span, "rigid_body"));
            }
        }
        Some(AnyModel::D2(model))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ctc_engine::model::MaterialLaw;

    #[test]
    fn plastic_viscoplastic_and_finite_strain_lower_to_the_model() {
        let text = "analysis { dimension = axisymmetric }\n\
            material st { elastic { E = 200e3 nu = 0.3 }\n\
              plastic { hardening = swift { K = 500 eps0 = 0.01 n = 0.2 } } viscoplastic { eta = 7 } }\n\
            material ru { neo_hookean { E = 10 nu = 0.45 } }\n\
            body b { mesh = rectangle { origin = (0, 0) size = (1, 1) divisions = (2, 2) } material = st kinematics = finite }\n\
            body c { mesh = rectangle { origin = (0, 2) size = (1, 1) divisions = (2, 2) } material = ru kinematics = finite }\n\
            body d { mesh = rectangle { origin = (0, 4) size = (1, 1) divisions = (2, 2) } material = st }\n\
            fix b.bottom { ux uy }\nfix c.bottom { ux uy }\nfix d.bottom { ux uy }\n\
            step s { time = 0 .. 1 }\n";
        let model = crate::compile(&crate::Source::new("t.ctc", text)).unwrap();
        assert_eq!(model.bodies[0].kinematics, m::Kinematics::Finite);
        assert_eq!(model.bodies[2].kinematics, m::Kinematics::Small);
        assert_eq!(
            model.materials[model.bodies[0].material].law,
            MaterialLaw::ElastoPlastic {
                young: 200e3,
                poisson: 0.3,
                hardening: m::Hardening::Swift {
                    k: 500.0,
                    eps0: 0.01,
                    n: 0.2
                },
                viscosity: Some(m::Viscosity::Perzyna { eta: 7.0 }),
            }
        );
        assert_eq!(
            model.materials[model.bodies[1].material].law,
            MaterialLaw::NeoHookean {
                young: 10.0,
                poisson: 0.45
            }
        );
    }

    #[test]
    fn norton_hoff_and_the_perzyna_power_law_lower_to_the_model() {
        let text = "analysis { dimension = axisymmetric }\n\
            material sp { elastic { E = 80e3 nu = 0.3 } norton_hoff { stress = 40 rate = 1e-3 m = 0.5 } }\n\
            material pp { elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 }\n\
              viscoplastic { rate = 0.01 exponent = 3 } }\n\
            body b { mesh = rectangle { origin = (0, 0) size = (1, 1) divisions = (2, 2) } material = sp kinematics = finite }\n\
            body d { mesh = rectangle { origin = (0, 4) size = (1, 1) divisions = (2, 2) } material = pp }\n\
            fix b.bottom { ux uy }\nfix d.bottom { ux uy }\n\
            step s { time = 0 .. 1 }\n";
        let model = crate::compile(&crate::Source::new("t.ctc", text)).unwrap();
        assert_eq!(
            model.materials[model.bodies[0].material].law,
            MaterialLaw::ElastoPlastic {
                young: 80e3,
                poisson: 0.3,
                hardening: m::Hardening::Linear {
                    yield_stress: 0.0,
                    modulus: 0.0
                },
                viscosity: Some(m::Viscosity::NortonHoff {
                    stress: 40.0,
                    rate: 1e-3,
                    m: 0.5
                }),
            }
        );
        assert_eq!(
            model.materials[model.bodies[1].material].law,
            MaterialLaw::ElastoPlastic {
                young: 200e3,
                poisson: 0.3,
                hardening: m::Hardening::Linear {
                    yield_stress: 250.0,
                    modulus: 0.0
                },
                viscosity: Some(m::Viscosity::PerzynaPower {
                    rate: 0.01,
                    exponent: 3.0
                }),
            }
        );
    }

    #[test]
    fn time_functions_ramp_spans_the_whole_analysis() {
        let f = TimeFn::Ramp {
            v0: 0.0,
            v1: -0.05,
            window: None,
        };
        assert_eq!(
            time_function(&f, (0.5, 3.0)),
            m::TimeFunction::Ramp {
                t0: 0.5,
                t1: 3.0,
                v0: 0.0,
                v1: -0.05
            }
        );
        let g = TimeFn::Ramp {
            v0: 1.0,
            v1: 2.0,
            window: Some([
                Spanned::new(1.0, Span::default()),
                Spanned::new(2.0, Span::default()),
            ]),
        };
        let lowered = time_function(&g, (0.0, 10.0));
        assert_eq!(lowered.eval(0.0), 1.0);
        assert_eq!(lowered.eval(1.5), 1.5);
        assert_eq!(lowered.eval(5.0), 2.0);
        assert_eq!(
            time_function(&TimeFn::Number(3.0), (0.0, 1.0)),
            m::TimeFunction::Constant(3.0)
        );
        let t = TimeFn::Table(vec![
            Spanned::new((0.0, 0.0), Span::default()),
            Spanned::new((0.5, 1.0), Span::default()),
            Spanned::new((1.0, 0.0), Span::default()),
        ]);
        let lowered = time_function(&t, (0.0, 1.0));
        assert_eq!(lowered.eval(0.25), 0.5);
        assert_eq!(lowered.eval(0.75), 0.5);
    }

    #[test]
    fn open_uniform_knot_vectors() {
        assert_eq!(open_uniform_knots(3, 2), vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0]);
        assert_eq!(
            open_uniform_knots(5, 2),
            vec![0.0, 0.0, 0.0, 1.0 / 3.0, 2.0 / 3.0, 1.0, 1.0, 1.0]
        );
        assert_eq!(open_uniform_knots(2, 1), vec![0.0, 0.0, 1.0, 1.0]);
    }

    #[test]
    fn analysis_window_from_first_to_last_step() {
        let (deck, d) = crate::parse::parse("step a { time = 0.5 .. 1 }\nstep b { time = 1 .. 4 }");
        assert!(d.is_empty());
        assert_eq!(analysis_window(&deck), (0.5, 4.0));
    }
}
