//! "Did you mean" suggestions by edit distance.

/// Optimal-string-alignment distance (Levenshtein plus adjacent
/// transpositions), case-insensitive, counted in characters.
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.to_lowercase().chars().collect();
    let b: Vec<char> = b.to_lowercase().chars().collect();
    let (n, m) = (a.len(), b.len());
    let mut d = vec![vec![0usize; m + 1]; n + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, v) in d[0].iter_mut().enumerate() {
        *v = j;
    }
    for i in 1..=n {
        for j in 1..=m {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut v = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                v = v.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = v;
        }
    }
    d[n][m]
}

/// The candidate closest to `word`, if it is close enough to be a plausible
/// misspelling (distance at most 1 for short words, about a third of the
/// length for longer ones). Ties go to the first candidate.
pub fn closest<'a, I, S>(word: &str, candidates: I) -> Option<String>
where
    I: IntoIterator<Item = S>,
    S: AsRef<str> + 'a,
{
    let limit = (word.chars().count() / 3).max(1);
    let mut best: Option<(usize, String)> = None;
    for c in candidates {
        let c = c.as_ref();
        if c == word {
            continue;
        }
        let dist = edit_distance(word, c);
        if dist <= limit && best.as_ref().is_none_or(|(b, _)| dist < *b) {
            best = Some((dist, c.to_string()));
        }
    }
    best.map(|(_, s)| s)
}

/// `did you mean `x`?` for the closest candidate, if any.
pub fn did_you_mean<'a, I, S>(word: &str, candidates: I) -> Option<String>
where
    I: IntoIterator<Item = S>,
    S: AsRef<str> + 'a,
{
    closest(word, candidates).map(|c| format!("did you mean `{c}`?"))
}

/// Formats a list of names as "`a`, `b` or `c`".
pub fn one_of<S: AsRef<str>>(names: &[S]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{}`", n.as_ref())).collect();
    match quoted.len() {
        0 => String::new(),
        1 => quoted[0].clone(),
        n => format!("{} or {}", quoted[..n - 1].join(", "), quoted[n - 1]),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("steel", "steeel"), 1);
        assert_eq!(edit_distance("plane_strain", "plane_stran"), 1);
        assert_eq!(edit_distance("nu", "un"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("E", "e"), 0);
    }

    #[test]
    fn closest_respects_threshold() {
        let names = ["plane_strain", "plane_stress", "axisymmetric", "3d"];
        assert_eq!(
            closest("plane_stran", names).as_deref(),
            Some("plane_strain")
        );
        assert_eq!(closest("banana", names), None);
        assert_eq!(
            closest("elastc", ["elastic", "plastic"]).as_deref(),
            Some("elastic")
        );
    }

    #[test]
    fn one_of_lists() {
        assert_eq!(one_of(&["a"]), "`a`");
        assert_eq!(one_of(&["a", "b", "c"]), "`a`, `b` or `c`");
    }
}
