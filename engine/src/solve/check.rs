//! Checks of a [`Model`] before solving: every index in range, every
//! parameter usable, every body held. Errors are user-facing sentences.

use crate::model::{AnalysisKind, HistoryRequest, Load, Model};

/// The valid components in words, by dimension (2, 3).
const COMPONENTS: [&str; 2] = ["0 (x) or 1 (y)", "0 (x), 1 (y) or 2 (z)"];

/// Returns every problem found in `model` (empty when it can be solved).
pub fn check_model<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut errors = Vec::new();
    let nn = model.mesh.nodes.len();
    let nc = model.mesh.cells.len();
    if nn == 0 || nc == 0 {
        errors.push("the model has no mesh (no nodes or no cells)".to_string());
    }
    if let Some(n) = model
        .mesh
        .nodes
        .iter()
        .position(|p| !p.iter().all(|x| x.is_finite()))
    {
        errors.push(format!("node {n} has a non-finite coordinate"));
    }
    let has_thickness = matches!(
        model.analysis.kind,
        AnalysisKind::PlaneStrain | AnalysisKind::PlaneStress
    );
    let thickness_ok = model.analysis.thickness.is_finite() && model.analysis.thickness > 0.0;
    if has_thickness && !thickness_ok {
        errors.push(format!(
            "thickness must be > 0 (got {})",
            model.analysis.thickness
        ));
    }
    errors.extend(super::free_tool::refusals(model));
    errors.extend(super::rigid_body::refusals(model));
    for d in &model.discrete {
        let (label, nodes, values) = match d {
            crate::model::Discrete::Ground {
                label,
                nodes,
                stiffness,
                damping,
            } => (
                label,
                nodes,
                vec![("stiffness", *stiffness), ("damping", *damping)],
            ),
            crate::model::Discrete::Link {
                label,
                pairs,
                stiffness,
                damping,
                release_at,
            } => {
                if release_at.is_some() && *damping != 0.0 {
                    errors.push(format!(
                        "{label}: a released link carries no dashpot (damping = {damping})"
                    ));
                }
                if release_at.is_some_and(|t| t.is_nan()) {
                    errors.push(format!("{label}: the release time is not a number"));
                }
                (
                    label,
                    &pairs.iter().flat_map(|&(a, b)| [a, b]).collect::<Vec<_>>(),
                    vec![("stiffness", *stiffness), ("damping", *damping)],
                )
            }
            crate::model::Discrete::Mass { label, nodes, mass } => {
                (label, nodes, vec![("mass", *mass)])
            }
            crate::model::Discrete::Rigid {
                label,
                nodes,
                stiffness,
                ..
            } => (label, nodes, vec![("stiffness", *stiffness)]),
        };
        if let Some(&n) = nodes.iter().find(|&&n| n >= nn) {
            errors.push(format!("{label}: node {n} is not in the mesh ({nn} nodes)"));
        }
        for (what, x) in values {
            if !(x.is_finite() && x >= 0.0) {
                errors.push(format!("{label}: {what} must be finite and >= 0 (got {x})"));
            }
        }
    }
    for (c, cell) in model.mesh.cells.iter().enumerate() {
        if let Some(&n) = cell.nodes.iter().find(|&&n| n >= nn) {
            errors.push(format!(
                "cell {c} refers to node {n}, but the mesh has {nn} nodes"
            ));
        }
    }
    let mut owner: Vec<Option<usize>> = vec![None; nc];
    for (b, body) in model.bodies.iter().enumerate() {
        if body.material >= model.materials.len() {
            errors.push(format!(
                "body `{}` refers to material {} but there are {}",
                body.name,
                body.material,
                model.materials.len()
            ));
        }
        if body.cells.end > nc || body.nodes.end > nn {
            errors.push(format!(
                "body `{}` has cells {:?} / nodes {:?} outside the mesh ({nc} cells, {nn} nodes)",
                body.name, body.cells, body.nodes
            ));
            continue;
        }
        for c in body.cells.clone() {
            if let Some(other) = owner[c] {
                errors.push(format!(
                    "cell {c} belongs to both bodies `{}` and `{}`",
                    model.bodies[other].name, body.name
                ));
                break;
            }
            owner[c] = Some(b);
        }
    }
    if let Some(c) = owner.iter().position(|o| o.is_none()) {
        errors.push(format!("cell {c} belongs to no body (no material)"));
    }
    for m in &model.materials {
        if let Err(e) = crate::material::build(m, model.analysis.kind) {
            errors.push(e);
        }
    }
    for d in &model.constraints {
        if d.component >= D {
            errors.push(format!(
                "`{}`: component {} is not {}",
                d.label,
                d.component,
                COMPONENTS[D - 2]
            ));
        }
        if let Some(n) = d.nodes.iter().find(|&&n| n >= nn) {
            errors.push(format!(
                "`{}` refers to node {n}, the mesh has {nn} nodes",
                d.label
            ));
        }
    }
    for l in &model.loads {
        match l {
            Load::NodalForce {
                label,
                nodes,
                component,
                ..
            } => {
                if *component >= D {
                    errors.push(format!(
                        "`{label}`: component {component} is not {}",
                        COMPONENTS[D - 2]
                    ));
                }
                if let Some(n) = nodes.iter().find(|&&n| n >= nn) {
                    errors.push(format!(
                        "`{label}` refers to node {n}, the mesh has {nn} nodes"
                    ));
                }
            }
            Load::Gravity {
                label, component, ..
            } => {
                if *component >= D {
                    errors.push(format!(
                        "`{label}`: component {component} is not {}",
                        COMPONENTS[D - 2]
                    ));
                }
            }
            Load::Pressure { label, edges, .. } => {
                if let Some(e) = edges.iter().find(|e| e[0] >= nn || e[1] >= nn) {
                    errors.push(format!("`{label}` refers to edge {e:?} outside the mesh"));
                }
                if D != 2 {
                    errors.push(format!(
                        "`{label}`: pressure on edges needs a planar model; a solid takes \
                         pressure on faces"
                    ));
                }
            }
            Load::FacetTraction {
                label,
                facets,
                component,
                ..
            } => {
                if *component >= D {
                    errors.push(format!(
                        "`{label}`: component {component} is not {}",
                        COMPONENTS[D - 2]
                    ));
                }
                let sizes: &[usize] = if D == 2 { &[2, 3] } else { &[3, 4, 6, 8, 9] };
                if let Some(f) = facets.iter().find(|f| {
                    f.nodes().iter().any(|&n| n >= nn) || !sizes.contains(&f.nodes().len())
                }) {
                    errors.push(format!(
                        "`{label}` refers to facet {:?}: outside the mesh or not a 2- or 3-node \
                         edge (planar) or a 3-, 4-, 6-, 8- or 9-node face (solid)",
                        f.nodes()
                    ));
                }
            }
            Load::RigidMoment {
                label, spin, axis, ..
            } => {
                let spins = model.discrete.iter().any(
                    |d| matches!(d, crate::model::Discrete::Rigid { spin: s, .. } if s == spin),
                );
                if D != 3 || !spins {
                    errors.push(format!(
                        "`{label}`: a moment needs the spin node of a 3D rigid body (node {spin})"
                    ));
                }
                let n = axis.iter().map(|x| x * x).sum::<f64>().sqrt();
                if (n - 1.0).abs().is_nan() || (n - 1.0).abs() >= 1e-12 {
                    errors.push(format!("`{label}`: the moment's axis is not a unit vector"));
                }
            }
            Load::FollowerPressure { label, facets, .. } => {
                let sizes: &[usize] = if D == 2 { &[2, 3] } else { &[3, 4, 6, 8, 9] };
                if let Some(f) = facets.iter().find(|f| {
                    f.nodes().iter().any(|&n| n >= nn) || !sizes.contains(&f.nodes().len())
                }) {
                    errors.push(format!(
                        "`{label}` refers to facet {:?}: outside the mesh or not a 2- or 3-node \
                         edge (planar) or a 3-, 4-, 6-, 8- or 9-node face (solid)",
                        f.nodes()
                    ));
                } else if let Some(b) = facets.iter().find_map(|f| {
                    model.bodies.iter().find(|b| {
                        b.nodes.contains(&f.nodes()[0])
                            && b.kinematics != crate::model::Kinematics::Finite
                    })
                }) {
                    errors.push(format!(
                        "`{label}`: a follower pressure acts on the deformed surface, but body \
                         `{}` has small kinematics (its surface does not move in the equations); \
                         give it `kinematics = finite`, or drop `follower = true`",
                        b.name
                    ));
                }
            }
            Load::FacetPressure { label, facets, .. } => {
                if let Some(f) = facets.iter().find(|f| {
                    f.nodes().iter().any(|&n| n >= nn)
                        || !(if D == 2 {
                            &[3][..]
                        } else {
                            &[3, 4, 6, 8, 9][..]
                        })
                        .contains(&f.nodes().len())
                }) {
                    errors.push(format!(
                        "`{label}` refers to face {:?}: outside the mesh or not a 3-, 4-, 6-, 8- \
                         or 9-node face (solid) or a 3-node edge (planar; 2-node edges take \
                         `Load::Pressure`)",
                        f.nodes()
                    ));
                }
            }
        }
    }
    for (p, c) in model.contacts.iter().enumerate() {
        let master_ok = match &c.master {
            crate::model::ContactMaster::Tool(t) if D == 3 => *t < model.surfaces.len(),
            crate::model::ContactMaster::Tool(t) => *t < model.tools.len(),
            crate::model::ContactMaster::Surface {
                body,
                edges,
                faces,
                nodes,
            } => {
                *body < model.bodies.len()
                    && edges
                        .iter()
                        .flatten()
                        .chain(nodes)
                        .chain(faces.iter().flat_map(|f| f.nodes()))
                        .all(|&n| n < nn)
            }
        };
        if c.body >= model.bodies.len() || !master_ok {
            errors.push(format!(
                "contact `{}` refers to a missing body or tool",
                c.name
            ));
        }
        // contact on quadratic faces: rigid tools by the face-integrated
        // penalty or augmented Lagrangian (`contact::face_integrated`);
        // what that does not cover is refused rather than given
        // node-based answers that are wrong (negative corner weights)
        if let Some(why) = quadratic_contact_refusal(model, c) {
            errors.push(format!("contact `{}`: {why}", c.name));
        }
        // heat across a 3D pair of deformable bodies: node-to-facet gives
        // the heat solver no master facet (`thermal::coupling::
        // contact_elements`), so the pair would exchange no heat at all
        let thermal = model
            .thermal
            .as_ref()
            .is_some_and(|t| t.contacts.get(p).is_some_and(Option::is_some));
        if D == 3 && thermal && matches!(c.master, crate::model::ContactMaster::Surface { .. }) {
            errors.push(format!(
                "contact `{}`: thermal contact between two deformable bodies is not available in \
                 3D yet (heat crosses 3D contact against rigid tools only)",
                c.name
            ));
        }
        if c.nodes
            .iter()
            .chain(c.edges.iter().flatten())
            .chain(c.faces.iter().flat_map(|f| f.nodes()))
            .any(|&n| n >= nn)
        {
            errors.push(format!(
                "contact `{}` refers to a node outside the mesh",
                c.name
            ));
        }
    }
    if D == 3 {
        if !model.tools.is_empty() {
            errors.push(
                "planar curve tools cannot be used in a 3D analysis: use surface tools".into(),
            );
        }
        for c in &model.contacts {
            if let crate::model::ContactMaster::Surface { faces, .. } = &c.master {
                // node-to-facet: what the 3D deformable pairs do not have yet
                let mortar = c.formulation == crate::model::ContactFormulation::Mortar;
                let missing = if mortar
                    && (c.strategy != crate::model::ContactStrategy::SinglePass
                        || matches!(
                            c.method,
                            crate::model::ContactMethod::Lagrange {
                                formulation: crate::model::LagrangeFormulation::Doubled
                            }
                        )) {
                    Some(
                        "mortar with a double pass or doubled Lagrange multipliers (mortar is \
                         single pass; its Lagrange multipliers are single, LU)",
                    )
                } else if c.smoothing == crate::model::NormalSmoothing::Nodal {
                    Some("nodal normal smoothing (use Nagata patches)")
                } else if c.friction.is_some()
                    && matches!(c.method, crate::model::ContactMethod::Lagrange { .. })
                {
                    Some(
                        "Lagrange-multiplier friction (use the penalty or the augmented \
                         Lagrangian with friction)",
                    )
                } else if faces.is_empty() {
                    Some("master faces (the master set has no face)")
                } else {
                    None
                };
                if let Some(what) = missing {
                    errors.push(format!(
                        "contact `{}`: 3D contact between deformable bodies (node-to-facet) has \
                         no {what} yet",
                        c.name
                    ));
                }
            }
            if c.faces.is_empty() {
                errors.push(format!("contact `{}`: a 3D pair needs slave faces", c.name));
            }
        }
    } else if !model.surfaces.is_empty() {
        errors.push("surface tools need a 3D analysis".into());
    }
    if model.steps.is_empty() {
        errors.push("the model has no step: nothing to solve".to_string());
    }
    for s in &model.steps {
        let n = &s.newton;
        let mut bad = |what: String| errors.push(format!("step `{}`: {what}", s.name));
        if !(s.t_start.is_finite() && s.t_end.is_finite() && s.t_end > s.t_start) {
            bad(format!(
                "time range {} .. {} must be increasing",
                s.t_start, s.t_end
            ));
        }
        if s.increments == 0 {
            bad("increments must be >= 1".into());
        }
        if !(s.min_fraction > 0.0 && s.min_fraction <= 1.0) {
            bad(format!(
                "min_increment must be in (0, 1] (got {})",
                s.min_fraction
            ));
        }
        if !(n.tol > 0.0 && n.tol_displacement > 0.0) {
            bad(format!(
                "newton tolerances must be > 0 (tol = {}, tol_displacement = {})",
                n.tol, n.tol_displacement
            ));
        }
        if n.max_iter == 0 {
            bad("newton max_iter must be >= 1".into());
        }
        if let Some(c) = n.stabilize.filter(|c| !(c.is_finite() && *c > 0.0)) {
            bad(format!("newton stabilize must be a number > 0 (got {c})"));
        }
    }
    // time functions must give finite values over the analysis
    let mut times: Vec<f64> = model
        .steps
        .iter()
        .flat_map(|s| [s.t_start, s.t_end])
        .collect();
    let functions = model
        .constraints
        .iter()
        .map(|d| (d.label.as_str(), &d.value))
        .chain(model.loads.iter().map(|l| match l {
            Load::NodalForce { label, value, .. }
            | Load::Gravity { label, value, .. }
            | Load::Pressure { label, value, .. }
            | Load::FacetPressure { label, value, .. }
            | Load::FollowerPressure { label, value, .. }
            | Load::FacetTraction { label, value, .. }
            | Load::RigidMoment { label, value, .. } => (label.as_str(), value),
        }));
    for (label, f) in functions {
        times.truncate(2 * model.steps.len());
        if let crate::model::TimeFunction::Table(points) = f {
            times.extend(points.iter().map(|p| p.0));
        }
        if let Some(t) = times.iter().find(|&&t| !f.eval(t).is_finite()) {
            errors.push(format!(
                "`{label}`: its value at time {t} is not a finite number"
            ));
        }
    }
    for h in &model.output.history {
        match h {
            HistoryRequest::Reaction { label, nodes }
            | HistoryRequest::Displacement { label, nodes }
            | HistoryRequest::Roughness { label, nodes, .. } => {
                if nodes.iter().any(|&n| n >= nn) {
                    errors.push(format!(
                        "history `{label}` refers to a node outside the mesh"
                    ));
                }
            }
            HistoryRequest::ContactForce { label, pair } => {
                if *pair >= model.contacts.len() {
                    errors.push(format!(
                        "history `{label}` refers to a missing contact pair"
                    ));
                }
            }
        }
    }
    if errors.is_empty() {
        errors.extend(unheld_bodies(model));
    }
    errors
}

