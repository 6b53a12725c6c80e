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

pub mod mesh;
pub mod sets;
pub mod thermal;

use crate::ast::{self, Deck, Dimension, Method, PenaltyKindAst, Span, Spanned, TimeFn};
use crate::diagnostics::Diagnostic;
use crate::source::Source;
use crate::validate::{step_label, Need};
use ctc_engine::mesh::Mesh;
use ctc_engine::model::{
    self as m, Analysis, AnalysisKind, ContactMaster, ContactMethod, ContactPair, ContactStrategy,
    Dirichlet, Field, Formulation, HistoryRequest, Load, Material, MaterialLaw, Model,
    NewtonSettings, OutputRequest, PenaltyKind, RigidTool, Step, ToolGeometry, ToolMotion,
    ToolSide,
};
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
    /// Whether there were earlier errors at all.
    prior_errors: bool,
    /// Names of deck `set`s that could not be built (already reported):
    /// references to them are skipped silently.
    skipped_sets: Vec<String>,
    diags: Vec<Diagnostic>,
    mesh: Mesh,
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
pub fn lower(deck: &Deck, src: &Source, prior: &[Diagnostic]) -> (Option<Model>, Vec<Diagnostic>) {
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
        prior_errors,
        skipped_sets: Vec::new(),
        diags: Vec::new(),
        mesh: Mesh::default(),
        body_nodes: BTreeMap::new(),
        window: analysis_window(deck),
    };
    let model = l.run();
    let has_errors = prior_errors || l.diags.iter().any(Diagnostic::is_error);
    (model.filter(|_| !has_errors), l.diags)
}

