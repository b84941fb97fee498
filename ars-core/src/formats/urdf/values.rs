//! The numbers of a URDF attribute, read as people write them: vectors separated by
//! spaces or commas, extra numbers dropped with a note (as PyBullet does), and xacro's
//! `$(optenv NAME default)` left in by a file not run through xacro read as xacro would
//! (the variable if it is set, else the default). Anything else that is not a number
//! is refused, naming the element, the attribute and the line.

use std::borrow::Cow;

use roxmltree::Node;

/// A problem at a line of the file: the element it is about (`link "arm"`, `joint
/// "elbow"`, `robot`) and what is wrong.
#[derive(Clone, Debug)]
pub(super) struct Problem {
    pub(super) element: String,
    pub(super) line: u32,
    pub(super) text: String,
}

pub(super) type Parsed<T> = std::result::Result<T, Problem>;

/// The line of a node's tag, from 1.
pub(super) fn line_of(node: &Node<'_, '_>) -> u32 {
    node.document().text_pos_at(node.range().start).row
}

/// A problem of `owner` (the link or joint, as errors name it) at `node`.
pub(super) fn problem(owner: &str, node: &Node<'_, '_>, text: impl Into<String>) -> Problem {
    Problem { element: owner.to_string(), line: line_of(node), text: text.into() }
}

/// Reads attribute values, keeping a note of what it reads leniently.
pub(super) struct Values<'n> {
    /// One line per value read leniently (extra numbers, xacro's `$(optenv)`).
    pub(super) notes: &'n mut Vec<String>,
}

impl Values<'_> {
    /// The number of attribute `attribute` of `node`, `None` when absent.
    pub(super) fn number(&mut self, owner: &str, node: &Node<'_, '_>, attribute: &str) -> Parsed<Option<f64>> {
        let Some(raw) = node.attribute(attribute) else { return Ok(None) };
        let value = self.expanded(owner, node, attribute, raw);
        match value.trim().parse::<f64>() {
            Ok(x) => Ok(Some(x)),
            Err(_) => Err(not_numbers(owner, node, attribute, raw, "is not a number")),
        }
    }

    /// The number of attribute `attribute`, or `default` when absent.
    pub(super) fn number_or(&mut self, owner: &str, node: &Node<'_, '_>, attribute: &str, default: f64) -> Parsed<f64> {
        Ok(self.number(owner, node, attribute)?.unwrap_or(default))
    }

    /// The number of attribute `attribute`, which must be there.
    pub(super) fn required(&mut self, owner: &str, node: &Node<'_, '_>, attribute: &str) -> Parsed<f64> {
        self.number(owner, node, attribute)?.ok_or_else(|| missing(owner, node, attribute))
    }

    /// The `N` numbers of attribute `attribute`, `None` when absent: separated by
    /// spaces or commas; more than `N` are cut to the first `N`, with a note.
    pub(super) fn vector<const N: usize>(
        &mut self,
        owner: &str,
        node: &Node<'_, '_>,
        attribute: &str,
    ) -> Parsed<Option<[f64; N]>> {
        let Some(raw) = node.attribute(attribute) else { return Ok(None) };
        let value = self.expanded(owner, node, attribute, raw);
        let mut numbers = Vec::with_capacity(N);
        for token in value.split(|c: char| c.is_whitespace() || c == ',').filter(|t| !t.is_empty()) {
            let Ok(x) = token.parse::<f64>() else {
                return Err(not_numbers(owner, node, attribute, raw, &format!("{token:?} is not a number")));
            };
            numbers.push(x);
        }
        if numbers.len() < N {
            let found = numbers.len();
            return Err(not_numbers(owner, node, attribute, raw, &format!("needs {N} numbers, has {found}")));
        }
        if numbers.len() > N {
            self.notes.push(format!(
                "{owner}: <{}> {attribute}={raw:?} at line {} has {} numbers: the first {N} are used, as PyBullet does",
                node.tag_name().name(),
                line_of(node),
                numbers.len()
            ));
        }
        let mut out = [0.0; N];
        out.copy_from_slice(&numbers[..N]);
        Ok(Some(out))
    }

    /// The attribute's text with xacro's `$(optenv NAME default)` replaced as xacro
    /// replaces it, with a note when it was there.
    fn expanded<'v>(&mut self, owner: &str, node: &Node<'_, '_>, attribute: &str, raw: &'v str) -> Cow<'v, str> {
        let expanded = expand_optenv(raw, |name| std::env::var(name).ok());
        if let Cow::Owned(value) = &expanded {
            self.notes.push(format!(
                "{owner}: <{}> {attribute}={raw:?} at line {}: xacro's $(optenv) read as {value:?}",
                node.tag_name().name(),
                line_of(node)
            ));
        }
        expanded
    }
}

/// `text` with each `$(optenv NAME default)` replaced by `env(NAME)`, or by the default
/// (the rest up to the closing parenthesis, trimmed) when it gives none.
pub(super) fn expand_optenv(text: &str, env: impl Fn(&str) -> Option<String>) -> Cow<'_, str> {
    const OPEN: &str = "$(optenv ";
    if !text.contains(OPEN) {
        return Cow::Borrowed(text);
    }
    let mut out = String::new();
    let mut rest = text;
    while let Some(start) = rest.find(OPEN) {
        let after = &rest[start + OPEN.len()..];
        let Some(end) = after.find(')') else { break };
        let inside = after[..end].trim();
        let (name, default) = inside.split_once(char::is_whitespace).unwrap_or((inside, ""));
        out.push_str(&rest[..start]);
        out.push_str(&env(name).unwrap_or_else(|| default.trim().to_string()));
        rest = &after[end + 1..];
    }
    out.push_str(rest);
    Cow::Owned(out)
}

/// An attribute that must be there and is not.
pub(super) fn missing(owner: &str, node: &Node<'_, '_>, attribute: &str) -> Problem {
    problem(owner, node, format!("<{}> needs a {attribute} attribute", node.tag_name().name()))
}

/// An attribute whose numbers cannot be read: `why`, and a hint when xacro was not run.
fn not_numbers(owner: &str, node: &Node<'_, '_>, attribute: &str, raw: &str, why: &str) -> Problem {
    let xacro = if raw.contains("$(") || raw.contains("${") {
        " (a xacro expression: run xacro on the file first)"
    } else {
        ""
    };
    problem(owner, node, format!("<{}> {attribute}={raw:?}: {why}{xacro}", node.tag_name().name()))
}

#[cfg(test)]
mod tests {
    use super::expand_optenv;

    #[test]
    fn optenv_reads_the_variable_if_set_else_its_default() {
        let env = |name: &str| (name == "SET").then(|| "1 2 3".to_string());
        assert_eq!(expand_optenv("$(optenv SET 0 0 0)", env), "1 2 3");
        assert_eq!(expand_optenv("$(optenv UNSET 0 -1.5708 3.1416)", env), "0 -1.5708 3.1416");
        assert_eq!(expand_optenv("a $(optenv UNSET) b", env), "a  b");
        assert_eq!(expand_optenv("1 2 3", env), "1 2 3");
        // Unclosed: left as written (then refused as no number).
        assert_eq!(expand_optenv("$(optenv UNSET 1", env), "$(optenv UNSET 1");
    }
}
