//! Parsing: text -> pest pairs -> generic syntax -> typed [`Deck`].
//!
//! One file per construct converts its item into a typed node, reporting
//! wrong value shapes, unknown keys ("did you mean") and missing required
//! keys as it goes; nothing stops at the first problem.
//!
//! Syntax errors: pest stops at the first one, so when the whole deck does
//! not parse, it is cut into chunks at every line that starts an item
//! (`material x {`, `step {`, ...) and each chunk is parsed on its own. Every
//! chunk that fails gives one syntax error; the others still produce typed
//! items, so semantic errors of the rest of the deck are reported as well.

pub mod analysis;
pub mod body;
pub mod boundary;
pub mod contact;
pub mod discrete;
pub mod errors;
pub mod fields;
pub mod friction;
pub mod load;
pub mod material;
pub mod output;
pub mod set;
pub mod settings;
pub mod step;
pub mod surface;
pub mod syntax;
pub mod thermal;
pub mod tool;
pub mod values;
pub mod velocity;

use crate::ast::syntax::{Block, Value, ValueKind};
use crate::ast::{BoundaryKind, BrokenItem, Deck, LoadKind};
use crate::diagnostics::Diagnostic;
use crate::span::{Ident, Span};
use crate::suggest::did_you_mean;
use pest::iterators::Pair;
use pest::Parser as _;
use values::Diags;

/// The pest grammar `ctc.pest`; [`Rule`] names its rules (generated code).
#[allow(missing_docs)]
pub mod grammar {
    /// The pest parser generated from `ctc.pest`.
    #[derive(pest_derive::Parser)]
    #[grammar = "ctc.pest"]
    pub struct CtcParser;
}

pub use grammar::{CtcParser, Rule};

/// Item keywords, in the order they are listed in messages.
pub const ITEM_KEYWORDS: [&str; 13] = [
    "analysis", "material", "body", "set", "tool", "contact", "fix", "displace", "pressure",
    "traction", "force", "step", "output",
];

/// Keywords that start a chunk of error recovery besides the items.
pub const CHUNK_KEYWORDS: [&str; 10] = [
    "let",
    "include",
    "temperature",
    "heat_flux",
    "convection",
    "initial_velocity",
    "spring",
    "point_mass",
    "rigid_body",
    "gravity",
];

/// Deepest bracket nesting accepted (deeper decks are certainly mistakes,
/// and recursion depth must stay bounded).
pub const MAX_NESTING: usize = 32;

/// The parts of an item header and its block, extracted from its pair.
#[derive(Debug, Clone, Default)]
pub struct ItemParts {
    /// The keyword (`material`, ...) as written.
    pub keyword_text: String,
    /// Span of the keyword.
    pub keyword: Span,
    /// First name after the keyword (item name, or tool after `->`).
    pub name: Option<Ident>,
    /// All names after the keyword in order (tool: its name then its kind).
    pub names: Vec<Ident>,
    /// The set reference of the header, if any.
    pub target: Option<Value>,
    /// `= value` of an unknown item.
    pub value: Option<Value>,
    /// The block.
    pub block: Option<Block>,
    /// The whole item.
    pub span: Span,
    /// Contact master written as a set reference (`a.b -> body.set`); a
    /// bare tool name goes to `names` instead.
    pub master: Option<Value>,
}

impl ItemParts {
    pub(crate) fn of(pair: Pair<'_, Rule>) -> ItemParts {
        let mut parts = ItemParts {
            span: Span::of(pair.as_span()),
            ..ItemParts::default()
        };
        let unknown = pair.as_rule() == Rule::unknown_item;
        for (i, p) in pair.into_inner().enumerate() {
            match p.as_rule() {
                Rule::name if unknown && i == 0 => {
                    parts.keyword = Span::of(p.as_span());
                    parts.keyword_text = p.as_str().to_string();
                }
                Rule::name => parts.names.push(syntax::ident(p)),
                Rule::call | Rule::path | Rule::set_expr => parts.target = Some(syntax::value(p)),
                Rule::value => parts.value = Some(syntax::value(p)),
                Rule::block => parts.block = Some(syntax::block(p)),
                Rule::master => {
                    let Some(inner) = p.into_inner().next() else {
                        continue;
                    };
                    let v = syntax::value(inner);
                    match &v.kind {
                        ValueKind::Path(path) if path.len() == 1 => {
                            parts.names.push(path[0].clone())
                        }
                        _ => parts.master = Some(v),
                    }
                }
                _ => {
                    parts.keyword = Span::of(p.as_span());
                    parts.keyword_text = p.as_str().to_string();
                }
            }
        }
        parts.name = parts.names.first().cloned();
        parts
    }
}

