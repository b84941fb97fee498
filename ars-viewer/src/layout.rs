//! The window at any size: where the camera aims when the panel covers part of the
//! window, and the text overlay wrapped to the window's width.

use kiss3d::camera::{Camera3d, OrbitCamera3d};
use kiss3d::event::WindowEvent;
use kiss3d::glamx::{Mat4, Pose3, Vec2, Vec3};
use kiss3d::window::Canvas;

/// A rectangle `[left, top, right, bottom]`, y down (window coordinates).
pub(crate) type Rect = [f32; 4];

/// The centre of the part of a `width × height` window that `panels` leave free: the
/// largest (by area) of the strips, each as tall or as wide as the window, that no
/// panel overlaps (between two panels side by side, beside one, above or below them
/// all); the window's centre when none is free.
pub(crate) fn free_centre_of(width: f32, height: f32, panels: &[Rect]) -> (f32, f32) {
    let middle = (width / 2.0, height / 2.0);
    // The intervals of [0, total] that none of `spans` covers.
    let gaps = |spans: Vec<(f32, f32)>, total: f32| {
        let mut spans: Vec<(f32, f32)> =
            spans.into_iter().map(|(a, b)| (a.clamp(0.0, total), b.clamp(0.0, total))).collect();
        spans.sort_by(|a, b| a.0.total_cmp(&b.0));
        let (mut free, mut reached) = (Vec::new(), 0.0f32);
        for (a, b) in spans {
            if a > reached {
                free.push((reached, a));
            }
            reached = reached.max(b);
        }
        if total > reached {
            free.push((reached, total));
        }
        free
    };
    let columns = gaps(panels.iter().map(|p| (p[0], p[2])).collect(), width)
        .into_iter()
        .map(|(a, b)| ((b - a) * height, ((a + b) / 2.0, middle.1)));
    let rows = gaps(panels.iter().map(|p| (p[1], p[3])).collect(), height)
        .into_iter()
        .map(|(a, b)| ((b - a) * width, (middle.0, (a + b) / 2.0)));
    columns.chain(rows).filter(|(area, _)| *area > 0.0).max_by(|a, b| a.0.total_cmp(&b.0)).map_or(middle, |(_, c)| c)
}

/// Whether a click at `cursor` is the panel's: egui's word (`egui_says`) when egui saw
/// the cursor there (`ui_cursor`, where it was when the panel was last drawn), else
/// whether it falls on one of `panels` (a click that arrives with the move that brought
/// the cursor, as xdotool sends them, would otherwise be judged where the cursor was).
pub(crate) fn pointer_on_panel(cursor: (f64, f64), ui_cursor: (f64, f64), egui_says: bool, panels: &[Rect]) -> bool {
    if cursor == ui_cursor {
        return egui_says;
    }
    let (x, y) = (cursor.0 as f32, cursor.1 as f32);
    panels.iter().any(|[l, t, r, b]| (*l..=*r).contains(&x) && (*t..=*b).contains(&y))
}

/// The shift, in normalised device coordinates (x right, y up, the window from −1 to
/// 1), that takes the window's centre to `centre` (window coordinates, y down).
pub(crate) fn ndc_shift(width: f32, height: f32, centre: (f32, f32)) -> Vec2 {
    Vec2::new(2.0 * centre.0 / width - 1.0, 1.0 - 2.0 * centre.1 / height)
}

/// An orbit camera whose image is shifted on the window by `shift` (normalised device
/// coordinates): what it looks at appears at the centre of the part of the window the
/// panel leaves free, not under the panel. The field of view and the scale are the
/// orbit camera's; projecting and unprojecting (picking) use the shifted projection,
/// and the mouse acts as if the window's centre were the shifted one (zooming towards
/// the cursor zooms towards the point under it).
pub(crate) struct FramedCamera {
    /// The orbit camera (the mouse orbits, pans and zooms it).
    pub(crate) orbit: OrbitCamera3d,
    /// The shift of the image, normalised device coordinates (zero: not shifted).
    pub(crate) shift: Vec2,
}

