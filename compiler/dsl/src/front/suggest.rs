//! "Did you mean …?" for unknown names and functions: the workspace's one
//! rule ([`ecc_util::suggest`]: case-insensitive edit distance d with
//! d ≤ max(2, ⌊n/3⌋) and d < the shorter length) after a table of common
//! misspellings.

/// The closest candidate to `name` if it is a plausible typo; `extra` maps
/// common misspellings to their intended names (checked first).
pub fn suggest<'a>(
    name: &str,
    candidates: impl Iterator<Item = &'a str>,
    extra: &[(&str, &'a str)],
) -> Option<String> {
    ecc_util::suggest(name, candidates, extra).map(str::to_string)
}
