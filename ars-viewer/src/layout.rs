//! The window at any size: the text overlay wrapped to the window's width.

/// `items` in lines no wider than `max_width` as `width` measures a line: the items of
/// a line joined by `separator`, every line but the last ending with the separator's
/// start without its trailing spaces (`", "`: a comma). An item wider than a line has a
/// line of its own.
pub(crate) fn wrap_items(items: &[&str], separator: &str, max_width: f32, width: impl Fn(&str) -> f32) -> Vec<String> {
    let trail = separator.trim_end();
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for (i, item) in items.iter().enumerate() {
        let last = i + 1 == items.len();
        let end = if last { "" } else { trail };
        if !line.is_empty() {
            let longer = format!("{line}{separator}{item}{end}");
            if width(&longer) <= max_width {
                line = format!("{line}{separator}{item}");
                continue;
            }
            lines.push(format!("{line}{trail}"));
        }
        line = (*item).to_string();
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn items_wrap_at_separators_to_the_width() {
        // Ten units per character.
        let width = |s: &str| 10.0 * s.chars().count() as f32;
        let items = ["space: pause", "n: step", "r: reset", "x: axes"];
        assert_eq!(wrap_items(&items, ", ", 1000.0, width), ["space: pause, n: step, r: reset, x: axes"]);
        // "space: pause, n: step," is 22 characters: it fits 230, with its comma.
        assert_eq!(wrap_items(&items, ", ", 230.0, width), ["space: pause, n: step,", "r: reset, x: axes"]);
        assert_eq!(wrap_items(&items, ", ", 210.0, width), ["space: pause,", "n: step, r: reset,", "x: axes"]);
        // Narrower than an item: one item a line, none lost.
        assert_eq!(wrap_items(&items, ", ", 50.0, width), ["space: pause,", "n: step,", "r: reset,", "x: axes"]);
        assert!(wrap_items(&[], ", ", 50.0, width).is_empty());
    }
}
