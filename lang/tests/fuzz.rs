//! Property tests: `compile` never panics, whatever the input — random
//! bytes, random strings over the deck alphabet, and mutations of valid
//! decks (delete, duplicate or swap a token, replace a number, cut the
//! text). Case counts are bounded so the whole file runs in a few seconds.

use ctc_lang::{check, compile, Source};
use proptest::prelude::*;

const VALID: &[&str] = &[
    include_str!("decks/brief.ctc"),
    include_str!("decks/axisymmetric_tools.ctc"),
];

/// Splits a deck into tokens (words, numbers, punctuation) and the
/// whitespace/comments between them, keeping everything so that joining
/// gives the deck back.
fn tokens(text: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut cur = String::new();
    let mut kind = 0u8; // 0: none, 1: word, 2: space
    for c in text.chars() {
        let k = if c.is_alphanumeric() || c == '_' || c == '.' || c == '-' {
            1
        } else if c.is_whitespace() {
            2
        } else {
            3
        };
        if k != kind || k == 3 {
            if !cur.is_empty() {
                out.push(std::mem::take(&mut cur));
            }
            kind = k;
        }
        cur.push(c);
    }
    if !cur.is_empty() {
        out.push(cur);
    }
    out
}

fn is_token(t: &str) -> bool {
    !t.trim().is_empty()
}

/// Runs the whole pipeline; diagnostics must render without panicking and
/// a failed compilation must say why.
fn run(text: &str) {
    let src = Source::new("tests/decks/fuzz.ctc", text);
    let c = check(&src);
    let rendered = c.diagnostics.render(&src);
    if c.model.is_none() {
        assert!(c.diagnostics.error_count() > 0);
        assert!(rendered.contains("error"));
    }
    let _ = compile(&src);
}

#[derive(Debug, Clone)]
enum Mutation {
    Delete(usize),
    Duplicate(usize),
    Swap(usize, usize),
    Number(usize, f64),
    Word(usize, &'static str),
    Truncate(usize),
}

const WORDS: &[&str] = &[
    "{", "}", "(", ")", "[", "]", "=", ",", "->", "..", "material", "body", "step", "set", "tool",
    "steel", "block", "top", "nodes", "edges", "ramp", "3d", "plastic", "\"", "#",
];

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::Delete),
        any::<usize>().prop_map(Mutation::Duplicate),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::Swap(a, b)),
        (
            any::<usize>(),
            prop_oneof![
                Just(0.0),
                Just(-1.0),
                Just(0.5),
                Just(1e-30),
                Just(1e300),
                Just(-3.0),
                Just(7.0),
                Just(2.5)
            ]
        )
            .prop_map(|(i, v)| Mutation::Number(i, v)),
        (any::<usize>(), proptest::sample::select(WORDS)).prop_map(|(i, w)| Mutation::Word(i, w)),
        any::<usize>().prop_map(Mutation::Truncate),
    ]
}

fn apply(deck: &str, muts: &[Mutation]) -> String {
    let mut toks = tokens(deck);
    for m in muts {
        let idx: Vec<usize> = (0..toks.len()).filter(|&i| is_token(&toks[i])).collect();
        if idx.is_empty() {
            break;
        }
        let pick = |i: usize| idx[i % idx.len()];
        match m {
            Mutation::Delete(i) => {
                toks.remove(pick(*i));
            }
            Mutation::Duplicate(i) => {
                let j = pick(*i);
                let t = toks[j].clone();
                toks.insert(j, format!("{t} "));
            }
            Mutation::Swap(a, b) => {
                let (a, b) = (pick(*a), pick(*b));
                toks.swap(a, b);
            }
            Mutation::Number(i, v) => {
                let nums: Vec<usize> = idx
                    .iter()
                    .copied()
                    .filter(|&k| toks[k].parse::<f64>().is_ok())
                    .collect();
                if !nums.is_empty() {
                    let k = nums[i % nums.len()];
                    toks[k] = format!("{v}");
                }
            }
            Mutation::Word(i, w) => {
                let j = pick(*i);
                toks[j] = (*w).to_string();
            }
            Mutation::Truncate(i) => {
                let j = pick(*i);
                toks.truncate(j);
            }
        }
    }
    toks.concat()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 300, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn compile_never_panics_on_random_bytes(bytes in proptest::collection::vec(any::<u8>(), 0..300)) {
        run(&String::from_utf8_lossy(&bytes));
    }

    #[test]
    fn compile_never_panics_on_deck_alphabet(s in "[a-z_{}()\\[\\]=,.\\-> 0-9\"#\n]{0,200}") {
        run(&s);
    }

}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1000, failure_persistence: None, ..ProptestConfig::default() })]

    #[test]
    fn compile_never_panics_on_mutated_decks(
        which in 0..VALID.len(),
        muts in proptest::collection::vec(mutation(), 1..6),
    ) {
        run(&apply(VALID[which], &muts));
    }
}

#[test]
fn tokens_roundtrip() {
    for d in VALID {
        assert_eq!(tokens(d).concat(), *d);
    }
}

#[test]
fn valid_decks_stay_valid_without_mutation() {
    for d in VALID {
        let src = Source::new("tests/decks/x.ctc", *d);
        assert!(compile(&src).is_ok());
    }
}
