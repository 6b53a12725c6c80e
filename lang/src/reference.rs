//! The keyword reference: every item of the deck language with its blocks
//! and keys, printed from the tables the parser reads
//! ([`crate::tables`], [`crate::generators`], [`crate::units`]).
//! `ctc doc [item]` prints one item or the index; `docs/DECK.md` is
//! [`markdown`] (a test fails when the committed file is stale).

use crate::generators::{GeneratorDef, REGISTRY};
use crate::keys::{Default, Key};
use crate::tables;
use std::fmt::Write as _;

/// One item of the language.
pub struct Item {
    /// Keyword (`ctc doc <name>`).
    pub name: &'static str,
    /// How it is written.
    pub syntax: &'static str,
    /// What it is.
    pub doc: &'static str,
    /// Its blocks: (path, table).
    pub blocks: &'static [(&'static str, &'static [Key])],
    /// An example.
    pub example: &'static str,
}

/// Every item, in the order of a deck.
pub static ITEMS: &[Item] = &[
    Item {
        name: "let",
        syntax: "let NAME = EXPRESSION",
        doc: "A parameter: a number (with an optional unit) usable in every later number. \
              Expressions: + - * / ^, parentheses, sqrt sin cos tan abs exp ln min max, pi.",
        blocks: &[],
        example: "let E = 210 GPa\nlet R = 8\nmaterial steel { elastic { E = E  nu = 0.3 } }",
    },
    Item {
        name: "include",
        syntax: "include \"FILE.ctc\"",
        doc: "Reads the items of another deck file here (path relative to the including \
              file; a line of its own, outside any block). Cycles and missing files are errors \
              naming the include chain.",
        blocks: &[],
        example: "include \"materials.ctc\"",
    },
    Item {
        name: "analysis",
        syntax: "analysis { .. }",
        doc: "The kind of analysis and the unit system (exactly one per deck).",
        blocks: &[("analysis", &tables::ANALYSIS)],
        example: "analysis { dimension = axisymmetric  units = mm_N_s }",
    },
    Item {
        name: "material",
        syntax: "material NAME { .. }",
        doc: "A constitutive law: `elastic` or `neo_hookean`, optionally `plastic` and \
              `viscoplastic`, and `thermal` properties.",
        blocks: &[
            ("material", &tables::MATERIAL),
            ("elastic / neo_hookean", &tables::ELASTIC),
            ("neo_hookean (moduli)", &tables::NEO_HOOKEAN_MODULI),
            ("plastic", &tables::PLASTIC),
            ("hardening = linear", &tables::LINEAR_HARDENING),
            ("hardening = swift", &tables::SWIFT_HARDENING),
            ("hardening = voce", &tables::VOCE_HARDENING),
            ("hardening = johnson_cook", &tables::JOHNSON_COOK_HARDENING),
            ("viscoplastic", &tables::VISCOPLASTIC),
            ("norton_hoff", &tables::NORTON_HOFF),
            ("thermal", &tables::MATERIAL_THERMAL),
        ],
        example: "material steel {\n  elastic { E = 210e3  nu = 0.3 }\n  plastic { yield = 250  hardening = linear { H = 1000 } }\n}",
    },
    Item {
        name: "body",
        syntax: "body NAME { .. }",
        doc: "A deformable body: its mesh (a generator, see `ctc doc mesh`, or a gmsh file) \
              and material. Every body has the sets `boundary` (edges) and `all` (nodes).",
        blocks: &[("body", &tables::BODY), ("thermal", &tables::BODY_THERMAL)],
        example: "body block {\n  mesh = rectangle { size = (2, 1)  divisions = (20, 10) }\n  material = steel\n}",
    },
    Item {
        name: "set",
        syntax: "set NAME = BODY.SELECTION",
        doc: "A named set of a body (`BODY.NAME` afterwards): a set, a geometric selection \
              `BODY.nodes(x = ..)` (or `y = ..`, and `z = ..` in 3d), \
              `BODY.nodes(box((x0, y0), (x1, y1)))` (3d: `box((x0, y0, z0), (x1, y1, z1))`), \
              `BODY.node(near(x, y))` (3d: `near(x, y, z)`), `BODY.edges(..)` (planar: boundary \
              edges with both nodes selected), `BODY.faces(..)` (3d: boundary faces with every \
              node selected), a quoted name `BODY.\"Hole Edge\"` (gmsh groups with spaces), or a \
              union and difference `a.top + a.side - a.corner_tl` (left to right; edges or faces \
              when every term has them). Coordinates match within 1e-6 x the diagonal of the \
              body; a selection that selects nothing is an error.",
        blocks: &[],
        example: "set clamp = block.bottom + block.left\nset hole = lug.\"Hole Edge\"\nset top = brick.faces(z = 1)",
    },
    Item {
        name: "tool",
        syntax: "tool NAME = KIND { .. }",
        doc: "A rigid analytical tool with an optional rigid `motion`: in planar analyses a \
              curve (plane, polyline, arc, circle or nurbs), in `3d` a surface (plane with \
              `(x, y, z)` points, sphere, cylinder, cone or torus, the CAD faces of an \
              IGES file, or the triangles of an STL file).",
        blocks: &[
            ("plane", &tables::PLANE),
            ("polyline", &tables::POLYLINE),
            ("arc", &tables::ARC),
            ("circle", &tables::CIRCLE),
            ("nurbs", &tables::NURBS),
            ("plane (3d)", &tables::PLANE_3D),
            ("sphere", &tables::SPHERE),
            ("cylinder", &tables::CYLINDER),
            ("cone", &tables::CONE),
            ("torus", &tables::TORUS),
            ("iges", &tables::IGES),
            ("stl", &tables::STL),
            ("motion", &tables::MOTION),
        ],
        example: "tool punch = circle { center = (0, 1)  radius = 1\n  motion { uy = ramp(0, -0.1) } }",
    },
    Item {
        name: "contact",
        syntax: "contact BODY.SET -> TOOL { .. }   or   contact BODY.SET -> BODY.SET { .. }",
        doc: "A contact pair: the slave surface (boundary edges; faces in 3d) against a rigid \
              tool or a deformable master surface (node-to-segment; 3d: node-to-facet). The \
              same surface on both sides is self contact: each node against the surface's \
              facets except its own patch, both directions at once with half the tributary \
              areas (the reported pressure is the interface pressure; in 3d only the facets \
              facing it; penalty or augmented Lagrangian, with or without friction). \
              In 3d a tool is a surface. The gap is positive when open; the pressure is \
              positive in compression.",
        blocks: &[
            ("contact", &tables::CONTACT),
            ("method = penalty", &tables::PENALTY),
            ("method = lagrange", &tables::LAGRANGE),
            ("method = augmented_lagrange", &tables::AUGMENTED_LAGRANGE),
            ("friction = coulomb", &tables::COULOMB),
            ("thermal", &tables::CONTACT_THERMAL),
            ("thermal.conductance = power", &tables::POWER_CONDUCTANCE),
        ],
        example: "contact disc.arc -> floor {\n  method = penalty { kind = area  stiffness = 2e4 }\n  friction = coulomb { mu = 0.1 }\n}",
    },
    Item {
        name: "fix",
        syntax: "fix SET { ux uy }",
        doc: "Holds displacement components at zero (`ux`: x or r, `uy`: y or z).",
        blocks: &[],
        example: "fix block.bottom { ux uy }",
    },
    Item {
        name: "displace",
        syntax: "displace SET { ux = F(t)  uy = F(t) }",
        doc: "Prescribes displacement components as time functions: a number, `constant(v)`, \
              `ramp(v0, v1)` (over the whole analysis), `ramp(v0, v1, t0, t1)`, \
              `table((t, v), ..)`.",
        blocks: &[],
        example: "displace block.top { uy = ramp(0, -0.05) }",
    },
    Item {
        name: "pressure",
        syntax: "pressure EDGES { p = F(t)  follower = BOOL  control = strain_rate { .. } }",
        doc: "A pressure on boundary edges (3d: faces), positive pushing into the body, along \
              the normal of the reference configuration (consistent load). `follower = true`: \
              on the deformed surface instead (it turns and stretches with it, with its load \
              stiffness; the bodies need `kinematics = finite`), as a gas pressure in blow \
              forming or hydroforming. `control = strain_rate { target = .. }` (follower \
              pressures): the pressure-cycle controller of superplastic forming; after every \
              increment the pressure is scaled by `(target / rate)^exponent` (bounded by \
              `max_change`, and by `max_pressure` on the applied value), `rate` the largest equivalent plastic strain rate of the pressed \
              body (or, with `at = (x, y)`, of the cells around the body's node nearest to that \
              point: the pole of a bulge), and follows the trend of the last two increments; \
              history.csv gets the applied pressure and the rate, and `ctc run` plots them \
              (pressure_cycle.svg, controlled_rate.svg).",
        blocks: &[("control = strain_rate", &tables::RATE_CONTROL)],
        example: "pressure pipe.inner { p = ramp(0, 100) }",
    },
    Item {
        name: "traction",
        syntax: "traction EDGES { tx = F(t)  ty = F(t)  tz = F(t) }",
        doc: "A dead traction on boundary edges (3d: faces): force per unit reference area \
              along the global axes, not following the surface; consistent nodal forces by \
              the face quadrature (planar: per unit thickness times `thickness`; \
              axisymmetric: totals over 2 pi). `tz` in 3d only.",
        blocks: &[],
        example: "traction block.faces(z = 1) { tx = ramp(0, 5) }",
    },
    Item {
        name: "force",
        syntax: "force NODES { fx = F(t)  fy = F(t) }",
        doc: "A force on each node of a set (axisymmetric: totals over 2 pi).",
        blocks: &[],
        example: "force block.node(near(0, 1)) { fy = -1 }",
    },
    Item {
        name: "gravity",
        syntax: "gravity { gx = F(t)  gy = F(t)  gz = F(t) }",
        doc: "Gravity: an acceleration (length/time^2) pulling every body that has a \
              `density` and every `point_mass`, in quasi-static and dynamic steps. Consistent \
              nodal forces `g int rho N_a dV` (the row sums of the consistent mass; \
              axisymmetric: totals over 2 pi) plus `m g` at point masses, in the reference \
              configuration; their work is part of the external work of the energy audit. \
              `gz` in 3d only; several items add up.",
        blocks: &[],
        example: "gravity { gy = -9.81 }",
    },
    Item {
        name: "initial_velocity",
        syntax: "initial_velocity NODES { vx = ..  vy = ..  vz = .. }",
        doc: "The velocity of a node set at the start of the analysis (`body.all` for a whole \
              body), for `dynamic` steps; other nodes start at rest. `vz` in 3d only.",
        blocks: &[],
        example: "initial_velocity bar.all { vx = -5 }",
    },
    Item {
        name: "spring",
        syntax: "spring NODES [-> NODES] { stiffness = ..  damping = .. }",
        doc: "A linear spring and a linear dashpot from each node of a set to the ground, in \
              every direction (force -k u - c v; the dashpot acts in `dynamic` steps), or with \
              `-> NODES` between the nodes of two sets (force -k (u_a - u_b) - c (v_a - v_b) \
              on a, its opposite on b; the i-th node of the first set, in node order, to the \
              i-th of the second, or every node to a single far node). Its energy is part of \
              the internal work of the energy audit, the dashpot's dissipation part of \
              `damping_work`. A spring to the ground holds its nodes; a spring between two \
              bodies lets a held one hold the other.",
        blocks: &[("spring", &crate::tables::SPRING)],
        example: "spring bar.left { stiffness = 1e3  damping = 2 }",
    },
    Item {
        name: "point_mass",
        syntax: "point_mass NODES { mass = .. }",
        doc: "A point mass at each node of a set (`dynamic` steps), added to the bodies' \
              mass (kinetic energy, inertia, initial acceleration).",
        blocks: &[("point_mass", &crate::tables::POINT_MASS)],
        example: "point_mass block.all { mass = 0.25 }",
    },
    Item {
        name: "rigid_body",
        syntax: "rigid_body NODES { center = (x, y[, z])  axis  mass  inertia | inertia_diagonal \
                 inertia_products  rotation | angular_velocity | moment  stiffness  damping  \
                 tie_stiffness }",
        doc: "The nodes of a set move as one rigid body (plane strain / plane stress: 3 dofs; \
              3d: 6 dofs): a pilot node at `center` carries its translation and bearing (a \
              spring and dashpot to the ground), a spin node its rotation (planar: the angle, \
              with the rotary inertia; 3d: the total rotation vector psi, R = exp(psi)); each \
              node is tied to its place `X_c + u_c + R (X - X_c)` at finite rotation by a stiff \
              spring (`tie_stiffness`, a penalty with its exact tangent). Planar, the mass sits \
              on the pilot; 3d, the mass and the inertia tensor are carried by six point masses \
              at body-fixed points tied like the nodes (their dynamics is the body's, \
              gyroscopic terms included). The rotation is prescribed (`rotation` or \
              `angular_velocity`, 3d about `axis`) or free, under `moment` (3d: a moment \
              `moment(t) axis` fixed in space, work-conjugate to the rotation: T(psi)^T m on \
              psi; any number of turns, less than half a turn per increment: past |psi| = pi \
              psi is replaced by the same rotation psi (1 - 2 pi / |psi|)). The kinetic energy and the \
              ties' and bearing's energy are in the energy audit; history.csv has the columns \
              `centre[NODES]_x`, `_y` (`_z`) (the orbit) and `rotation[NODES]_x` (the angle; 3d \
              `_x _y _z` psi, |psi| <= pi for a free body).",
        blocks: &[("rigid_body", &crate::tables::RIGID_BODY)],
        example: "rigid_body disc.inner { center = (0, 0)  mass = 2  inertia = 0.01  \
                  angular_velocity = 100  stiffness = 1e5  tie_stiffness = 1e7 }",
    },
    Item {
        name: "temperature",
        syntax: "temperature SET { value = F(t) }",
        doc: "A prescribed temperature (thermal decks).",
        blocks: &[],
        example: "temperature bar.left { value = 100 }",
    },
    Item {
        name: "heat_flux",
        syntax: "heat_flux EDGES { q = F(t) }",
        doc: "A heat flux into the body through boundary edges (3d: faces), positive heating the body.",
        blocks: &[],
        example: "heat_flux bar.right { q = 1e3 }",
    },
    Item {
        name: "convection",
        syntax: "convection EDGES { h = ..  ambient = F(t) }",
        doc: "Convection to an ambient temperature, film coefficient `h`, through boundary edges (3d: faces).",
        blocks: &[],
        example: "convection bar.top { h = 10  ambient = 20 }",
    },
    Item {
        name: "step",
        syntax: "step [NAME] { .. }",
        doc: "A load step: a time range split into increments (cut back by halving on \
              failure, grown back x1.5), with its Newton settings. Steps follow each other.",
        blocks: &[
            ("step", &tables::STEP),
            ("newton", &tables::NEWTON),
            ("dynamic", &tables::DYNAMIC),
        ],
        example: "step press { time = 0 .. 1  increments = 10  newton { tol = 1e-9 } }",
    },
    Item {
        name: "output",
        syntax: "output { .. }",
        doc: "What is written (at most one block).",
        blocks: &[("output", &tables::OUTPUT)],
        example: "output { fields = [displacement, stress, contact]  history = [reaction(block.bottom)] }",
    },
];

