//! Refinement levels of a deck, declared in the deck itself.
//!
//! A verification deck is a plain, runnable `.ctc` file written at its
//! coarsest level. Marker comments list the values a key takes at each
//! refinement level:
//!
//! ```text
//! # refine: radial = 6 12 24 48
//! # refine: circumferential = 16 32 64 128
//! # refine: divisions = (8, 8) (16, 16) (32, 32)
//! ```
//!
//! Level `k` is the deck with every assignment `key = <value>` (outside
//! comments and strings; `key` a whole word; the value a number or a
//! parenthesised tuple) replaced by the k-th listed value. The first listed
//! value must be the one written in the deck, so that the deck as written is
//! level 0, and all markers must list the same number of levels. Nothing else
//! is changed: grading ratios, loads and penalties stay as written.

/// One `# refine:` marker: a key and its value at each level.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RefineParam {
    /// The assignment key (`radial`, `divisions`, ...).
    pub key: String,
    /// Its value text at each level (level 0 first).
    pub values: Vec<String>,
}

/// A deck with its refinement markers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RefinableDeck {
    /// The deck text as written (level 0).
    pub text: String,
    /// The markers, in the order they appear.
    pub params: Vec<RefineParam>,
}

/// Marker prefix inside a comment.
const MARKER: &str = "refine:";

impl RefinableDeck {
    /// Reads the markers of `text` and checks that they are consistent with
    /// the deck (every key assigned at least once, level 0 = the written value).
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut params = Vec::new();
        for (i, line) in text.lines().enumerate() {
            let Some(comment) = comment_of(line) else {
                continue;
            };
            let Some(rest) = comment.trim_start().strip_prefix(MARKER) else {
                continue;
            };
            let param = parse_marker(rest).map_err(|e| format!("line {}: {e}", i + 1))?;
            if params.iter().any(|p: &RefineParam| p.key == param.key) {
                return Err(format!(
                    "line {}: key `{}` has two refine markers",
                    i + 1,
                    param.key
                ));
            }
            params.push(param);
        }
        if let Some(first) = params.first() {
            let n = first.values.len();
            if let Some(bad) = params.iter().find(|p| p.values.len() != n) {
                return Err(format!(
                    "refine markers disagree on the number of levels: `{}` lists {n}, `{}` lists {}",
                    first.key,
                    bad.key,
                    bad.values.len()
                ));
            }
        }
        let deck = RefinableDeck {
            text: text.to_string(),
            params,
        };
        for p in &deck.params {
            let written = assigned_values(&deck.text, &p.key);
            if written.is_empty() {
                return Err(format!(
                    "refine marker for `{}`: the deck never assigns `{} = ..`",
                    p.key, p.key
                ));
            }
            for w in written {
                if normalise(&w) != normalise(&p.values[0]) {
                    return Err(format!(
                        "refine marker for `{}`: level 0 is `{}` but the deck writes `{} = {}`",
                        p.key, p.values[0], p.key, w
                    ));
                }
            }
        }
        Ok(deck)
    }

    /// Number of levels (1 when the deck has no marker).
    pub fn levels(&self) -> usize {
        self.params.first().map_or(1, |p| p.values.len())
    }

    /// The deck text at `level`.
    pub fn render(&self, level: usize) -> Result<String, String> {
        if level >= self.levels() {
            return Err(format!(
                "level {level} requested but the deck defines {} level(s)",
                self.levels()
            ));
        }
        if level == 0 {
            // Checked by `parse`: the written values are the level-0 values.
            return Ok(self.text.clone());
        }
        let mut out = String::with_capacity(self.text.len());
        for line in self.text.split_inclusive('\n') {
            let split = comment_start(line).unwrap_or(line.len());
            let (code, comment) = line.split_at(split);
            let mut code = code.to_string();
            for p in &self.params {
                code = substitute(&code, &p.key, &p.values[level]);
            }
            out.push_str(&code);
            out.push_str(comment);
        }
        Ok(out)
    }
}

/// Byte offset of the `#` starting the comment of `line`, ignoring `#`
/// inside double-quoted strings.
pub(crate) fn comment_start(line: &str) -> Option<usize> {
    let mut in_string = false;
    for (i, c) in line.char_indices() {
        match c {
            '"' => in_string = !in_string,
            '#' if !in_string => return Some(i),
            _ => {}
        }
    }
    None
}

/// The comment text of `line` (after `#`), if any.
fn comment_of(line: &str) -> Option<&str> {
    comment_start(line).map(|i| &line[i + 1..])
}

/// Parses `key = v0 v1 ...` (values: numbers or parenthesised tuples).
fn parse_marker(rest: &str) -> Result<RefineParam, String> {
    let (key, values) = rest.split_once('=').ok_or_else(|| {
        format!(
            "refine marker `{}` has no `=`; expected `# refine: key = v0 v1 ..`",
            rest.trim()
        )
    })?;
    let key = key.trim();
    if key.is_empty() || !key.chars().all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Err(format!("refine marker key `{key}` is not a name"));
    }
    let mut tokens = Vec::new();
    let mut depth = 0usize;
    let mut current = String::new();
    for c in values.chars() {
        match c {
            '(' => {
                depth += 1;
                current.push(c);
            }
            ')' => {
                depth = depth
                    .checked_sub(1)
                    .ok_or_else(|| format!("unbalanced `)` in refine marker for `{key}`"))?;
                current.push(c);
            }
            c if c.is_whitespace() && depth == 0 => {
                if !current.is_empty() {
                    tokens.push(std::mem::take(&mut current));
                }
            }
            c => current.push(c),
        }
    }
    if depth != 0 {
        return Err(format!("unbalanced `(` in refine marker for `{key}`"));
    }
    if !current.is_empty() {
        tokens.push(current);
    }
    if tokens.is_empty() {
        return Err(format!("refine marker for `{key}` lists no value"));
    }
    Ok(RefineParam {
        key: key.to_string(),
        values: tokens,
    })
}