/// Per body: whether its own `fix`/`displace` conditions leave a
/// rigid-body motion free, so that only contact can hold it (the bodies
/// `newton { stabilize }` acts on, see [`super::stabilize`]).
pub fn held_only_by_contact<const D: usize>(model: &Model<D>) -> Vec<bool> {
    let mut constrained = vec![[false; D]; model.mesh.nodes.len()];
    for d in &model.constraints {
        for &n in &d.nodes {
            if let Some(c) = constrained.get_mut(n).and_then(|c| c.get_mut(d.component)) {
                *c = true;
            }
        }
    }
    model
        .bodies
        .iter()
        .map(|body| {
            body.nodes.end <= model.mesh.nodes.len()
                && !free_motions(model, body, &constrained, &[]).is_empty()
        })
        .collect()
}

/// Bodies that nothing holds: their constrained dofs leave a rigid-body
/// motion free (plane: translations x, y and the in-plane rotation;
/// axisymmetric: the translation along the axis; solid: three
/// translations and three rotations), and no chain of contact pairs links
/// them to a support.
///
/// Each constrained dof `(node, c)` constrains the rigid velocity
/// `(a, b, w)` through the row `[1, 0, -y]` (c = 0) or `[0, 1, x]`
/// (c = 1); the motion is held when these rows have full rank.
///
/// A body with a density (or a point mass on every node) in an analysis
/// whose every step is dynamic is held by its inertia; bodies linked by
/// springs between their nodes hold each other.
///
/// Contact holds only once closed, so it is given the benefit of the
/// doubt, but it must lead somewhere and can hold only along its normals:
/// - a frictionless pair against a rigid tool adds, for every slave node,
///   the row of the tool's normal at its closest point (start of the
///   analysis), as if every node were closed: a body still free with all
///   of them (a block on a frictionless flat floor with nothing holding
///   it in x) is reported; a pair with friction may hold every motion;
/// - the bodies linked by node-to-segment pairs (slave and master, either
///   side) form groups, and a group is supported when one of its bodies is
///   held by its own conditions or by a tool as above. A body whose group
///   has no support is reported with its free motions (a body that is only
///   the master of a pair with a held slave is supported through that
///   pair).
fn unheld_bodies<const D: usize>(model: &Model<D>) -> Vec<String> {
    let mut errors = Vec::new();
    let nb = model.bodies.len();
    let mut constrained = vec![[false; D]; model.mesh.nodes.len()];
    for d in &model.constraints {
        for &n in &d.nodes {
            constrained[n][d.component] = true;
        }
    }
    // a spring to the ground holds its node in every direction, and so
    // does a rigid body (its pilot has the bearing or the body's mass)
    for d in &model.discrete {
        if let crate::model::Discrete::Rigid { nodes, .. } = d {
            for &n in nodes {
                if let Some(c) = constrained.get_mut(n) {
                    *c = [true; D];
                }
            }
        }
        if let crate::model::Discrete::Ground {
            nodes, stiffness, ..
        } = d
        {
            for &n in nodes.iter().filter(|_| *stiffness > 0.0) {
                if let Some(c) = constrained.get_mut(n) {
                    *c = [true; D];
                }
            }
        }
    }
    // in an analysis whose every step is dynamic, the mass of a body with
    // a density holds its rigid-body motions (the tangent has M / (beta
    // dt^2) on its diagonal): two bars flying at each other are solvable
    // (and so do point masses on every node of a massless body)
    let inertial = !model.steps.is_empty() && model.steps.iter().all(|s| s.dynamic.is_some());
    let mut point_mass = vec![false; model.mesh.nodes.len()];
    for d in &model.discrete {
        if let crate::model::Discrete::Mass { nodes, mass, .. } = d {
            for &n in nodes.iter().filter(|_| *mass > 0.0) {
                if let Some(p) = point_mass.get_mut(n) {
                    *p = true;
                }
            }
        }
    }
    let free: Vec<Vec<&str>> = model
        .bodies
        .iter()
        .map(|body| {
            let rho = model
                .materials
                .get(body.material)
                .map_or(0.0, |m| m.density);
            let lumped = body.nodes.clone().all(|n| point_mass[n]);
            if inertial && (rho > 0.0 || lumped) {
                Vec::new()
            } else {
                free_motions(model, body, &constrained, &[])
            }
        })
        .collect();
    // groups of bodies linked by contact pairs (union-find)
    let mut parent: Vec<usize> = (0..nb).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    // normals of the rigid tools at the slave nodes; friction may hold all
    let mut tool_rows: Vec<Vec<([f64; 2], [f64; 2])>> = vec![Vec::new(); nb];
    let mut tool_friction = vec![false; nb];
    let mut on_tool = vec![false; nb];
    for c in &model.contacts {
        match &c.master {
            crate::model::ContactMaster::Tool(t) => {
                on_tool[c.body] = true;
                if c.friction.is_some_and(|f| f.mu > 0.0) {
                    tool_friction[c.body] = true;
                } else {
                    tool_rows[c.body].extend(tool_normals(model, *t, &c.nodes));
                }
            }
            crate::model::ContactMaster::Surface { body, .. } => {
                let (a, b) = (root(&mut parent, c.body), root(&mut parent, *body));
                parent[a] = b;
            }
        }
    }
    // bodies linked by springs between their nodes hold each other
    for d in &model.discrete {
        if let crate::model::Discrete::Link {
            pairs, stiffness, ..
        } = d
        {
            if *stiffness <= 0.0 {
                continue;
            }
            for &(a, b) in pairs {
                let owner = |n: usize| model.bodies.iter().position(|x| x.nodes.contains(&n));
                if let (Some(x), Some(y)) = (owner(a), owner(b)) {
                    let (x, y) = (root(&mut parent, x), root(&mut parent, y));
                    parent[x] = y;
                }
            }
        }
    }
    // free even with every frictionless tool contact closed: certainly singular
    let mut sliding = vec![Vec::new(); nb];
    for (b, body) in model.bodies.iter().enumerate() {
        if D == 2 && on_tool[b] && !tool_friction[b] && !free[b].is_empty() {
            sliding[b] = free_motions(model, body, &constrained, &tool_rows[b]);
        }
    }
    let mut supported = vec![false; nb];
    for b in 0..nb {
        if free[b].is_empty() || (on_tool[b] && sliding[b].is_empty()) {
            let r = root(&mut parent, b);
            supported[r] = true;
        }
    }
    for (b, body) in model.bodies.iter().enumerate() {
        if free[b].is_empty() || supported[root(&mut parent, b)] {
            continue;
        }
        if !sliding[b].is_empty() {
            errors.push(format!(
                "body `{}` is free to {} even with every node of its contact pairs with tools \
                 closed (a frictionless contact holds only along the tool's normals, and its \
                 `fix`/`displace` conditions do not hold the rest: the stiffness matrix would \
                 be singular); constrain that motion (e.g. `fix` one node in x) or give the \
                 pair friction",
                body.name,
                sliding[b].join(" and ")
            ));
            continue;
        }
        let linked: Vec<&str> = (0..nb)
            .filter(|&o| o != b && root(&mut parent, o) == root(&mut parent, b))
            .map(|o| model.bodies[o].name.as_str())
            .collect();
        let contact = if linked.is_empty() {
            "no contact pair involves it".to_string()
        } else {
            format!(
                "its contact pairs link it only to bodies that are not held either ({})",
                linked
                    .iter()
                    .map(|n| format!("`{n}`"))
                    .collect::<Vec<_>>()
                    .join(", ")
            )
        };
        errors.push(format!(
            "body `{}` is free to {} (a rigid-body motion: the stiffness matrix would be \
             singular): its `fix`/`displace` conditions do not hold it and {contact}; \
             constrain e.g. one node in x and y and a second node in the other direction",
            body.name,
            free[b].join(" and ")
        ));
    }
    errors
}