/// The item called `name` (also `mesh` and generator names).
pub fn item(name: &str) -> Option<&'static Item> {
    ITEMS.iter().find(|i| i.name == name)
}

fn cell(s: &str) -> String {
    s.replace('|', "\\|").replace('\n', " ")
}

fn default_text(k: &Key) -> String {
    match (k.required, k.default) {
        (Some(_), _) => "required".into(),
        (None, Default::None) => "-".into(),
        (None, d) => d.to_string(),
    }
}

/// A key table as Markdown.
pub fn table(keys: &[Key]) -> String {
    let mut s = String::from("| key | value | default | range | dimension | meaning |\n");
    s.push_str("| --- | --- | --- | --- | --- | --- |\n");
    for k in keys {
        let _ = writeln!(
            s,
            "| `{}` | {} | {} | {} | {} | {} |",
            k.name,
            cell(&k.ty.describe()),
            cell(&default_text(k)),
            cell(&k.range.to_string()),
            k.dim.describe(),
            cell(k.doc)
        );
    }
    s
}

/// One item as Markdown.
pub fn item_markdown(i: &Item) -> String {
    let mut s = format!("## `{}`\n\n`{}`\n\n{}\n\n", i.name, i.syntax, i.doc);
    for (path, keys) in i.blocks {
        let _ = writeln!(s, "### {path}\n\n{}", table(keys));
    }
    let _ = writeln!(s, "```\n{}\n```\n", i.example);
    s
}

