//! Bad input never panics (issue 10): structure-aware fuzzing of the deck
//! compiler (`ctc_lang::compile`) and of the gmsh reader
//! (`ctc_engine::mesh::gmsh::parse`) with mutations of real inputs (the
//! example decks, the gmsh test files): deleted, duplicated and swapped
//! spans, inserted tokens of the language, changed digits. Each test prints
//! its number of executions; a panic fails the test with the input.
//!
//! The case count follows `PROPTEST_CASES` (default 256), e.g.
//! `PROPTEST_CASES=100000 cargo test --release --test suite robust_fuzz:: -- --nocapture`.

use proptest::prelude::*;
use proptest::test_runner::{Config, TestRunner};
use std::path::Path;

/// Tokens inserted by the mutations (deck language and gmsh keywords).
const TOKENS: &[&str] = &[
    "{",
    "}",
    "(",
    ")",
    "[",
    "]",
    "=",
    ",",
    "->",
    ".",
    "\"",
    "#",
    "\n",
    " ",
    "0",
    "-1",
    "1e308",
    "-0",
    "nan",
    "inf",
    "1e-320",
    "99999999999999999999",
    "analysis",
    "material",
    "body",
    "tool",
    "contact",
    "fix",
    "displace",
    "pressure",
    "force",
    "step",
    "output",
    "set",
    "mesh",
    "rectangle",
    "half_disc",
    "annulus",
    "file",
    "circle",
    "plane",
    "polyline",
    "arc",
    "nurbs",
    "ramp",
    "table",
    "constant",
    "center",
    "geometric",
    "uniform",
    "box",
    "near",
    "nodes",
    "edges",
    "node",
    "method",
    "penalty",
    "lagrange",
    "augmented_lagrange",
    "stiffness",
    "increments",
    "time",
    "..",
    "elastic",
    "plastic",
    "E",
    "nu",
    "ux",
    "uy",
    "divisions",
    "$MeshFormat",
    "$EndMeshFormat",
    "$Nodes",
    "$EndNodes",
    "$Elements",
    "$EndElements",
    "$PhysicalNames",
    "$EndPhysicalNames",
    "$Entities",
    "$EndEntities",
    "2.2",
    "4.1",
    "3",
    "15",
    "1 2 3 4",
];

/// One edit of an input text (byte offsets are taken modulo the length and
/// moved back to a char boundary).
#[derive(Debug, Clone)]
enum Edit {
    Delete(usize, usize),
    Duplicate(usize, usize),
    Insert(usize, usize),
    Swap(usize, usize, usize),
    Digit(usize, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    let pos = any::<usize>();
    prop_oneof![
        (pos, 0usize..64).prop_map(|(a, n)| Edit::Delete(a, n)),
        (pos, 0usize..128).prop_map(|(a, n)| Edit::Duplicate(a, n)),
        (pos, 0..TOKENS.len()).prop_map(|(a, t)| Edit::Insert(a, t)),
        (pos, pos, 1usize..40).prop_map(|(a, b, n)| Edit::Swap(a, b, n)),
        (pos, b'0'..=b'9').prop_map(|(a, d)| Edit::Digit(a, d)),
    ]
}

fn boundary(s: &str, mut i: usize) -> usize {
    if s.is_empty() {
        return 0;
    }
    i %= s.len() + 1;
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

fn apply(text: &str, edits: &[Edit]) -> String {
    let mut s = text.to_string();
    for e in edits {
        match *e {
            Edit::Delete(a, n) => {
                let a = boundary(&s, a);
                let b = boundary(&s, (a + n).min(s.len()));
                s.replace_range(a..b.max(a), "");
            }
            Edit::Duplicate(a, n) => {
                let a = boundary(&s, a);
                let b = boundary(&s, (a + n).min(s.len())).max(a);
                let piece = s[a..b].to_string();
                s.insert_str(b, &piece);
            }
            Edit::Insert(a, t) => {
                let a = boundary(&s, a);
                s.insert_str(a, TOKENS[t]);
            }
            Edit::Swap(a, b, n) => {
                let (a, b) = (boundary(&s, a), boundary(&s, b));
                let (lo, hi) = (a.min(b), a.max(b));
                let lo_end = boundary(&s, (lo + n).min(hi));
                let hi_end = boundary(&s, (hi + n).min(s.len()));
                let first = s[lo..lo_end].to_string();
                let second = s[hi..hi_end].to_string();
                s.replace_range(hi..hi_end, &first);
                s.replace_range(lo..lo_end, &second);
            }
            Edit::Digit(a, d) => {
                let a = boundary(&s, a);
                if let Some(c) = s[a..].chars().next() {
                    if c.is_ascii_digit() {
                        s.replace_range(a..a + 1, &char::from(d).to_string());
                    }
                }
            }
        }
    }
    s
}

fn seeds(dir: &Path, ext: &str) -> Vec<String> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == ext))
        .collect();
    v.sort();
    v.iter()
        .map(|p| std::fs::read_to_string(p).unwrap())
        .collect()
}

fn runner() -> TestRunner {
    TestRunner::new(Config {
        failure_persistence: None,
        ..Config::default()
    })
}

/// Runs `check` on mutations of `seeds`; returns the number of executions.
fn fuzz(seeds: &[String], check: impl Fn(&str)) -> usize {
    assert!(!seeds.is_empty());
    let count = std::cell::Cell::new(0usize);
    let strategy = (0..seeds.len(), proptest::collection::vec(edit(), 1..10));
    runner()
        .run(&strategy, |(i, edits)| {
            let text = apply(&seeds[i], &edits);
            check(&text);
            count.set(count.get() + 1);
            Ok(())
        })
        .unwrap();
    count.get()
}

#[test]
fn fuzz_deck_compiler_with_mutated_example_decks_never_panics() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut decks = seeds(&root.join("examples"), "ctc");
    decks.extend(seeds(&root.join("lang/tests/decks"), "ctc"));
    let n = fuzz(&decks, |text| {
        let source = ctc_lang::Source::new(root.join("examples/fuzz.ctc"), text);
        if let Err(d) = ctc_lang::compile(&source) {
            // rendering the diagnostics must not panic either
            let _ = d.render(&source);
        }
    });
    eprintln!("deck compiler: {n} executions, 0 panics");
}

#[test]
fn fuzz_gmsh_reader_with_mutated_msh_files_never_panics() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let files = seeds(&root.join("engine/tests/data"), "msh");
    let n = fuzz(&files, |text| {
        if let Ok(mesh) = ctc_engine::mesh::gmsh::parse(text) {
            // a mesh read without error passes through the checks
            let _ = ctc_engine::mesh::validate::check(&mesh);
        }
    });
    eprintln!("gmsh reader: {n} executions, 0 panics");
}

#[test]
fn mutations_apply_at_any_offset_without_panicking() {
    let s = "aé{b}";
    for a in 0..20 {
        for n in 0..8 {
            let _ = apply(
                s,
                &[
                    Edit::Delete(a, n),
                    Edit::Duplicate(a, n),
                    Edit::Insert(a, 3),
                    Edit::Swap(a, a * 7, n + 1),
                    Edit::Digit(a, b'7'),
                ],
            );
        }
    }
    assert_eq!(apply("ab", &[Edit::Insert(1, 0)]), "a{b");
    assert_eq!(apply("a1", &[Edit::Digit(1, b'9')]), "a9");
}
