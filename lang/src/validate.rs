//! Semantic checks of a parsed deck, all at once: unknown and duplicate
//! names (with "did you mean"), set references (does the set exist, does it
//! have edges where edges are needed), out-of-range values, time ranges,
//! and features that are reserved but not supported yet.
//!
//! Shape errors (wrong value types, unknown keys, missing required keys) are
//! reported while parsing (see [`crate::parse`]); this pass only looks at
//! values that parsed, so nothing is reported twice.

use crate::ast::*;
use crate::diagnostics::{Diagnostic, LineIndex};
use crate::suggest::did_you_mean;
use std::collections::BTreeMap;

/// Maximum number of cells a generator may be asked for.
pub const MAX_CELLS: i64 = 4_000_000;

/// Whether a set provides edges (and their nodes) or only nodes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SetKind {
    /// Boundary edges and their nodes.
    Edges,
    /// Nodes only.
    Nodes,
}

/// What a reference is used for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Need {
    /// Any set (its nodes are used).
    Nodes,
    /// Boundary edges (pressure, contact).
    Edges,
}

/// The sets a generator creates (see `ctc_engine::mesh::generate::MeshSpec`),
/// plus the built-in `boundary` and `all`.
pub fn generator_sets(g: &Generator) -> BTreeMap<String, SetKind> {
    let mut m = BTreeMap::new();
    let mut add = |names: &[&str], k: SetKind| {
        for n in names {
            m.insert(n.to_string(), k);
        }
    };
    match &g.kind {
        GeneratorKind::Rectangle { .. } => {
            add(&["bottom", "right", "top", "left"], SetKind::Edges);
            add(
                &["corner_bl", "corner_br", "corner_tr", "corner_tl"],
                SetKind::Nodes,
            );
        }
        GeneratorKind::Disc { quarter, .. } => {
            add(&["arc", "flat"], SetKind::Edges);
            if *quarter {
                add(&["axis"], SetKind::Edges);
            }
            add(&["center"], SetKind::Nodes);
        }
        GeneratorKind::Annulus { start, end, .. } => {
            add(&["inner", "outer"], SetKind::Edges);
            let s = start.as_ref().map_or(0.0, |s| s.value);
            let e = end.as_ref().map_or(360.0, |e| e.value);
            if (e - s - 360.0).abs() > 1e-9 {
                add(&["start", "end"], SetKind::Edges);
            }
        }
    }
    add_builtin_sets(&mut m);
    m
}

/// Adds the sets every body has: `boundary` (edges) and `all` (nodes).
pub fn add_builtin_sets(m: &mut BTreeMap<String, SetKind>) {
    m.insert("boundary".to_string(), SetKind::Edges);
    m.insert("all".to_string(), SetKind::Nodes);
}

/// What validation knows about a body's sets.
struct BodyInfo {
    /// Known sets; `None` when they are only known after reading a mesh file
    /// (or the mesh is broken): then any name is accepted here and checked
    /// when the mesh is built.
    sets: Option<BTreeMap<String, SetKind>>,
    /// Sets defined by `set` items so far (plus the built-in sets when
    /// `sets` is `None`).
    deck_sets: BTreeMap<String, SetKind>,
}

struct Checker<'a> {
    /// Names of `set` items whose body is unknown (already reported):
    /// references to them are not reported again.
    orphan_sets: Vec<String>,
    deck: &'a Deck,
    lines: LineIndex<'a>,
    diags: Vec<Diagnostic>,
    bodies: BTreeMap<String, BodyInfo>,
}

/// Checks `deck` (parsed from `text`) and returns every problem found.
pub fn validate(deck: &Deck, text: &str) -> Vec<Diagnostic> {
    let mut c = Checker {
        orphan_sets: Vec::new(),
        deck,
        lines: LineIndex::new(text),
        diags: Vec::new(),
        bodies: BTreeMap::new(),
    };
    c.analysis();
    c.materials();
    c.bodies();
    c.sets();
    c.tools();
    c.contacts();
    c.boundaries();
    c.loads();
    c.steps();
    c.output();
    c.diags
}

fn positive(x: &Option<Spanned<f64>>) -> Option<&Spanned<f64>> {
    x.as_ref().filter(|v| v.value <= 0.0)
}