/// Parses a whole deck. Returns the typed deck (with whatever could be
/// understood) and the diagnostics found on the way.
pub fn parse(text: &str) -> (Deck, Vec<Diagnostic>) {
    let mut deck = Deck::default();
    let mut diags = Diags::new();
    if let Some(d) = nesting_error(text) {
        return (deck, vec![d]);
    }
    match CtcParser::parse(Rule::deck, text) {
        Ok(pairs) => {
            let items: Vec<Pair<'_, Rule>> =
                pairs.flatten().filter(|p| is_item(p.as_rule())).collect();
            convert_items(items, &mut deck, &mut diags);
        }
        Err(whole) => recover(text, &whole, &mut deck, &mut diags),
    }
    (deck, diags.into_vec())
}

/// Converts items in deck order, except that the unit system of the
/// `analysis` block is read first (every number of the deck is in it).
fn convert_items(items: Vec<Pair<'_, Rule>>, deck: &mut Deck, diags: &mut Diags) {
    if diags.env.system.is_none() {
        diags.env.system = items
            .iter()
            .filter(|p| p.as_rule() == Rule::analysis)
            .find_map(|p| analysis::unit_system(p.clone()));
    }
    for pair in items {
        convert_item(pair, deck, diags);
    }
}

fn is_item(rule: Rule) -> bool {
    matches!(
        rule,
        Rule::let_item
            | Rule::include_item
            | Rule::analysis
            | Rule::material
            | Rule::body
            | Rule::set
            | Rule::tool
            | Rule::contact
            | Rule::fix
            | Rule::displace
            | Rule::pressure
            | Rule::force
            | Rule::step
            | Rule::output
            | Rule::unknown_item
    )
}

/// Converts one item pair into the deck.
fn convert_item(pair: Pair<'_, Rule>, deck: &mut Deck, diags: &mut Diags) {
    let rule = pair.as_rule();
    match rule {
        Rule::let_item => return let_item(pair, deck, diags),
        // the included text follows the statement (inserted by `Source`)
        Rule::include_item => return,
        _ => {}
    }
    let parts = ItemParts::of(pair);
    let broken = BrokenItem {
        keyword: parts.keyword_text.clone(),
        name: parts.name.as_ref().map(|n| n.name.clone()),
        span: parts.span,
    };
    let ok = match rule {
        Rule::analysis => analysis::parse(parts, diags).map(|x| deck.analysis.push(x)),
        Rule::material => material::parse(parts, diags).map(|x| deck.materials.push(x)),
        Rule::body => body::parse(parts, diags).map(|x| deck.bodies.push(x)),
        Rule::set => set::parse(parts, diags).map(|x| deck.sets.push(x)),
        Rule::tool => tool::parse(parts, diags).map(|x| deck.tools.push(x)),
        Rule::contact => contact::parse(parts, diags).map(|x| deck.contacts.push(x)),
        Rule::fix => {
            boundary::parse(parts, BoundaryKind::Fix, diags).map(|x| deck.boundaries.push(x))
        }
        Rule::displace => {
            boundary::parse(parts, BoundaryKind::Displace, diags).map(|x| deck.boundaries.push(x))
        }
        Rule::pressure => load::parse(parts, LoadKind::Pressure, diags).map(|x| deck.loads.push(x)),
        Rule::force => load::parse(parts, LoadKind::Force, diags).map(|x| deck.loads.push(x)),
        Rule::step => step::parse(parts, diags).map(|x| deck.steps.push(x)),
        Rule::output => output::parse(parts, diags).map(|x| deck.outputs.push(x)),
        // `traction` is not a grammar keyword (an older deck may use the
        // word as a name): the generic item rule carries it
        _ if parts.keyword_text == velocity::KEYWORD => {
            velocity::parse(parts, diags).map(|x| deck.initial_velocities.push(x))
        }
        _ if discrete::KEYWORDS.contains(&parts.keyword_text.as_str()) => {
            discrete::parse(parts, diags).map(|x| deck.discrete.push(x))
        }
        _ if parts.keyword_text == load::GRAVITY => {
            load::gravity(parts, diags).map(|x| deck.gravity.push(x))
        }
        _ if parts.keyword_text == "traction" => {
            load::parse(parts, LoadKind::Traction, diags).map(|x| deck.loads.push(x))
        }
        _ if thermal::ITEMS.contains(&parts.keyword_text.as_str()) => {
            thermal::item(parts, diags).map(|x| deck.thermal_loads.push(x))
        }
        _ => {
            unknown_item(parts, deck, diags);
            Some(())
        }
    };
    if ok.is_none() {
        deck.broken.push(broken);
    }
}