impl FramedCamera {
    /// An unshifted camera at `eye` looking at `at`.
    pub(crate) fn new(eye: Vec3, at: Vec3) -> Self {
        FramedCamera { orbit: OrbitCamera3d::new(eye, at), shift: Vec2::ZERO }
    }

    /// The shift as a matrix applied after the projection.
    fn shift_matrix(&self) -> Mat4 {
        Mat4::from_translation(Vec3::new(self.shift.x, self.shift.y, 0.0))
    }

    /// The shift in pixels of a `width × height` window (y down).
    fn pixel_shift(&self, width: f32, height: f32) -> Vec2 {
        Vec2::new(self.shift.x * width / 2.0, -self.shift.y * height / 2.0)
    }
}

impl Camera3d for FramedCamera {
    fn handle_event(&mut self, canvas: &Canvas, event: &WindowEvent) {
        match *event {
            // The orbit camera takes the centre of the window for the centre of its
            // image: give it the cursor where it would be on the unshifted image.
            WindowEvent::CursorPos(x, y, modifiers) => {
                let (w, h) = canvas.size();
                let d = self.pixel_shift(w as f32, h as f32);
                let moved = WindowEvent::CursorPos(x - f64::from(d.x), y - f64::from(d.y), modifiers);
                self.orbit.handle_event(canvas, &moved);
            }
            _ => self.orbit.handle_event(canvas, event),
        }
    }

    fn eye(&self) -> Vec3 {
        self.orbit.eye()
    }

    fn view_transform(&self) -> Pose3 {
        self.orbit.view_transform()
    }

    fn transformation(&self) -> Mat4 {
        self.shift_matrix() * self.orbit.transformation()
    }

    fn inverse_transformation(&self) -> Mat4 {
        self.orbit.inverse_transformation() * self.shift_matrix().inverse()
    }

    fn clip_planes(&self) -> (f32, f32) {
        self.orbit.clip_planes()
    }

    fn update(&mut self, canvas: &Canvas) {
        self.orbit.update(canvas);
    }

    fn view_transform_pair(&self, pass: usize) -> (Pose3, Mat4) {
        let (view, projection) = self.orbit.view_transform_pair(pass);
        (view, self.shift_matrix() * projection)
    }

