//! Contact-method variants of a verification deck.
//!
//! A case deck is written with one contact method (`method = penalty {..}`).
//! A [`MethodVariant`] is the same deck with every `method = <name> {..}`
//! assignment (outside comments and strings) replaced by another method:
//! mesh, loads and steps stay as written, so all methods are compared on
//! identical meshes at every refinement level (the variant is applied after
//! the `# refine:` rendering, see [`crate::refine`]).

use crate::refine::comment_start;

/// One contact method to run a deck with.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct MethodVariant {
    /// Short label used in tables, plot legends and JSON, e.g.
    /// `penalty k=1e5`.
    pub label: String,
    /// Family of the method (curves of the same family share a marker).
    pub family: MethodFamily,
    /// The right-hand side of `method = ..` in deck syntax, e.g.
    /// `lagrange { formulation = doubled }`.
    pub deck: String,
    /// Penalty of the variant (penalty stiffness, or the augmented
    /// Lagrangian's penalty), `None` for Lagrange multipliers.
    pub penalty: Option<f64>,
    /// Penetration tolerance of the augmented Lagrangian (`None` otherwise).
    pub tolerance: Option<f64>,
    /// Whether errors above the case's tolerances count as failures (false
    /// for a penalty deliberately softer than the deck's, run to show the
    /// penalty error).
    pub judged: bool,
}

/// The three families of normal-contact enforcement.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MethodFamily {
    /// Penalty (area-weighted or nodal).
    Penalty,
    /// Lagrange multipliers with an active-set loop.
    Lagrange,
    /// Augmented Lagrangian (Uzawa).
    AugmentedLagrange,
}

impl MethodVariant {
    /// An area-weighted penalty with stiffness `k` (pressure per unit gap).
    pub fn penalty_area(k: f64) -> Self {
        MethodVariant {
            label: format!("penalty k={k:.0e}"),
            family: MethodFamily::Penalty,
            deck: format!("penalty {{ kind = area  stiffness = {k:e} }}"),
            penalty: Some(k),
            tolerance: None,
            judged: true,
        }
    }

    /// A nodal penalty with stiffness `alpha` (force per unit gap).
    pub fn penalty_nodal(alpha: f64) -> Self {
        MethodVariant {
            label: format!("nodal penalty alpha={alpha:.2e}"),
            family: MethodFamily::Penalty,
            deck: format!("penalty {{ kind = nodal  stiffness = {alpha:e} }}"),
            penalty: Some(alpha),
            tolerance: None,
            judged: true,
        }
    }

    /// Lagrange multipliers, single (`doubled = false`, sparse LU) or
    /// doubled (L D L^T) formulation.
    pub fn lagrange(doubled: bool) -> Self {
        let f = if doubled { "doubled" } else { "single" };
        MethodVariant {
            label: format!("lagrange ({f})"),
            family: MethodFamily::Lagrange,
            deck: format!("lagrange {{ formulation = {f} }}"),
            penalty: None,
            tolerance: None,
            judged: true,
        }
    }

    /// Augmented Lagrangian with area penalty `k`, penetration tolerance
    /// `tol` (length) and Uzawa updates after each converged Newton loop.
    pub fn augmented(k: f64, tol: f64) -> Self {
        MethodVariant {
            label: format!("augmented k={k:.0e} tol={tol:.0e}"),
            family: MethodFamily::AugmentedLagrange,
            deck: format!(
                "augmented_lagrange {{ penalty = {k:e}  tolerance = {tol:e}  update = converged }}"
            ),
            penalty: Some(k),
            tolerance: Some(tol),
            judged: true,
        }
    }

    /// The same variant, its tolerance misses reported but not failures.
    pub fn unjudged(mut self) -> Self {
        self.judged = false;
        self
    }

    /// The deck `text` with every `method = ..` assignment replaced by this
    /// variant's method.
    pub fn apply(&self, text: &str) -> Result<String, String> {
        replace_method(text, &self.deck)
    }
}

