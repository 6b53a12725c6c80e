//! The variants of a sweep: the cartesian product of the `--vary` options
//! (the first option varies slowest), each a list of `(path, value)`
//! overrides applied to the deck's text.

use ctc_lang::override_path::{apply_override, parse_variation, Variation};
use ctc_lang::Source;

/// One combination of values.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Variant {
    /// Position in the sweep (the Slurm array index).
    pub index: usize,
    /// `(path, value)` per `--vary`, in option order.
    pub overrides: Vec<(String, String)>,
}

impl Variant {
    /// Directory name inside the sweep directory: `v000`, `v001`, ...
    pub fn name(&self) -> String {
        format!("v{:03}", self.index)
    }

    /// `path = value, path = value`.
    pub fn describe(&self) -> String {
        self.overrides
            .iter()
            .map(|(p, v)| format!("{p} = {v}"))
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The variant deck: the deck's text with every override applied; the
    /// path stays the deck's (mesh files resolve as for the deck itself).
    pub fn source(&self, deck: &Source) -> Result<Source, String> {
        let mut text = deck.text.clone();
        for (path, value) in &self.overrides {
            let src = Source::new(deck.path.clone(), text);
            text = apply_override(&src, path, value)?;
        }
        Ok(Source::new(deck.path.clone(), text))
    }
}

/// All variants of the `--vary` options, checked against the deck: every
/// path must resolve (an unknown path is reported before anything runs).
pub fn plan(deck: &Source, vary: &[String]) -> Result<Vec<Variant>, String> {
    if vary.is_empty() {
        return Err("error: `ctc sweep` needs at least one `--vary \"PATH = v1, v2\"`".into());
    }
    let variations: Vec<Variation> = vary
        .iter()
        .map(|v| parse_variation(v).map_err(|e| format!("error: {e}")))
        .collect::<Result<_, _>>()?;
    for v in &variations {
        // the path resolves on the deck (values are checked per variant)
        apply_override(deck, &v.path, &v.values[0])?;
    }
    let mut combos: Vec<Vec<(String, String)>> = vec![Vec::new()];
    for v in &variations {
        combos = combos
            .into_iter()
            .flat_map(|c| {
                v.values.iter().map(move |value| {
                    let mut next = c.clone();
                    next.push((v.path.clone(), value.clone()));
                    next
                })
            })
            .collect();
    }
    Ok(combos
        .into_iter()
        .enumerate()
        .map(|(index, overrides)| Variant { index, overrides })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    const DECK: &str = "material m { elastic { E = 1  nu = 0.3 } }\n\
                        contact b.s -> t { method = penalty { stiffness = 1 } }\n";

    #[test]
    fn cartesian_product_first_option_slowest() {
        let deck = Source::new("d.ctc", DECK);
        let v = plan(
            &deck,
            &[
                "contact.method.stiffness = 1e4, 1e5".into(),
                "material.elastic.E = 10, 20, 30".into(),
            ],
        )
        .unwrap();
        assert_eq!(v.len(), 6);
        assert_eq!(
            v[1].describe(),
            "contact.method.stiffness = 1e4, material.elastic.E = 20"
        );
        assert_eq!(v[3].name(), "v003");
        assert_eq!(v[3].overrides[0].1, "1e5");
        let text = v[5].source(&deck).unwrap().text;
        assert!(
            text.contains("E = 30") && text.contains("stiffness = 1e5"),
            "{text}"
        );
    }

    #[test]
    fn unknown_paths_stop_before_running() {
        let deck = Source::new("d.ctc", DECK);
        let e = plan(&deck, &["contact.method.stifness = 1".into()]).unwrap_err();
        assert!(e.contains("did you mean `stiffness`?"), "{e}");
        assert!(plan(&deck, &[]).is_err());
    }
}
