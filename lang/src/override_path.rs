//! Overrides of deck values by path, for `ctc sweep --vary`.
//!
//! A path names one value of the deck's syntax tree:
//!
//! ```text
//! contact.method.stiffness          the only contact item, key method, its block, key stiffness
//! contact[1].method.stiffness       the second contact item (deck order)
//! contact[floor].method.stiffness   the contact item whose slave, master or `slave->master` is `floor`
//! material.soft.elastic.E           = material[soft].elastic.E
//! soft.elastic.E                    any item named `soft`
//! body.disc.mesh.radial             into a constructor value (`mesh = half_disc { .. }`)
//! tool[floor].normal[1]             element 1 of a tuple value
//! step[press].increments
//! k                                 a `let k = ..` parameter of the deck
//! ```
//!
//! The value is replaced *in the text*, so comments and layout stay, and
//! the variant deck compiles (and reports errors) like any deck. An unknown
//! step of a path is an error pointing at the block where it was looked
//! for, with "did you mean".

use crate::ast::syntax::{Block, EntryBody, Value, ValueKind};
use crate::diagnostics::Diagnostic;
use crate::parse::{CtcParser, ItemParts, Rule};
use crate::source::Source;
use crate::span::Span;
use crate::suggest::{did_you_mean, one_of};
use pest::Parser as _;

/// One `--vary` option: a path and the values it takes in turn.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Variation {
    /// The path (`contact.method.stiffness`).
    pub path: String,
    /// The values as deck text (`1e4`, `(0, 1)`, `ramp(0, -0.1)`).
    pub values: Vec<String>,
}

/// Parses `PATH = v1, v2, ...` (commas inside brackets or quotes do not
/// split: `center = (0, 8), (0, 9)` has two values).
pub fn parse_variation(spec: &str) -> Result<Variation, String> {
    let Some((path, values)) = spec.split_once('=') else {
        return Err(format!(
            "`--vary {spec}`: expected `PATH = value, value, ...` (e.g. `contact.method.stiffness = 1e4, 1e5`)"
        ));
    };
    let path = path.trim().to_string();
    if path.is_empty() {
        return Err(format!("`--vary {spec}`: the path before `=` is empty"));
    }
    let mut out = Vec::new();
    let (mut depth, mut quoted, mut current) = (0i32, false, String::new());
    for ch in values.chars() {
        match ch {
            '"' => quoted = !quoted,
            '(' | '[' | '{' if !quoted => depth += 1,
            ')' | ']' | '}' if !quoted => depth -= 1,
            ',' if !quoted && depth == 0 => {
                out.push(std::mem::take(&mut current).trim().to_string());
                continue;
            }
            _ => {}
        }
        current.push(ch);
    }
    out.push(current.trim().to_string());
    if let Some(i) = out.iter().position(String::is_empty) {
        return Err(format!("`--vary {spec}`: value {} is empty", i + 1));
    }
    Ok(Variation { path, values: out })
}

/// `name` or `name[selector]`, one step of a path.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Segment {
    name: String,
    select: Option<Select>,
}

#[derive(Debug, Clone, PartialEq, Eq)]
enum Select {
    Index(usize),
    Name(String),
}

fn parse_path(path: &str) -> Result<Vec<Segment>, String> {
    let mut segments = Vec::new();
    let mut rest = path.trim();
    while !rest.is_empty() {
        let end = rest.find(['.', '[']).unwrap_or(rest.len());
        let name = rest[..end].trim().to_string();
        if name.is_empty() {
            return Err(format!("path `{path}`: empty step"));
        }
        rest = &rest[end..];
        let mut select = None;
        if let Some(r) = rest.strip_prefix('[') {
            let Some(close) = r.find(']') else {
                return Err(format!("path `{path}`: `[` without `]`"));
            };
            let sel = r[..close].trim().trim_matches('"');
            select = Some(match sel.parse::<usize>() {
                Ok(i) => Select::Index(i),
                Err(_) => Select::Name(sel.split_whitespace().collect()),
            });
            rest = &r[close + 1..];
        }
        if let Some(r) = rest.strip_prefix('.') {
            if r.is_empty() {
                return Err(format!("path `{path}` ends with `.`"));
            }
            rest = r;
        } else if !rest.is_empty() {
            return Err(format!("path `{path}`: expected `.` after `{name}`"));
        }
        segments.push(Segment { name, select });
    }
    if segments.is_empty() {
        return Err("empty path".into());
    }
    Ok(segments)
}

