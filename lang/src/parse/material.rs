//! `material name { elastic { E = .. nu = .. } }` and the reserved
//! `plastic`, `viscoplastic`, `thermal` blocks.

use super::fields::Fields;
use super::values::Diags;
use super::ItemParts;
use crate::ast::{Elastic, Material};

/// Material blocks that parse but are not supported yet.
pub const RESERVED: [&str; 3] = ["plastic", "viscoplastic", "thermal"];

/// Converts a `material` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Material> {
    let name = item.name?;
    let block = item.block?;
    let mut f = Fields::new(
        &block,
        format!("material `{}`", name.name),
        &["elastic", "plastic", "viscoplastic", "thermal"],
    );
    let elastic = f.block("elastic", diags).map(|b| {
        let mut e = Fields::new(b, "`elastic` block", &["E", "nu"]);
        let young = e.number("E", diags);
        let poisson = e.number("nu", diags);
        e.require(
            &young,
            "E",
            b.span,
            "add Young's modulus, e.g. `E = 210e3`",
            diags,
        );
        e.require(
            &poisson,
            "nu",
            b.span,
            "add Poisson's ratio, e.g. `nu = 0.3`",
            diags,
        );
        e.finish(diags);
        Elastic {
            young,
            poisson,
            span: b.span,
        }
    });
    let reserved: Vec<_> = f
        .take_all(&RESERVED)
        .into_iter()
        .map(|e| e.key.clone())
        .collect();
    if reserved.is_empty() {
        f.require(
            &elastic,
            "elastic",
            name.span,
            "add `elastic { E = ..  nu = .. }`",
            diags,
        );
    }
    f.finish(diags);
    Some(Material {
        name,
        elastic,
        reserved,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::parse::test_support::{parse_messages, parse_ok};

    #[test]
    fn elastic_material() {
        let deck = parse_ok("material steel { elastic { E = 210e3  nu = 0.3 } }");
        let m = &deck.materials[0];
        assert_eq!(m.name.name, "steel");
        let e = m.elastic.as_ref().unwrap();
        assert_eq!(e.young.as_ref().unwrap().value, 210e3);
        assert_eq!(e.poisson.as_ref().unwrap().value, 0.3);
        assert!(m.reserved.is_empty());
    }

    #[test]
    fn reserved_blocks_parse_generically() {
        let deck = parse_ok(
            "material al { elastic { E = 70e3 nu = 0.33 }\n plastic { yield = 250 hardening = linear { H = 1000 } } }",
        );
        assert_eq!(deck.materials[0].reserved[0].name, "plastic");
    }

    #[test]
    fn missing_elastic_block() {
        assert_eq!(
            parse_messages("material steel { }"),
            ["missing `elastic` in the material `steel`"]
        );
    }
}
