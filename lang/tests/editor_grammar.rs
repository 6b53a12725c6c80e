//! The editor grammar `editors/vscode/syntaxes/ctc.tmLanguage.json` (TextMate,
//! used by VS Code, Sublime Text, GitHub-style highlighters) against the
//! pest grammar `lang/src/ctc.pest`, on every deck of the repository.
//!
//! Reference: the TextMate grammar rules as VS Code's `vscode-textmate`
//! applies them (macromates.com/manual/en/language_grammars): a line at a
//! time, a stack of `begin`/`end` rules, at each position the leftmost match
//! among the current rule's `end` and its patterns (the `end` first on a tie),
//! `captures` naming groups. The tokenizer below implements exactly that
//! subset (the grammar uses no other feature), with `fancy-regex`, whose
//! syntax for what the grammar uses (classes, `\b`, look-ahead and
//! look-behind) is Oniguruma's.
//!
//! ```text
//!   deck text ──pest──▶ ground truth: keyword, number, unit, string, key, comment spans
//!             ──TextMate tokenizer──▶ a scope per byte
//!   every ground-truth byte has its scope, and every byte with one of these
//!   scopes is ground truth of that kind (no false keywords or numbers)
//! ```

use ctc_lang::parse::{CtcParser, Rule, CHUNK_KEYWORDS, ITEM_KEYWORDS};
use fancy_regex::Regex;
use pest::iterators::Pair;
use pest::Parser;
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// The kinds of token both grammars agree on, with the TextMate scope prefix.
const KINDS: [(&str, &str); 6] = [
    ("keyword", "keyword.control.item"),
    ("number", "constant.numeric"),
    ("unit", "keyword.other.unit"),
    ("string", "string.quoted.double"),
    ("key", "variable.other.key"),
    ("comment", "comment.line"),
];

/// A compiled TextMate rule.
enum TmRule {
    /// `match` with a scope for the whole match and scopes for groups.
    Match {
        re: Regex,
        name: Option<String>,
        captures: Vec<(usize, String)>,
    },
    /// `begin` .. `end` with nested patterns.
    Span {
        begin: Regex,
        end: Regex,
        begin_captures: Vec<(usize, String)>,
        end_captures: Vec<(usize, String)>,
        patterns: Vec<String>,
    },
}

/// The grammar: top-level patterns and the repository, by name.
struct Grammar {
    top: Vec<String>,
    repo: BTreeMap<String, TmRule>,
}

fn captures(v: &Value) -> Vec<(usize, String)> {
    v.as_object()
        .map(|o| {
            o.iter()
                .map(|(k, c)| (k.parse().unwrap(), c["name"].as_str().unwrap().to_string()))
                .collect()
        })
        .unwrap_or_default()
}

fn includes(v: &Value) -> Vec<String> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|p| {
            p["include"]
                .as_str()
                .expect("patterns are includes of the repository")
                .trim_start_matches('#')
                .to_string()
        })
        .collect()
}

/// A TextMate regex: Oniguruma's `^` and `$` are line anchors (`$` before
/// the line's newline), fancy-regex's with the `m` flag.
fn regex(s: &str) -> Regex {
    Regex::new(&format!("(?m){s}")).unwrap_or_else(|e| panic!("{s}: {e}"))
}

fn load() -> Grammar {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../editors/vscode/syntaxes/ctc.tmLanguage.json");
    let g: Value = serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
    assert_eq!(g["scopeName"], "source.ctc");
    let mut repo = BTreeMap::new();
    for (name, r) in g["repository"].as_object().unwrap() {
        let rule = if let Some(m) = r["match"].as_str() {
            TmRule::Match {
                re: regex(m),
                name: r["name"].as_str().map(String::from),
                captures: captures(&r["captures"]),
            }
        } else {
            TmRule::Span {
                begin: regex(r["begin"].as_str().unwrap()),
                end: regex(r["end"].as_str().unwrap()),
                begin_captures: captures(&r["beginCaptures"]),
                end_captures: captures(&r["endCaptures"]),
                patterns: includes(&r["patterns"]),
            }
        };
        repo.insert(name.clone(), rule);
    }
    let top = includes(&g["patterns"]);
    for name in top.iter().chain(repo.values().flat_map(|r| match r {
        TmRule::Span { patterns, .. } => patterns.iter().collect::<Vec<_>>(),
        TmRule::Match { .. } => vec![],
    })) {
        assert!(repo.contains_key(name), "#{name} is not in the repository");
    }
    Grammar { top, repo }
}