    fn render_layers(&self) -> u32 {
        self.orbit.render_layers()
    }
}

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
    fn the_free_centre_is_beside_a_panel_where_most_room_is() {
        // No panel: the window's centre.
        assert_eq!(free_centre_of(800.0, 600.0, &[]), (400.0, 300.0));
        // The panel down the left, 348 px wide (43 % of 800): the centre of the 452 px
        // to its right.
        assert_eq!(free_centre_of(800.0, 600.0, &[[8.0, 8.0, 348.0, 590.0]]), (574.0, 300.0));
        // Moved to the right edge: the centre of what is left of it.
        assert_eq!(free_centre_of(800.0, 600.0, &[[500.0, 0.0, 800.0, 600.0]]), (250.0, 300.0));
        // Collapsed to its title bar at the top: the whole width below it.
        assert_eq!(free_centre_of(800.0, 600.0, &[[8.0, 8.0, 348.0, 40.0]]), (400.0, 320.0));
        // Over the whole window (or beyond it): nothing is free, the window's centre.
        assert_eq!(free_centre_of(800.0, 600.0, &[[-10.0, -10.0, 900.0, 700.0]]), (400.0, 300.0));
    }

    #[test]
    fn the_free_centre_of_several_panels_is_in_the_widest_gap() {
        // The panel on the left and the editor on the right, both tall: between them.
        let (panel, editor) = ([8.0, 8.0, 353.0, 590.0], [722.0, 8.0, 1016.0, 500.0]);
        assert_eq!(free_centre_of(1024.0, 768.0, &[panel, editor]), (537.5, 384.0));
        // Both short: the whole width below them holds more.
        let (panel, editor) = ([8.0, 8.0, 353.0, 340.0], [722.0, 8.0, 1016.0, 380.0]);
        assert_eq!(free_centre_of(1024.0, 768.0, &[panel, editor]), (512.0, 574.0));
        // Both collapsed to their title bars: the whole width below them.
        let (panel, editor) = ([8.0, 8.0, 353.0, 40.0], [722.0, 8.0, 1016.0, 40.0]);
        assert_eq!(free_centre_of(1024.0, 768.0, &[panel, editor]), (512.0, 404.0));
        // Overlapping panels count once.
        assert_eq!(
            free_centre_of(800.0, 600.0, &[[0.0, 0.0, 300.0, 600.0], [100.0, 0.0, 400.0, 600.0]]),
            (600.0, 300.0)
        );
    }

    #[test]
    fn a_click_is_the_panels_where_egui_saw_it_or_on_a_panel() {
        let panels = [[8.0, 8.0, 348.0, 590.0]];
        // Where egui last saw the cursor, egui decides (a pop-up outside the panel).
        assert!(pointer_on_panel((500.0, 300.0), (500.0, 300.0), true, &panels));
        assert!(!pointer_on_panel((100.0, 100.0), (100.0, 100.0), false, &panels));
        // Moved since: the panel's rectangle decides, whatever egui said before.
        assert!(!pointer_on_panel((573.0, 450.0), (170.0, 142.0), true, &panels));
        assert!(pointer_on_panel((170.0, 142.0), (573.0, 450.0), false, &panels));
        assert!(!pointer_on_panel((170.0, 142.0), (573.0, 450.0), false, &[]));
    }

    #[test]
    fn the_shift_takes_the_window_centre_to_the_free_centre() {
        assert_eq!(ndc_shift(800.0, 600.0, (400.0, 300.0)), Vec2::ZERO);
        assert_eq!(ndc_shift(800.0, 600.0, (600.0, 300.0)), Vec2::new(0.5, 0.0));
        // y down in the window, up in device coordinates.
        assert_eq!(ndc_shift(800.0, 600.0, (400.0, 450.0)), Vec2::new(0.0, -0.5));
    }

    #[test]
    fn a_shifted_camera_shows_its_target_at_the_free_centre_and_picks_through_it() {
        let at = Vec3::new(1.0, 0.5, 2.0);
        let mut camera = FramedCamera::new(Vec3::new(6.0, 3.0, 6.0), at);
        // The orbit camera's image is 800 × 600 until the window says otherwise.
        let size = Vec2::new(800.0, 600.0);
        let centre = camera.project(at, size);
        assert!((centre - Vec2::new(400.0, 300.0)).length() < 1e-3, "{centre}");
        let free = free_centre_of(size.x, size.y, &[[8.0, 8.0, 348.0, 590.0]]);
        camera.shift = ndc_shift(size.x, size.y, free);
        // kiss3d's `project` gives y up from the bottom: the middle row either way.
        let shown = camera.project(at, size);
        assert!((shown - Vec2::new(free.0, free.1)).length() < 1e-3, "{shown} for {free:?}");
        // Another point keeps its distance to the target on the image: a shift, not a
        // zoom.
        let other = Vec3::new(1.0, 1.5, 2.0);
        let (before, after) = (
            FramedCamera::new(Vec3::new(6.0, 3.0, 6.0), at).project(other, size) - centre,
            camera.project(other, size) - shown,
        );
        assert!((before - after).length() < 1e-3, "{before} then {after}");
        // The ray through the free centre (window coordinates, y down) passes through
        // the target.
        let (origin, direction) = camera.unproject(Vec2::new(free.0, free.1), size);
        let to_target = at - origin;
        let miss = (to_target - direction * to_target.dot(direction)).length();
        assert!(miss < 1e-3, "the ray misses the target by {miss}");
    }

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
