//! `output { every = n  fields = [..]  history = [..]  format = binary | ascii
//! thickness = (body.a, body.b) }`.

use super::fields::Fields;
use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::syntax::{ArgKind, Value, ValueKind};
use crate::ast::{FieldName, History, Output, OutputFormat};
use crate::diagnostics::Diagnostic;
use crate::span::Spanned;
use crate::suggest::did_you_mean;

/// Output field names.
pub const FIELDS: [(&str, FieldName); 8] = [
    ("displacement", FieldName::Displacement),
    ("stress", FieldName::Stress),
    ("strain", FieldName::Strain),
    ("von_mises", FieldName::VonMises),
    ("reaction", FieldName::Reaction),
    ("contact", FieldName::Contact),
    ("velocity", FieldName::Velocity),
    ("acceleration", FieldName::Acceleration),
];

/// VTU formats.
pub const FORMATS: [(&str, OutputFormat); 2] = [
    ("binary", OutputFormat::Binary),
    ("ascii", OutputFormat::Ascii),
];

const HISTORIES: [&str; 4] = ["reaction", "displacement", "contact_force", "roughness"];

/// Converts an `output` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Output> {
    let block = item.block?;
    let mut f = Fields::keyed(&block, "`output` block", &crate::tables::OUTPUT);
    let every = f.integer("every", diags);
    let fields = f.value("fields", diags).and_then(|v| {
        let items = values::list(v, "a list of fields `[displacement, stress, ..]`", diags)?;
        let out: Vec<_> = items
            .iter()
            .filter_map(|x| values::choice(x, "output field", &FIELDS, diags))
            .collect();
        Some(Spanned::new(out, v.span))
    });
    let history = f.value("history", diags).and_then(|v| {
        let items = values::list(v, "a list of histories `[reaction(body.set), ..]`", diags)?;
        Some(items.iter().filter_map(|x| history(x, diags)).collect())
    });
    let format = f.choice("format", "VTU format", &FORMATS, diags);
    let thickness = f
        .value("thickness", diags)
        .and_then(|v| thickness(v, diags));
    f.finish(diags);
    Some(Output {
        every,
        fields,
        history,
        format,
        thickness,
        keyword: item.keyword,
        span: item.span,
    })
}

/// `thickness = (body.a, body.b)`: two face set references.
fn thickness(v: &Value, diags: &mut Diags) -> Option<Spanned<[crate::ast::SetRef; 2]>> {
    let help = "expected two face sets of one body, e.g. `(sheet.zmax, sheet.zmin)`";
    match &v.kind {
        ValueKind::Tuple(items) if items.len() == 2 => {
            let a = values::set_ref(&items[0], diags);
            let b = values::set_ref(&items[1], diags);
            Some(Spanned::new([a?, b?], v.span))
        }
        _ => {
            diags.push(Diagnostic::error(
                format!("expected a pair of face sets, found {}", v.kind.describe()),
                v.span,
                help,
            ));
            None
        }
    }
}

fn history(v: &Value, diags: &mut Diags) -> Option<Spanned<History>> {
    let help = "expected `reaction(body.set)`, `displacement(body.set)`, `contact_force(body.set -> tool)` or `roughness(body.set)`";
    let ValueKind::Call { path, args } = &v.kind else {
        diags.push(Diagnostic::error(
            format!("expected a history request, found {}", v.kind.describe()),
            v.span,
            help,
        ));
        return None;
    };
    if path.len() != 1 || !HISTORIES.contains(&path[0].name.as_str()) {
        let name = crate::ast::syntax::path_text(path);
        diags.push(
            Diagnostic::error(format!("unknown history `{name}`"), v.span, help)
                .with_help_opt(did_you_mean(&name, HISTORIES)),
        );
        return None;
    }
    let name = &path[0].name;
    if args.len() != 1 {
        diags.push(Diagnostic::error(
            format!("`{name}` takes 1 argument, found {}", args.len()),
            v.span,
            help,
        ));
        return None;
    }
    let h = match (&args[0].kind, name.as_str()) {
        (ArgKind::Positional(r), "reaction") => History::Reaction(values::set_ref(r, diags)?),
        (ArgKind::Positional(r), "displacement") => {
            History::Displacement(values::set_ref(r, diags)?)
        }
        (ArgKind::Positional(r), "roughness") => History::Roughness(values::set_ref(r, diags)?),
        (ArgKind::Arrow(r, tool), "contact_force") => {
            History::ContactForce(values::set_ref(r, diags)?, tool.clone())
        }
        (_, "contact_force") => {
            diags.push(Diagnostic::error(
                "`contact_force` names a contact pair",
                args[0].span,
                "expected `body.set -> tool`",
            ));
            return None;
        }
        _ => {
            diags.push(Diagnostic::error(
                format!("`{name}` takes a set reference"),
                args[0].span,
                "expected `body.set`",
            ));
            return None;
        }
    };
    Some(Spanned::new(h, v.span))
}

#[cfg(test)]
mod tests {
    use crate::ast::{FieldName, History};
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn output_block() {
        let deck = parse_ok(
            "output {\n  every = 2\n  fields = [displacement, stress, strain, von_mises, reaction, contact]\n  history = [reaction(block.bottom), displacement(block.top), contact_force(block.top -> punch)]\n}",
        );
        let o = &deck.outputs[0];
        assert_eq!(o.every.as_ref().unwrap().value, 2);
        assert_eq!(o.fields.as_ref().unwrap().value.len(), 6);
        assert_eq!(
            o.fields.as_ref().unwrap().value[3].value,
            FieldName::VonMises
        );
        assert!(o.format.is_none());
        let h = o.history.as_ref().unwrap();
        assert!(matches!(&h[0].value, History::Reaction(r) if r.to_string() == "block.bottom"));
        assert!(
            matches!(&h[2].value, History::ContactForce(r, t) if r.to_string() == "block.top" && t.name == "punch")
        );
    }

    #[test]
    fn output_thickness() {
        let deck = parse_ok("output { thickness = (sheet.zmax, sheet.zmin) }");
        let t = &deck.outputs[0].thickness.as_ref().unwrap().value;
        assert_eq!(t[0].to_string(), "sheet.zmax");
        assert_eq!(t[1].to_string(), "sheet.zmin");
        assert_eq!(
            parse_messages("output { thickness = sheet.zmax }"),
            ["expected a pair of face sets, found a dotted name"]
        );
    }

    #[test]
    fn output_format() {
        let deck = parse_ok("output { format = ascii }");
        assert_eq!(
            deck.outputs[0].format.as_ref().unwrap().value,
            crate::ast::OutputFormat::Ascii
        );
        assert_eq!(
            parse_messages("output { format = binry }"),
            ["unknown VTU format `binry`"]
        );
    }

    #[test]
    fn output_mistakes() {
        assert_eq!(
            parse_messages("output { fields = [displacment] }"),
            ["unknown output field `displacment`"]
        );
        assert_eq!(
            parse_messages("output { history = [reactoin(a.b)] }"),
            ["unknown history `reactoin`"]
        );
    }
}
