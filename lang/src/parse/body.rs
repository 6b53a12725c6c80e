//! `body name { mesh = .. material = .. formulation = .. }` and the mesh
//! generators.

use super::fields::Fields;
use super::settings;
use super::values::Diags;
use super::ItemParts;
use crate::ast::syntax::{Block, Value, ValueKind};
use crate::ast::{Body, FormulationKind, Generator, KinematicsKind, MeshDef};
use crate::diagnostics::Diagnostic;
use crate::generators;
use crate::span::{Ident, Spanned};
use crate::suggest::did_you_mean;

/// `kinematics` keywords.
const KINEMATICS: [(&str, KinematicsKind); 2] = [
    ("small", KinematicsKind::Small),
    ("finite", KinematicsKind::Finite),
];

const FORMULATIONS: [(&str, FormulationKind); 2] = [
    ("full", FormulationKind::Full),
    ("selective_reduced", FormulationKind::SelectiveReduced),
];

/// "expected `rectangle { .. }`, .. or `file "part.msh"`", from the registry.
fn mesh_help() -> String {
    let gens: Vec<String> = generators::names()
        .iter()
        .map(|n| format!("`{n} {{ .. }}`"))
        .collect();
    format!("expected {} or `file \"part.msh\"`", gens.join(", "))
}

/// Converts a `body` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Body> {
    let name = item.name?;
    let block = item.block?;
    let mut f = Fields::keyed(
        &block,
        format!("body `{}`", name.name),
        &crate::tables::BODY,
    );
    let thermal = f
        .block("thermal", diags)
        .map(|b| super::thermal::body_block(b, diags));
    let mesh = f.value("mesh", diags).and_then(|v| mesh(v, diags));
    let material = f.value("material", diags).and_then(|v| match &v.kind {
        ValueKind::Path(p) if p.len() == 1 => Some(p[0].clone()),
        _ => {
            diags.push(Diagnostic::error(
                format!("expected a material name, found {}", v.kind.describe()),
                v.span,
                "expected the name of a `material`",
            ));
            None
        }
    });
    let formulation = f.choice("formulation", "formulation", &FORMULATIONS, diags);
    let kinematics = f.choice("kinematics", "kinematics", &KINEMATICS, diags);
    for e in f.take_all(&["element"]) {
        diags.push(
            Diagnostic::error(
                "`element` belongs to the mesh generator",
                e.key.span,
                "not a key of a body",
            )
            .with_help(
                "write it inside the generator block: `mesh = rectangle { .. element = tri3 }`",
            ),
        );
    }
    f.require(
        &mesh,
        "mesh",
        name.span,
        "add e.g. `mesh = rectangle { size = (1, 1)  divisions = (10, 10) }`",
        diags,
    );
    f.require(
        &material,
        "material",
        name.span,
        "add `material = <name of a material>`",
        diags,
    );
    f.finish(diags);
    Some(Body {
        name,
        mesh,
        material,
        formulation,
        kinematics,
        span: item.span,
        thermal,
    })
}

/// `mesh = generator { .. }` or `mesh = file "path"` (also the value of a
/// generator key of type mesh).
pub fn mesh(v: &Value, diags: &mut Diags) -> Option<Spanned<MeshDef>> {
    match &v.kind {
        ValueKind::CtorStr {
            name,
            text,
            text_span,
        } if name.name == "file" => Some(Spanned::new(
            MeshDef::File(Spanned::new(text.clone(), *text_span)),
            v.span,
        )),
        ValueKind::Ctor { name, block } if generators::find(&name.name).is_some() => {
            generator(name, block, diags)
                .map(|g| Spanned::new(MeshDef::Generator(Box::new(g)), v.span))
        }
        ValueKind::Ctor { name, .. } | ValueKind::CtorStr { name, .. } => {
            let mut options = generators::names();
            options.push("file");
            diags.push(
                Diagnostic::error(
                    format!("unknown mesh generator `{}`", name.name),
                    name.span,
                    "not a mesh generator",
                )
                .with_help(did_you_mean(&name.name, &options).unwrap_or_else(mesh_help)),
            );
            None
        }
        ValueKind::Path(p) if p.len() == 1 && generators::find(&p[0].name).is_some() => {
            diags.push(Diagnostic::error(
                format!("the `{}` generator needs its settings", p[0].name),
                v.span,
                format!("expected `{} {{ .. }}`", p[0].name),
            ));
            None
        }
        other => {
            diags.push(
                Diagnostic::error(
                    format!("expected a mesh, found {}", other.describe()),
                    v.span,
                    "expected a mesh generator or a file",
                )
                .with_help(mesh_help()),
            );
            None
        }
    }
}