/// An item of the deck as the path sees it.
struct Item {
    parts: ItemParts,
    /// Names that select it (`soft`; a contact: slave, master, `slave->master`).
    ids: Vec<String>,
    /// Its header as written, for listings.
    label: String,
}

fn items(text: &str) -> Result<Vec<Item>, String> {
    let pairs = CtcParser::parse(Rule::deck, text).map_err(|_| {
        "the deck does not parse: fix it first (`ctc check` shows the errors)".to_string()
    })?;
    let squash = |s: &str| s.split_whitespace().collect::<String>();
    let mut out = Vec::new();
    for deck in pairs {
        for pair in deck.into_inner().filter(|p| p.as_rule() != Rule::EOI) {
            let parts = ItemParts::of(pair);
            let mut ids: Vec<String> = parts
                .names
                .first()
                .map(|n| n.name.clone())
                .into_iter()
                .collect();
            if parts.keyword_text == "contact" {
                let slave = parts.target.as_ref().map(|t| squash(t.span.text(text)));
                let master = parts
                    .master
                    .as_ref()
                    .map(|m| squash(m.span.text(text)))
                    .or_else(|| parts.names.first().map(|n| n.name.clone()));
                if let (Some(s), Some(m)) = (&slave, &master) {
                    ids.push(format!("{s}->{m}"));
                }
                ids.extend(slave);
                ids.extend(master);
            } else if ids.is_empty() {
                // `let k = ..` read as a generic item, `fix block.left { .. }`
                ids.extend(parts.target.as_ref().map(|t| squash(t.span.text(text))));
            }
            let header_end = parts
                .block
                .as_ref()
                .map_or(parts.span.end, |b| b.span.start);
            let label = parts.span.text(text)[..header_end - parts.span.start]
                .split_whitespace()
                .collect::<Vec<_>>()
                .join(" ");
            out.push(Item { parts, ids, label });
        }
    }
    Ok(out)
}

/// Why a path does not resolve.
struct Miss {
    message: String,
    at: Option<(Span, String)>,
    help: Option<String>,
}

impl Miss {
    fn plain(message: String, help: Option<String>) -> Miss {
        Miss {
            message,
            at: None,
            help,
        }
    }

    fn render(self, src: &Source) -> String {
        match self.at {
            Some((span, label)) => Diagnostic::error(self.message, span, label)
                .with_help_opt(self.help)
                .render(src),
            None => {
                let mut s = format!("error: {}", self.message);
                if let Some(h) = self.help {
                    s.push_str(&format!("\n  = help: {h}"));
                }
                s
            }
        }
    }
}

/// Returns the deck text with the value at `path` replaced by `value`
/// (deck syntax), or a rendered error (an unknown path, with "did you mean",
/// or a value that is not deck syntax).
pub fn apply_override(src: &Source, path: &str, value: &str) -> Result<String, String> {
    let value = value.trim();
    let parsed_ok = CtcParser::parse(Rule::value, value)
        .ok()
        .and_then(|mut p| p.next())
        .is_some_and(|p| p.as_str().len() == value.len());
    if !parsed_ok {
        return Err(format!(
            "error: `{value}` (for `{path}`) is not a deck value (a number, name, string, tuple, list, call or block)"
        ));
    }
    let segments = parse_path(path).map_err(|e| format!("error: {e}"))?;
    let items = items(&src.text).map_err(|e| format!("error: {e}"))?;
    let span = resolve(&items, &segments, path).map_err(|m| m.render(src))?;
    let mut text = String::with_capacity(src.text.len() + value.len());
    text.push_str(&src.text[..span.start]);
    text.push_str(value);
    text.push_str(&src.text[span.end..]);
    Ok(text)
}

