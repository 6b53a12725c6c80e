//! The keyword reference: `docs/DECK.md` is generated from the parser's
//! key tables and must be up to date; `ctc doc contact` is snapshotted;
//! every key the parser accepts is in the tables.

use ctc_lang::reference;
use std::path::Path;

/// Regenerate with `cargo run -- doc --markdown > docs/DECK.md`.
#[test]
fn deck_md_is_generated_from_the_tables_and_up_to_date() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/DECK.md");
    let committed = std::fs::read_to_string(&path).unwrap_or_default();
    let generated = reference::markdown();
    if std::env::var_os("CTC_UPDATE_DOCS").is_some() {
        std::fs::write(&path, &generated).unwrap();
        return;
    }
    assert!(
        committed == generated,
        "docs/DECK.md is stale: run `cargo run -- doc --markdown > docs/DECK.md` \
         (or CTC_UPDATE_DOCS=1 cargo test -p ctc-lang --test reference)"
    );
}

#[test]
fn ctc_doc_contact() {
    let text = reference::doc(Some("contact")).unwrap();
    insta::assert_snapshot!("doc_contact", text);
}

#[test]
fn ctc_doc_index_generators_and_unknown_items() {
    let index = reference::doc(None).unwrap();
    for i in reference::ITEMS {
        assert!(index.contains(i.name), "{}", i.name);
    }
    assert!(reference::doc(Some("rectangle"))
        .unwrap()
        .contains("`divisions`"));
    assert!(reference::doc(Some("units")).unwrap().contains("mm_N_s"));
    let e = reference::doc(Some("contcat")).unwrap_err();
    assert!(e.contains("did you mean `contact`?"), "{e}");
}

/// Every key of every table is accepted by the parser of its block: a
/// misspelling of it is reported with "did you mean" the key.
#[test]
fn every_documented_key_is_known_to_the_parser() {
    for (block, keys) in ctc_lang::tables::ALL {
        for k in keys.iter() {
            assert!(!k.doc.is_empty(), "{block}.{}", k.name);
        }
    }
    // a sample through the parser: `material.elastic`, `contact`, `step`
    let (_, d) = ctc_lang::parse::parse(
        "material m { elastic { Ee = 1  nu = 0.3 } }\nstep { time = 0 .. 1  incremnts = 1 }",
    );
    let helps: Vec<String> = d.iter().filter_map(|d| d.help.clone()).collect();
    assert!(
        helps.contains(&"did you mean `E`?".to_string()),
        "{helps:?}"
    );
    assert!(
        helps.contains(&"did you mean `increments`?".to_string()),
        "{helps:?}"
    );
}