/// `let name = expression`: evaluates the expression now (parameters are
/// known to the items after it) and records it.
fn let_item(pair: Pair<'_, Rule>, deck: &mut Deck, diags: &mut Diags) {
    let span = Span::of(pair.as_span());
    let mut inner = pair.into_inner().skip(1);
    let (Some(n), Some(v)) = (inner.next(), inner.next()) else {
        return;
    };
    let name = syntax::ident(n);
    let value = syntax::value(v);
    if let Some(first) = deck.lets.iter().find(|l| l.name.name == name.name) {
        diags.push(
            Diagnostic::error(
                format!("parameter `{}` is defined twice", name.name),
                name.span,
                "second definition",
            )
            .with_secondary(first.name.span, "first definition")
            .with_help("a parameter is defined once; rename one of them"),
        );
        return;
    }
    if crate::expr::RESERVED.contains(&name.name.as_str()) {
        diags.push(
            Diagnostic::error(
                format!("`{}` is a built-in name", name.name),
                name.span,
                "reserved",
            )
            .with_help("choose another parameter name"),
        );
        return;
    }
    let (env, out) = diags.split();
    let q = crate::expr::eval(&value, env, out);
    if let Some(q) = q {
        diags.env.params.push((name.clone(), q));
    }
    deck.lets.push(crate::ast::Let { name, value, span });
}

/// `materal steel { .. }`: an unknown item keyword.
fn unknown_item(parts: ItemParts, deck: &mut Deck, diags: &mut Diags) {
    let word = parts.keyword_text.clone();
    let suggestion = crate::suggest::closest(&word, ITEM_KEYWORDS);
    diags.push(
        Diagnostic::error(
            format!("unknown item `{word}`"),
            parts.keyword,
            "not an item keyword",
        )
        .with_help(did_you_mean(&word, ITEM_KEYWORDS).unwrap_or_else(|| {
            "items are `analysis`, `material`, `body`, `set`, `tool`, `contact`, `fix`, \
                 `displace`, `pressure`, `traction`, `force`, `step` and `output`"
                .to_string()
        })),
    );
    // The name of what was meant: `materal steel {..}` -> material `steel`.
    let name = match parts.target.as_ref().map(|v| &v.kind) {
        Some(ValueKind::Path(p)) if p.len() == 1 => Some(p[0].name.clone()),
        _ => None,
    };
    deck.broken.push(BrokenItem {
        keyword: suggestion.unwrap_or(word),
        name,
        span: parts.span,
    });
}

/// Serialises the parses made with pest's error detail on (the switch is
/// process-global).
static DETAIL: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// The error of a parse that failed, again with pest's error detail (the
/// expected literal tokens of the message) switched on for this parse only:
/// the detail makes every token attempt of a parse record itself, several
/// times slower, so only a parse already known to fail pays for it, and
/// later parses of the process (a sweep's decks, a fuzzer's inputs) do not
/// (fuzz/README.md). `None` if it parses after all.
fn detailed_error(rule: Rule, text: &str) -> Option<pest::error::Error<Rule>> {
    let _only_one = DETAIL.lock().unwrap_or_else(|e| e.into_inner());
    pest::set_error_detail(true);
    let e = CtcParser::parse(rule, text).err();
    pest::set_error_detail(false);
    e
}

