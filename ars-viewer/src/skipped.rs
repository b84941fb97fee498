//! What opening an MJCF model skipped, said in one line: the model's list
//! (`OpenedFile::skipped`, `MjcfModel::skipped`) has a line per item, one per geom for
//! a model such as Gymnasium's ant, too many for a terminal.

/// One line for the items an opened file's model skipped (`None` when it skipped
/// nothing): how many, and how many of each kind (by the element they are on; a geom's
/// or a pair's unused contact parameters are their own kind).
///
/// ```
/// let skipped = [
///     "<geom> at line 12: friction, condim not used (contacts take ARS's surface: Scene::set_contact_surface)",
///     "<geom> at line 14: margin not used (contacts take ARS's surface: Scene::set_contact_surface)",
///     "<motor> at line 40: gear 150 is read as ...",
/// ]
/// .map(String::from);
/// assert_eq!(
///     ars_viewer::skipped_summary(&skipped).unwrap(),
///     "skipped 3 unsupported MJCF items (contact parameters of 2 <geom>, 1 <motor>); \
///      each is listed in the opened file's `skipped`"
/// );
/// assert_eq!(ars_viewer::skipped_summary(&[]), None);
/// ```
pub fn skipped_summary(skipped: &[String]) -> Option<String> {
    if skipped.is_empty() {
        return None;
    }
    // (what, element, count), in the order first met.
    let mut kinds: Vec<(&str, &str, usize)> = Vec::new();
    for item in skipped {
        let element = match item.strip_prefix('<').and_then(|rest| rest.find('>')) {
            Some(end) => &item[..end + 2],
            None => item.split_whitespace().next().unwrap_or("item"),
        };
        let what = if item.contains(" not used (contacts take") { "contact parameters of " } else { "" };
        match kinds.iter_mut().find(|(w, e, _)| *w == what && *e == element) {
            Some((_, _, n)) => *n += 1,
            None => kinds.push((what, element, 1)),
        }
    }
    let kinds: Vec<String> = kinds.iter().map(|(what, element, n)| format!("{what}{n} {element}")).collect();
    Some(format!(
        "skipped {} unsupported MJCF items ({}); each is listed in the opened file's `skipped`",
        skipped.len(),
        kinds.join(", ")
    ))
}
