//! `analysis { dimension = .. thickness = .. }`.

use super::fields::Fields;
use super::values::Diags;
use super::ItemParts;
use crate::ast::{Analysis, Dimension};

/// Accepted `dimension` values.
pub const DIMENSIONS: [(&str, Dimension); 4] = [
    ("plane_strain", Dimension::PlaneStrain),
    ("plane_stress", Dimension::PlaneStress),
    ("axisymmetric", Dimension::Axisymmetric),
    ("3d", Dimension::ThreeD),
];

/// Converts an `analysis` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<Analysis> {
    let block = item.block?;
    let mut f = Fields::new(&block, "`analysis` block", &["dimension", "thickness"]);
    let dimension = f.choice("dimension", "dimension", &DIMENSIONS, diags);
    let thickness = f.number("thickness", diags);
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
