//! `history = [roughness(set)]`: lowered with the set's nodes and the
//! height axis (the axis of the set's smallest extent), located errors for
//! a set of fewer than 3 nodes and a misspelt name.

use ctc_engine::model::HistoryRequest;
use ctc_lang::{check, Source};

fn deck(history: &str) -> Source {
    Source::new(
        "roughness.ctc",
        format!(
            "analysis {{ dimension = plane_strain }}
material steel {{ elastic {{ E = 210e3  nu = 0.3 }} }}
body b {{ mesh = rectangle {{ size = (4, 1)  divisions = (8, 2) }}  material = steel }}
fix b.bottom {{ ux uy }}
step s {{ time = 0 .. 1 }}
output {{ history = [{history}] }}
"
        ),
    )
}

#[test]
fn roughness_of_a_top_and_a_side_lowers_with_its_height_axis() {
    let src = deck("roughness(b.top), roughness(b.right)");
    let c = check(&src);
    let m = c
        .model
        .as_ref()
        .unwrap_or_else(|| panic!("{}", c.diagnostics.render(&src)));
    let mut found = Vec::new();
    for h in &m.output.history {
        if let HistoryRequest::Roughness { label, nodes, axis } = h {
            found.push((label.clone(), nodes.len(), *axis));
        }
    }
    assert_eq!(
        found,
        [
            ("roughness(b.top)".to_string(), 9, 1),
            ("roughness(b.right)".to_string(), 3, 0)
        ]
    );
    let cols = ctc_engine::output::history::columns(m);
    for c in [
        "roughness(b.top)_Ra",
        "roughness(b.top)_Rq",
        "roughness(b.top)_mean",
    ] {
        assert!(cols.iter().any(|x| x == c), "{cols:?}");
    }
    // the reference configuration is flat: no roughness
    let zeros = vec![[0.0; 2]; m.mesh.nodes.len()];
    let row = ctc_engine::output::history::row(m, 0.0, &zeros, &zeros, &[]);
    assert_eq!(row.len(), cols.len());
    assert_eq!(&row[1..4], &[0.0, 0.0, 1.0]);
}

#[test]
fn roughness_of_too_few_nodes_or_a_misspelt_name_is_a_located_error() {
    let src = deck("roughness(b.corner_tl)");
    let c = check(&src);
    assert!(c.model.is_none());
    let text = c.diagnostics.render(&src);
    assert!(
        text.contains("needs at least 3 nodes, the set has 1"),
        "{text}"
    );
    assert!(text.contains("roughness(b.corner_tl)"), "{text}");
    let src = deck("roughnes(b.top)");
    let text = check(&src).diagnostics.render(&src);
    assert!(text.contains("unknown history `roughnes`"), "{text}");
    assert!(text.contains("roughness"), "{text}");
}
