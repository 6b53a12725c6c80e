//! `analysis { dimension = .. thickness = .. }`.

use super::fields::Fields;
use super::values::Diags;
use super::ItemParts;
use crate::ast::{Analysis, Dimension};
use crate::span::Spanned;

/// Accepted `dimension` values.
pub const DIMENSIONS: [(&str, Dimension); 4] = [
    ("plane_strain", Dimension::PlaneStrain),
    ("plane_stress", Dimension::PlaneStress),
    ("axisymmetric", Dimension::Axisymmetric),
    ("3d", Dimension::ThreeD),
];

/// The unit system of an `analysis` pair (`units = SI`), read before the
/// rest of the deck; an unknown name is reported by [`parse`].
pub fn unit_system(
    pair: pest::iterators::Pair<'_, super::Rule>,
) -> Option<&'static crate::units::System> {
    let parts = super::ItemParts::of(pair);
    let block = parts.block?;
    block.entries.iter().find_map(|e| match &e.body {
        crate::ast::syntax::EntryBody::Assign(v) => match &v.kind {
            crate::ast::syntax::ValueKind::Path(p) if e.key.name == "units" && p.len() == 1 => {
                crate::units::system(&p[0].name)
            }
            _ => None,
        },
        _ => None,
    })
}

/// Converts an `analysis` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Analysis> {
    let block = item.block?;
    let mut f = Fields::keyed(&block, "`analysis` block", &crate::tables::ANALYSIS);
    let dimension = f.choice("dimension", "dimension", &DIMENSIONS, diags);
    let thickness = f.number("thickness", diags);
    let systems: Vec<(&str, &'static crate::units::System)> =
        crate::units::SYSTEMS.iter().map(|s| (s.name, s)).collect();
    let units = f.choice("units", "unit system", &systems, diags);
    f.require(
        &dimension,
        "dimension",
        item.keyword,
        "add `dimension = plane_strain` (or `plane_stress`, `axisymmetric`)",
        diags,
    );
    f.finish(diags);
    Some(Analysis {
        dimension,
        thickness,
        units: units.map(|u| Spanned::new(u.value.name, u.span)),
        keyword: item.keyword,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::Dimension;
    use crate::parse::test_support::parse_ok;

    #[test]
    fn analysis_block_with_defaults_left_out() {
        let deck = parse_ok("analysis { dimension = axisymmetric }");
        let a = &deck.analysis[0];
        assert_eq!(a.dimension.as_ref().unwrap().value, Dimension::Axisymmetric);
        assert!(a.thickness.is_none());
        let deck = parse_ok("analysis {\n  dimension = plane_stress\n  thickness = 2.5 # mm\n}");
        assert_eq!(deck.analysis[0].thickness.as_ref().unwrap().value, 2.5);
    }

    #[test]
    fn three_d_is_parsed_for_validation_to_reject() {
        let deck = parse_ok("analysis { dimension = 3d }");
        assert_eq!(
            deck.analysis[0].dimension.as_ref().unwrap().value,
            Dimension::ThreeD
        );
    }
}
