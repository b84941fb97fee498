//! `<include>`d files: gathered once, each parsed, a cycle refused.

use std::collections::HashMap;
use std::path::Path;

use super::problem::{Parsed, Problem, problem};

/// A file and its text: the model's, then those it includes, in the order met.
pub(super) type Files = Vec<(String, String)>;

/// Where each `<include>` leads: (its file's index, its byte offset there) → the
/// included file's index.
pub(super) type Includes = HashMap<(usize, usize), usize>;

/// Deepest chain of `<include>`s followed.
pub(super) const MAX_INCLUDE_DEPTH: usize = 32;

/// Reads the files that `text` (the file `name`) includes, wherever their `<include>`
/// is, depth first, into `files` after it; `stack` is the chain of files being read (a
/// cycle is refused). Returns the file's index.
pub(super) fn gather(
    name: &str,
    text: String,
    files: &mut Files,
    includes: &mut Includes,
    stack: &mut Vec<String>,
) -> Parsed<usize> {
    let document = roxmltree::Document::parse(&text).map_err(|e| Problem {
        element: "mujoco".into(),
        line: e.pos().row,
        text: format!("not XML: {e}"),
        file: Some(name.to_string()),
        document: 0,
    })?;
    let in_file = |mut p: Problem| {
        p.file.get_or_insert_with(|| name.to_string());
        p
    };
    let root = document.root_element();
    // The model's own file is a <mujoco>; an included file's root is dropped whatever its
    // name (<mujocoinclude> by convention), as MuJoCo does.
    if stack.len() <= 1 && root.tag_name().name() != "mujoco" {
        return Err(in_file(problem(&root, "the root element must be <mujoco>")));
    }
    let mut found = Vec::new();
    for node in root.descendants().filter(|c| c.is_element() && c.tag_name().name() == "include") {
        let file = node.attribute("file").ok_or_else(|| in_file(problem(&node, "needs a file")))?;
        // Relative to the model's own file, at any depth of includes (as MuJoCo).
        let main = stack.first().map_or(name, String::as_str);
        let path = Path::new(main).parent().unwrap_or(Path::new("")).join(file);
        let path_name = path.display().to_string();
        if stack.contains(&path_name) || stack.len() >= MAX_INCLUDE_DEPTH {
            return Err(in_file(problem(&node, format!("includes {path_name} again: a cycle of includes"))));
        }
        let included = std::fs::read_to_string(&path)
            .map_err(|e| in_file(problem(&node, format!("cannot read {path_name}: {e}"))))?;
        found.push((node.range().start, path_name, included));
    }
    drop(document);
    let me = files.len();
    files.push((name.to_string(), text));
    for (offset, path, included) in found {
        stack.push(path.clone());
        let index = gather(&path, included, files, includes, stack)?;
        includes.insert((me, offset), index);
        stack.pop();
    }
    Ok(me)
}

/// The parsed files of a model, read through their `<include>`s.
pub(super) struct Tree<'a, 'input> {
    pub(super) documents: &'a [roxmltree::Document<'input>],
    pub(super) includes: &'a Includes,
}

impl<'a, 'input> Tree<'a, 'input> {
    /// The index of the file `node` is in.
    pub(super) fn file_of(&self, node: &roxmltree::Node<'a, 'input>) -> usize {
        self.file_at(std::ptr::from_ref(node.document()) as usize).unwrap_or(0)
    }

    /// The index of the file whose document is at `address` (a [`Problem`]'s).
    pub(super) fn file_at(&self, address: usize) -> Option<usize> {
        self.documents.iter().position(|d| std::ptr::from_ref(d) as usize == address)
    }

    /// `node`'s child elements, each `<include>` replaced by the included file's
    /// top-level elements (MuJoCo reads an include in place, wherever it is).
    pub(super) fn elements(&self, node: roxmltree::Node<'a, 'input>) -> Vec<roxmltree::Node<'a, 'input>> {
        let mut out = Vec::new();
        for child in node.children().filter(|c| c.is_element()) {
            if child.tag_name().name() == "include" {
                let included = self.includes[&(self.file_of(&child), child.range().start)];
                out.extend(self.elements(self.documents[included].root_element()));
            } else {
                out.push(child);
            }
        }
        out
    }
}
