//! "Did you mean …?": the closest known name by edit distance.
//!
//! **The rule** (one for every caller): compare case-insensitively; a
//! candidate equal to the name up to case wins outright; otherwise the
//! candidate with the smallest Levenshtein distance d is suggested when
//!
//! ```text
//! d ≤ max(2, ⌊n/3⌋)   and   d < min(|name|, |candidate|)
//! ```
//!
//! with n the longer of the two lengths (in characters): up to two edits
//! for short names (`stl` → `vtk`, `gravty` → `gravity`), one more per three
//! characters for long ones, and never a candidate that shares nothing with
//! the name (`x` is not a typo of `d`). Ties go to the alphabetically first
//! candidate, so suggestions are deterministic.

/// Levenshtein distance between `a` and `b` (in characters).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != *cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// The distance of `candidate` from `name` if it passes the rule (0 for a
/// match up to case), else `None`.
fn score(name: &str, candidate: &str) -> Option<usize> {
    let (a, b) = (name.to_lowercase(), candidate.to_lowercase());
    if a == b {
        return Some(0);
    }
    let (la, lb) = (a.chars().count(), b.chars().count());
    let d = edit_distance(&a, &b);
    (d <= (la.max(lb) / 3).max(2) && d < la.min(lb)).then_some(d)
}

/// The closest of `candidates` to `name` under the rule (the name itself is
/// never suggested).
pub fn suggest_among<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
) -> Option<&'a str> {
    let mut best: Option<(usize, &str)> = None;
    for c in candidates {
        if c == name {
            continue;
        }
        if let Some(d) = score(name, c)
            && best.is_none_or(|(bd, bc)| d < bd || (d == bd && c < bc))
        {
            best = Some((d, c));
        }
    }
    best.map(|(_, c)| c)
}

/// [`suggest_among`] after a table of common misspellings (`extra`, matched
/// case-insensitively, e.g. `ln` → `log`).
pub fn suggest<'a>(
    name: &str,
    candidates: impl IntoIterator<Item = &'a str>,
    extra: &[(&str, &'a str)],
) -> Option<&'a str> {
    if let Some((_, to)) = extra
        .iter()
        .find(|(from, _)| from.eq_ignore_ascii_case(name))
    {
        return Some(to);
    }
    suggest_among(name, candidates)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("gravty", "gravity"), 1);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("kitten", "sitting"), 3);
    }

    #[test]
    fn the_rule() {
        let keys = ["density", "gravity", "ground"];
        assert_eq!(suggest_among("gravty", keys), Some("gravity"));
        assert_eq!(suggest_among("zzzzzz", keys), None);
        assert_eq!(suggest_among("stl", ["obj", "vtk"]), Some("vtk"));
        assert_eq!(suggest_among("lamda", ["lambda", "mu"]), Some("lambda"));
        assert_eq!(suggest_among("i2", ["I1", "I2", "I3"]), Some("I2"));
        // nothing in common with a one-letter name
        assert_eq!(suggest_among("x", ["d", "J"]), None);
        assert_eq!(suggest_among("ab", ["mu"]), None);
        // ties: alphabetical
        assert_eq!(suggest_among("mx", ["mz", "my"]), Some("my"));
        // never the name itself
        assert_eq!(suggest_among("mu", ["mu"]), None);
        // long names allow one edit per three characters
        assert_eq!(
            suggest_among("integratr_kinds", ["integrator_kind"]),
            Some("integrator_kind")
        );
    }

    #[test]
    fn misspellings_first() {
        assert_eq!(suggest("LN", ["log", "exp"], &[("ln", "log")]), Some("log"));
        assert_eq!(suggest("lg", ["log", "exp"], &[("ln", "log")]), Some("log"));
    }
}