/// Error recovery after the whole deck failed to parse: parse each chunk
/// starting at an item line on its own.
fn recover(text: &str, whole: &pest::error::Error<Rule>, deck: &mut Deck, diags: &mut Diags) {
    let mut failed = 0;
    for (start, end) in chunks(text) {
        // The chunk alone (its spans moved to their place in the deck)
        match CtcParser::parse(Rule::items, &text[start..end]) {
            Ok(pairs) => {
                let items: Vec<Pair<'_, Rule>> =
                    pairs.flatten().filter(|p| is_item(p.as_rule())).collect();
                crate::span::at_offset(start, || convert_items(items, deck, diags));
            }
            Err(plain) => {
                failed += 1;
                // the message is worked out on the deck up to the chunk's
                // end with everything before the chunk blanked out
                let e = detailed_error(Rule::items, &text[start..end]).unwrap_or(plain);
                let padded = pad(text, start, end);
                diags.push(chunk_error(&padded, &e, start, end, text.len()));
                deck.broken.extend(broken_chunk(text, start, end));
            }
        }
    }
    if failed == 0 {
        // The chunks parse on their own but not together (items sharing a
        // line across a cut): report the error of the whole deck.
        let again = detailed_error(Rule::deck, text);
        let e = again.as_ref().unwrap_or(whole);
        diags.push(errors::syntax_error(e, text));
        *deck = Deck {
            broken: vec![BrokenItem {
                keyword: String::new(),
                name: None,
                span: Span::new(0, text.len()),
            }],
            ..Deck::default()
        };
    }
}

/// A copy of `text` with every byte outside `start..end` replaced by a space
/// (byte offsets are preserved, and the result is valid UTF-8 because whole
/// characters are replaced byte by byte).
fn pad(text: &str, start: usize, end: usize) -> String {
    let mut out = String::with_capacity(end);
    for (i, c) in text[..end].char_indices() {
        if i < start {
            for _ in 0..c.len_utf8() {
                out.push(' ');
            }
        } else {
            out.push(c);
        }
    }
    out
}

/// Byte ranges of the chunks: a new chunk starts at every line whose first
/// word is an item keyword not followed by `=` (so `material = steel` inside
/// a body does not start one).
pub fn chunks(text: &str) -> Vec<(usize, usize)> {
    let mut starts = vec![0];
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        let indent = line.len() - trimmed.len();
        let word: String = trimmed
            .chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect();
        if ITEM_KEYWORDS.contains(&word.as_str()) || CHUNK_KEYWORDS.contains(&word.as_str()) {
            let after = trimmed[word.len()..].trim_start();
            if !after.starts_with('=') && offset + indent > 0 {
                starts.push(offset + indent);
            }
        }
        offset += line.len();
    }
    starts.dedup();
    let mut out = Vec::new();
    for (i, &s) in starts.iter().enumerate() {
        let e = starts.get(i + 1).copied().unwrap_or(text.len());
        out.push((s, e));
    }
    out
}