/// The unit normal of tool `tool` at the closest point of each of `nodes`
/// at the start of the analysis: (node position, normal); planar models
/// only (the rigid tools are planar curves).
fn tool_normals<const D: usize>(
    model: &Model<D>,
    tool: usize,
    nodes: &[usize],
) -> Vec<([f64; 2], [f64; 2])> {
    let Some(t) = model.tools.get(tool).filter(|_| D == 2) else {
        return vec![];
    };
    let Ok(shape) = crate::contact::geometry::ToolShape::new(&t.geometry) else {
        return vec![];
    };
    let t0 = model.steps.first().map_or(0.0, |s| s.t_start);
    let placement = crate::contact::motion::Placement::at(&t.motion, t0);
    let mut tests = 0;
    nodes
        .iter()
        .filter_map(|&n| {
            let p = model.mesh.nodes[n];
            let x = [p[0], p[1]];
            let found =
                crate::contact::search::brute_force(&shape, placement.to_reference(x), &mut tests)?;
            Some((x, placement.rotate(found.projection.normal)))
        })
        .collect()
}

/// The rigid-body motions that the `fix`/`displace` conditions of `body`
/// and the contact normals `normals` (position, unit normal; planar) leave
/// free (empty: held; a body without nodes is held).
fn free_motions<const D: usize>(
    model: &Model<D>,
    body: &crate::model::Body,
    constrained: &[[bool; D]],
    normals: &[([f64; 2], [f64; 2])],
) -> Vec<&'static str> {
    if body.nodes.is_empty() {
        return vec![];
    }
    let pts = &model.mesh.nodes[body.nodes.clone()];
    if D == 3 {
        return free_solid_motions(pts, &constrained[body.nodes.clone()]);
    }
    let axi = model.analysis.kind == AnalysisKind::Axisymmetric;
    let k = pts.len() as f64;
    let c = pts
        .iter()
        .fold([0.0, 0.0], |a, p| [a[0] + p[0] / k, a[1] + p[1] / k]);
    let size = pts
        .iter()
        .map(|p| (p[0] - c[0]).hypot(p[1] - c[1]))
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut g = nalgebra::Matrix3::<f64>::zeros();
    for n in body.nodes.clone() {
        let (x, y) = (
            (pts[n - body.nodes.start][0] - c[0]) / size,
            (pts[n - body.nodes.start][1] - c[1]) / size,
        );
        for (comp, row) in [(0, [1.0, 0.0, -y]), (1, [0.0, 1.0, x])] {
            if constrained[n][comp] {
                let r = nalgebra::Vector3::from(row);
                g += r * r.transpose();
            }
        }
    }
    for (p, nrm) in normals {
        let (x, y) = ((p[0] - c[0]) / size, (p[1] - c[1]) / size);
        let r = nalgebra::Vector3::new(nrm[0], nrm[1], nrm[1] * x - nrm[0] * y);
        g += r * r.transpose();
    }
    if axi {
        // a condition adds 1; normals add n_y^2 (a wall parallel to the
        // axis holds nothing along it)
        return if g[(1, 1)] > 1e-8 {
            vec![]
        } else {
            vec!["translate along the axis (y)"]
        };
    }
    let eig = g.symmetric_eigen();
    let max = eig.eigenvalues.max().max(f64::MIN_POSITIVE);
    (0..3)
        .filter(|&i| eig.eigenvalues[i] <= 1e-10 * max)
        .map(|i| {
            let v = eig.eigenvectors.column(i);
            if v[2].abs() > 0.5 {
                "rotate"
            } else if v[0].abs() > v[1].abs() {
                "translate along x"
            } else {
                "translate along y"
            }
        })
        .collect()
}