impl Lowerer<'_> {
    /// Whether an earlier error lies inside `span`.
    fn has_error_in(&self, span: Span) -> bool {
        self.prior
            .iter()
            .any(|e| e.start >= span.start && e.end <= span.end)
    }

    /// Records that something validation guarantees is missing. Only an
    /// internal error when there were no earlier errors (otherwise the
    /// earlier error explains it).
    fn missing(&mut self, what: &str, span: Span) {
        if !self.prior_errors {
            self.diags.push(Diagnostic::error(
                format!("internal: {what} is missing after validation"),
                span,
                "please report this deck",
            ));
        }
    }

    fn tf(&self, f: &Spanned<TimeFn>) -> m::TimeFunction {
        time_function(&f.value, self.window)
    }

    fn resolve(&mut self, r: &ast::SetRef, need: Need, user: &str) -> Option<Resolved> {
        match resolve(&self.mesh, &self.body_nodes, r, need, user) {
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

    fn run(&mut self) -> Option<Model> {
        let analysis = self.analysis();
        let (bodies, materials) = self.bodies();
        self.sets();
        let constraints = self.constraints();
        let loads = self.loads();
        let tools = self.tools();
        let contacts = self.contacts(&bodies, &tools);
        let steps = self.steps();
        let output = self.output(&contacts);
        let thermal = thermal::lower(
            self.deck,
            &self.mesh,
            &self.body_nodes,
            &bodies,
            &materials,
            &contacts,
            self.window,
            &mut self.diags,
        );
        Some(Model {
            analysis: analysis?,
            mesh: std::mem::take(&mut self.mesh),
            bodies,
            materials,
            constraints,
            loads,
            tools,
            contacts,
            steps,
            output,
            thermal,
        })
    }

    fn analysis(&mut self) -> Option<Analysis> {
        let Some(a) = self.deck.analysis.first() else {
            self.missing("the analysis block", Span::default());
            return None;
        };
        let kind = match a.dimension.as_ref().map(|d| d.value) {
            Some(Dimension::PlaneStrain) => AnalysisKind::PlaneStrain,
            Some(Dimension::PlaneStress) => AnalysisKind::PlaneStress,
            Some(Dimension::Axisymmetric) => AnalysisKind::Axisymmetric,
            _ => {
                self.missing("a supported dimension", a.keyword);
                return None;
            }
        };
        let thickness = match kind {
            AnalysisKind::Axisymmetric => 1.0,
            _ => a.thickness.as_ref().map_or(1.0, |t| t.value),
        };
        Some(Analysis { kind, thickness })
    }

    fn bodies(&mut self) -> (Vec<m::Body>, Vec<Material>) {
        let deck = self.deck;
        let axisymmetric = deck
            .analysis
            .first()
            .and_then(|a| a.dimension.as_ref())
            .is_some_and(|d| d.value == Dimension::Axisymmetric);
        let mut bodies = Vec::new();
        let mut materials: Vec<Material> = Vec::new();
        for b in &deck.bodies {
            let Some(mesh_def) = &b.mesh else {
                self.missing("the mesh", b.name.span);
                continue;
            };
            if self.has_error_in(mesh_def.span) {
                continue;
            }
            let built = match mesh::build(&b.name.name, mesh_def, self.src) {
                Ok(mesh) => mesh,
                Err(ds) => {
                    self.diags.extend(ds);
                    continue;
                }
            };
            if axisymmetric {
                if let Some(d) = mesh::negative_radius(&b.name.name, &built, mesh_def.span) {
                    self.diags.push(d);
                    continue;
                }
            }
            let (placed, warnings) =
                mesh::append(&mut self.mesh, &b.name.name, built, mesh_def.span);
            self.diags.extend(warnings);
            self.body_nodes
                .insert(b.name.name.clone(), placed.nodes.clone());
            let material = match self.material_index(b, &mut materials) {
                Some(i) => i,
                None => continue,
            };
            let formulation = match b.formulation.as_ref().map(|f| f.value) {
                Some(ast::FormulationKind::SelectiveReduced) => Formulation::SelectiveReduced,
                _ => Formulation::Full,
            };
            bodies.push(m::Body {
                name: b.name.name.clone(),
                nodes: placed.nodes,
                cells: placed.cells,
                material,
                formulation,
                kinematics: match b.kinematics.as_ref().map(|k| k.value) {
                    Some(ast::KinematicsKind::Finite) => m::Kinematics::Finite,
                    _ => m::Kinematics::Small,
                },
            });
        }
        (bodies, materials)
    }

    /// Index of the body's material in `materials`, adding it on first use.
    fn material_index(&mut self, b: &ast::Body, materials: &mut Vec<Material>) -> Option<usize> {
        let name = b.material.as_ref()?;
        if let Some(i) = materials.iter().position(|m| m.name == name.name) {
            return Some(i);
        }
        let Some(def) = self
            .deck
            .materials
            .iter()
            .find(|m| m.name.name == name.name)
        else {
            self.missing("the material", name.span);
            return None;
        };
        let e = def.elastic.as_ref().or(def.neo_hookean.as_ref());
        let (Some(young), Some(poisson)) = (
            e.and_then(|e| e.young.as_ref()),
            e.and_then(|e| e.poisson.as_ref()),
        ) else {
            self.missing("the elastic constants", def.name.span);
            return None;
        };
        let (young, poisson) = (young.value, poisson.value);
        let law = if def.neo_hookean.is_some() {
            MaterialLaw::NeoHookean { young, poisson }
        } else if let Some(p) = &def.plastic {
            let v = |x: &Option<crate::span::Spanned<f64>>| x.as_ref().map(|x| x.value);
            let yield_stress = v(&p.yield_stress);
            let hardening = match p.hardening.as_ref().map(|h| &h.value) {
                None => m::Hardening::Linear {
                    yield_stress: yield_stress?,
                    modulus: 0.0,
                },
                Some(ast::HardeningAst::Linear { modulus }) => m::Hardening::Linear {
                    yield_stress: yield_stress?,
                    modulus: v(modulus)?,
                },
                Some(ast::HardeningAst::Swift { k, eps0, n }) => m::Hardening::Swift {
                    k: v(k)?,
                    eps0: v(eps0)?,
                    n: v(n)?,
                },
                Some(ast::HardeningAst::Voce { sigma_inf, delta }) => m::Hardening::Voce {
                    yield_stress: yield_stress?,
                    sigma_inf: v(sigma_inf)?,
                    delta: v(delta)?,
                },
            };
            MaterialLaw::ElastoPlastic {
                young,
                poisson,
                hardening,
                viscosity: def.viscoplastic.as_ref().and_then(|vp| v(&vp.eta)),
            }
        } else {
            MaterialLaw::LinearElastic { young, poisson }
        };
        materials.push(Material {
            name: name.name.clone(),
            law,
        });
        Some(materials.len() - 1)
    }

    /// Deck `set` items become `body.name` sets of the global mesh, in order.
    fn sets(&mut self) {
        for s in &self.deck.sets {
            if self.has_error_in(s.span) || !self.body_nodes.contains_key(&s.target.body.name) {
                // Already reported (or its body's mesh failed).
                self.skipped_sets.push(s.name.name.clone());
                continue;
            }
            let Some(r) = self.resolve(&s.target, Need::Nodes, "set") else {
                self.skipped_sets.push(s.name.name.clone());
                continue;
            };
            let key = format!("{}.{}", s.target.body.name, s.name.name);
            if let Some(edges) = r.edges {
                self.mesh.edge_sets.insert(key.clone(), edges);
            }
            self.mesh.node_sets.insert(key, r.nodes);
        }
    }

    /// Whether references to this body must be skipped: it has no mesh
    /// (its mesh failed, or it is unknown, both already reported).
    fn body_failed(&mut self, r: &ast::SetRef) -> bool {
        if self.body_nodes.contains_key(&r.body.name) {
            return false;
        }
        if !self.deck.bodies.iter().any(|b| b.name.name == r.body.name) {
            self.missing("the body", r.body.span);
        }
        true
    }

    fn constraints(&mut self) -> Vec<Dirichlet> {
        let mut out = Vec::new();
        // (node, component) -> (label, value) of the first prescription.
        let mut seen: BTreeMap<(usize, usize), (String, m::TimeFunction)> = BTreeMap::new();
        for b in &self.deck.boundaries {
            if self.has_error_in(b.span) || self.body_failed(&b.target) {
                continue;
            }
            let word = match b.kind {
                ast::BoundaryKind::Fix => "fix",
                ast::BoundaryKind::Displace => "displace",
            };
            let Some(r) = self.resolve(&b.target, Need::Nodes, word) else {
                continue;
            };
            let label = format!("{word} {}", b.target);
            for (c, f) in &b.components {
                let value = self.tf(f);
                let component = c.value.index();
                let mut clashes: BTreeMap<String, usize> = BTreeMap::new();
                for &n in &r.nodes {
                    match seen.get(&(n, component)) {
                        Some((other, v)) if *v != value => {
                            *clashes.entry(other.clone()).or_default() += 1
                        }
                        Some(_) => {}
                        None => {
                            seen.insert((n, component), (label.clone(), value.clone()));
                        }
                    }
                }
                let comp = if component == 0 { "ux" } else { "uy" };
                for (other, count) in clashes {
                    self.diags.push(
                        Diagnostic::warning(
                            format!("`{label}` and `{other}` prescribe different values of {comp} on {count} node(s)"),
                            c.span,
                            "conflicting prescription",
                        )
                        .with_help("make them agree, or use sets that do not share nodes"),
                    );
                }
                out.push(Dirichlet {
                    label: label.clone(),
                    nodes: r.nodes.clone(),
                    component,
                    value,
                });
            }
        }
        out
    }

    fn loads(&mut self) -> Vec<Load> {
        let mut out = Vec::new();
        for l in &self.deck.loads {
            if self.has_error_in(l.span) || self.body_failed(&l.target) {
                continue;
            }
            match l.kind {
                ast::LoadKind::Pressure => {
                    let Some(r) = self.resolve(&l.target, Need::Edges, "pressure") else {
                        continue;
                    };
                    let label = format!("pressure {}", l.target);
                    for (_, f) in &l.values {
                        out.push(Load::Pressure {
                            label: label.clone(),
                            edges: r.edges.clone().unwrap_or_default(),
                            value: self.tf(f),
                        });
                    }
                }
                ast::LoadKind::Force => {
                    let Some(r) = self.resolve(&l.target, Need::Nodes, "force") else {
                        continue;
                    };
                    let label = format!("force {}", l.target);
                    for (c, f) in &l.values {
                        out.push(Load::NodalForce {
                            label: label.clone(),
                            nodes: r.nodes.clone(),
                            component: c.map_or(0, |c| c.index()),
                            value: self.tf(f),
                        });
                    }
                }
            }
        }
        out
    }

    fn tools(&mut self) -> Vec<RigidTool> {
        let mut out = Vec::new();
        for t in &self.deck.tools {
            if self.has_error_in(t.span) {
                continue;
            }
            let Some((geometry, reference)) = self.tool_geometry(t) else {
                self.missing("a tool setting", t.kind.span);
                continue;
            };
            let mut motion = ToolMotion::fixed();
            motion.center = reference;
            if let Some(mo) = &t.motion {
                if let Some(f) = &mo.ux {
                    motion.ux = self.tf(f);
                }
                if let Some(f) = &mo.uy {
                    motion.uy = self.tf(f);
                }
                if let Some(f) = &mo.rotation {
                    motion.rotation = self.tf(f);
                }
                if let Some(c) = &mo.center {
                    motion.center = c.value;
                }
            }
            out.push(RigidTool {
                name: t.name.name.clone(),
                geometry,
                motion,
            });
        }
        out
    }

    /// The engine geometry and the tool's reference point (default centre
    /// of rotation: circle/arc centre, plane point, first point otherwise).
    fn tool_geometry(&self, t: &ast::Tool) -> Option<(ToolGeometry, [f64; 2])> {
        Some(match &t.geometry {
            ast::ToolGeometry::Plane { point, normal } => {
                let p = point.as_ref()?.value;
                let n = normal.as_ref()?.value;
                let len = (n[0] * n[0] + n[1] * n[1]).sqrt();
                if len == 0.0 {
                    return None;
                }
                (
                    ToolGeometry::Plane {
                        point: p,
                        normal: [n[0] / len, n[1] / len],
                    },
                    p,
                )
            }
            ast::ToolGeometry::Polyline { points } => {
                let pts: Vec<[f64; 2]> = points.as_ref()?.value.iter().map(|p| p.value).collect();
                let first = *pts.first()?;
                (ToolGeometry::Polyline { points: pts }, first)
            }
            ast::ToolGeometry::Arc {
                center,
                radius,
                start,
                end,
            } => {
                let c = center.as_ref()?.value;
                (
                    ToolGeometry::Arc {
                        center: c,
                        radius: radius.as_ref()?.value,
                        start_angle: start.as_ref()?.value.to_radians(),
                        end_angle: end.as_ref()?.value.to_radians(),
                    },
                    c,
                )
            }
            ast::ToolGeometry::Circle {
                center,
                radius,
                side,
            } => {
                let c = center.as_ref()?.value;
                let side = match side.as_ref().map(|s| s.value) {
                    Some(ast::Side::Inside) => ToolSide::Inside,
                    _ => ToolSide::Outside,
                };
                (
                    ToolGeometry::Circle {
                        center: c,
                        radius: radius.as_ref()?.value,
                        side,
                    },
                    c,
                )
            }
            ast::ToolGeometry::Nurbs {
                degree,
                points,
                weights,
                knots,
            } => {
                let degree = usize::try_from(degree.as_ref()?.value).ok()?;
                let control_points: Vec<[f64; 2]> =
                    points.as_ref()?.value.iter().map(|p| p.value).collect();
                let n = control_points.len();
                let first = *control_points.first()?;
                let weights = match weights {
                    Some(w) => w.value.iter().map(|x| x.value).collect(),
                    None => vec![1.0; n],
                };
                let knots = match knots {
                    Some(k) => k.value.iter().map(|x| x.value).collect(),
                    None => open_uniform_knots(n, degree),
                };
                (
                    ToolGeometry::Nurbs {
                        degree,
                        control_points,
                        weights,
                        knots,
                    },
                    first,
                )
            }
        })
    }

    fn contacts(&mut self, bodies: &[m::Body], tools: &[RigidTool]) -> Vec<ContactPair> {
        let mut out = Vec::new();
        for c in &self.deck.contacts {
            if self.has_error_in(c.span) || self.body_failed(&c.target) {
                continue;
            }
            let Some(r) = self.resolve(&c.target, Need::Edges, "contact") else {
                continue;
            };
            let Some(body) = bodies.iter().position(|b| b.name == c.target.body.name) else {
                continue;
            };
            let master = match &c.master {
                Some(m) => {
                    if self.body_failed(m) {
                        continue;
                    }
                    let Some(mr) = self.resolve(m, Need::Edges, "contact master") else {
                        continue;
                    };
                    let Some(mbody) = bodies.iter().position(|b| b.name == m.body.name) else {
                        continue;
                    };
                    let medges = mr.edges.unwrap_or_default();
                    ContactMaster::Surface {
                        body: mbody,
                        nodes: mesh::edge_nodes(&medges),
                        edges: medges,
                    }
                }
                None => {
                    let Some(tool) = tools.iter().position(|t| t.name == c.tool.name) else {
                        self.missing("the tool", c.tool.span);
                        continue;
                    };
                    ContactMaster::Tool(tool)
                }
            };
            let method = match c.method.as_ref().map(|m| &m.value) {
                Some(Method::Penalty {
                    kind,
                    stiffness: Some(s),
                }) => ContactMethod::Penalty {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(PenaltyKindAst::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    stiffness: s.value,
                },
                Some(Method::Lagrange { formulation }) => ContactMethod::Lagrange {
                    formulation: match formulation.as_ref().map(|f| f.value) {
                        Some(ast::LagrangeFormulationAst::Doubled) => {
                            m::LagrangeFormulation::Doubled
                        }
                        _ => m::LagrangeFormulation::Single,
                    },
                },
                Some(Method::AugmentedLagrange {
                    kind,
                    penalty: Some(p),
                    tolerance: Some(tol),
                    update,
                }) => ContactMethod::AugmentedLagrange {
                    kind: match kind.as_ref().map(|k| k.value) {
                        Some(PenaltyKindAst::Nodal) => PenaltyKind::Nodal,
                        _ => PenaltyKind::Area,
                    },
                    penalty: p.value,
                    tolerance: tol.value,
                    update: match update.as_ref().map(|u| u.value) {
                        Some(ast::MultiplierUpdateAst::Newton) => m::MultiplierUpdate::Newton,
                        _ => m::MultiplierUpdate::Converged,
                    },
                },
                _ => {
                    self.missing("a supported contact method", c.tool.span);
                    continue;
                }
            };
            let edges = r.edges.unwrap_or_default();
            out.push(ContactPair {
                name: format!("{} -> {}", c.target, c.tool.name),
                body,
                nodes: mesh::edge_nodes(&edges),
                edges,
                master,
                strategy: match c.strategy.as_ref().map(|s| s.value) {
                    Some(ast::StrategyAst::DoublePass) => ContactStrategy::DoublePass,
                    Some(ast::StrategyAst::ModifiedDoublePass) => {
                        ContactStrategy::ModifiedDoublePass
                    }
                    _ => ContactStrategy::SinglePass,
                },
                search: match c.search.as_ref().map(|s| s.value) {
                    Some(ast::SearchAst::Circle) => m::LocalSearch::Circle,
                    _ => m::LocalSearch::Memory,
                },
                method,
                prof: c.prof.as_ref().map(|p| p.value),
                friction: c.friction.as_ref().and_then(|f| {
                    Some(m::Friction {
                        mu: f.value.mu.as_ref()?.value,
                        stiffness: f.value.stiffness.as_ref().map(|s| s.value),
                        first_impact: match f.value.first_impact.as_ref().map(|v| v.value) {
                            Some(ast::FirstImpactAst::Frictionless) => m::FirstImpact::Frictionless,
                            _ => m::FirstImpact::Intersect,
                        },
                        cut_at_impact: f.value.cut_at_impact.as_ref().is_some_and(|v| v.value),
                    })
                }),
            });
        }
        out
    }

    fn steps(&mut self) -> Vec<Step> {
        let mut out = Vec::new();
        for (i, s) in self.deck.steps.iter().enumerate() {
            if self.has_error_in(s.span) {
                continue;
            }
            let Some(t) = &s.time else {
                self.missing("the step time", s.keyword);
                continue;
            };
            let mut newton = NewtonSettings::default();
            if let Some(n) = &s.newton {
                if let Some(x) = &n.tol {
                    newton.tol = x.value;
                }
                if let Some(x) = &n.tol_displacement {
                    newton.tol_displacement = x.value;
                }
                if let Some(x) = &n.max_iter {
                    newton.max_iter = x.value.max(1) as usize;
                }
                if let Some(x) = &n.line_search {
                    newton.line_search = x.value;
                }
            }
            let name = s
                .name
                .as_ref()
                .map(|n| n.name.clone())
                .unwrap_or_else(|| step_label(s, i).replace(' ', "_"));
            // Contiguity was validated; chain exactly so no rounding gap remains.
            let t_start = match out.last() {
                Some(Step { t_end, .. }) => *t_end,
                None => t.value[0].value,
            };
            out.push(Step {
                name,
                t_start,
                t_end: t.value[1].value,
                increments: s.increments.as_ref().map_or(1, |n| n.value.max(1) as usize),
                min_fraction: s
                    .min_increment
                    .as_ref()
                    .map_or(DEFAULT_MIN_FRACTION, |x| x.value),
                newton,
            });
        }
        out
    }

    fn output(&mut self, contacts: &[ContactPair]) -> OutputRequest {
        let Some(o) = self.deck.outputs.first() else {
            return OutputRequest::default();
        };
        let mut out = OutputRequest::default();
        if let Some(e) = &o.every {
            out.every = e.value.max(1) as usize;
        }
        if let Some(fields) = &o.fields {
            let mut list: Vec<Field> = Vec::new();
            for f in &fields.value {
                let field = match f.value {
                    ast::FieldName::Displacement => Field::Displacement,
                    ast::FieldName::Stress => Field::Stress,
                    ast::FieldName::Strain => Field::Strain,
                    ast::FieldName::VonMises => Field::VonMises,
                    ast::FieldName::Reaction => Field::Reaction,
                    ast::FieldName::Contact => Field::Contact,
                };
                if !list.contains(&field) {
                    list.push(field);
                }
            }
            out.fields = list;
        }
        for h in o.history.iter().flatten() {
            if self.has_error_in(h.span) {
                continue;
            }
            match &h.value {
                ast::History::Reaction(r) | ast::History::Displacement(r) => {
                    if self.body_failed(r) {
                        continue;
                    }
                    let is_reaction = matches!(h.value, ast::History::Reaction(_));
                    let word = if is_reaction {
                        "reaction"
                    } else {
                        "displacement"
                    };
                    let Some(res) = self.resolve(r, Need::Nodes, word) else {
                        continue;
                    };
                    let label = format!("{word}({r})");
                    out.history.push(if is_reaction {
                        HistoryRequest::Reaction {
                            label,
                            nodes: res.nodes,
                        }
                    } else {
                        HistoryRequest::Displacement {
                            label,
                            nodes: res.nodes,
                        }
                    });
                }
                ast::History::ContactForce(r, tool) => {
                    let name = format!("{r} -> {}", tool.name);
                    match contacts.iter().position(|c| c.name == name) {
                        Some(pair) => out.history.push(HistoryRequest::ContactForce {
                            label: format!("contact_force({name})"),
                            pair,
                        }),
                        None if self.body_failed(r) => {}
                        None => self.missing("the contact pair", h.span),
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
                viscosity: Some(7.0),
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