/// Scope of every byte of `text` (the innermost named one, or "").
fn tokenize(g: &Grammar, text: &str) -> Vec<String> {
    let mut scope = vec![String::new(); text.len()];
    let mut stack: Vec<&str> = Vec::new();
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let mut pos = 0;
        while pos < line.len() {
            let patterns = match stack.last() {
                None => &g.top,
                Some(s) => match &g.repo[*s] {
                    TmRule::Span { patterns, .. } => patterns,
                    TmRule::Match { .. } => unreachable!(),
                },
            };
            // (start, order, what): the end pattern is order 0
            let mut best: Option<(usize, usize, Option<&str>)> = None;
            if let Some(s) = stack.last() {
                if let TmRule::Span { end, .. } = &g.repo[*s] {
                    if let Some(m) = end.find_from_pos(line, pos).unwrap() {
                        best = Some((m.start(), 0, None));
                    }
                }
            }
            for (i, p) in patterns.iter().enumerate() {
                let re = match &g.repo[p] {
                    TmRule::Match { re, .. } => re,
                    TmRule::Span { begin, .. } => begin,
                };
                if let Some(m) = re.find_from_pos(line, pos).unwrap() {
                    if best.is_none_or(|b| m.start() < b.0) {
                        best = Some((m.start(), i + 1, Some(p)));
                    }
                }
            }
            let Some((_, _, what)) = best else { break };
            let mut paint = |re: &Regex, name: Option<&str>, caps: &[(usize, String)]| {
                let c = re.captures_from_pos(line, pos).unwrap().unwrap();
                let whole = c.get(0).unwrap();
                if let Some(n) = name {
                    for s in &mut scope[offset + whole.start()..offset + whole.end()] {
                        *s = n.to_string();
                    }
                }
                for (k, n) in caps {
                    if let Some(m) = c.get(*k) {
                        for s in &mut scope[offset + m.start()..offset + m.end()] {
                            *s = n.clone();
                        }
                    }
                }
                whole.end().max(whole.start() + 1)
            };
            pos = match what {
                None => {
                    let TmRule::Span {
                        end, end_captures, ..
                    } = &g.repo[stack.pop().unwrap()]
                    else {
                        unreachable!()
                    };
                    paint(end, None, end_captures)
                }
                Some(p) => match &g.repo[p] {
                    TmRule::Match { re, name, captures } => paint(re, name.as_deref(), captures),
                    TmRule::Span {
                        begin,
                        begin_captures,
                        ..
                    } => {
                        stack.push(p);
                        paint(begin, None, begin_captures)
                    }
                },
            };
        }
        offset += line.len();
    }
    scope
}

/// Ground truth from the pest parse: (kind, byte range).
fn truth(text: &str) -> Option<Vec<(&'static str, usize, usize)>> {
    let deck = CtcParser::parse(Rule::deck, text).ok()?;
    let mut out = Vec::new();
    let is_keyword = |w: &str| {
        ITEM_KEYWORDS.contains(&w) || CHUNK_KEYWORDS.contains(&w) || ["let", "include"].contains(&w)
    };
    fn walk<'a>(p: Pair<'a, Rule>, text: &str, out: &mut Vec<(&'static str, usize, usize)>) {
        let (a, b) = (p.as_span().start(), p.as_span().end());
        let unsigned = |a: usize| a + usize::from(matches!(text.as_bytes()[a], b'-' | b'+'));
        match p.as_rule() {
            Rule::number | Rule::number_core => return out.push(("number", unsigned(a), b)),
            Rule::unit => return out.push(("unit", a, b)),
            Rule::string => return out.push(("string", a, b)),
            Rule::entry | Rule::named_arg => {
                let name = p.clone().into_inner().next().unwrap();
                let after = text[name.as_span().end()..].trim_start();
                if after.starts_with('=') {
                    out.push(("key", name.as_span().start(), name.as_span().end()));
                }
            }
            _ => {}
        }
        for c in p.into_inner() {
            walk(c, text, out);
        }
    }
    for item in deck.flatten().filter(|p| p.as_rule() == Rule::deck) {
        for p in item.into_inner() {
            let first = p.as_str().split(|c: char| !c.is_alphanumeric() && c != '_');
            let word = first.clone().next().unwrap_or("");
            if p.as_rule() != Rule::EOI && is_keyword(word) {
                let a = p.as_span().start();
                out.push(("keyword", a, a + word.len()));
            }
            walk(p, text, &mut out);
        }
    }
    // comments: pest's COMMENT is silent; `#` to the end of the line,
    // outside strings
    let strings: Vec<(usize, usize)> = out
        .iter()
        .filter(|t| t.0 == "string")
        .map(|t| (t.1, t.2))
        .collect();
    let mut i = 0;
    while let Some(k) = text[i..].find('#') {
        let a = i + k;
        if strings.iter().any(|&(s, e)| s < a && a < e) {
            i = a + 1;
            continue;
        }
        let b = text[a..].find('\n').map_or(text.len(), |n| a + n);
        out.push(("comment", a, b));
        i = b;
    }
    // a number or unit inside a comment or string is not a token
    let covers = |t: &(&str, usize, usize)| {
        out.iter()
            .any(|o| (o.0 == "comment" || o.0 == "string") && o != t && o.1 <= t.1 && t.2 <= o.2)
    };
    Some(out.iter().filter(|t| !covers(t)).cloned().collect())
}

