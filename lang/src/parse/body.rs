//! `body name { mesh = .. material = .. formulation = .. }` and the mesh
//! generators.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{Block, Value, ValueKind};
use crate::ast::{
    Body, ElementKind, FormulationKind, Generator, GeneratorKind, KinematicsKind, MeshDef,
};
use crate::diagnostics::Diagnostic;
use crate::span::{Ident, Spanned};
use crate::suggest::did_you_mean;

/// Names of the built-in mesh generators.
pub const GENERATORS: [&str; 4] = ["rectangle", "half_disc", "quarter_disc", "annulus"];

/// `kinematics` keywords.
const KINEMATICS: [(&str, KinematicsKind); 2] = [
    ("small", KinematicsKind::Small),
    ("finite", KinematicsKind::Finite),
];

const FORMULATIONS: [(&str, FormulationKind); 2] = [
    ("full", FormulationKind::Full),
    ("selective_reduced", FormulationKind::SelectiveReduced),
];

const ELEMENTS: [(&str, ElementKind); 2] =
    [("tri3", ElementKind::Tri3), ("quad4", ElementKind::Quad4)];

const MESH_HELP: &str = "expected `rectangle { .. }`, `half_disc { .. }`, `quarter_disc { .. }`, \
`annulus { .. }` or `file \"part.msh\"`";

/// Converts a `body` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Body> {
    let name = item.name?;
    let block = item.block?;
    let mut f = Fields::new(
        &block,
        format!("body `{}`", name.name),
        &["mesh", "material", "formulation", "kinematics", "thermal"],
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

/// `mesh = generator { .. }` or `mesh = file "path"`.
fn mesh(v: &Value, diags: &mut Diags) -> Option<Spanned<MeshDef>> {
    match &v.kind {
        ValueKind::CtorStr {
            name,
            text,
            text_span,
        } if name.name == "file" => Some(Spanned::new(
            MeshDef::File(Spanned::new(text.clone(), *text_span)),
            v.span,
        )),
        ValueKind::Ctor { name, block } if GENERATORS.contains(&name.name.as_str()) => {
            generator(name, block, diags)
                .map(|g| Spanned::new(MeshDef::Generator(Box::new(g)), v.span))
        }
        ValueKind::Ctor { name, .. } | ValueKind::CtorStr { name, .. } => {
            let mut options = GENERATORS.to_vec();
            options.push("file");
            diags.push(
                Diagnostic::error(
                    format!("unknown mesh generator `{}`", name.name),
                    name.span,
                    "not a mesh generator",
                )
                .with_help(did_you_mean(&name.name, &options).unwrap_or(MESH_HELP.into())),
            );
            None
        }
        ValueKind::Path(p) if p.len() == 1 && GENERATORS.contains(&p[0].name.as_str()) => {
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
                .with_help(MESH_HELP),
            );
            None
        }
    }
}

