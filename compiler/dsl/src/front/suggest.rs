//! "Did you mean …?": the closest known name by edit distance.

/// The closest candidate by edit distance (case-insensitive matches first),
/// if it is close enough to be a plausible typo; `extra` maps common
/// misspellings to their intended names.
pub fn suggest<'a>(
    name: &str,
    candidates: impl Iterator<Item = &'a str>,
    extra: &[(&str, &str)],
) -> Option<String> {
    if let Some((_, to)) = extra
        .iter()
        .find(|(from, _)| from.eq_ignore_ascii_case(name))
    {
        return Some((*to).to_string());
    }
    let mut best: Option<(usize, String)> = None;
    let mut cands: Vec<&str> = candidates.collect();
    cands.sort_unstable();
    cands.dedup();
    for c in cands {
        if c == name {
            continue;
        }
        let d = if c.eq_ignore_ascii_case(name) {
            0
        } else {
            levenshtein(&name.to_lowercase(), &c.to_lowercase()) + 1
        };
        let limit = 1 + name.chars().count().max(c.chars().count()) / 3;
        if d <= limit && best.as_ref().is_none_or(|(bd, _)| d < *bd) {
            best = Some((d, c.to_string()));
        }
    }
    best.map(|(_, s)| s)
}

fn levenshtein(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for i in 1..=a.len() {
        let mut cur = vec![i; b.len() + 1];
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            cur[j] = (prev[j] + 1).min(cur[j - 1] + 1).min(prev[j - 1] + cost);
        }
        prev = cur;
    }
    prev[b.len()]
}