fn decks() -> Vec<PathBuf> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let mut out = Vec::new();
    let mut dirs: Vec<PathBuf> = [
        "examples",
        "tests/decks",
        "verification/cases",
        "lang/tests",
    ]
    .iter()
    .map(|d| root.join(d))
    .collect();
    while let Some(d) = dirs.pop() {
        let Ok(rd) = std::fs::read_dir(&d) else {
            continue;
        };
        for e in rd.flatten() {
            let p = e.path();
            if p.is_dir() {
                dirs.push(p);
            } else if p.extension().is_some_and(|x| x == "ctc") {
                out.push(p);
            }
        }
    }
    out.sort();
    out
}

/// Compares the two grammars on one deck; returns the disagreements.
fn disagreements(g: &Grammar, text: &str) -> Option<Vec<String>> {
    let truth = truth(text)?;
    let scope = tokenize(g, text);
    let mut kind_of = vec![""; text.len()];
    let mut bad = Vec::new();
    let line_of = |a: usize| text[..a].matches('\n').count() + 1;
    for &(kind, a, b) in &truth {
        let want = KINDS.iter().find(|k| k.0 == kind).unwrap().1;
        kind_of[a..b].fill(kind);
        if let Some(i) = (a..b).find(|&i| !scope[i].starts_with(want)) {
            bad.push(format!(
                "line {}: `{}` is a {kind} but the editor grammar says `{}`",
                line_of(a),
                &text[a..b],
                scope[i]
            ));
        }
    }
    for (i, s) in scope.iter().enumerate() {
        if i > 0 && scope[i - 1] == *s {
            continue; // report each token once, at its start
        }
        for (kind, prefix) in KINDS {
            if s.starts_with(prefix)
                && (i..text.len())
                    .take_while(|&j| scope[j] == *s)
                    .any(|j| kind_of[j] != kind)
            {
                let end = (i..text.len())
                    .find(|&j| scope[j] != *s)
                    .unwrap_or(text.len());
                bad.push(format!(
                    "line {}: `{}` is scoped {s} but the deck grammar reads no {kind} there",
                    line_of(i),
                    &text[i..end]
                ));
            }
        }
    }
    bad.dedup();
    Some(bad)
}

#[test]
fn editor_grammar_agrees_with_the_deck_grammar_on_every_deck() {
    let g = load();
    let mut checked = 0;
    let mut counts: BTreeMap<&str, usize> = BTreeMap::new();
    let mut all_bad = Vec::new();
    for path in decks() {
        let text = std::fs::read_to_string(&path).unwrap();
        let Some(bad) = disagreements(&g, &text) else {
            continue; // a deck with a syntax error on purpose
        };
        for t in truth(&text).unwrap() {
            *counts.entry(t.0).or_default() += 1;
        }
        checked += 1;
        all_bad.extend(bad.into_iter().map(|b| format!("{}: {b}", path.display())));
    }
    assert!(checked >= 100, "only {checked} decks parsed");
    for (kind, _) in KINDS {
        assert!(
            counts.get(kind).copied().unwrap_or(0) > 5,
            "{kind}: {counts:?}"
        );
    }
    assert!(
        all_bad.is_empty(),
        "{} disagreements:\n{}",
        all_bad.len(),
        all_bad[..all_bad.len().min(40)].join("\n")
    );
}

/// The comparison itself can fail: a deliberately wrong grammar (numbers
/// scoped as keys) is caught on a small deck.
#[test]
fn a_wrong_editor_grammar_is_caught() {
    let mut g = load();
    g.repo.insert(
        "number".into(),
        TmRule::Match {
            re: regex(r"\d+"),
            name: Some("variable.other.key.ctc".into()),
            captures: vec![],
        },
    );
    let deck = "analysis { dimension = plane_strain }  # a comment with 2 words\n\
                let E = 2 * 100\n\
                material m { elastic { E = 210 GPa  nu = 0.3 } }\n";
    let bad = disagreements(&g, deck).unwrap();
    assert!(bad.iter().any(|b| b.contains("`2` is a number")), "{bad:?}");
    assert!(disagreements(&load(), deck).unwrap().is_empty());
}