/// The rigid motions of a solid body (3 translations, 3 rotations) its
/// constrained dofs leave free: the velocity `a + w x (p - c)` has rows
/// `[e_c, (p - c) x e_c]` per constrained component `c`; a null direction
/// of their Gram matrix is named by its largest part.
fn free_solid_motions<const D: usize>(
    pts: &[[f64; D]],
    constrained: &[[bool; D]],
) -> Vec<&'static str> {
    let k = pts.len() as f64;
    let mut c = [0.0; 3];
    for p in pts {
        for (ci, pi) in c.iter_mut().zip(p) {
            *ci += pi / k;
        }
    }
    let size = pts
        .iter()
        .map(|p| (0..D).map(|i| (p[i] - c[i]).powi(2)).sum::<f64>().sqrt())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let mut g = nalgebra::Matrix6::<f64>::zeros();
    for (p, held) in pts.iter().zip(constrained) {
        let x = [
            (p[0] - c[0]) / size,
            (p[1] - c[1]) / size,
            (p[2 % D] - c[2 % D]) / size,
        ];
        let rows = [
            [1.0, 0.0, 0.0, 0.0, x[2], -x[1]],
            [0.0, 1.0, 0.0, -x[2], 0.0, x[0]],
            [0.0, 0.0, 1.0, x[1], -x[0], 0.0],
        ];
        for (comp, row) in rows.iter().enumerate().take(D) {
            if held[comp] {
                let r = nalgebra::Vector6::from(*row);
                g += r * r.transpose();
            }
        }
    }
    let eig = g.symmetric_eigen();
    let max = eig.eigenvalues.max().max(f64::MIN_POSITIVE);
    const NAMES: [&str; 6] = [
        "translate along x",
        "translate along y",
        "translate along z",
        "rotate about x",
        "rotate about y",
        "rotate about z",
    ];
    let mut free: Vec<&str> = (0..6)
        .filter(|&i| eig.eigenvalues[i] <= 1e-10 * max)
        .map(|i| {
            let v = eig.eigenvectors.column(i);
            let j = (0..6)
                .max_by(|&a, &b| v[a].abs().total_cmp(&v[b].abs()))
                .unwrap_or(0);
            NAMES[j]
        })
        .collect();
    free.sort_unstable();
    free.dedup();
    free
}

