//! `set name = body.selection`.

use super::values::{self, Diags};
use super::ItemParts;
use crate::ast::SetDef;

/// Converts a `set` item.
pub fn parse(item: ItemParts, diags: &mut Diags) -> Option<SetDef> {
    let name = item.name?;
    let target = values::set_ref(item.target.as_ref()?, diags)?;
    Some(SetDef {
        name,
        target,
        span: item.span,
    })
}

#[cfg(test)]
mod tests {
    use crate::ast::{Selection, SetRefKind};
    use crate::parse::test_support::parse_ok;

    #[test]
    fn geometric_sets() {
        let deck = parse_ok(
            "set clamp = block.nodes(y = -4)\nset load = block.edges(box((-1, -0.01), (1, 0.01)))\nset tip = block.node(near(0, 0))\nset alias = block.top",
        );
        assert_eq!(deck.sets.len(), 4);
        assert_eq!(deck.sets[0].name.name, "clamp");
        match &deck.sets[0].target.kind {
            SetRefKind::Nodes(s) => assert_eq!(s.value, Selection::Y(-4.0)),
            k => panic!("{k:?}"),
        }
        assert!(matches!(deck.sets[1].target.kind, SetRefKind::Edges(_)));
        assert!(matches!(deck.sets[2].target.kind, SetRefKind::Node(_)));
        assert!(matches!(deck.sets[3].target.kind, SetRefKind::Named(_)));
        assert_eq!(deck.sets[3].target.body.name, "block");
    }
}
