//! "Did you mean" suggestions for misspelt names.

/// Names longer than this get no suggestions (the distance is quadratic in the length).
const MAX_NAME_CHARS: usize = 256;

/// Edit distance between two strings (Levenshtein, by characters).
pub fn edit_distance(a: &str, b: &str) -> usize {
    strsim::levenshtein(a, b)
}

/// Up to three names closest to `wanted`, closest first, within a distance that scales with its length.
pub fn closest<'a>(wanted: &str, candidates: impl Iterator<Item = &'a str>) -> Vec<&'a str> {
    let wanted_len = wanted.chars().count();
    if wanted_len > MAX_NAME_CHARS {
        return Vec::new();
    }
    let limit = (wanted_len / 3).max(2);
    let mut scored: Vec<(usize, &str)> = candidates
        .filter(|c| c.len() <= 4 * MAX_NAME_CHARS)
        .filter_map(|c| {
            if c.contains(wanted) || wanted.contains(c) {
                return Some((edit_distance(wanted, c), c));
            }
            // The distance is at least the length difference: skip hopeless candidates cheaply.
            if c.chars().count().abs_diff(wanted_len) > limit {
                return None;
            }
            let distance = edit_distance(wanted, c);
            (distance <= limit).then_some((distance, c))
        })
        .collect();
    scored.sort();
    scored.into_iter().take(3).map(|(_, c)| c).collect()
}

/// A help sentence: "did you mean 'a' or 'b'?", or a plain note when nothing is close.
pub fn did_you_mean<'a>(wanted: &str, candidates: impl Iterator<Item = &'a str>) -> String {
    let names = closest(wanted, candidates);
    match names.as_slice() {
        [] => "no similarly named item exists".to_string(),
        [one] => format!("did you mean '{one}'?"),
        many => {
            let quoted: Vec<String> = many.iter().map(|n| format!("'{n}'")).collect();
            format!("did you mean one of {}?", quoted.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distance_and_suggestions() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        let names = ["base_link", "arm_link_1", "arm_link_2", "gripper"];
        assert_eq!(
            closest("base_lnk", names.iter().copied()),
            vec!["base_link"]
        );
        assert_eq!(
            did_you_mean("zzzzzz", names.iter().copied()),
            "no similarly named item exists"
        );
    }
}