/// Replaces every `method = <name> { .. }` (or `method = <name>` without a
/// block) in `text`, outside comments and strings, by `method = <new>`.
/// Errors when the deck has no such assignment or a block is not closed.
pub fn replace_method(text: &str, new: &str) -> Result<String, String> {
    // Blank out comments so that `method` and braces in them are ignored,
    // keeping byte offsets.
    let code: String = text
        .split_inclusive('\n')
        .map(|line| match comment_start(line) {
            Some(i) => {
                let (c, rest) = line.split_at(i);
                let blanks: String = rest
                    .chars()
                    .map(|ch| if ch == '\n' { '\n' } else { ' ' })
                    .collect();
                format!("{c}{blanks}")
            }
            None => line.to_string(),
        })
        .collect();
    let bytes = code.as_bytes();
    let is_word = |b: u8| b.is_ascii_alphanumeric() || b == b'_';
    let mut out = String::with_capacity(text.len() + new.len());
    let mut copied = 0;
    let mut found = 0;
    let mut i = 0;
    while let Some(pos) = code[i..].find("method") {
        let start = i + pos;
        let end = start + "method".len();
        i = end;
        if (start > 0 && is_word(bytes[start - 1])) || (end < bytes.len() && is_word(bytes[end])) {
            continue;
        }
        // `=` then a name, then optionally a braced block.
        let mut j = end;
        while j < bytes.len() && bytes[j].is_ascii_whitespace() {
            j += 1;
        }
        if j >= bytes.len() || bytes[j] != b'=' {
            continue;
        }
        j += 1;
        while j < bytes.len() && bytes[j].is_ascii_whitespace() {
            j += 1;
        }
        let name_start = j;
        while j < bytes.len() && is_word(bytes[j]) {
            j += 1;
        }
        if j == name_start {
            return Err(format!(
                "`method =` at byte {start} is not followed by a method name"
            ));
        }
        let mut stop = j;
        let mut k = j;
        while k < bytes.len() && bytes[k].is_ascii_whitespace() {
            k += 1;
        }
        if k < bytes.len() && bytes[k] == b'{' {
            let mut depth = 0usize;
            let mut closed = None;
            for (m, &b) in bytes.iter().enumerate().skip(k) {
                match b {
                    b'{' => depth += 1,
                    b'}' => {
                        depth -= 1;
                        if depth == 0 {
                            closed = Some(m + 1);
                            break;
                        }
                    }
                    _ => {}
                }
            }
            stop = closed.ok_or_else(|| {
                format!("the block of `method = ..` at byte {start} is not closed")
            })?;
        }
        out.push_str(&text[copied..start]);
        out.push_str("method = ");
        out.push_str(new);
        copied = stop;
        i = stop;
        found += 1;
    }
    if found == 0 {
        return Err("the deck has no `method = ..` assignment to replace".into());
    }
    out.push_str(&text[copied..]);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn method_variant_replaces_block_outside_comments() {
        let deck = "# method = penalty { old }\ncontact a -> b {\n  method = penalty { kind = area\n  stiffness = 1e7 }  # method = x\n  prof = 0.5\n}\n";
        let out = MethodVariant::lagrange(true).apply(deck).unwrap();
        assert_eq!(
            out,
            "# method = penalty { old }\ncontact a -> b {\n  method = lagrange { formulation = doubled }  # method = x\n  prof = 0.5\n}\n"
        );
        let bare = replace_method(
            "contact a -> b { method = lagrange }",
            "penalty { stiffness = 1 }",
        )
        .unwrap();
        assert_eq!(
            bare,
            "contact a -> b { method = penalty { stiffness = 1 } }"
        );
    }

    #[test]
    fn method_variant_errors() {
        assert!(replace_method("contact a -> b { }", "lagrange").is_err());
        assert!(
            replace_method("contact a -> b { method = penalty { x = 1 ", "lagrange")
                .unwrap_err()
                .contains("not closed")
        );
        // `methods` is another word.
        assert!(replace_method("methods = 1", "lagrange").is_err());
    }

    #[test]
    fn method_variant_decks_compile() {
        let base = std::fs::read_to_string(
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("cases/hertz_cylinder.ctc"),
        )
        .unwrap();
        for v in [
            MethodVariant::penalty_area(1e5),
            MethodVariant::penalty_nodal(2.5e3),
            MethodVariant::lagrange(false),
            MethodVariant::lagrange(true),
            MethodVariant::augmented(1e5, 1e-6),
        ] {
            let text = v.apply(&base).unwrap();
            crate::deck::compile_text(std::path::Path::new("v.ctc"), &text)
                .unwrap_or_else(|e| panic!("{}: {e}", v.label));
        }
    }
}