/// Removes all whitespace (to compare `(8,4)` with `(8, 4)`).
fn normalise(s: &str) -> String {
    s.chars().filter(|c| !c.is_whitespace()).collect()
}

/// A located assignment `key = value` in a code fragment: byte range of the value.
fn find_assignments(code: &str, key: &str) -> Vec<std::ops::Range<usize>> {
    let bytes = code.as_bytes();
    let is_word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut found = Vec::new();
    let mut from = 0;
    while let Some(pos) = code[from..].find(key) {
        let start = from + pos;
        let end = start + key.len();
        from = end;
        if (start > 0 && is_word(bytes[start - 1])) || (end < bytes.len() && is_word(bytes[end])) {
            continue;
        }
        let mut i = end;
        while i < bytes.len() && (bytes[i] == b' ' || bytes[i] == b'\t') {
            i += 1;
        }
        if i >= bytes.len() || bytes[i] != b'=' {
            continue;
        }
        i += 1;
        while i < bytes.len() && (bytes[i] == b' ' || bytes[i] == b'\t') {
            i += 1;
        }
        let v0 = i;
        if i < bytes.len() && bytes[i] == b'(' {
            let mut depth = 0;
            while i < bytes.len() {
                match bytes[i] {
                    b'(' => depth += 1,
                    b')' => {
                        depth -= 1;
                        if depth == 0 {
                            i += 1;
                            break;
                        }
                    }
                    _ => {}
                }
                i += 1;
            }
        } else {
            while i < bytes.len()
                && (bytes[i].is_ascii_alphanumeric() || matches!(bytes[i], b'.' | b'-' | b'+'))
            {
                i += 1;
            }
        }
        if i > v0 {
            found.push(v0..i);
            from = i;
        }
    }
    found
}

/// Values assigned to `key` in the code (comments stripped) of `text`.
fn assigned_values(text: &str, key: &str) -> Vec<String> {
    text.lines()
        .flat_map(|line| {
            let code = &line[..comment_start(line).unwrap_or(line.len())];
            find_assignments(code, key)
                .into_iter()
                .map(|r| code[r].to_string())
                .collect::<Vec<_>>()
        })
        .collect()
}

/// Replaces the value of every `key = ..` in `code` by `value`.
fn substitute(code: &str, key: &str, value: &str) -> String {
    let mut out = String::with_capacity(code.len());
    let mut last = 0;
    for r in find_assignments(code, key) {
        out.push_str(&code[last..r.start]);
        out.push_str(value);
        last = r.end;
    }
    out.push_str(&code[last..]);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    const DECK: &str = "\
# refine: radial = 4 8 16
# refine: divisions = (8, 4) (16,8) (32, 16)
body b {
  mesh = quarter_disc { radial = 4  circumferential = 12  radial_grading = geometric(0.2) }
}
body c { mesh = rectangle { origin = (0, 0) size = (1, 1) divisions = (8,4) } }
# radial = 4 in a comment is left alone
";

    #[test]
    fn refine_markers_substitute_whole_keys() {
        let d = RefinableDeck::parse(DECK).unwrap();
        assert_eq!(d.levels(), 3);
        assert_eq!(d.render(0).unwrap(), DECK);
        let l2 = d.render(2).unwrap();
        assert!(
            l2.contains("radial = 16  circumferential = 12  radial_grading = geometric(0.2)"),
            "{l2}"
        );
        assert!(l2.contains("divisions = (32, 16) }"), "{l2}");
        assert!(l2.contains("# radial = 4 in a comment"), "{l2}");
        assert!(d.render(3).is_err());
    }

    #[test]
    fn refine_marker_level_0_must_match_deck() {
        let text = "# refine: radial = 5 10\nmesh = quarter_disc { radial = 4 }\n";
        let err = RefinableDeck::parse(text).unwrap_err();
        assert!(err.contains("level 0 is `5`"), "{err}");
    }

    #[test]
    fn refine_marker_errors_are_reported() {
        let unknown = RefinableDeck::parse("# refine: nope = 1 2\nx = 1\n").unwrap_err();
        assert!(unknown.contains("never assigns"), "{unknown}");
        let counts = RefinableDeck::parse("# refine: a = 1 2\n# refine: b = 1 2 3\na = 1 b = 1\n")
            .unwrap_err();
        assert!(counts.contains("disagree"), "{counts}");
        let syntax = RefinableDeck::parse("# refine: a 1 2\n").unwrap_err();
        assert!(syntax.contains("no `=`"), "{syntax}");
        let paren = RefinableDeck::parse("# refine: a = (1, 2\n").unwrap_err();
        assert!(paren.contains("unbalanced"), "{paren}");
    }

    #[test]
    fn refine_no_marker_is_one_level() {
        let d = RefinableDeck::parse("analysis { dimension = plane_strain }\n").unwrap();
        assert_eq!(d.levels(), 1);
        assert_eq!(
            d.render(0).unwrap(),
            "analysis { dimension = plane_strain }\n"
        );
    }

    #[test]
    fn refine_ignores_hash_inside_strings() {
        let text = "# refine: radial = 2 4\nmesh = file \"a#b.msh\" radial = 2\n";
        let d = RefinableDeck::parse(text).unwrap();
        assert_eq!(
            d.render(1).unwrap(),
            "# refine: radial = 2 4\nmesh = file \"a#b.msh\" radial = 4\n"
        );
    }
}
