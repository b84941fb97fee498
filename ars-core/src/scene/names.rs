//! Unique, deterministic names for objects and joints, and "did you mean" suggestions.

use std::collections::{BTreeMap, HashMap};

use crate::error::{Error, Result};

/// Names of one kind of thing ("object" or "joint") mapped to their ids.
#[derive(Debug)]
pub(crate) struct Names<Id> {
    kind: &'static str,
    by_name: BTreeMap<String, Id>,
    /// For each base name, a suffix below which every `base/i` is taken: `unique`
    /// starts its search there instead of at 1 (10,000 spheres once took 11 s).
    next_suffix: HashMap<String, u64>,
}

impl<Id: Copy + PartialEq> Names<Id> {
    pub(crate) fn new(kind: &'static str) -> Self {
        Names { kind, by_name: BTreeMap::new(), next_suffix: HashMap::new() }
    }

    /// `base` if free, else `base/1`, `base/2`... (the first free one): deterministic,
    /// unlike the original's memory-address suffixes.
    pub(crate) fn unique(&mut self, base: &str) -> String {
        if !self.by_name.contains_key(base) {
            return base.to_string();
        }
        let start = self.next_suffix.get(base).copied().unwrap_or(1);
        let (i, name) = (start..)
            .map(|i| (i, format!("{base}/{i}")))
            .find(|(_, n)| !self.by_name.contains_key(n))
            .expect("a free suffix exists");
        self.next_suffix.insert(base.to_string(), i);
        name
    }

    pub(crate) fn insert(&mut self, name: String, id: Id) -> Result<()> {
        if name.is_empty() {
            let what = match self.kind {
                "object" => "an object name",
                "joint" => "a joint name",
                _ => "a name",
            };
            return Err(Error::Invalid { what, problem: "must not be empty".into() });
        }
        if self.by_name.contains_key(&name) {
            return Err(Error::DuplicateName { kind: self.kind, name });
        }
        self.by_name.insert(name, id);
        Ok(())
    }

    pub(crate) fn remove(&mut self, name: &str) {
        self.by_name.remove(name);
        // A freed `base/i` below the hint becomes the first free suffix again.
        if let Some((base, suffix)) = name.rsplit_once('/')
            && let Ok(i) = suffix.parse::<u64>()
            && let Some(next) = self.next_suffix.get_mut(base)
            && i < *next
        {
            *next = i;
        }
    }

    pub(crate) fn contains(&self, name: &str) -> bool {
        self.by_name.contains_key(name)
    }

    pub(crate) fn get(&self, name: &str) -> Result<Id> {
        self.by_name.get(name).copied().ok_or_else(|| Error::UnknownName {
            kind: self.kind,
            name: name.to_string(),
            close_matches: close_matches(name, self.by_name.keys().map(String::as_str)),
        })
    }

    /// Names in alphabetical order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (&str, Id)> + '_ {
        self.by_name.iter().map(|(n, id)| (n.as_str(), *id))
    }
}

/// Up to three of `known` within a small edit distance of `name`, closest first: what
/// an unknown name's error suggests.
pub(crate) fn close_matches<'a>(name: &str, known: impl Iterator<Item = &'a str>) -> Vec<String> {
    let limit = (name.chars().count() / 3).max(2);
    let lower = name.to_lowercase();
    let mut scored: Vec<(usize, &str)> = known
        .map(|k| (edit_distance(&lower, &k.to_lowercase()), k))
        .filter(|(d, k)| *d <= limit || k.to_lowercase().starts_with(&lower))
        .collect();
    scored.sort();
    scored.into_iter().take(3).map(|(_, k)| k.to_string()).collect()
}

/// Levenshtein distance between two strings (in chars).
fn edit_distance(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1).min(row[j] + 1).min(diagonal + usize::from(ca != *cb));
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn duplicates_get_deterministic_suffixes() {
        let mut names = Names::new("object");
        for i in 0..3 {
            let n = names.unique("sphere");
            names.insert(n, i).unwrap();
        }
        let all: Vec<_> = names.iter().map(|(n, _)| n.to_string()).collect();
        assert_eq!(all, ["sphere", "sphere/1", "sphere/2"]);
        // The first free suffix, also after a removal or a name taken by hand.
        names.remove("sphere/1");
        assert_eq!(names.unique("sphere"), "sphere/1");
        names.insert("sphere/1".into(), 5).unwrap();
        names.insert("sphere/3".into(), 6).unwrap();
        assert_eq!(names.unique("sphere"), "sphere/4");
        names.remove("sphere/2");
        assert_eq!(names.unique("sphere"), "sphere/2");
    }

    #[test]
    fn unknown_names_suggest_close_ones() {
        let mut names = Names::new("joint");
        names.insert("shoulder".into(), 1).unwrap();
        names.insert("waist".into(), 2).unwrap();
        let err = names.get("sholder").unwrap_err();
        assert_eq!(err.to_string(), r#"no joint named "sholder" (did you mean shoulder?)"#);
        assert!(matches!(names.get("zzz"), Err(Error::UnknownName { close_matches, .. }) if close_matches.is_empty()));
        assert!(matches!(names.insert("waist".into(), 3), Err(Error::DuplicateName { .. })));
    }

    #[test]
    fn edit_distances() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("r1", "r1"), 0);
    }
}
