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
    let wanted_chars: Vec<char> = wanted.chars().collect();
    let wanted_counts = CharCounts::of(wanted);
    let mut candidate_chars = Vec::new();
    let mut scored: Vec<(usize, &str)> = candidates
        .filter(|c| c.len() <= 4 * MAX_NAME_CHARS)
        .filter_map(|c| {
            if c.contains(wanted) || wanted.contains(c) {
                return Some((edit_distance(wanted, c), c));
            }
            if wanted_counts.bag_distance(c) > limit {
                return None;
            }
            candidate_chars.clear();
            candidate_chars.extend(c.chars());
            distance_within(&wanted_chars, &candidate_chars, limit).map(|d| (d, c))
        })
        .collect();
    scored.sort();
    scored.into_iter().take(3).map(|(_, c)| c).collect()
}

/// How many times each character occurs in a name, ASCII characters each on their own and every other
/// character counted as one (which only lowers the bag distance below).
struct CharCounts([i16; 128]);

impl CharCounts {
    fn of(name: &str) -> CharCounts {
        let mut counts = [0i16; 128];
        for c in name.chars() {
            counts[Self::bucket(c)] += 1;
        }
        CharCounts(counts)
    }

    fn bucket(c: char) -> usize {
        if c.is_ascii() {
            c as usize
        } else {
            0
        }
    }

    /// A lower bound of the edit distance to `other` (shorter than 32,768 characters): the
    /// larger of the characters this name has beyond `other`'s and those `other` has beyond this one's
    /// (the bag distance; an edit changes each by at most one). Linear in the length, where the edit
    /// distance is quadratic, so most names are ruled out before it.
    fn bag_distance(&self, other: &str) -> usize {
        let mut difference = self.0;
        for c in other.chars() {
            difference[Self::bucket(c)] -= 1;
        }
        let (mut beyond, mut short) = (0usize, 0usize);
        for d in difference {
            beyond += d.max(0) as usize;
            short += (-d).max(0) as usize;
        }
        beyond.max(short)
    }
}

/// The edit distance between `a` and `b` (as [`edit_distance`]) when it is at most `limit`: only the
/// entries within `limit` of the diagonal are computed (the others exceed it), and a row whose entries
/// all exceed it ends the search. A robot with many misspelt references asks this of every name.
fn distance_within(a: &[char], b: &[char], limit: usize) -> Option<usize> {
    if a.len().abs_diff(b.len()) > limit {
        return None;
    }
    // Entries above the limit are kept as `over`: only whether they exceed it matters.
    let over = limit + 1;
    // `row[j]`: the distance between the first `i` characters of `a` and the first `j` of `b`. Entries
    // right of the band still hold their first row's value, which is `over` there.
    let mut row: Vec<usize> = (0..=b.len()).map(|j| j.min(over)).collect();
    for i in 1..=a.len() {
        let first = i.saturating_sub(limit).max(1);
        let last = (i + limit).min(b.len());
        let mut diagonal = row[first - 1];
        row[first - 1] = if first == 1 { i.min(over) } else { over };
        let mut lowest = row[first - 1];
        for j in first..=last {
            let above = row[j];
            let substitution = diagonal + usize::from(a[i - 1] != b[j - 1]);
            let value = substitution.min(above + 1).min(row[j - 1] + 1).min(over);
            diagonal = above;
            row[j] = value;
            lowest = lowest.min(value);
        }
        if lowest > limit {
            return None;
        }
    }
    Some(row[b.len()]).filter(|&d| d <= limit)
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

    /// The banded distance agrees with the full one on random words over a small alphabet (many near
    /// misses), for every limit: the distance when it is within the limit, nothing otherwise.
    #[test]
    fn the_banded_distance_is_the_edit_distance_within_its_limit() {
        let mut rng = crate::rng::SplitMix64::new(11);
        let word = |rng: &mut crate::rng::SplitMix64| -> Vec<char> {
            let len = (rng.next_u64() % 9) as usize;
            (0..len)
                .map(|_| ['a', 'b', 'c', 'é'][(rng.next_u64() % 4) as usize])
                .collect()
        };
        for _ in 0..5000 {
            let (a, b) = (word(&mut rng), word(&mut rng));
            let full = edit_distance(&a.iter().collect::<String>(), &b.iter().collect::<String>());
            for limit in 0..10 {
                let expected = (full <= limit).then_some(full);
                assert_eq!(
                    distance_within(&a, &b, limit),
                    expected,
                    "{a:?} {b:?} {limit}"
                );
            }
        }
    }

    /// The bag distance never exceeds the edit distance (random words, ASCII and not), and is often
    /// well above the half of it that a single edit could make it.
    #[test]
    fn the_bag_distance_is_a_lower_bound_of_the_edit_distance() {
        let mut rng = crate::rng::SplitMix64::new(12);
        let word = |rng: &mut crate::rng::SplitMix64| -> String {
            let len = (rng.next_u64() % 12) as usize;
            (0..len)
                .map(|_| ['a', 'b', '_', '1', 'é', 'ü'][(rng.next_u64() % 6) as usize])
                .collect()
        };
        let mut tight = 0;
        for _ in 0..5000 {
            let (a, b) = (word(&mut rng), word(&mut rng));
            let bag = CharCounts::of(&a).bag_distance(&b);
            let full = edit_distance(&a, &b);
            assert!(bag <= full, "{a:?} {b:?}: bag {bag} > edit {full}");
            tight += usize::from(2 * bag >= full);
        }
        assert!(tight > 2500, "{tight}");
    }

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