impl Checker<'_> {
    fn err(&mut self, d: Diagnostic) {
        self.diags.push(d);
    }

    fn line(&self, span: Span) -> usize {
        self.lines.line_col(span.start).0
    }

    /// Error if `x <= 0`.
    fn must_be_positive(&mut self, x: &Option<Spanned<f64>>, what: &str) {
        if let Some(v) = positive(x) {
            self.err(Diagnostic::error(
                format!("{what} must be positive"),
                v.span,
                "must be > 0",
            ));
        }
    }

    /// Error if a whole number is below `min`.
    fn at_least(&mut self, x: &Option<Spanned<i64>>, min: i64, what: &str) {
        if let Some(v) = x.as_ref().filter(|v| v.value < min) {
            self.err(Diagnostic::error(
                format!("{what} must be at least {min}"),
                v.span,
                format!("must be >= {min}"),
            ));
        }
    }

    fn duplicates<'n>(&mut self, names: impl IntoIterator<Item = &'n Ident>, what: &str) {
        let mut seen: BTreeMap<&str, Span> = BTreeMap::new();
        for n in names {
            match seen.get(n.name.as_str()) {
                Some(first) => {
                    let line = self.line(*first);
                    self.err(
                        Diagnostic::error(
                            format!("{what} `{}` is defined twice", n.name),
                            n.span,
                            format!("second definition of `{}`", n.name),
                        )
                        .with_help(format!(
                            "the first definition is on line {line}; rename one of them"
                        )),
                    );
                }
                None => {
                    seen.insert(&n.name, n.span);
                }
            }
        }
    }

    // ------------------------------------------------------------ analysis
    fn analysis(&mut self) {
        let deck = self.deck;
        if deck.analysis.is_empty() && !deck.has_broken("analysis") {
            self.err(
                Diagnostic::error(
                    "the deck has no `analysis` block",
                    Span::new(0, 0),
                    "expected an `analysis` block",
                )
                .with_help("add `analysis { dimension = plane_strain }` (or `plane_stress`, `axisymmetric`)"),
            );
        }
        for extra in deck.analysis.iter().skip(1) {
            let line = self.line(deck.analysis[0].keyword);
            self.err(
                Diagnostic::error(
                    "more than one `analysis` block",
                    extra.keyword,
                    "second `analysis` block",
                )
                .with_help(format!("the first one is on line {line}; merge them")),
            );
        }
        let Some(a) = deck.analysis.first() else {
            return;
        };
        let dim = a.dimension.as_ref().map(|d| d.value);
        if let Some(d) = a
            .dimension
            .as_ref()
            .filter(|d| d.value == Dimension::ThreeD)
        {
            self.err(
                Diagnostic::error(
                    "3d analyses are not supported yet",
                    d.span,
                    "not supported yet",
                )
                .with_help("use `plane_strain`, `plane_stress` or `axisymmetric`"),
            );
        }
        if let Some(t) = &a.thickness {
            if dim == Some(Dimension::Axisymmetric) {
                self.err(
                    Diagnostic::warning(
                        "`thickness` is ignored in axisymmetric analyses",
                        t.span,
                        "ignored",
                    )
                    .with_help(
                        "axisymmetric results are totals over the full 2*pi; remove `thickness`",
                    ),
                );
            } else {
                self.must_be_positive(&a.thickness, "thickness");
            }
        }
    }

    // ------------------------------------------------------------ materials
    fn materials(&mut self) {
        let deck = self.deck;
        self.duplicates(deck.materials.iter().map(|m| &m.name), "material");
        for m in &deck.materials {
            for r in &m.reserved {
                self.err(
                    Diagnostic::error(
                        format!("`{}` materials are not supported yet", r.name),
                        r.span,
                        "not supported yet",
                    )
                    .with_help("use `elastic`, `neo_hookean`, `plastic` and `viscoplastic` blocks"),
                );
            }
            self.inelastic(m);
            let Some(e) = m.elastic.as_ref().or(m.neo_hookean.as_ref()) else {
                continue;
            };
            self.must_be_positive(&e.young, "Young's modulus E");
            if let Some(nu) = e
                .poisson
                .as_ref()
                .filter(|nu| !(nu.value > -1.0 && nu.value < 0.5))
            {
                let help = if nu.value == 0.5 {
                    "nu = 0.5 is incompressible, which a displacement formulation cannot represent; \
                     use e.g. nu = 0.499 with `formulation = selective_reduced`"
                } else {
                    "Poisson's ratio of an isotropic elastic material lies strictly between -1 and 0.5"
                };
                self.err(
                    Diagnostic::error(
                        "Poisson's ratio nu must lie in (-1, 0.5)",
                        nu.span,
                        format!("nu = {}", num(nu.value)),
                    )
                    .with_help(help),
                );
            }
            let used = deck
                .bodies
                .iter()
                .any(|b| b.material.as_ref().is_some_and(|n| n.name == m.name.name));
            // A body naming an unknown material probably meant this one.
            let dangling = deck.bodies.iter().any(|b| {
                b.material
                    .as_ref()
                    .is_some_and(|n| !deck.materials.iter().any(|m| m.name.name == n.name))
            });
            let unassigned = deck.bodies.iter().any(|b| b.material.is_none());
            if !used && !dangling && !unassigned && !deck.has_broken("body") {
                self.err(Diagnostic::warning(
                    format!("material `{}` is not used by any body", m.name.name),
                    m.name.span,
                    "unused",
                ));
            }
        }
    }

    /// Kinematics against the material law and the analysis dimension.
    fn body_kinematics(&mut self, b: &Body, dim: Option<Dimension>) {
        let deck = self.deck;
        let finite = b
            .kinematics
            .as_ref()
            .filter(|k| k.value == KinematicsKind::Finite);
        let material = b
            .material
            .as_ref()
            .and_then(|n| deck.materials.iter().find(|m| m.name.name == n.name));
        let plastic = material.is_some_and(|m| m.plastic.is_some());
        if dim == Some(Dimension::PlaneStress) {
            if let Some(k) = finite {
                self.err(
                    Diagnostic::error(
                        "finite strain in plane stress is not supported yet",
                        k.span,
                        "not supported yet",
                    )
                    .with_help("use `dimension = plane_strain` or `axisymmetric`"),
                );
            } else if plastic {
                self.err(
                    Diagnostic::error(
                        "plasticity in plane stress is not supported yet",
                        b.name.span,
                        "not supported yet",
                    )
                    .with_help("use `dimension = plane_strain` or `axisymmetric`"),
                );
            }
        }
        if let Some(m) = material.filter(|m| m.neo_hookean.is_some()) {
            if finite.is_none() {
                self.err(
                    Diagnostic::error(
                        format!(
                            "material `{}` is Neo-Hookean, a finite-strain law: body `{}` needs \
                             `kinematics = finite`",
                            m.name.name, b.name.name
                        ),
                        b.name.span,
                        "small-strain body",
                    )
                    .with_help("add `kinematics = finite` to the body"),
                );
            }
        }
    }

    /// `neo_hookean`, `plastic`, `viscoplastic` blocks of a material.
    fn inelastic(&mut self, m: &Material) {
        if let (Some(n), Some(_)) = (&m.neo_hookean, &m.elastic) {
            self.err(
                Diagnostic::error(
                    "a material has either `elastic` or `neo_hookean`, not both",
                    n.span,
                    "second elastic law",
                )
                .with_help("remove one of the two blocks"),
            );
        }
        if let (Some(n), Some(p)) = (&m.neo_hookean, &m.plastic) {
            let _ = n;
            self.err(
                Diagnostic::error(
                    "plasticity on a Neo-Hookean material is not supported yet",
                    p.span,
                    "not supported yet",
                )
                .with_help("use `elastic { .. }` with `plastic { .. }` (Hencky elasticity at finite strain)"),
            );
        }
        if let (Some(v), None) = (&m.viscoplastic, &m.plastic) {
            self.err(
                Diagnostic::error(
                    "`viscoplastic` needs a `plastic` block (the static yield stress and hardening)",
                    v.span,
                    "no `plastic` block",
                )
                .with_help("add e.g. `plastic { yield = 250  hardening = linear { H = 1000 } }`"),
            );
        }
        if let Some(v) = &m.viscoplastic {
            self.must_be_positive(&v.eta, "the viscosity eta");
        }
        let Some(p) = &m.plastic else { return };
        let swift = matches!(
            p.hardening.as_ref().map(|h| &h.value),
            Some(HardeningAst::Swift { .. })
        );
        match (&p.yield_stress, swift) {
            (Some(y), true) => self.err(
                Diagnostic::error(
                    "`yield` is not used with Swift hardening",
                    y.span,
                    "the initial yield stress is K eps0^n",
                )
                .with_help("remove `yield` (or use `linear` / `voce` hardening)"),
            ),
            (None, false) => self.err(
                Diagnostic::error(
                    "missing `yield` in the `plastic` block",
                    p.span,
                    "no yield stress",
                )
                .with_help("add the initial yield stress, e.g. `yield = 250`"),
            ),
            _ => self.must_be_positive(&p.yield_stress, "the yield stress"),
        }
        let Some(h) = &p.hardening else { return };
        match &h.value {
            HardeningAst::Linear { modulus } => {
                if let Some(v) = modulus.as_ref().filter(|v| v.value < 0.0) {
                    self.err(
                        Diagnostic::error(
                            "the hardening modulus H must be >= 0",
                            v.span,
                            "negative",
                        )
                        .with_help(
                            "softening is not supported: it makes the solution mesh dependent",
                        ),
                    );
                }
            }
            HardeningAst::Swift { k, eps0, n } => {
                self.must_be_positive(k, "Swift K");
                self.must_be_positive(eps0, "Swift eps0");
                if let Some(v) = n.as_ref().filter(|v| !(0.0..=1.0).contains(&v.value)) {
                    self.err(Diagnostic::error(
                        "Swift n must lie in [0, 1]",
                        v.span,
                        format!("n = {}", num(v.value)),
                    ));
                }
            }
            HardeningAst::Voce { sigma_inf, delta } => {
                self.must_be_positive(delta, "Voce delta");
                if let (Some(si), Some(y)) = (sigma_inf, &p.yield_stress) {
                    if si.value < y.value {
                        self.err(Diagnostic::error(
                            "Voce sigma_inf must be at least the yield stress",
                            si.span,
                            format!("sigma_inf = {} < yield = {}", num(si.value), num(y.value)),
                        ));
                    }
                }
            }
        }
    }

    // ------------------------------------------------------------ bodies
    fn bodies(&mut self) {
        let deck = self.deck;
        if deck.bodies.is_empty()
            && !deck.has_broken("body")
            && !deck.broken.iter().any(|b| b.keyword.is_empty())
        {
            self.err(
                Diagnostic::error("the deck has no `body`", Span::new(0, 0), "expected a `body`")
                    .with_help("add e.g. `body block { mesh = rectangle { size = (1, 1)  divisions = (10, 10) }  material = steel }`"),
            );
        }
        self.duplicates(deck.bodies.iter().map(|b| &b.name), "body");
        let material_names: Vec<&str> = deck
            .materials
            .iter()
            .map(|m| m.name.name.as_str())
            .collect();
        let dim = deck
            .analysis
            .first()
            .and_then(|a| a.dimension.as_ref())
            .map(|d| d.value);
        for b in &deck.bodies {
            self.body_kinematics(b, dim);
            if let Some(m) = &b.material {
                if !material_names.contains(&m.name.as_str())
                    && !deck.broken_named("material", &m.name)
                {
                    self.err(
                        Diagnostic::error(
                            format!("unknown material `{}`", m.name),
                            m.span,
                            "no material with this name",
                        )
                        .with_help(
                            did_you_mean(&m.name, &material_names).unwrap_or_else(|| {
                                format!(
                                "define it with `material {} {{ elastic {{ E = ..  nu = .. }} }}`",
                                m.name
                            )
                            }),
                        ),
                    );
                }
            }
            let mut sets = None;
            if let Some(mesh) = &b.mesh {
                if let MeshDef::Generator(g) = &mesh.value {
                    self.generator(g);
                    sets = Some(generator_sets(g));
                    if let (Some(f), Some(el)) = (&b.formulation, &g.element) {
                        if f.value == FormulationKind::SelectiveReduced
                            && el.value == ElementKind::Tri3
                        {
                            self.err(
                                Diagnostic::warning(
                                    "`selective_reduced` has no effect on triangles",
                                    f.span,
                                    "tri3 elements always use one integration point",
                                )
                                .with_help(
                                    "use `element = quad4` for selective reduced integration",
                                ),
                            );
                        }
                    }
                }
            }
            let mut deck_sets = BTreeMap::new();
            if sets.is_none() {
                // A mesh file's sets are only known once it is read, but the
                // built-in ones exist anyway (and their kinds are known).
                add_builtin_sets(&mut deck_sets);
            }
            self.bodies
                .entry(b.name.name.clone())
                .or_insert(BodyInfo { sets, deck_sets });
        }
    }

    fn grading(&mut self, g: &Option<Spanned<Grading>>) {
        if let Some(g) = g {
            if let Grading::Geometric(r) | Grading::Center(r) = &g.value {
                self.must_be_positive(&Some(r.clone()), "grading ratio");
            }
        }
    }

    fn generator(&mut self, g: &Generator) {
        let mut cells: i64 = 1;
        match &g.kind {
            GeneratorKind::Rectangle {
                size,
                divisions,
                grading,
                ..
            } => {
                if let Some(s) = size {
                    self.must_be_positive(&Some(s.value[0].clone()), "width");
                    self.must_be_positive(&Some(s.value[1].clone()), "height");
                }
                if let Some(d) = divisions {
                    for (v, dir) in d.value.iter().zip(["x", "y"]) {
                        self.at_least(&Some(v.clone()), 1, &format!("divisions along {dir}"));
                        cells = cells.saturating_mul(v.value.max(1));
                    }
                }
                if let Some(gr) = grading {
                    for g in &gr.value {
                        self.grading(&Some(g.clone()));
                    }
                }
            }
            GeneratorKind::Disc {
                quarter,
                radius,
                radial,
                circumferential,
                radial_grading,
                circumferential_grading,
                ..
            } => {
                self.must_be_positive(radius, "radius");
                self.at_least(radial, 1, "radial divisions");
                self.at_least(
                    circumferential,
                    if *quarter { 1 } else { 2 },
                    "circumferential divisions",
                );
                for n in [radial, circumferential].into_iter().flatten() {
                    cells = cells.saturating_mul(n.value.max(1));
                }
                self.grading(radial_grading);
                self.grading(circumferential_grading);
            }
            GeneratorKind::Annulus {
                inner,
                outer,
                start,
                end,
                radial,
                circumferential,
                radial_grading,
                ..
            } => {
                self.must_be_positive(inner, "inner radius");
                if let (Some(i), Some(o)) = (inner, outer) {
                    if o.value <= i.value && i.value > 0.0 {
                        self.err(Diagnostic::error(
                            "the outer radius must be larger than the inner radius",
                            o.span,
                            format!("outer = {} <= inner = {}", num(o.value), num(i.value)),
                        ));
                    }
                }
                let s = start.as_ref().map_or(0.0, |s| s.value);
                let e_val = end.as_ref().map_or(360.0, |e| e.value);
                let at = end
                    .as_ref()
                    .or(start.as_ref())
                    .map_or(g.name.span, |x| x.span);
                if e_val <= s {
                    self.err(Diagnostic::error(
                        "the annulus `end` angle must be larger than `start`",
                        at,
                        format!("start = {}, end = {}", num(s), num(e_val)),
                    ));
                } else if e_val - s > 360.0 + 1e-9 {
                    self.err(Diagnostic::error(
                        "an annulus spans at most 360 degrees",
                        at,
                        format!("end - start = {}", num(e_val - s)),
                    ));
                }
                self.at_least(radial, 1, "radial divisions");
                let full = (e_val - s - 360.0).abs() <= 1e-9;
                self.at_least(
                    circumferential,
                    if full { 3 } else { 1 },
                    "circumferential divisions",
                );
                if let Some(c) = circumferential.as_ref().filter(|c| c.value >= 1) {
                    let sweep = e_val - s;
                    if sweep > 0.0 && sweep / c.value as f64 >= 180.0 {
                        self.err(Diagnostic::error(
                            "each circumferential division must span less than 180 degrees",
                            c.span,
                            format!("{} division(s) over {} degrees", c.value, num(sweep)),
                        ));
                    }
                }
                for n in [radial, circumferential].into_iter().flatten() {
                    cells = cells.saturating_mul(n.value.max(1));
                }
                self.grading(radial_grading);
            }
        }
        if cells > MAX_CELLS {
            self.err(
                Diagnostic::error(
                    format!("the `{}` mesh would have {cells} cells", g.name.name),
                    g.name.span,
                    "too many cells",
                )
                .with_help(format!("at most {MAX_CELLS} cells per generated mesh")),
            );
        }
    }

    // ------------------------------------------------------------ sets
    fn sets(&mut self) {
        let deck = self.deck;
        for s in &deck.sets {
            let ok = self.set_ref(&s.target, Need::Nodes, "set");
            let Some(info) = self.bodies.get(&s.target.body.name) else {
                self.orphan_sets.push(s.name.name.clone());
                continue;
            };
            let name = &s.name.name;
            let clash = info.deck_sets.contains_key(name)
                || info.sets.as_ref().is_some_and(|m| m.contains_key(name));
            if clash {
                let what = if matches!(name.as_str(), "boundary" | "all") {
                    format!("`{name}` is a built-in set of every body")
                } else {
                    format!("body `{}` already has a set `{name}`", s.target.body.name)
                };
                self.err(
                    Diagnostic::error(
                        format!("set `{}.{name}` is defined twice", s.target.body.name),
                        s.name.span,
                        what,
                    )
                    .with_help("choose another name"),
                );
                continue;
            }
            let kind = match &s.target.kind {
                SetRefKind::Edges(_) => SetKind::Edges,
                // Unknown kind (set of a mesh file): be permissive here, the
                // lowering checks it against the mesh.
                SetRefKind::Named(_) => ok.unwrap_or(SetKind::Edges),
                _ => SetKind::Nodes,
            };
            if let Some(info) = self.bodies.get_mut(&s.target.body.name) {
                info.deck_sets.insert(name.clone(), kind);
            }
        }
    }

    /// Checks a set reference; returns the kind of the set when known.
    fn set_ref(&mut self, r: &SetRef, need: Need, user: &str) -> Option<SetKind> {
        let deck = self.deck;
        let body = &r.body.name;
        let Some(info) = self.bodies.get(body) else {
            if !deck.broken_named("body", body) {
                let names: Vec<&str> = deck.bodies.iter().map(|b| b.name.name.as_str()).collect();
                self.err(
                    Diagnostic::error(
                        format!("unknown body `{body}`"),
                        r.body.span,
                        "no body with this name",
                    )
                    .with_help_opt(did_you_mean(body, &names)),
                );
            }
            return None;
        };
        let kind = match &r.kind {
            SetRefKind::Nodes(_) | SetRefKind::Node(_) => Some(SetKind::Nodes),
            SetRefKind::Edges(_) => Some(SetKind::Edges),
            SetRefKind::Named(n) => {
                let found = info
                    .deck_sets
                    .get(&n.name)
                    .or_else(|| info.sets.as_ref().and_then(|m| m.get(&n.name)))
                    .copied();
                match (&info.sets, found) {
                    (_, Some(k)) => Some(k),
                    (None, None) => None,
                    (Some(_), None) if self.orphan_sets.contains(&n.name) => None,
                    (Some(known), None) => {
                        let mut names: Vec<&str> = known.keys().map(String::as_str).collect();
                        names.extend(info.deck_sets.keys().map(String::as_str));
                        let d = Diagnostic::error(
                            format!("body `{body}` has no set `{}`", n.name),
                            n.span,
                            "no set with this name",
                        )
                        .with_help(
                            did_you_mean(&n.name, &names).unwrap_or_else(|| {
                                format!("its sets are {}", crate::suggest::one_of(&names))
                            }),
                        );
                        self.err(d);
                        return None;
                    }
                }
            }
        };
        if need == Need::Edges && kind == Some(SetKind::Nodes) {
            let help = match &r.kind {
                SetRefKind::Nodes(s) => {
                    format!("select boundary edges with `{body}.edges({})`", s.value)
                }
                _ => format!("use a set with edges, e.g. `{body}.boundary` or `{body}.edges(..)`"),
            };
            self.err(
                Diagnostic::error(
                    format!("`{user}` needs boundary edges, but `{r}` is a set of nodes"),
                    r.span,
                    "nodes only",
                )
                .with_help(help),
            );
        }
        kind
    }

    // ------------------------------------------------------------ tools
    fn tools(&mut self) {
        let deck = self.deck;
        self.duplicates(deck.tools.iter().map(|t| &t.name), "tool");
        for t in &deck.tools {
            match &t.geometry {
                ToolGeometry::Plane { normal, .. } => {
                    if let Some(n) = normal
                        .as_ref()
                        .filter(|n| n.value[0] == 0.0 && n.value[1] == 0.0)
                    {
                        self.err(Diagnostic::error(
                            "the plane normal is zero",
                            n.span,
                            "normal = (0, 0)",
                        ));
                    }
                }
                ToolGeometry::Polyline { points } => {
                    if let Some(p) = points {
                        self.polyline(p);
                    }
                }
                ToolGeometry::Arc {
                    radius, start, end, ..
                } => {
                    self.must_be_positive(radius, "radius");
                    if let (Some(s), Some(e)) = (start, end) {
                        let sweep = (e.value - s.value).abs();
                        if sweep == 0.0 {
                            self.err(Diagnostic::error(
                                "the arc has no length",
                                e.span,
                                format!("start = end = {}", num(e.value)),
                            ));
                        } else if sweep > 360.0 {
                            self.err(Diagnostic::error(
                                "an arc spans at most 360 degrees",
                                e.span,
                                format!("|end - start| = {}", num(sweep)),
                            ));
                        }
                    }
                }
                ToolGeometry::Circle { radius, .. } => self.must_be_positive(radius, "radius"),
                ToolGeometry::Nurbs {
                    degree,
                    points,
                    weights,
                    knots,
                } => self.nurbs(degree, points, weights, knots),
            }
            if let Some(m) = &t.motion {
                for f in [&m.ux, &m.uy, &m.rotation].into_iter().flatten() {
                    self.time_fn(f);
                }
            }
            let used = deck.contacts.iter().any(|c| c.tool.name == t.name.name);
            let dangling = deck
                .contacts
                .iter()
                .any(|c| !deck.tools.iter().any(|t| t.name.name == c.tool.name));
            if !used && !dangling && !deck.has_broken("contact") {
                self.err(Diagnostic::warning(
                    format!("tool `{}` is not used by any contact pair", t.name.name),
                    t.name.span,
                    "unused",
                ));
            }
        }
    }

    fn polyline(&mut self, p: &Spanned<Vec<Point>>) {
        if p.value.len() < 2 {
            self.err(Diagnostic::error(
                "a polyline needs at least 2 points",
                p.span,
                format!("{} point(s)", p.value.len()),
            ));
        }
        for w in p.value.windows(2) {
            if w[0].value == w[1].value {
                self.err(
                    Diagnostic::error(
                        "zero-length polyline segment",
                        w[1].span,
                        "same point as the previous one",
                    )
                    .with_help("remove the repeated point"),
                );
            }
        }
    }

    fn nurbs(
        &mut self,
        degree: &Option<Spanned<i64>>,
        points: &Option<Spanned<Vec<Point>>>,
        weights: &Option<Spanned<Vec<Spanned<f64>>>>,
        knots: &Option<Spanned<Vec<Spanned<f64>>>>,
    ) {
        self.at_least(degree, 1, "degree");
        let p = degree.as_ref().map(|d| d.value).filter(|d| *d >= 1);
        let n = points.as_ref().map(|pts| pts.value.len());
        if let (Some(p), Some(n), Some(pts)) = (p, n, points) {
            if (n as i64) < p + 1 {
                self.err(
                    Diagnostic::error(
                        format!("a degree {p} curve needs at least {} control points", p + 1),
                        pts.span,
                        format!("{n} control point(s)"),
                    )
                    .with_help("add control points or lower the degree"),
                );
            }
        }
        if let Some(w) = weights {
            if let Some(n) = n.filter(|n| *n != w.value.len()) {
                self.err(Diagnostic::error(
                    "one weight per control point is needed",
                    w.span,
                    format!("{} weights for {n} control points", w.value.len()),
                ));
            }
            for x in w.value.iter().filter(|x| x.value <= 0.0) {
                self.err(Diagnostic::error(
                    "NURBS weights must be positive",
                    x.span,
                    format!("weight = {}", num(x.value)),
                ));
            }
        }
        let (Some(k), Some(p), Some(n)) = (knots, p, n) else {
            return;
        };
        let want = n as i64 + p + 1;
        if k.value.len() as i64 != want {
            self.err(
                Diagnostic::error(
                    format!("the knot vector needs {want} knots (control points + degree + 1)"),
                    k.span,
                    format!("{} knots", k.value.len()),
                )
                .with_help("leave `knots` out for an open uniform knot vector"),
            );
            return;
        }
        for w in k.value.windows(2) {
            if w[1].value < w[0].value {
                self.err(Diagnostic::error(
                    "knots must be non-decreasing",
                    w[1].span,
                    format!("{} < {}", num(w[1].value), num(w[0].value)),
                ));
                return;
            }
        }
        let (p, n) = (p as usize, n);
        // Multiplicities: at most p + 1 at the ends, p inside (beyond that
        // the curve breaks apart).
        let mut start = 0;
        while start < k.value.len() {
            let mut end = start + 1;
            while end < k.value.len() && k.value[end].value == k.value[start].value {
                end += 1;
            }
            let at_end = start == 0 || end == k.value.len();
            let max = if at_end { p + 1 } else { p };
            if end - start > max {
                self.err(
                    Diagnostic::error(
                        format!("knot {} is repeated {} times", num(k.value[start].value), end - start),
                        k.value[start].span.to(k.value[end - 1].span),
                        format!("at most {max} here for degree {p}"),
                    )
                    .with_help("a knot repeated more than the degree inside the vector disconnects the curve"),
                );
                return;
            }
            start = end;
        }
        if k.value[p].value >= k.value[n].value {
            self.err(Diagnostic::error(
                "the knot vector spans no parameter range",
                k.span,
                format!("knot {} and knot {} are equal", p + 1, n + 1),
            ));
        }
    }

    // ------------------------------------------------------------ contact
    fn contacts(&mut self) {
        let deck = self.deck;
        let tool_names: Vec<&str> = deck.tools.iter().map(|t| t.name.name.as_str()).collect();
        let mut seen: BTreeMap<String, Span> = BTreeMap::new();
        for c in &deck.contacts {
            self.set_ref(&c.target, Need::Edges, "contact");
            if let Some(m) = &c.master {
                // deformable master surface: a boundary of a body
                self.set_ref(m, Need::Edges, "contact master");
            } else if !tool_names.contains(&c.tool.name.as_str())
                && !deck.broken_named("tool", &c.tool.name)
            {
                self.err(
                    Diagnostic::error(format!("unknown tool `{}`", c.tool.name), c.tool.span, "no tool with this name")
                        .with_help(did_you_mean(&c.tool.name, &tool_names).unwrap_or_else(|| {
                            format!("define it, e.g. `tool {} = plane {{ point = (0, 0)  normal = (0, 1) }}`", c.tool.name)
                        })),
                );
            }
            let key = format!("{} -> {}", c.target, c.tool.name);
            if let Some(first) = seen.get(&key) {
                let line = self.line(*first);
                self.err(
                    Diagnostic::error(
                        format!("contact pair `{key}` is defined twice"),
                        c.target.span.to(c.tool.span),
                        "duplicate pair",
                    )
                    .with_help(format!("the first definition is on line {line}")),
                );
            } else {
                seen.insert(key, c.target.span);
            }
            match c.method.as_ref().map(|m| &m.value) {
                Some(Method::Penalty { stiffness, .. }) => {
                    self.must_be_positive(stiffness, "penalty stiffness")
                }
                Some(Method::AugmentedLagrange {
                    penalty, tolerance, ..
                }) => {
                    self.must_be_positive(penalty, "augmented Lagrangian penalty");
                    self.must_be_positive(tolerance, "augmented Lagrangian tolerance");
                }
                Some(Method::Lagrange { .. }) | None => {}
            }
            self.must_be_positive(&c.prof, "prof");
            if let Some(f) = &c.friction {
                if let Some(mu) = f
                    .value
                    .mu
                    .as_ref()
                    .filter(|m| m.value.is_nan() || m.value < 0.0)
                {
                    self.err(Diagnostic::error(
                        "friction coefficient `mu` must not be negative",
                        mu.span,
                        "must be >= 0",
                    ));
                }
                self.must_be_positive(&f.value.stiffness, "friction stiffness");
            }
            if let (None, Some(st)) = (&c.master, &c.strategy) {
                self.err(
                    Diagnostic::error(
                        "`strategy` applies to deformable masters only",
                        st.span,
                        "the master is a rigid tool",
                    )
                    .with_help(
                        "a rigid tool is always the master (single pass); write the master as \
                         `body.set` for contact between deformable bodies",
                    ),
                );
            }
            for r in &c.reserved {
                self.err(
                    Diagnostic::error(
                        format!("`{}` is not supported yet", r.name),
                        r.span,
                        "not supported yet",
                    )
                    .with_help("contact is frictionless for now"),
                );
            }
        }
    }

    // ------------------------------------------------------------ fix / displace, loads
    fn boundaries(&mut self) {
        for b in &self.deck.boundaries {
            let user = match b.kind {
                BoundaryKind::Fix => "fix",
                BoundaryKind::Displace => "displace",
            };
            self.set_ref(&b.target, Need::Nodes, user);
            for (_, f) in &b.components {
                self.time_fn(f);
            }
        }
    }

    fn loads(&mut self) {
        for l in &self.deck.loads {
            let (need, user) = match l.kind {
                LoadKind::Pressure => (Need::Edges, "pressure"),
                LoadKind::Force => (Need::Nodes, "force"),
            };
            self.set_ref(&l.target, need, user);
            for (_, f) in &l.values {
                self.time_fn(f);
            }
        }
    }

    fn time_fn(&mut self, f: &Spanned<TimeFn>) {
        match &f.value {
            TimeFn::Ramp {
                window: Some([t0, t1]),
                ..
            } if t1.value <= t0.value => {
                self.err(Diagnostic::error(
                    "the ramp's time window is empty",
                    t0.span.to(t1.span),
                    format!("t1 = {} <= t0 = {}", num(t1.value), num(t0.value)),
                ));
            }
            TimeFn::Table(points) => {
                for w in points.windows(2) {
                    if w[1].value.0 <= w[0].value.0 {
                        self.err(Diagnostic::error(
                            "table times must be strictly increasing",
                            w[1].span,
                            format!("t = {} after t = {}", num(w[1].value.0), num(w[0].value.0)),
                        ));
                        return;
                    }
                }
            }
            _ => {}
        }
    }

    // ------------------------------------------------------------ steps
    fn steps(&mut self) {
        let deck = self.deck;
        if deck.steps.is_empty()
            && !deck.has_broken("step")
            && !deck.broken.iter().any(|b| b.keyword.is_empty())
        {
            self.err(
                Diagnostic::error(
                    "the deck has no `step`",
                    Span::new(0, 0),
                    "expected a `step`",
                )
                .with_help("add e.g. `step load { time = 0 .. 1  increments = 10 }`"),
            );
        }
        self.duplicates(deck.steps.iter().filter_map(|s| s.name.as_ref()), "step");
        let mut previous: Option<(String, f64)> = None;
        for (i, s) in deck.steps.iter().enumerate() {
            let label = step_label(s, i);
            if let Some(t) = &s.time {
                let [t0, t1] = &t.value;
                if t1.value <= t0.value {
                    self.err(
                        Diagnostic::error(
                            format!("empty time range in {label}"),
                            t.span,
                            format!("{} .. {} is empty", num(t0.value), num(t1.value)),
                        )
                        .with_help("the end time must be larger than the start time"),
                    );
                }
                if let Some((prev, end)) = &previous {
                    let tol = 1e-12 * end.abs().max(1.0);
                    if t0.value < end - tol {
                        self.err(
                            Diagnostic::error(
                                format!("{label} starts at {} before {prev} ends", num(t0.value)),
                                t0.span,
                                format!("{prev} ends at {}", num(*end)),
                            )
                            .with_help(format!(
                                "steps follow each other in time: start this one at {}",
                                num(*end)
                            )),
                        );
                    } else if t0.value > end + tol {
                        self.err(
                            Diagnostic::error(
                                format!("{label} leaves a gap after {prev}"),
                                t0.span,
                                format!("{prev} ends at {}", num(*end)),
                            )
                            .with_help(format!(
                                "steps follow each other in time: start this one at {}",
                                num(*end)
                            )),
                        );
                    }
                }
                previous = Some((label.clone(), t1.value));
            }
            self.at_least(&s.increments, 1, "increments");
            if let Some(m) = s
                .min_increment
                .as_ref()
                .filter(|m| !(m.value > 0.0 && m.value <= 1.0))
            {
                self.err(
                    Diagnostic::error("`min_increment` must lie in (0, 1]", m.span, format!("min_increment = {}", num(m.value)))
                        .with_help("it is the smallest cutback increment as a fraction of the initial increment, e.g. 1e-3"),
                );
            }
            if let Some(n) = &s.newton {
                self.must_be_positive(&n.tol, "tol");
                self.must_be_positive(&n.tol_displacement, "tol_displacement");
                self.at_least(&n.max_iter, 1, "max_iter");
            }
        }
    }

    // ------------------------------------------------------------ output
    fn output(&mut self) {
        let deck = self.deck;
        for extra in deck.outputs.iter().skip(1) {
            let line = self.line(deck.outputs[0].keyword);
            self.err(
                Diagnostic::error(
                    "more than one `output` block",
                    extra.keyword,
                    "second `output` block",
                )
                .with_help(format!("the first one is on line {line}; merge them")),
            );
        }
        let Some(o) = deck.outputs.first() else {
            return;
        };
        self.at_least(&o.every, 1, "every");
        if let Some(fields) = &o.fields {
            for (i, f) in fields.value.iter().enumerate() {
                if fields.value[..i].iter().any(|g| g.value == f.value) {
                    self.err(Diagnostic::warning(
                        "output field listed twice",
                        f.span,
                        "already listed",
                    ));
                }
            }
        }
        let pairs: Vec<String> = deck
            .contacts
            .iter()
            .map(|c| format!("{} -> {}", c.target, c.tool.name))
            .collect();
        for h in o.history.iter().flatten() {
            match &h.value {
                History::Reaction(r) => {
                    self.set_ref(r, Need::Nodes, "reaction");
                }
                History::Displacement(r) => {
                    self.set_ref(r, Need::Nodes, "displacement");
                }
                History::ContactForce(r, tool) => {
                    let key = format!("{r} -> {}", tool.name);
                    if !pairs.contains(&key) && !deck.has_broken("contact") {
                        self.err(
                            Diagnostic::error(
                                format!("no contact pair `{key}`"),
                                h.span,
                                "not a contact pair of this deck",
                            )
                            .with_help(
                                did_you_mean(&key, &pairs).unwrap_or_else(|| {
                                    if pairs.is_empty() {
                                        "the deck has no contact pairs".to_string()
                                    } else {
                                        format!(
                                            "the contact pairs are {}",
                                            crate::suggest::one_of(&pairs)
                                        )
                                    }
                                }),
                            ),
                        );
                    }
                }
            }
        }
    }
}

