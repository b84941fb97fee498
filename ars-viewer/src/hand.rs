//! The mouse's hold on the simulation in the window: the selected body, and the drag of
//! it in progress with the hooks that push it while running.

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{HookId, ObjectId, Simulation};
use kiss3d::camera::Camera3d;
use kiss3d::event::{Action, Key as WindowKey, Modifiers};
use kiss3d::glamx::{Vec2, Vec3};
use kiss3d::window::Window;

use crate::convert;
use crate::interact::{DragMode, Grab, Push, pick};
use crate::layout;

/// How far the mouse may move between press and release for a click, pixels.
const CLICK_SLOP: f64 = 5.0;

/// What a drag with these modifiers does: Ctrl pulls, Shift or Alt turns.
pub(crate) fn drag_mode(modifiers: Modifiers) -> Option<DragMode> {
    if modifiers.contains(Modifiers::Control) {
        Some(DragMode::Force)
    } else if modifiers.intersects(Modifiers::Shift | Modifiers::Alt) {
        Some(DragMode::Torque)
    } else {
        None
    }
}

/// The modifier keys held down, as the window saw their keys (X11 stamps events with
/// the modifiers only while the window has the focus).
pub(crate) fn held_modifiers(window: &Window) -> Modifiers {
    let down = |keys: [WindowKey; 2]| keys.iter().any(|k| window.get_key(*k) == Action::Press);
    let mut modifiers = Modifiers::empty();
    modifiers.set(Modifiers::Control, down([WindowKey::LControl, WindowKey::RControl]));
    modifiers.set(Modifiers::Shift, down([WindowKey::LShift, WindowKey::RShift]));
    modifiers.set(Modifiers::Alt, down([WindowKey::LAlt, WindowKey::RAlt]));
    modifiers
}

/// The mouse's hold on the simulation: the selected body, and the drag in progress
/// with the hooks that push it while running.
#[derive(Default)]
pub(crate) struct Hand {
    /// The cursor, window pixels.
    pub(crate) cursor: (f64, f64),
    /// Where the left button went down (not for a drag): a click if it comes up there.
    press: Option<(f64, f64)>,
    pub(crate) selected: Option<ObjectId>,
    pub(crate) grab: Option<Grab>,
    /// The hooks pushing the grabbed body (while running).
    push: Option<HookId<Push>>,
    /// Escape went down to deselect: its release must not close the window.
    pub(crate) escape_held: bool,
    /// The cursor when the panel was last drawn (where egui last saw it).
    pub(crate) ui_cursor: (f64, f64),
}

impl Hand {
    /// The picking ray under the cursor.
    pub(crate) fn ray(&self, camera: &layout::FramedCamera, size: Vec2) -> (Point3<f64>, Vector3<f64>) {
        let (o, d) = camera.unproject(Vec2::new(self.cursor.0 as f32, self.cursor.1 as f32), size);
        (convert::point_back(o), convert::vector_back(d))
    }

    /// The left button went down with `modifiers`: a drag of the selected body starts
    /// (at the point under the cursor when it is on the body, else at its centre).
    /// Returns whether a drag started.
    pub(crate) fn press(
        &mut self,
        sim: &Simulation,
        ray: (Point3<f64>, Vector3<f64>),
        view: Vector3<f64>,
        modifiers: Modifiers,
    ) -> bool {
        self.press = Some(self.cursor);
        let (Some(mode), Some(id)) = (drag_mode(modifiers), self.selected) else { return false };
        let at = match pick(sim, ray.0, ray.1) {
            Some((hit, at)) if hit == id => at,
            _ => match sim.scene().body(id) {
                Ok(b) => b.position(),
                Err(_) => return false,
            },
        };
        self.grab = Grab::new(sim, id, at, view, mode).ok();
        self.press = None;
        self.grab.is_some()
    }

    /// The left button came up: the drag ends, or a click selects the body under the
    /// cursor (or nothing, off every body).
    pub(crate) fn release(&mut self, sim: &mut Simulation, ray: (Point3<f64>, Vector3<f64>)) {
        if self.grab.take().is_some() {
            self.stop_pushing(sim);
        } else if let Some((x, y)) = self.press.take()
            && (x - self.cursor.0).hypot(y - self.cursor.1) <= CLICK_SLOP
        {
            self.selected = pick(sim, ray.0, ray.1).map(|(id, _)| id);
        }
    }

    fn stop_pushing(&mut self, sim: &mut Simulation) {
        if let Some(hook) = self.push.take() {
            let _ = sim.remove_hooks(hook);
        }
    }

    /// Forgets the selection and any drag.
    pub(crate) fn deselect(&mut self, sim: &mut Simulation) {
        self.stop_pushing(sim);
        self.grab = None;
        self.selected = None;
    }

    /// Moves the drag's target under the cursor: while running, the hooks push the
    /// body toward it at every step; paused, the body is moved there now.
    pub(crate) fn drag(
        &mut self,
        sim: &mut Simulation,
        ray: (Point3<f64>, Vector3<f64>),
        paused: bool,
    ) -> ars_core::Result<()> {
        let Some(grab) = self.grab.as_mut() else { return Ok(()) };
        if sim.scene().body(grab.object).is_err() {
            self.deselect(sim);
            return Ok(());
        }
        grab.aim(ray.0, ray.1);
        let grab = *grab;
        if paused {
            self.stop_pushing(sim);
            return grab.place(sim);
        }
        match self.push {
            Some(hook) => sim.hooks_mut(hook)?.0 = grab,
            None => self.push = Some(sim.add_hooks(Push(grab))?),
        }
        Ok(())
    }

    /// The selected body outlined (its bounding box), and the drag's line.
    pub(crate) fn draw(&self, sim: &Simulation, window: &mut Window) {
        if let Some(id) = self.selected
            && let Ok(object) = sim.scene().object(id)
        {
            let world = sim.scene().world();
            let boxes: Vec<_> = object.geoms().filter_map(|g| world.geom(g).ok()).map(|g| g.aabb()).collect();
            if let Some((mut low, mut high)) = boxes.first().copied() {
                for (l, h) in &boxes {
                    low = low.inf(l);
                    high = high.sup(h);
                }
                outline(window, convert::point(&low), convert::point(&high));
            }
        }
        if let Some(grab) = &self.grab
            && let Ok(from) = grab.point(sim)
        {
            let colour = match grab.mode {
                DragMode::Force => kiss3d::color::Color::new(1.0, 0.2, 0.6, 1.0),
                DragMode::Torque => kiss3d::color::Color::new(0.2, 0.6, 1.0, 1.0),
            };
            window.draw_line(convert::point(&from), convert::point(&grab.target), colour, 4.0, false);
            window.draw_point(convert::point(&grab.target), colour, 10.0);
        }
    }
}

/// The 12 edges of the box from `low` to `high`, in yellow.
fn outline(window: &mut Window, low: Vec3, high: Vec3) {
    let yellow = kiss3d::color::Color::new(1.0, 0.85, 0.0, 1.0);
    let corner = |i: u32| {
        Vec3::new(
            if i & 1 == 0 { low.x } else { high.x },
            if i & 2 == 0 { low.y } else { high.y },
            if i & 4 == 0 { low.z } else { high.z },
        )
    };
    for i in 0..8u32 {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                window.draw_line(corner(i), corner(i | bit), yellow, 3.0, false);
            }
        }
    }
}