/// One generator as Markdown.
pub fn generator_markdown(g: &GeneratorDef) -> String {
    let mut s = format!(
        "### `{} {{ .. }}`\n\n{}.\n\n{}\n",
        g.name,
        g.doc,
        table(g.keys)
    );
    s.push_str("Sets:");
    for set in g.sets {
        let kind = match set.kind {
            crate::generators::SetKind::Edges => "edges",
            crate::generators::SetKind::Nodes => "nodes",
            crate::generators::SetKind::Faces => "faces",
        };
        let _ = write!(s, " `{}` ({kind}: {})", set.name, set.doc);
        s.push(';');
    }
    s.pop();
    s.push_str(".\n\n");
    s
}

/// The mesh generators section.
pub fn mesh_markdown() -> String {
    let mut s = String::from(
        "## `mesh`\n\n`mesh = GENERATOR { .. }` or `mesh = file \"part.msh\"` (gmsh ASCII 2.2 \
         or 4.1, path relative to the deck; physical groups become sets, quoted when their \
         names have spaces: `lug.\"Hole Edge\"`).\n\n",
    );
    for g in REGISTRY {
        s.push_str(&generator_markdown(g));
    }
    s
}

/// Units, sign conventions, status codes and output fields.
pub fn conventions_markdown() -> String {
    let mut s = String::from("## Units\n\n");
    s.push_str(
        "A number may carry a unit: `210 GPa`, `5 mm`, `1e-3 /s`, `7.8e-9 t/mm^3` (products \
         and quotients of unit names with integer powers). Numbers without a unit are in the \
         deck's unit system; numbers with a unit are converted into it, which needs \
         `analysis { units = .. }`, and must have the dimension of their key (the dimension \
         column of the tables). Mixed dimensions in a sum are errors.\n\n",
    );
    s.push_str("| system | base units |\n| --- | --- |\n");
    for sys in crate::units::SYSTEMS {
        let _ = writeln!(s, "| `{}` | {} |", sys.name, sys.doc);
    }
    s.push_str("\nUnit names: ");
    let names: Vec<String> = crate::units::ATOMS
        .iter()
        .map(|a| format!("`{}`", a.name))
        .collect();
    s.push_str(&names.join(", "));
    s.push_str(".\n\n");
    s.push_str(
        "## Sign conventions\n\n\
         - Cells are counter-clockwise; boundary edges have the body on their left (outward \
           normal `(dy, -dx)/len`).\n\
         - Axisymmetric analyses: x = r, y = z; forces, reactions and contact forces are \
           totals over the full 2 pi.\n\
         - Contact: the gap is positive when open, negative when penetrating; the contact \
           pressure is positive in compression; `force_x, force_y` are the force of the \
           master on the slave node.\n\
         - Friction: the tangent is `t = (n_y, -n_x)`; the tangential force and slip are \
           measured along it.\n\
         - Pressure loads push into the body; time functions are functions of the global \
           analysis time; tool rotations are counter-clockwise, in radians.\n\n\
         ## Status codes\n\n\
         | field | values |\n| --- | --- |\n\
         | `contact_status` (VTU) | -1 not a slave node, 0 open or out of reach, 1 closed |\n\
         | `status` (contact CSV) | 0 open or out of reach, 1 closed |\n\
         | `friction_status` (VTU, contact CSV) | 0 frictionless, 1 stick, 2 slip |\n\
         | `completed` (summary.json) | false when the analysis stopped before the end (the last converged increment is written) |\n\
         | exit code of `ctc run` / `ctc check` | 0 success, 1 deck error or run stopped |\n\n\
         ## Output files\n\n\
         | file | content |\n| --- | --- |\n\
         | `results.pvd` | the increments written, with their times; the bodies are part 0, rigid tool `k` part `k + 1` |\n\
         | `tool_<k>_NNNN.vtu` | rigid tool `k` at its current position at an increment: line cells walked with the free side on their left, cell data free_side (unit normal into free space; planes are cut to the bodies' extent); field data TIME, CYCLE, TOOL. Points are current coordinates: warp only the bodies' block by displacement |\n\
         | `inc_NNNN.vtu` | fields at an increment (binary, appended raw zlib, by default; `output { format = ascii }` for text): point data displacement, stress, strain, von_mises, equivalent_plastic_strain, reaction, contact (status, gap, pressure, friction), temperature, velocity and acceleration (dynamic steps); cell data body and the integration-point means of stress, strain, von_mises, equivalent_plastic_strain; field data TIME, CYCLE (increment) |\n\
         | `history.csv` | one row per converged increment: time, history requests (x, y), the friction work of the increment per pair (`friction_work[pair]`: its running sum is summary.json's `friction_work`), the energy audit of dynamic steps (`kinetic_energy` .. `energy_error`: totals since the start), temperatures |\n\
         | `contact_<pair>_<inc>.csv` | slave nodes along the surface: node, x, y, gap, pressure, status, force_x, force_y (+ master_1, master_2, xi; + tangential_force, slip, friction_status, dissipation) |\n\
         | `summary.json` | increments, residual sequences, timings, factorizations, warnings, friction work, heat |\n\
         | `restart.bin` | restart point (`ctc run --restart`) |\n\
         | `progress.sta` | one line per converged increment: step, increment, attempts, Newton iterations, total and step time, dt, closed contact nodes, max penetration, residual; the last line says how the run ended |\n\n\
         Numbers in CSV, PVD and ASCII VTU files are in their shortest round-trip form \
         (`0.1`, `3.5e-300`); times on the increment grid are `t_start + n dt` computed \
         as such (`0.3`, not `0.30000000000000004`). A run into an existing directory \
         first removes the files above left by a previous run (`inc_*.vtu`, \
         `contact_*_*.csv`, ..), and no other file.\n\n",
    );
    s
}