/// "step `name`" or "step 2" for unnamed steps.
pub fn step_label(s: &Step, index: usize) -> String {
    match &s.name {
        Some(n) => format!("step `{}`", n.name),
        None => format!("step {}", index + 1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse::parse;

    const BASE: &str = "analysis { dimension = plane_strain }\n\
        material steel { elastic { E = 210e3  nu = 0.3 } }\n\
        body block { mesh = rectangle { origin = (0, 0) size = (2, 1) divisions = (4, 2) } material = steel }\n\
        fix block.bottom { ux uy }\n\
        step load { time = 0 .. 1  increments = 2 }\n";

    fn messages(extra: &str) -> Vec<String> {
        let text = format!("{BASE}{extra}");
        let (deck, d) = parse(&text);
        assert!(d.is_empty(), "{d:?}");
        validate(&deck, &text)
            .into_iter()
            .map(|d| d.message)
            .collect()
    }

    /// Messages of a deck with one body `b` of material `m` (given in full).
    fn material_messages(dim: &str, material: &str, body_extra: &str) -> Vec<String> {
        let text = format!(
            "analysis {{ dimension = {dim} }}\nmaterial m {{ {material} }}\n\
             body b {{ mesh = rectangle {{ origin = (0, 0) size = (2, 1) divisions = (4, 2) }} \
             material = m {body_extra} }}\nfix b.bottom {{ ux uy }}\n\
             step load {{ time = 0 .. 1  increments = 2 }}\n"
        );
        let (deck, d) = parse(&text);
        assert!(d.is_empty(), "{d:?}");
        validate(&deck, &text)
            .into_iter()
            .map(|d| d.message)
            .collect()
    }

    #[test]
    fn plastic_and_finite_strain_decks_validate() {
        let ok = [
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 hardening = linear { H = 1000 } }", ""),
            ("axisymmetric", "elastic { E = 200e3 nu = 0.3 } plastic { hardening = swift { K = 500 eps0 = 0.01 n = 0.2 } }", "kinematics = finite"),
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 200 hardening = voce { sigma_inf = 300 delta = 5 } } viscoplastic { eta = 10 }", "kinematics = finite"),
            ("plane_strain", "neo_hookean { E = 10 nu = 0.45 }", "kinematics = finite"),
            ("plane_strain", "elastic { E = 200e3 nu = 0.3 } plastic { yield = 250 }", ""),
        ];
        for (dim, m, b) in ok {
            assert!(
                material_messages(dim, m, b).is_empty(),
                "{m}: {:?}",
                material_messages(dim, m, b)
            );
        }
    }

    #[test]
    fn unsupported_or_inconsistent_plasticity_is_explained() {
        let el = "elastic { E = 200e3 nu = 0.3 }";
        let cases = [
            ("plane_stress", format!("{el} plastic {{ yield = 250 }}"), "", "plasticity in plane stress is not supported yet"),
            ("plane_stress", el.to_string(), "kinematics = finite", "finite strain in plane stress is not supported yet"),
            ("plane_strain", "neo_hookean { E = 10 nu = 0.4 }".to_string(), "", "material `m` is Neo-Hookean, a finite-strain law: body `b` needs `kinematics = finite`"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = swift {{ K = 500 eps0 = 0.01 n = 0.2 }} }}"), "", "`yield` is not used with Swift hardening"),
            ("plane_strain", format!("{el} plastic {{ hardening = linear {{ H = 1 }} }}"), "", "missing `yield` in the `plastic` block"),
            ("plane_strain", format!("{el} viscoplastic {{ eta = 1 }}"), "", "`viscoplastic` needs a `plastic` block (the static yield stress and hardening)"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = voce {{ sigma_inf = 100 delta = 1 }} }}"), "", "Voce sigma_inf must be at least the yield stress"),
            ("plane_strain", format!("{el} plastic {{ yield = 250 hardening = swift {{ K = 5 eps0 = 0.01 n = 2 }} }}"), "", "`yield` is not used with Swift hardening"),
        ];
        for (dim, m, b, expected) in cases {
            let got = material_messages(dim, &m, b);
            assert!(got.iter().any(|g| g == expected), "{m}: {got:?}");
        }
        let got = material_messages(
            "plane_strain",
            &format!("{el} plastic {{ hardening = swift {{ K = 5 eps0 = 0.01 n = 2 }} }}"),
            "",
        );
        assert_eq!(got, ["Swift n must lie in [0, 1]"]);
    }

    #[test]
    fn base_deck_is_clean() {
        assert!(messages("").is_empty());
    }

    #[test]
    fn out_of_range_material_values() {
        let text = "analysis { dimension = plane_strain }\nmaterial m { elastic { E = 0 nu = 0.5 } }\nbody b { mesh = rectangle { size = (1, 1) divisions = (1, 1) } material = m }\nstep { time = 0 .. 1 }";
        let (deck, _) = parse(text);
        let m: Vec<String> = validate(&deck, text)
            .into_iter()
            .map(|d| d.message)
            .collect();
        assert_eq!(
            m,
            [
                "Young's modulus E must be positive",
                "Poisson's ratio nu must lie in (-1, 0.5)"
            ]
        );
    }

    #[test]
    fn unknown_names_with_suggestions() {
        let m = messages("set s = blok.nodes(x = 0)\ndisplace block.tpo { uy = -1 }\ncontact block.top -> punh { method = penalty { stiffness = 1 } }\ntool punch = circle { center = (0, 2) radius = 1 }");
        assert_eq!(
            m,
            [
                "unknown body `blok`",
                "unknown tool `punh`",
                "body `block` has no set `tpo`"
            ]
        );
    }

    #[test]
    fn edges_needed_for_pressure_and_contact() {
        let m = messages("pressure block.nodes(y = 1) { p = 1 }\npressure block.corner_tl { p = 1 }\npressure block.edges(y = 1) { p = 1 }");
        assert_eq!(
            m,
            [
                "`pressure` needs boundary edges, but `block.nodes(y = 1)` is a set of nodes",
                "`pressure` needs boundary edges, but `block.corner_tl` is a set of nodes"
            ]
        );
    }

    #[test]
    fn step_times_must_be_contiguous() {
        let m = messages("step b { time = 0.5 .. 2 }\nstep c { time = 3 .. 3 }");
        assert_eq!(
            m,
            [
                "step `b` starts at 0.5 before step `load` ends",
                "empty time range in step `c`",
                "step `c` leaves a gap after step `b`"
            ]
        );
    }

    #[test]
    fn deck_sets_are_known_to_later_references() {
        let m = messages(
            "set clamp = block.edges(y = 0)\npressure block.clamp { p = 1 }\nset clamp = block.top",
        );
        assert_eq!(m, ["set `block.clamp` is defined twice"]);
    }

    #[test]
    fn annulus_divisions_must_span_less_than_half_a_turn() {
        let m = messages("body ring { mesh = annulus { center = (0, 0) inner = 1 outer = 2 radial = 1 circumferential = 2 } material = steel }");
        assert_eq!(
            m,
            [
                "circumferential divisions must be at least 3",
                "each circumferential division must span less than 180 degrees"
            ]
        );
    }

    #[test]
    fn nurbs_knot_multiplicity_is_bounded_by_the_degree() {
        let m = messages("tool c = nurbs { degree = 1 points = [(0,0), (1,1), (2,0), (3, 0)] knots = [0, 0, 0.5, 0.5, 1, 1] }\ncontact block.top -> c { method = penalty { stiffness = 1 } }");
        assert_eq!(m, ["knot 0.5 is repeated 2 times"]);
    }

    #[test]
    fn nurbs_knots_are_checked() {
        let m = messages("tool c = nurbs { degree = 2 points = [(0,0), (1,1), (2,0)] weights = [1, -1, 1] knots = [0, 0, 1, 1] }\ncontact block.top -> c { method = penalty { stiffness = 1 } }");
        assert_eq!(
            m,
            [
                "NURBS weights must be positive",
                "the knot vector needs 6 knots (control points + degree + 1)"
            ]
        );
    }
}