/// The items a failing chunk may have contained (every item keyword in it,
/// with the word after it as the name), to silence references to them and
/// "the deck has no ..." errors.
fn broken_chunk(text: &str, start: usize, end: usize) -> Vec<BrokenItem> {
    let chunk = &text[start..end];
    let words: Vec<&str> = chunk
        .split(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .filter(|w| !w.is_empty())
        .collect();
    let mut out = Vec::new();
    for (i, w) in words.iter().enumerate() {
        if ITEM_KEYWORDS.contains(w) {
            let name = match *w {
                "material" | "body" | "tool" | "step" | "set" => {
                    words.get(i + 1).map(|n| n.to_string())
                }
                _ => None,
            };
            out.push(BrokenItem {
                keyword: w.to_string(),
                name,
                span: Span::new(start, end),
            });
        }
    }
    if out.is_empty() {
        out.push(BrokenItem {
            keyword: words.first().map_or(String::new(), |w| w.to_string()),
            name: None,
            span: Span::new(start, end),
        });
    }
    out
}

/// An opening bracket found while scanning.
#[derive(Debug, Clone, Copy)]
struct Open {
    ch: char,
    at: usize,
}

/// What [`scan_brackets`] found.
struct Scan {
    /// Brackets still open at the end, innermost last.
    open: Vec<Open>,
    /// Where the nesting first got deeper than the limit.
    too_deep: Option<usize>,
    /// Opening quote of the first string not closed on its line.
    unterminated: Option<usize>,
}

/// Scans `text[start..end]` for brackets, skipping comments and strings.
fn scan_brackets(text: &str, start: usize, end: usize, limit: usize) -> Scan {
    let mut stack: Vec<Open> = Vec::new();
    let mut too_deep = None;
    let mut unterminated = None;
    let mut in_comment = false;
    let mut string_start: Option<usize> = None;
    for (i, c) in text[start..end].char_indices() {
        let at = start + i;
        if in_comment {
            in_comment = c != '\n';
            continue;
        }
        if let Some(q) = string_start {
            if c == '\n' && unterminated.is_none() {
                unterminated = Some(q);
            }
            if c == '"' || c == '\n' {
                string_start = None;
            }
            continue;
        }
        match c {
            '#' => in_comment = true,
            '"' => string_start = Some(at),
            '{' | '(' | '[' => {
                stack.push(Open { ch: c, at });
                if stack.len() > limit && too_deep.is_none() {
                    too_deep = Some(at);
                }
            }
            '}' | ')' | ']' => {
                let want = match c {
                    '}' => '{',
                    ')' => '(',
                    _ => '[',
                };
                if stack.last().is_some_and(|o| o.ch == want) {
                    stack.pop();
                }
            }
            _ => {}
        }
    }
    if let (Some(q), None) = (string_start, unterminated) {
        unterminated = Some(q);
    }
    Scan {
        open: stack,
        too_deep,
        unterminated,
    }
}

fn nesting_error(text: &str) -> Option<Diagnostic> {
    scan_brackets(text, 0, text.len(), MAX_NESTING)
        .too_deep
        .map(|at| {
            Diagnostic::error(
                format!("brackets nested more than {MAX_NESTING} deep"),
                Span::new(at, at + 1),
                "too deep",
            )
            .with_help("check for missing closing brackets")
        })
}

/// The diagnostic for a chunk that failed to parse: an unclosed bracket if
/// the parser ran off the end of the chunk with brackets still open,
/// otherwise the parser's own expected/found error.
///
/// `e` is the error of the chunk parsed on its own (positions from
/// `start`); `padded` the deck up to `end`, blank before `start`.
fn chunk_error(
    padded: &str,
    e: &pest::error::Error<Rule>,
    start: usize,
    end: usize,
    total: usize,
) -> Diagnostic {
    let pos = errors::error_position(e) + start;
    let rest_is_blank = padded.get(pos..).is_some_and(|r| {
        r.lines()
            .all(|l| l.trim().is_empty() || l.trim_start().starts_with('#'))
    });
    let scan = scan_brackets(padded, start, end, usize::MAX);
    if let Some(q) = scan.unterminated.filter(|q| *q <= pos) {
        return Diagnostic::error(
            "unterminated string",
            Span::new(q, q + 1),
            "this string is not closed",
        )
        .with_help("close it with `\"` on the same line");
    }
    if rest_is_blank {
        if let Some(o) = scan.open.last() {
            let close = match o.ch {
                '{' => '}',
                '(' => ')',
                _ => ']',
            };
            let whr = if end >= total {
                "before the end of the file"
            } else {
                "before the next item"
            };
            return Diagnostic::error(
                format!("unclosed `{}`", o.ch),
                Span::new(o.at, o.at + 1),
                format!("this `{}` is never closed", o.ch),
            )
            .with_help(format!("add `{close}` {whr}"));
        }
    }
    errors::syntax_error_at(e, start, padded)
}

#[cfg(test)]
pub(crate) mod test_support {
    //! Helpers for the construct tests.
    use super::*;

    /// Parses `text` as a single value.
    pub fn value_of(text: &str) -> Value {
        let deck = format!("x {{ v = {text} }}");
        let pair = CtcParser::parse(Rule::deck, &deck)
            .unwrap_or_else(|e| panic!("{e}"))
            .flatten()
            .find(|p| p.as_rule() == Rule::value)
            .expect("a value");
        syntax::value(pair)
    }

    /// Parses `text` as a block.
    pub fn block_of(text: &str) -> Block {
        let deck = format!("x {text}");
        let pair = CtcParser::parse(Rule::deck, &deck)
            .unwrap_or_else(|e| panic!("{e}"))
            .flatten()
            .find(|p| p.as_rule() == Rule::block)
            .expect("a block");
        syntax::block(pair)
    }

    /// Parses a deck that must produce no diagnostics.
    pub fn parse_ok(text: &str) -> Deck {
        let (deck, diags) = parse(text);
        assert!(diags.is_empty(), "unexpected diagnostics: {diags:#?}");
        deck
    }

    /// The messages of the diagnostics of parsing `text`.
    pub fn parse_messages(text: &str) -> Vec<String> {
        parse(text).1.into_iter().map(|d| d.message).collect()
    }
}

#[cfg(test)]
mod tests {
    use super::test_support::*;
    use super::*;

    #[test]
    fn comments_and_number_forms() {
        let deck = parse_ok(
            "# a comment\nanalysis { # trailing\n dimension = plane_strain thickness = 1.2E+3 }\n# end",
        );
        assert_eq!(deck.analysis[0].thickness.as_ref().unwrap().value, 1200.0);
        let v = value_of("0..1");
        assert!(matches!(v.kind, ValueKind::Range(..)));
        let v = value_of("1.");
        assert_eq!(v.kind, ValueKind::Number(1.0));
    }

    #[test]
    fn chunks_start_at_item_lines_only() {
        let text = "material m {\n  elastic { E = 1 nu = 0.3 }\n}\nbody b {\n  material = m\n}\n";
        let c = chunks(text);
        assert_eq!(c.len(), 2);
        assert!(text[c[1].0..].starts_with("body b"));
    }

    #[test]
    fn syntax_error_names_expected_tokens() {
        let (_, d) = parse("material steel { elastic { E 210e3 nu = 0.3 } }");
        assert_eq!(d.len(), 1);
        assert_eq!(
            d[0].message,
            "expected `=`, `{`, `}` or a name, found `210e3`"
        );
    }

    #[test]
    fn recovery_reports_errors_of_several_items() {
        let text = "material m { elastic { E = , nu = 0.3 } }\nbody b {\n  mesh = rectangle { size = (1, 1) divisions = (1, 1) }\n  material = m\n}\ntool t = circle { center = (0 0) radius = 1 }\nstep s { time = 0 .. 1  incremnts = 2 }\n";
        let (deck, d) = parse(text);
        let msgs: Vec<&str> = d.iter().map(|x| x.message.as_str()).collect();
        assert_eq!(
            msgs,
            [
                "expected a value, found `,`",
                "expected `)`, `,` or `..`, found `0`",
                "unknown key `incremnts` in the step `s`"
            ]
        );
        assert_eq!(deck.bodies.len(), 1);
        assert!(deck.broken_named("material", "m"));
        assert!(deck.broken_named("tool", "t"));
    }

    #[test]
    fn unclosed_block_points_at_the_open_brace() {
        let text = "material m {\n  elastic { E = 1  nu = 0.3 }\n\nbody b { material = m  mesh = file \"x.msh\" }\n";
        let (deck, d) = parse(text);
        assert_eq!(d.len(), 1, "{d:?}");
        assert_eq!(deck.bodies.len(), 1);
        assert_eq!(d[0].message, "unclosed `{`");
        assert_eq!(d[0].span, Span::new(11, 12));
    }

    #[test]
    fn unknown_item_suggests_keyword() {
        let (deck, d) = parse("materal steel { elastic { E = 1 nu = 0.3 } }");
        assert_eq!(d[0].message, "unknown item `materal`");
        assert_eq!(d[0].help.as_deref(), Some("did you mean `material`?"));
        assert!(deck.broken_named("material", "steel"));
    }

    #[test]
    fn deep_nesting_is_an_error_not_a_crash() {
        let text = format!("x {{ v = {}1{} }}", "(".repeat(5000), ")".repeat(5000));
        let (_, d) = parse(&text);
        assert_eq!(d.len(), 1);
        assert!(d[0].message.contains("nested"));
    }
}