/// The span of the value named by `segments`.
fn resolve(items: &[Item], segments: &[Segment], path: &str) -> Result<Span, Miss> {
    let (item, used) = pick_item(items, segments)?;
    let rest = &segments[used..];
    let shown: Vec<String> = segments[..used].iter().map(show).collect();
    let mut here = shown.join(".");
    if rest.is_empty() {
        return match &item.parts.value {
            Some(v) => Ok(v.span),
            None => Err(Miss {
                message: format!("`{path}` names the item `{}`, not a value", item.label),
                at: item
                    .parts
                    .block
                    .as_ref()
                    .map(|b| (b.span, "name one of its keys".to_string())),
                help: item
                    .parts
                    .block
                    .as_ref()
                    .map(|b| format!("keys here: {}", keys_of(b))),
            }),
        };
    }
    let Some(mut block) = item.parts.block.as_ref() else {
        return Err(Miss {
            message: format!(
                "the item `{}` has no block: `{path}` cannot go inside it",
                item.label
            ),
            at: Some((item.parts.span, "this item".into())),
            help: None,
        });
    };
    for (k, seg) in rest.iter().enumerate() {
        let last = k + 1 == rest.len();
        let found: Vec<_> = block
            .entries
            .iter()
            .filter(|e| e.key.name == seg.name)
            .collect();
        let entry = match found.as_slice() {
            [] => {
                let where_ = if here.is_empty() {
                    "the item".to_string()
                } else {
                    format!("`{here}`")
                };
                return Err(Miss {
                    message: format!("no key `{}` in {where_} (path `{path}`)", seg.name),
                    at: Some((block.span, format!("keys here: {}", keys_of(block)))),
                    help: did_you_mean(
                        &seg.name,
                        block.entries.iter().map(|e| e.key.name.as_str()),
                    ),
                });
            }
            [e] => *e,
            many => {
                return Err(Miss {
                    message: format!("`{}` is written {} times in `{here}`", seg.name, many.len()),
                    at: Some((many[1].span, "again here".into())),
                    help: None,
                })
            }
        };
        if !here.is_empty() {
            here.push('.');
        }
        here.push_str(&show(seg));
        match &entry.body {
            EntryBody::Block(b) => {
                if last {
                    return Err(Miss {
                        message: format!("`{here}` is a block, not a value"),
                        at: Some((b.span, format!("name one of its keys: {}", keys_of(b)))),
                        help: None,
                    });
                }
                if seg.select.is_some() {
                    return Err(Miss {
                        message: format!("`{here}`: a block has no elements to index"),
                        at: Some((entry.key.span, "a block".into())),
                        help: None,
                    });
                }
                block = b;
            }
            EntryBody::Flag => {
                return Err(Miss {
                    message: format!("`{here}` is a bare flag, it has no value"),
                    at: Some((entry.span, "a flag".into())),
                    help: None,
                })
            }
            EntryBody::Assign(v) => {
                let target = element(v, seg, &here)?;
                if last {
                    return Ok(target.span);
                }
                match &target.kind {
                    ValueKind::Ctor { block: b, .. } => block = b,
                    other => {
                        return Err(Miss {
                            message: format!(
                                "`{here}` is {}, it has no key `{}`",
                                other.describe(),
                                rest[k + 1].name
                            ),
                            at: Some((target.span, "this value".into())),
                            help: None,
                        })
                    }
                }
            }
        }
    }
    unreachable!("the loop returns at the last segment")
}

/// The value of an entry, or its element `[i]` for a tuple or list.
fn element<'a>(v: &'a Value, seg: &Segment, here: &str) -> Result<&'a Value, Miss> {
    match (&seg.select, &v.kind) {
        (None, _) => Ok(v),
        (Some(Select::Index(i)), ValueKind::Tuple(xs) | ValueKind::List(xs)) => {
            xs.get(*i).ok_or_else(|| Miss {
                message: format!(
                    "`{here}`: index {i} but the value has {} elements",
                    xs.len()
                ),
                at: Some((v.span, format!("{} elements", xs.len()))),
                help: None,
            })
        }
        (Some(_), kind) => Err(Miss {
            message: format!(
                "`{here}`: only a tuple or a list has elements, this is {}",
                kind.describe()
            ),
            at: Some((v.span, "this value".into())),
            help: None,
        }),
    }
}

fn show(s: &Segment) -> String {
    match &s.select {
        None => s.name.clone(),
        Some(Select::Index(i)) => format!("{}[{i}]", s.name),
        Some(Select::Name(n)) => format!("{}[{n}]", s.name),
    }
}

fn keys_of(b: &Block) -> String {
    let keys: Vec<&str> = b.entries.iter().map(|e| e.key.name.as_str()).collect();
    if keys.is_empty() {
        "none".into()
    } else {
        keys.join(", ")
    }
}