/// The whole reference (`docs/DECK.md`).
pub fn markdown() -> String {
    let mut s = String::from(
        "# The .ctc deck language\n\n\
         <!-- Generated by `ctc doc --markdown` from the parser's key tables \
         (lang/src/tables.rs, lang/src/generators/); do not edit: \
         `cargo test -p ctc-lang --test reference` fails when this file is stale. -->\n\n\
         A deck is a list of items. Blocks hold `key = value`, `key { .. }` or bare `key` \
         entries; `#` starts a comment. `ctc doc ITEM` prints one item.\n\n",
    );
    s.push_str("Items: ");
    let names: Vec<String> = ITEMS.iter().map(|i| format!("`{}`", i.name)).collect();
    s.push_str(&names.join(", "));
    s.push_str(", and `mesh` generators.\n\n");
    for i in ITEMS {
        s.push_str(&item_markdown(i));
        if i.name == "body" {
            s.push_str(&mesh_markdown());
        }
    }
    s.push_str(&conventions_markdown());
    s
}

/// `ctc doc [name]`: the index, one item, `mesh`, a generator, or `units`.
pub fn doc(name: Option<&str>) -> Result<String, String> {
    let Some(name) = name else {
        let mut s = String::from("items (`ctc doc ITEM`):\n");
        for i in ITEMS {
            let _ = writeln!(s, "  {:<12} {}", i.name, i.syntax);
        }
        s.push_str("  mesh         mesh generators (`ctc doc rectangle`, ...)\n");
        s.push_str("  units        unit systems, units, sign conventions, status codes, outputs\n");
        s.push_str("  status       the same (status codes, output files)\n");
        return Ok(s);
    };
    if let Some(i) = item(name) {
        return Ok(item_markdown(i));
    }
    if name == "mesh" {
        return Ok(mesh_markdown());
    }
    if let Some(g) = crate::generators::find(name) {
        return Ok(generator_markdown(g));
    }
    if ["units", "conventions", "status", "outputs"].contains(&name) {
        return Ok(conventions_markdown());
    }
    let mut names: Vec<&str> = ITEMS.iter().map(|i| i.name).collect();
    names.extend(crate::generators::names());
    names.extend(["mesh", "units", "status", "outputs"]);
    Err(format!(
        "no item `{name}`{}",
        crate::suggest::did_you_mean(name, &names).map_or(String::new(), |d| format!("; {d}"))
    ))
}