/// Why pair `c` (one of `model.contacts`) cannot run on quadratic faces,
/// if it cannot: a deformable master or slave with quadratic cells
/// (node-to-segment and mortar are linear), Lagrange-multiplier friction
/// (frictionless Lagrange multipliers are built on a positive-weight
/// basis, `contact::face_integrated::multiplier_basis`), or a nodal penalty (a force per node
/// has no meaning at integration points). Friction is integrated at the
/// points (`contact::face_integrated`), and so is the heat exchange of a
/// thermal pair against a tool (`thermal::contact_faces`).
pub fn quadratic_contact_refusal<const D: usize>(
    model: &Model<D>,
    c: &crate::model::ContactPair,
) -> Option<String> {
    use crate::contact::face_integrated::body_is_quadratic;
    use crate::model::{ContactMaster, ContactMethod, PenaltyKind};
    let body = |b: usize| model.bodies.get(b).map_or("?", |b| b.name.as_str());
    let nodal = matches!(
        c.method,
        ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            ..
        } | ContactMethod::AugmentedLagrange {
            kind: PenaltyKind::Nodal,
            ..
        }
    );
    if let ContactMaster::Surface { body: m, .. } = &c.master {
        let quadratic: Vec<usize> = [c.body, *m]
            .into_iter()
            .filter(|&b| body_is_quadratic(model, b))
            .collect();
        let first = *quadratic.first()?;
        // mortar on quadratic faces (both sides quadratic, or one side
        // linear: mixed orders take the linear side's own shape functions):
        // area penalty / augmented Lagrangian, with or without Coulomb
        // friction (`contact::mortar::friction_quadratic`; mixed orders in
        // 3D only), or frictionless single
        // Lagrange multipliers (2D seg3: `contact::mortar::seg3`; 3D tri6 /
        // quad8 / quad9: `contact::mortar::quadratic3d`)
        let what = if c.formulation != crate::model::ContactFormulation::Mortar {
            "node-to-segment contact between deformable bodies on quadratic faces is not \
             available (its nodal weights are wrong at the corners); use `formulation = \
             mortar`"
        } else if D == 2 && c.friction.is_some() && quadratic.len() == 1 {
            // the friction of `contact::mortar::friction_quadratic` with one
            // side linear is verified in 3D only
            // (`contact_patch_friction_quadratic_3d`: hex8 | hex20, hex20 |
            // hex8)
            "friction with mortar between a linear and a quadratic side is not available in \
             2D (mesh both bodies with quadratic cells, or drop `friction`)"
        } else if c.friction.is_some() && matches!(c.method, ContactMethod::Lagrange { .. }) {
            // Coulomb friction is built for the penalty and the augmented
            // Lagrangian (`contact::mortar::friction_quadratic`)
            "Lagrange-multiplier friction with mortar on quadratic faces is not available (use \
             `penalty` or `augmented_lagrange` with friction, or drop `friction`)"
        } else if nodal {
            "a nodal penalty has no meaning on quadratic faces (the gap is integrated over \
             the faces); use `kind = area`"
        } else {
            return None;
        };
        return Some(format!(
            "body `{}` has quadratic cells: {what}",
            body(first)
        ));
    }
    if !body_is_quadratic(model, c.body) {
        return None;
    }
    let what = match &c.method {
        ContactMethod::Lagrange { .. } if c.friction.is_some() => {
            "Lagrange-multiplier friction is not available on quadratic faces; use \
             `penalty` or `augmented_lagrange` with friction (frictionless Lagrange \
             multipliers are)"
        }
        _ if nodal => {
            "a nodal penalty has no meaning on quadratic faces (the gap is integrated over \
             the faces); use `kind = area`"
        }
        _ => return None,
    };
    Some(format!(
        "body `{}` has quadratic cells: {what}",
        body(c.body)
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{Cell, Mesh};
    use crate::model::*;

    fn square(kind: AnalysisKind, constraints: Vec<(usize, usize)>) -> Model {
        let mut b = crate::testkit::ModelBuilder::new(kind)
            .elastic("m", 1.0, 0.3)
            .body(
                "sq",
                Mesh::new(
                    vec![[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]],
                    vec![Cell::quad(0, 1, 2, 3)],
                ),
                "m",
            );
        for (n, c) in constraints {
            b = b.fix([n], c);
        }
        b.step("s", 1.0, 1).min_fraction(0.5).build()
    }

    #[test]
    fn contact_on_quadratic_faces_is_refused_where_it_is_not_built() {
        let mesh = |kind| {
            let m = Mesh::new(
                vec![[1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            );
            if kind == crate::mesh::CellKind::Quad4 {
                m
            } else {
                crate::mesh::elevate::elevate(&m, kind).unwrap()
            }
        };
        let area = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1.0,
        };
        let nodal = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 1.0,
        };
        let lagrange = ContactMethod::Lagrange {
            formulation: LagrangeFormulation::Single,
        };
        use crate::mesh::CellKind::{Quad4, Quad8};
        for (kind, method, rubs, refused) in [
            (Quad4, lagrange.clone(), false, None),
            (Quad8, area.clone(), true, None),
            (Quad8, lagrange.clone(), false, None),
            (
                Quad8,
                lagrange,
                true,
                Some("Lagrange-multiplier friction is not available on quadratic faces"),
            ),
            (Quad8, nodal, false, Some("a nodal penalty has no meaning")),
        ] {
            let m = crate::testkit::ModelBuilder::new(AnalysisKind::PlaneStrain)
                .elastic("m", 1.0, 0.3)
                .body("sq", mesh(kind), "m")
                .fix([0, 1], 0)
                .fix([0, 1], 1)
                .tool(
                    "floor",
                    ToolGeometry::Plane {
                        point: [0.0, 0.0],
                        normal: [0.0, 1.0],
                    },
                    ToolMotion::fixed(),
                )
                .contact_tool("sq -> floor", "sq", vec![[0, 1]], "floor", method)
                .step("s", 1.0, 1)
                .build();
            let mut m = m;
            // friction is integrated at the faces' points: accepted with
            // the penalty
            if rubs {
                m.contacts[0].friction = Some(crate::model::Friction {
                    mu: 0.3,
                    stiffness: None,
                    first_impact: crate::model::FirstImpact::Intersect,
                    cut_at_impact: false,
                });
            }
            let errors = check_model(&m);
            match refused {
                None => assert!(errors.is_empty(), "{kind:?}: {errors:?}"),
                Some(why) => assert!(
                    errors.len() == 1 && errors[0].contains(why),
                    "{kind:?}: {errors:?}"
                ),
            }
        }
    }

    /// Deformable pairs on quadratic faces: 2D mortar (both sides quadratic
    /// or mixed orders), area penalty, with friction when both sides are
    /// quadratic; the rest (friction with Lagrange multipliers or with
    /// mixed orders among it) refused.
    #[test]
    fn deformable_pairs_on_quadratic_faces_need_mortar_on_both_sides() {
        use crate::mesh::CellKind::{Quad4, Quad8};
        use crate::model::{ContactFormulation as F, Friction};
        let square = |y0: f64, kind| {
            let m = Mesh::new(
                vec![[0.0, y0], [1.0, y0], [1.0, y0 + 1.0], [0.0, y0 + 1.0]],
                vec![Cell::quad(0, 1, 2, 3)],
            );
            if kind == Quad4 {
                m
            } else {
                crate::mesh::elevate::elevate(&m, kind).unwrap()
            }
        };
        let area = ContactMethod::Penalty {
            kind: PenaltyKind::Area,
            stiffness: 1.0,
        };
        let nodal = ContactMethod::Penalty {
            kind: PenaltyKind::Nodal,
            stiffness: 1.0,
        };
        for (lower, formulation, method, rubs, refused) in [
            (Quad8, F::Mortar, area.clone(), false, None),
            (
                Quad8,
                F::NodeToSegment,
                area.clone(),
                false,
                Some("use `formulation = mortar`"),
            ),
            // mixed orders (quad4 | quad8): the linear side's own functions
            (Quad4, F::Mortar, area.clone(), false, None),
            (
                Quad4,
                F::Mortar,
                area.clone(),
                true,
                Some("friction with mortar between a linear and a quadratic side"),
            ),
            (Quad8, F::Mortar, area.clone(), true, None),
            (
                Quad8,
                F::Mortar,
                ContactMethod::Lagrange {
                    formulation: LagrangeFormulation::Single,
                },
                true,
                Some("Lagrange-multiplier friction with mortar on quadratic faces"),
            ),
            (
                Quad8,
                F::Mortar,
                nodal,
                false,
                Some("a nodal penalty has no meaning"),
            ),
        ] {
            let b = crate::testkit::ModelBuilder::new(AnalysisKind::PlaneStrain)
                .elastic("m", 1.0, 0.3)
                .body("low", square(0.0, lower), "m")
                .body("up", square(1.0, Quad8), "m");
            let n0 = b.model().bodies[1].nodes.start;
            let (low, up) = (vec![0, 1], vec![n0 + 2, n0 + 3]);
            let mut m = b
                .fix(low.clone(), 0)
                .fix(low, 1)
                .fix(up.clone(), 0)
                .fix(up, 1)
                .contact_surface(
                    "up -> low",
                    ("up", vec![[n0, n0 + 1]]),
                    ("low", vec![[2, 3]]),
                    method,
                )
                .formulation_of_pair(formulation)
                .step("s", 1.0, 1)
                .build();
            if rubs {
                m.contacts[0].friction = Some(Friction {
                    mu: 0.3,
                    stiffness: None,
                    first_impact: crate::model::FirstImpact::Intersect,
                    cut_at_impact: false,
                });
            }
            let errors = check_model(&m);
            match refused {
                None => assert!(errors.is_empty(), "{lower:?} {formulation:?}: {errors:?}"),
                Some(why) => assert!(
                    errors.len() == 1 && errors[0].contains(why),
                    "{lower:?} {formulation:?}: {errors:?}"
                ),
            }
        }
    }

    #[test]
    fn well_held_body_passes() {
        let m = square(AnalysisKind::PlaneStrain, vec![(0, 0), (0, 1), (1, 1)]);
        assert!(check_model(&m).is_empty(), "{:?}", check_model(&m));
    }

    #[test]
    fn rigid_body_modes_are_named() {
        let m = square(AnalysisKind::PlaneStrain, vec![(0, 0), (0, 1)]);
        let e = check_model(&m);
        assert!(e.len() == 1 && e[0].contains("rotate"), "{e:?}");
        let m = square(AnalysisKind::PlaneStress, vec![(0, 0), (3, 0)]);
        let e = check_model(&m);
        assert!(e.len() == 1 && e[0].contains("translate along y"), "{e:?}");
        assert!(!e[0].contains("rotate"), "{e:?}");
    }

    #[test]
    fn axisymmetric_needs_only_an_axial_constraint() {
        let m = square(AnalysisKind::Axisymmetric, vec![(0, 1)]);
        assert!(check_model(&m).is_empty());
        let m = square(AnalysisKind::Axisymmetric, vec![(0, 0), (1, 0)]);
        let e = check_model(&m);
        assert!(e.len() == 1 && e[0].contains("axis"), "{e:?}");
    }

    #[test]
    fn bad_indices_and_settings_are_all_reported() {
        let mut m = square(AnalysisKind::PlaneStrain, vec![(0, 0), (0, 1), (1, 1)]);
        m.constraints[0].nodes = vec![99];
        m.steps[0].increments = 0;
        m.steps[0].newton.max_iter = 0;
        m.bodies[0].material = 3;
        m.constraints[1].value = TimeFunction::Constant(f64::NAN);
        let e = check_model(&m);
        assert!(e.iter().any(|s| s.contains("not a finite number")), "{e:?}");
        assert!(e.iter().any(|s| s.contains("node 99")), "{e:?}");
        assert!(e.iter().any(|s| s.contains("increments")), "{e:?}");
        assert!(e.iter().any(|s| s.contains("max_iter")), "{e:?}");
        assert!(e.iter().any(|s| s.contains("material 3")), "{e:?}");
    }
}
