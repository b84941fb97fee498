//! A problem at a line of an MJCF file: what the reader refuses, or skips with a
//! warning.

/// A problem at a place of the file (or of a file it includes).
#[derive(Clone, Debug)]
pub(super) struct Problem {
    pub(super) element: String,
    pub(super) line: u32,
    pub(super) text: String,
    /// The included file it is in, if not the main one (set from `document` when the
    /// problem reaches [`read`](super::read::read)).
    pub(super) file: Option<String>,
    /// The address of the document its element is in: which file it is.
    pub(super) document: usize,
}

pub(super) type Parsed<T> = std::result::Result<T, Problem>;

/// What cannot be read: with `skip` (`MjcfOptions::skip_unsupported`) a line in
/// `skipped` naming its element and line, else the error.
pub(super) fn skip_or_refuse(mut p: Problem, skip: bool, skipped: &mut Vec<String>) -> Parsed<()> {
    if !skip {
        // The refusal says how to load the rest of the model.
        p.text.push_str(" (skip_unsupported skips what ARS cannot read, with a warning)");
        return Err(p);
    }
    skipped.push(format!("<{}> at line {}: {}", p.element, p.line, p.text));
    Ok(())
}

pub(super) fn problem(node: &roxmltree::Node<'_, '_>, text: impl Into<String>) -> Problem {
    let line = node.document().text_pos_at(node.range().start).row;
    let document = std::ptr::from_ref(node.document()) as usize;
    Problem { element: node.tag_name().name().to_string(), line, text: text.into(), file: None, document }
}