/// A generator's block, read through its registry entry's keys.
fn generator(name: &Ident, block: &Block, diags: &mut Diags) -> Option<Generator> {
    let def = generators::find(&name.name)?;
    let settings = settings::read(
        block,
        format!("`{}` mesh", name.name),
        def.keys,
        name.span,
        diags,
    );
    Some(Generator {
        name: name.clone(),
        def,
        settings,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::settings::SettingValue;
    use crate::ast::{FormulationKind, Grading, MeshDef};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn rectangle_body_with_grading() {
        let deck = parse_ok(
            "body block {\n  mesh = rectangle { origin = (-4, -4)  size = (8, 4)  divisions = (40, 20)\n grading = (center(4), geometric(0.2))  element = quad4 }\n  material = steel\n  formulation = selective_reduced\n}",
        );
        let b = &deck.bodies[0];
        assert_eq!(b.name.name, "block");
        assert_eq!(b.material.as_ref().unwrap().name, "steel");
        assert_eq!(
            b.formulation.as_ref().unwrap().value,
            FormulationKind::SelectiveReduced
        );
        assert!(b.kinematics.is_none());
        let MeshDef::Generator(g) = &b.mesh.as_ref().unwrap().value else {
            panic!()
        };
        assert_eq!(g.def.name, "rectangle");
        let s = &g.settings;
        assert_eq!(s.choice("element", g.def.keys), Some("quad4"));
        assert_eq!(s.pair("origin", g.def.keys), Some([-4.0, -4.0]));
        assert_eq!(s.pair("size", g.def.keys), Some([8.0, 4.0]));
        assert_eq!(s.integers("divisions"), Some(vec![40, 20]));
        let g = s.gradings("grading", 2);
        assert!(matches!(&g[0], Grading::Center(r) if r.value == 4.0));
        assert!(matches!(&g[1], Grading::Geometric(r) if r.value == 0.2));
    }

    #[test]
    fn disc_annulus_and_file_meshes() {
        let deck = parse_ok(
            "body a { mesh = half_disc { center = (0, 1) radius = 1 radial = 10 circumferential = 40 radial_grading = geometric(0.3) circumferential_grading = center(5) upper = false element = tri3 } material = m }\n\
             body b { mesh = quarter_disc { center = (0, 1) radius = 1 radial = 10 circumferential = 20 upper = true } material = m }\n\
             body c { mesh = annulus { center = (0, 0) inner = 1 outer = 2 start = 0 end = 90 radial = 8 circumferential = 16 radial_grading = uniform } material = m }\n\
             body d { mesh = file \"part.msh\" material = m }",
        );
        assert_eq!(deck.bodies.len(), 4);
        let kinds: Vec<String> = deck
            .bodies
            .iter()
            .map(|b| match &b.mesh.as_ref().unwrap().value {
                MeshDef::Generator(g) => g.name.name.clone(),
                MeshDef::File(f) => format!("file {}", f.value),
            })
            .collect();
        assert_eq!(
            kinds,
            ["half_disc", "quarter_disc", "annulus", "file part.msh"]
        );
        let MeshDef::Generator(g) = &deck.bodies[1].mesh.as_ref().unwrap().value else {
            panic!()
        };
        assert_eq!(g.def.name, "quarter_disc");
        assert_eq!(g.settings.bool("upper", g.def.keys), Some(true));
        // defaults come from the key table
        let MeshDef::Generator(g) = &deck.bodies[2].mesh.as_ref().unwrap().value else {
            panic!()
        };
        assert_eq!(g.settings.choice("element", g.def.keys), Some("quad4"));
        assert!(matches!(
            g.settings.get("end").unwrap().value.value,
            SettingValue::Number(x) if x == 90.0
        ));
    }

    #[test]
    fn body_mistakes() {
        assert_eq!(
            parse_messages("body b { mesh = rectangel { } }"),
            [
                "unknown mesh generator `rectangel`",
                "missing `material` in the body `b`"
            ]
        );
        assert_eq!(
            parse_messages(
                "body b { mesh = rectangle { size = (1, 1) divisons = (2, 2) } material = m }"
            ),
            ["unknown key `divisons` in the `rectangle` mesh"]
        );
        assert_eq!(
            parse_messages(
                "body b { mesh = rectangle { size = (1, 1, 1) divisions = (2, 2) } material = m }"
            ),
            ["expected a pair `(a, b)`, found a tuple of 3"]
        );
    }
}
