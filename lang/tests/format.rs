//! `ctc fmt` on every deck of the repository and on mutated decks: the
//! formatted deck parses to the same AST (spans aside) with the same
//! diagnostics, and formatting is idempotent.

use ctc_lang::format::format;
use ctc_lang::parse::parse;
use proptest::prelude::*;
use std::path::{Path, PathBuf};

/// Every `.ctc` file of the repository (examples, verification cases,
/// language test decks, bad decks).
fn repo_decks() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out = Vec::new();
    for dir in [
        "examples",
        "verification/cases",
        "lang/tests/decks",
        "lang/tests/bad_decks",
        "lang/tests/bad_decks/parts",
    ] {
        let Ok(rd) = std::fs::read_dir(root.join(dir)) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.extension().is_some_and(|x| x == "ctc") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// The Debug text of a deck with every span removed.
fn ast_without_spans(text: &str) -> String {
    let (deck, _) = parse(text);
    let s = format!("{deck:?}");
    let mut out = String::with_capacity(s.len());
    let mut rest = s.as_str();
    while let Some(i) = rest.find("Span { start: ") {
        out.push_str(&rest[..i]);
        let after = &rest[i..];
        let end = after.find('}').map_or(after.len(), |j| j + 1);
        out.push_str("Span");
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

fn messages(text: &str) -> Vec<String> {
    parse(text).1.into_iter().map(|d| d.message).collect()
}

/// Checks one deck text; `Ok(false)` when it has a syntax error (not
/// formatted).
fn check(name: &str, text: &str) -> Result<bool, String> {
    let Ok(once) = format(text) else {
        return Ok(false);
    };
    let twice =
        format(&once).map_err(|e| format!("{name}: formatted deck does not parse: {e}\n{once}"))?;
    if once != twice {
        return Err(format!(
            "{name}: not idempotent\n--- once\n{once}\n--- twice\n{twice}"
        ));
    }
    if ast_without_spans(text) != ast_without_spans(&once) {
        return Err(format!("{name}: the AST changed\n--- formatted\n{once}"));
    }
    if messages(text) != messages(&once) {
        return Err(format!(
            "{name}: diagnostics changed: {:?} vs {:?}",
            messages(text),
            messages(&once)
        ));
    }
    // comments are kept
    let count = |t: &str| t.lines().filter(|l| l.contains('#')).count();
    if count(text) != count(&once) {
        return Err(format!("{name}: comments lost\n{once}"));
    }
    Ok(true)
}

#[test]
fn fmt_every_repo_deck_is_idempotent_and_keeps_the_ast() {
    let decks = repo_decks();
    assert!(decks.len() >= 30, "found {} decks", decks.len());
    let mut formatted = 0;
    for p in &decks {
        let text = std::fs::read_to_string(p).unwrap();
        match check(&p.display().to_string(), &text) {
            Ok(true) => formatted += 1,
            Ok(false) => {}
            Err(e) => panic!("{e}"),
        }
    }
    eprintln!(
        "ctc fmt: {formatted} of {} repository decks formatted, idempotent, same AST",
        decks.len()
    );
    assert!(
        formatted + 10 >= decks.len(),
        "{formatted} of {}",
        decks.len()
    );
}

#[test]
fn fmt_canonical_layout() {
    let text = "analysis{dimension=plane_strain}\n\n\n# a material\nmaterial steel { elastic { E = 2*100   nu = 0.3 }   # trailing\n}\nlet  a=1+2*3^2\n";
    let out = format(text).unwrap();
    assert_eq!(
        out,
        "analysis { dimension = plane_strain }\n\n# a material\nmaterial steel {\n  elastic { E = 2 * 100  nu = 0.3 }  # trailing\n}\nlet a = 1 + 2 * 3^2\n"
    );
}

/// Consecutive `let` lines with trailing comments: each comment stays on
/// its own line (pest's span of an expression runs on over the comment it
/// skipped looking for another operator; the comment of the next line used
/// to move up and the value was copied verbatim).
#[test]
fn fmt_keeps_trailing_comments_of_consecutive_lets() {
    let text = "let a = 4   # one\nlet b = (1,2)  # two\nlet c = 2*a # three\nanalysis {\n  x = 1\n}  # end\n";
    let out = format(text).unwrap();
    assert_eq!(
        out,
        "let a = 4  # one\nlet b = (1, 2)  # two\nlet c = 2 * a  # three\nanalysis { x = 1 }  # end\n"
    );
    assert_eq!(format(&out).unwrap(), out);
}

/// A mutation of a deck's lines.
#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize),
    Duplicate(usize),
    Swap(usize, usize),
    Blank(usize),
    Comment(usize),
    Indent(usize, usize),
}

fn mutate(text: &str, ms: &[Mutation]) -> String {
    let mut lines: Vec<String> = text.lines().map(str::to_string).collect();
    for m in ms {
        if lines.is_empty() {
            break;
        }
        let n = lines.len();
        match *m {
            Mutation::Delete(i) => {
                lines.remove(i % n);
            }
            Mutation::Duplicate(i) => {
                let l = lines[i % n].clone();
                lines.insert(i % n, l);
            }
            Mutation::Swap(i, j) => lines.swap(i % n, j % n),
            Mutation::Blank(i) => lines.insert(i % n, String::new()),
            Mutation::Comment(i) => lines.insert(i % n, "# mutated".into()),
            Mutation::Indent(i, k) => {
                let l = format!("{}{}", " ".repeat(k % 7), lines[i % n].trim_start());
                lines[i % n] = l;
            }
        }
    }
    lines.join("\n")
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::Delete),
        any::<usize>().prop_map(Mutation::Duplicate),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::Swap(a, b)),
        any::<usize>().prop_map(Mutation::Blank),
        any::<usize>().prop_map(Mutation::Comment),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::Indent(a, b)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]
    #[test]
    fn fmt_mutated_decks_keep_their_ast(deck in 0usize..1000, ms in prop::collection::vec(mutation(), 1..4)) {
        let decks = repo_decks();
        let text = std::fs::read_to_string(&decks[deck % decks.len()]).unwrap();
        let mutated = mutate(&text, &ms);
        if let Err(e) = check("mutated", &mutated) {
            return Err(TestCaseError::fail(e));
        }
    }
}
