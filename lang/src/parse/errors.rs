//! pest syntax errors -> diagnostics that name the expected tokens in
//! words ("expected `=`, `{` or `}`, found `210e3`"), never rule names.

use super::Rule;
use crate::diagnostics::Diagnostic;
use crate::span::Span;
use pest::error::{Error, InputLocation};

const ITEM_KEYWORDS: [&str; 12] = [
    "analysis", "material", "body", "set", "tool", "contact", "fix", "displace", "pressure",
    "force", "step", "output",
];

/// Punctuation in the order it is listed in messages.
const PUNCTUATION: [&str; 10] = ["=", "{", "}", "(", ")", "[", "]", ",", "->", ".."];

/// Byte position of the error: the furthest point the parser reached.
pub fn error_position(err: &Error<Rule>) -> usize {
    match err.parse_attempts() {
        Some(a) => a.max_position,
        None => match err.location {
            InputLocation::Pos(p) => p,
            InputLocation::Span((s, _)) => s,
        },
    }
}

fn is_word_char(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The token found at `pos` for "found X" and its span.
pub fn found_token(text: &str, pos: usize) -> (String, Span) {
    let rest = text.get(pos..).unwrap_or("");
    let Some(c) = rest.chars().next() else {
        return ("end of file".to_string(), Span::new(pos, pos));
    };
    let len = if is_word_char(c) || c == '.' || c == '-' || c == '+' {
        let two = rest.get(..2).unwrap_or("");
        if two == "->" || two == ".." {
            2
        } else {
            let mut n = c.len_utf8();
            for d in rest[n..].chars() {
                let exp_sign = (d == '-' || d == '+')
                    && matches!(rest[..n].chars().last(), Some('e' | 'E'))
                    && rest
                        .trim_start_matches(['-', '+'])
                        .starts_with(|c: char| c.is_ascii_digit() || c == '.');
                if is_word_char(d) || (d == '.' && !rest[n..].starts_with("..")) || exp_sign {
                    n += d.len_utf8();
                } else {
                    break;
                }
            }
            n
        }
    } else {
        c.len_utf8()
    };
    let tok = &rest[..len];
    let shown = if c == '"' {
        "a string".to_string()
    } else {
        format!("`{tok}`")
    };
    (shown, Span::new(pos, pos + len))
}

/// Describes the tokens the parser would have accepted at `pos`. Tokens
/// that would only continue the word just before `pos` (more letters or
/// digits) are left out when `skip_continuations` is set.
pub fn expected_words(
    err: &Error<Rule>,
    text: &str,
    pos: usize,
    skip_continuations: bool,
) -> Vec<String> {
    let mut literals: Vec<String> = Vec::new();
    let (mut name, mut number, mut string, mut item) = (false, false, false, false);
    let after_word = skip_continuations && word_before(text, pos);
    // `ParsingToken` is not exported by pest; its `Display` gives the
    // literal text, or `a..z` for a character range.
    let tokens: Vec<String> = err
        .parse_attempts()
        .map(|a| a.expected_tokens().iter().map(|t| t.to_string()).collect())
        .unwrap_or_default();
    for tok in &tokens {
        let tok = tok.as_str();
        let chars: Vec<char> = tok.chars().collect();
        if chars.len() == 4 && chars[1] == '.' && chars[2] == '.' {
            // A character range such as `0..9` or `a..z`.
            if !after_word {
                if chars[0].is_ascii_digit() {
                    number = true;
                } else {
                    name = true;
                }
            }
            continue;
        }
        if matches!(
            tok,
            " " | "\t" | "\r" | "\n" | "#" | "BUILTIN_RULE" | "2d" | "3d"
        ) {
            continue;
        }
        if ITEM_KEYWORDS.contains(&tok) {
            item = true;
            continue;
        }
        // operators and units may always follow a number: listing them
        // would hide what is missing
        if matches!(tok, "+" | "-" | "*" | "/" | "^") || crate::units::find(tok).is_some() {
            continue;
        }
        let continuation = chars.len() == 1
            && chars
                .iter()
                .all(|&c| is_word_char(c) || c == '.' || c == '+' || c == '-');
        if continuation {
            if !after_word {
                match tok {
                    "_" => name = true,
                    "." | "+" | "-" => number = true,
                    _ => {}
                }
            }
            continue;
        }
        match tok {
            "\"" => string = true,
            _ => literals.push(tok.to_string()),
        }
    }
    let mut out: Vec<String> = Vec::new();
    let value = name && number && string;
    for p in PUNCTUATION {
        if value && (p == "(" || p == "[") {
            continue;
        }
        if literals.iter().any(|l| l == p) {
            out.push(p.to_string());
        }
    }
    for l in &literals {
        if !PUNCTUATION.contains(&l.as_str()) {
            out.push(l.clone());
        }
    }
    let mut out: Vec<String> = out.into_iter().map(|p| format!("`{p}`")).collect();
    if item {
        out.push("an item (`material`, `body`, `tool`, `step`, ..)".to_string());
    } else if value {
        out.push("a value".to_string());
    } else {
        if name {
            out.push("a name".to_string());
        }
        if number {
            out.push("a number".to_string());
        }
        if string {
            out.push("a string".to_string());
        }
    }
    out
}

/// Whether the character before `pos` belongs to a word or number.
fn word_before(text: &str, pos: usize) -> bool {
    text.get(..pos)
        .and_then(|t| t.chars().next_back())
        .is_some_and(|c| is_word_char(c) || c == '.')
}

/// The word or number ending at `pos`.
fn word_ending_at(text: &str, pos: usize) -> Span {
    let before = text.get(..pos).unwrap_or("");
    let len: usize = before
        .chars()
        .rev()
        .take_while(|&c| is_word_char(c) || matches!(c, '.' | '+' | '-'))
        .map(char::len_utf8)
        .sum();
    Span::new(pos - len, pos)
}

/// The diagnostic for a pest error on `text`.
pub fn syntax_error(err: &Error<Rule>, text: &str) -> Diagnostic {
    syntax_error_at(err, 0, text)
}

/// The diagnostic for a pest error of a parse that read `text` from byte
/// `offset` on (a chunk of the deck parsed on its own: the error's
/// positions are in the chunk, `text` is the deck up to the chunk's end).
pub fn syntax_error_at(err: &Error<Rule>, offset: usize, text: &str) -> Diagnostic {
    if let pest::error::ErrorVariant::CustomError { message } = &err.variant {
        return Diagnostic::error(
            format!("the deck could not be parsed: {message}"),
            Span::new(0, 0),
            "",
        );
    }
    let pos = (error_position(err) + offset).min(text.len());
    let (found, span) = found_token(text, pos);
    let expected = expected_words(err, text, pos, true);
    if expected.is_empty() && word_before(text, pos) {
        // Only a continuation of the word before would do: e.g. `-1e`.
        let word = word_ending_at(text, pos);
        let all = expected_words(err, text, pos, false);
        let list = if all.is_empty() {
            "more".to_string()
        } else {
            one_of_words(&all)
        };
        return Diagnostic::error(
            format!("incomplete `{}`", word.text(text)),
            word,
            format!("expected {list} after this"),
        );
    }
    if found == "`}`" && expected.iter().any(|e| e.starts_with("an item")) {
        return Diagnostic::error("unexpected `}`", span, "no open block to close here")
            .with_help("remove it, or check the braces of the item above");
    }
    if (found == "`,`" || found == "`;`") && expected.iter().any(|e| e == "`}`") {
        return Diagnostic::error(
            format!("unexpected {found} in a block"),
            span,
            "not allowed here",
        )
        .with_help(
            "entries of a block are separated by spaces or new lines: `{ E = 1  nu = 0.3 }`",
        );
    }
    let list = if expected.is_empty() {
        "something else".to_string()
    } else {
        one_of_words(&expected)
    };
    Diagnostic::error(
        format!("expected {list}, found {found}"),
        span,
        format!("expected {list}"),
    )
}

/// Joins already-formatted words: "a, b or c".
fn one_of_words(words: &[String]) -> String {
    match words.len() {
        1 => words[0].clone(),
        n => format!("{} or {}", words[..n - 1].join(", "), words[n - 1]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn found_tokens() {
        assert_eq!(found_token("E 210e3 nu", 2).0, "`210e3`");
        assert_eq!(found_token("x = -1.5e-3 y", 4).0, "`-1.5e-3`");
        assert_eq!(found_token("a -> b", 2).0, "`->`");
        assert_eq!(found_token("{ }", 2).0, "`}`");
        assert_eq!(found_token("abc", 3).0, "end of file");
        assert_eq!(found_token("f \"x\"", 2).0, "a string");
    }
}