fn generator(name: &Ident, block: &Block, diags: &mut Diags) -> Option<Generator> {
    let what = format!("`{}` mesh", name.name);
    let at = name.span;
    let (kind, element) = match name.name.as_str() {
        "rectangle" => {
            let mut f = Fields::new(
                block,
                what,
                &["origin", "size", "divisions", "grading", "element"],
            );
            let origin = f.point("origin", diags);
            let size = f.pair("size", diags);
            let divisions = f
                .value("divisions", diags)
                .and_then(|v| values::int_pair(v, diags));
            let grading = f.value("grading", diags).and_then(|v| {
                let [a, b] = values::pair_of(v, "a pair of gradings `(x, y)`", diags)?;
                let ga = values::grading(a, diags);
                let gb = values::grading(b, diags);
                Some(Spanned::new([ga?, gb?], v.span))
            });
            let element = f.choice("element", "element", &ELEMENTS, diags);
            f.require(&size, "size", at, "add `size = (width, height)`", diags);
            f.require(
                &divisions,
                "divisions",
                at,
                "add `divisions = (nx, ny)`",
                diags,
            );
            f.finish(diags);
            (
                GeneratorKind::Rectangle {
                    origin,
                    size,
                    divisions,
                    grading,
                },
                element,
            )
        }
        "half_disc" | "quarter_disc" => {
            let mut f = Fields::new(
                block,
                what,
                &[
                    "center",
                    "radius",
                    "radial",
                    "circumferential",
                    "radial_grading",
                    "circumferential_grading",
                    "upper",
                    "element",
                ],
            );
            let center = f.point("center", diags);
            let radius = f.number("radius", diags);
            let radial = f.integer("radial", diags);
            let circumferential = f.integer("circumferential", diags);
            let radial_grading = f.grading("radial_grading", diags);
            let circumferential_grading = f.grading("circumferential_grading", diags);
            let upper = f.boolean("upper", diags);
            let element = f.choice("element", "element", &ELEMENTS, diags);
            f.require(&center, "center", at, "add `center = (x, y)`", diags);
            f.require(&radius, "radius", at, "add `radius = ..`", diags);
            f.require(
                &radial,
                "radial",
                at,
                "add `radial = <radial divisions>`",
                diags,
            );
            f.require(
                &circumferential,
                "circumferential",
                at,
                "add `circumferential = <divisions along the arc>`",
                diags,
            );
            f.finish(diags);
            (
                GeneratorKind::Disc {
                    quarter: name.name == "quarter_disc",
                    center,
                    radius,
                    radial,
                    circumferential,
                    radial_grading,
                    circumferential_grading,
                    upper,
                },
                element,
            )
        }
        _ => {
            let mut f = Fields::new(
                block,
                what,
                &[
                    "center",
                    "inner",
                    "outer",
                    "start",
                    "end",
                    "radial",
                    "circumferential",
                    "radial_grading",
                    "element",
                ],
            );
            let center = f.point("center", diags);
            let inner = f.number("inner", diags);
            let outer = f.number("outer", diags);
            let start = f.number("start", diags);
            let end = f.number("end", diags);
            let radial = f.integer("radial", diags);
            let circumferential = f.integer("circumferential", diags);
            let radial_grading = f.grading("radial_grading", diags);
            let element = f.choice("element", "element", &ELEMENTS, diags);
            f.require(&center, "center", at, "add `center = (x, y)`", diags);
            f.require(&inner, "inner", at, "add `inner = <inner radius>`", diags);
            f.require(&outer, "outer", at, "add `outer = <outer radius>`", diags);
            f.require(
                &radial,
                "radial",
                at,
                "add `radial = <radial divisions>`",
                diags,
            );
            f.require(
                &circumferential,
                "circumferential",
                at,
                "add `circumferential = <divisions along the arc>`",
                diags,
            );
            f.finish(diags);
            (
                GeneratorKind::Annulus {
                    center,
                    inner,
                    outer,
                    start,
                    end,
                    radial,
                    circumferential,
                    radial_grading,
                },
                element,
            )
        }
    };
    Some(Generator {
        name: name.clone(),
        kind,
        element,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::{ElementKind, FormulationKind, GeneratorKind, Grading, MeshDef};
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
        assert_eq!(g.element.as_ref().unwrap().value, ElementKind::Quad4);
        let GeneratorKind::Rectangle {
            origin,
            size,
            divisions,
            grading,
        } = &g.kind
        else {
            panic!()
        };
        assert_eq!(origin.as_ref().unwrap().value, [-4.0, -4.0]);
        assert_eq!(size.as_ref().unwrap().value[0].value, 8.0);
        assert_eq!(divisions.as_ref().unwrap().value[1].value, 20);
        let g = &grading.as_ref().unwrap().value;
        assert!(matches!(&g[0].value, Grading::Center(r) if r.value == 4.0));
        assert!(matches!(&g[1].value, Grading::Geometric(r) if r.value == 0.2));
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
        assert!(matches!(g.kind, GeneratorKind::Disc { quarter: true, .. }));
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
    }
}