/// The item named by the first one or two segments, and how many were used.
fn pick_item<'a>(items: &'a [Item], segments: &[Segment]) -> Result<(&'a Item, usize), Miss> {
    let first = &segments[0];
    let of_kind: Vec<&Item> = items
        .iter()
        .filter(|i| i.parts.keyword_text == first.name)
        .collect();
    let listing = |c: &[&Item]| {
        c.iter()
            .enumerate()
            .map(|(i, it)| format!("{}[{i}] = `{}`", first.name, it.label))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if !of_kind.is_empty() {
        match &first.select {
            Some(Select::Index(i)) => {
                return of_kind.get(*i).map(|it| (*it, 1)).ok_or_else(|| {
                    Miss::plain(
                        format!(
                            "`{}[{i}]`: the deck has {} `{}` items",
                            first.name,
                            of_kind.len(),
                            first.name
                        ),
                        Some(listing(&of_kind)),
                    )
                })
            }
            Some(Select::Name(n)) => {
                let hits: Vec<&Item> = of_kind
                    .iter()
                    .copied()
                    .filter(|it| it.ids.contains(n))
                    .collect();
                return match hits.as_slice() {
                    [it] => Ok((*it, 1)),
                    [] => Err(Miss::plain(
                        format!("no `{}` item is called `{n}`", first.name),
                        did_you_mean(n, of_kind.iter().flat_map(|it| it.ids.iter()))
                            .or(Some(listing(&of_kind))),
                    )),
                    _ => Err(Miss::plain(
                        format!("`{n}` names several `{}` items", first.name),
                        Some(format!("pick one by index: {}", listing(&hits))),
                    )),
                };
            }
            None => {
                if let Some(next) = segments.get(1) {
                    let named: Vec<&Item> = of_kind
                        .iter()
                        .copied()
                        .filter(|it| it.ids.contains(&next.name))
                        .collect();
                    if named.len() == 1 && next.select.is_none() {
                        return Ok((named[0], 2));
                    }
                }
                if of_kind.len() == 1 {
                    return Ok((of_kind[0], 1));
                }
                return Err(Miss::plain(
                    format!(
                        "the deck has {} `{}` items: say which one",
                        of_kind.len(),
                        first.name
                    ),
                    Some(format!(
                        "{} (or by name: `{}[NAME]`)",
                        listing(&of_kind),
                        first.name
                    )),
                ));
            }
        }
    }
    let named: Vec<&Item> = items
        .iter()
        .filter(|it| it.ids.contains(&first.name))
        .collect();
    match named.as_slice() {
        [it] if first.select.is_none() => Ok((*it, 1)),
        [] | [_] => {
            let mut names: Vec<&str> = items
                .iter()
                .map(|i| i.parts.keyword_text.as_str())
                .collect();
            names.extend(items.iter().flat_map(|i| i.ids.iter().map(String::as_str)));
            names.sort_unstable();
            names.dedup();
            Err(Miss::plain(
                format!("the deck has no item or name `{}`", first.name),
                did_you_mean(&first.name, names.iter().copied())
                    .or_else(|| Some(format!("a path starts with one of {}", one_of(&names)))),
            ))
        }
        many => Err(Miss::plain(
            format!("`{}` names {} items", first.name, many.len()),
            Some(format!(
                "say which: {}",
                many.iter()
                    .map(|it| format!("`{}`", it.label))
                    .collect::<Vec<_>>()
                    .join(", ")
            )),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DECK: &str = "\
# a comment that stays
analysis { dimension = plane_strain }
material soft { elastic { E = 200  nu = 0.3 } }
body disc {
  mesh = half_disc { center = (0, 8)  radius = 8  radial = 4  circumferential = 8 }
  material = soft
}
tool floor = plane { point = (0, 0)  normal = (0, 1) }
tool wall = plane { point = (9, 0)  normal = (-1, 0) }
contact disc.arc -> floor {
  method = penalty { kind = area  stiffness = 2e4 }
}
contact disc.arc -> wall { method = penalty { stiffness = 1e3 } }
step press { time = 0 .. 1  increments = 4 }
";

    fn over(path: &str, value: &str) -> Result<String, String> {
        apply_override(&Source::new("deck.ctc", DECK), path, value)
    }

    /// The line of the result that differs from the deck.
    fn changed(path: &str, value: &str) -> String {
        let out = over(path, value).unwrap();
        out.lines()
            .zip(DECK.lines())
            .find(|(a, b)| a != b)
            .map(|(a, _)| a.trim().to_string())
            .unwrap_or_default()
    }

    #[test]
    fn paths_reach_nested_and_constructor_values() {
        assert_eq!(
            changed("material.elastic.E", "210"),
            "material soft { elastic { E = 210  nu = 0.3 } }"
        );
        assert_eq!(
            changed("soft.elastic.nu", "0.25"),
            "material soft { elastic { E = 200  nu = 0.25 } }"
        );
        assert_eq!(
            changed("body.disc.mesh.radial", "12"),
            "mesh = half_disc { center = (0, 8)  radius = 8  radial = 12  circumferential = 8 }"
        );
        assert_eq!(
            changed("body.mesh.center[1]", "9"),
            "mesh = half_disc { center = (0, 9)  radius = 8  radial = 4  circumferential = 8 }"
        );
        assert_eq!(
            changed("step[press].increments", "8"),
            "step press { time = 0 .. 1  increments = 8 }"
        );
        assert!(over("step.increments", "8")
            .unwrap()
            .starts_with("# a comment that stays\n"));
    }

    #[test]
    fn several_contact_pairs_are_picked_by_index_or_name() {
        assert_eq!(
            changed("contact[0].method.stiffness", "1e5"),
            "method = penalty { kind = area  stiffness = 1e5 }"
        );
        assert_eq!(
            changed("contact[floor].method.stiffness", "1e5"),
            "method = penalty { kind = area  stiffness = 1e5 }"
        );
        assert_eq!(
            changed("contact[disc.arc->wall].method.stiffness", "7"),
            "contact disc.arc -> wall { method = penalty { stiffness = 7 } }"
        );
        assert_eq!(
            changed("tool[wall].normal[0]", "-2"),
            "tool wall = plane { point = (9, 0)  normal = (-2, 0) }"
        );
        let e = over("contact.method.stiffness", "1e5").unwrap_err();
        assert!(e.contains("the deck has 2 `contact` items"), "{e}");
        assert!(e.contains("contact[1] = `contact disc.arc -> wall`"), "{e}");
        let e = over("contact[2].method.stiffness", "1").unwrap_err();
        assert!(e.contains("the deck has 2 `contact` items"), "{e}");
    }

    #[test]
    fn unknown_steps_say_did_you_mean() {
        let e = over("contact[0].method.stifness", "1e5").unwrap_err();
        assert!(
            e.contains("no key `stifness` in `contact[0].method`"),
            "{e}"
        );
        assert!(e.contains("did you mean `stiffness`?"), "{e}");
        assert!(e.contains("deck.ctc:11:20"), "located at the block: {e}");
        let e = over("contct[0].method.stiffness", "1").unwrap_err();
        assert!(e.contains("did you mean `contact`?"), "{e}");
        let e = over("material.elastic", "1").unwrap_err();
        assert!(e.contains("`material.elastic` is a block"), "{e}");
        let e = over("material.elastic.E.x", "1").unwrap_err();
        assert!(e.contains("is a number, it has no key `x`"), "{e}");
        let e = over("material.elastic.E", "1e4x").unwrap_err();
        assert!(e.contains("is not a deck value"), "{e}");
    }

    #[test]
    fn let_parameters_are_overridden_by_name() {
        let deck = "let k = 2e4\nstep { time = 0 .. 1 }\n";
        let out = apply_override(&Source::new("d.ctc", deck), "k", "5e5").unwrap();
        assert_eq!(out, "let k = 5e5\nstep { time = 0 .. 1 }\n");
    }

    #[test]
    fn variations_split_on_top_level_commas() {
        let v = parse_variation("contact.method.stiffness = 1e4, 1e5,1e6").unwrap();
        assert_eq!(v.path, "contact.method.stiffness");
        assert_eq!(v.values, ["1e4", "1e5", "1e6"]);
        let v = parse_variation("body.mesh.center = (0, 8), (0, 9)").unwrap();
        assert_eq!(v.values, ["(0, 8)", "(0, 9)"]);
        assert!(parse_variation("stiffness 1e4").is_err());
        assert!(parse_variation("a = 1,,2").is_err());
    }
}
