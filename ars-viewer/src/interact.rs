//! Touching the simulation with the mouse: picking the body under the cursor, and
//! dragging it (a spring force toward the mouse, or a spring torque turning it, while
//! running; moved kinematically while paused). Plain functions of the simulation and
//! a ray, so that they are tested without a window.

use ars_core::nalgebra::{Matrix3, Point3, UnitQuaternion, Vector3};
use ars_core::world::raycast::Ray;
use ars_core::{Hooks, ObjectId, Result, Simulation};

/// The spring's stiffness per kilogram (N/m per kg, s⁻²): every body follows the
/// mouse with the same natural frequency (10 rad/s), whatever its mass. The damping is
/// critical (`2 √k` per kilogram).
pub const SPRING_STIFFNESS: f64 = 100.0;

/// The farthest a click picks, m.
const PICK_DISTANCE: f64 = 1000.0;

/// The largest force or torque a drag applies (ODE's accumulators refuse more than
/// 10⁹): a spring stretched across the scene on a heavy body is capped, not an error.
const MAX_PUSH: f64 = 1e8;

/// The shortest lever used to turn a dragged point into an angle, m (a body grabbed at
/// its centre still turns).
const MIN_LEVER: f64 = 0.1;

/// The moving object (one with a body) whose geoms the ray meets first, with the point
/// hit; `None` when the ray meets nothing, or a static object (a floor) first.
///
/// ```
/// use ars_core::nalgebra::{Point3, Vector3};
/// use ars_core::{Mass, Simulation};
///
/// let mut sim = Simulation::new()?;
/// sim.scene_mut().add_floor_plane(Vector3::y(), 0.0)?;
/// let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0))?;
/// let hit = ars_viewer::pick(&sim, Point3::new(0.0, 1.0, 5.0), -Vector3::z());
/// assert_eq!(hit.map(|(id, _)| id), Some(ball));
/// assert!((hit.unwrap().1.z - 0.5).abs() < 1e-9);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub fn pick(sim: &Simulation, origin: Point3<f64>, direction: Vector3<f64>) -> Option<(ObjectId, Point3<f64>)> {
    let direction = direction.try_normalize(1e-12)?;
    let world = sim.scene().world();
    let hit = world.cast_ray(Ray { origin, direction }, PICK_DISTANCE, None).ok()??;
    let body = world.geom(hit.geom).ok()?.body()?;
    let (id, _) = sim.scene().bodies().find(|(_, b)| *b == body)?;
    Some((id, hit.position))
}

/// Where the ray meets the plane through `point` with normal `normal`; `None` when it
/// runs parallel to the plane or points away from it.
pub fn ray_plane(
    origin: Point3<f64>,
    direction: Vector3<f64>,
    point: Point3<f64>,
    normal: Vector3<f64>,
) -> Option<Point3<f64>> {
    let along = direction.dot(&normal);
    if along.abs() < 1e-9 {
        return None;
    }
    let t = (point - origin).dot(&normal) / along;
    (t >= 0.0).then(|| origin + direction * t)
}

/// The spring force pulling a body's grabbed point at `point` (moving at `velocity`)
/// toward `target`, for a body of `mass` kg: `m (k (target − point) − 2 √k v)`, with
/// `k` = [`SPRING_STIFFNESS`]. Proportional to the mass, so that light and heavy bodies
/// follow alike; capped at 10⁸ N.
pub fn spring_force(mass: f64, point: Point3<f64>, velocity: Vector3<f64>, target: Point3<f64>) -> Vector3<f64> {
    let k = SPRING_STIFFNESS;
    cap(mass * (k * (target - point) - 2.0 * k.sqrt() * velocity))
}

/// The spring torque turning a body of world-frame inertia `inertia` (kg·m², about its
/// centre of mass) by the rotation vector `error` (rad, axis times angle), against its
/// angular velocity: `I (k θ − 2 √k ω)`. Through the inertia, so that every body turns
/// with the same natural frequency; capped at 10⁸ N·m.
pub fn spring_torque(inertia: &Matrix3<f64>, error: Vector3<f64>, angular_velocity: Vector3<f64>) -> Vector3<f64> {
    let k = SPRING_STIFFNESS;
    cap(inertia * (k * error - 2.0 * k.sqrt() * angular_velocity))
}

fn cap(v: Vector3<f64>) -> Vector3<f64> {
    if v.iter().all(|c| c.is_finite()) { v.cap_magnitude(MAX_PUSH) } else { Vector3::zeros() }
}

/// What a drag does to the body.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum DragMode {
    /// Pulls the grabbed point toward the mouse (Ctrl).
    Force,
    /// Turns the body about its centre, the grabbed point toward the mouse (Shift).
    Torque,
}

/// A body held by the mouse: where it was grabbed, and where the mouse is, on the plane
/// through the grabbed point facing the camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Grab {
    /// The object held.
    pub object: ObjectId,
    /// Force or torque.
    pub mode: DragMode,
    /// The grabbed point in the body's frame.
    pub local: Point3<f64>,
    /// The grabbed point where it was when grabbed, world frame (a point of the plane).
    pub start: Point3<f64>,
    /// The body's orientation when grabbed.
    pub start_rotation: UnitQuaternion<f64>,
    /// The plane's unit normal (toward the camera).
    pub normal: Vector3<f64>,
    /// The point under the mouse, on the plane.
    pub target: Point3<f64>,
}

impl Grab {
    /// Grabs `object` at the world point `at`, seen along `view` (the camera's viewing
    /// direction).
    pub fn new(
        sim: &Simulation,
        object: ObjectId,
        at: Point3<f64>,
        view: Vector3<f64>,
        mode: DragMode,
    ) -> Result<Self> {
        let body = sim.scene().body(object)?;
        let normal = (-view).try_normalize(1e-12).unwrap_or_else(Vector3::y);
        Ok(Grab {
            object,
            mode,
            local: body.pose().inverse_transform_point(&at),
            start: at,
            start_rotation: body.quaternion(),
            normal,
            target: at,
        })
    }

    /// Moves the target to where the ray meets the grab's plane (kept when it does not).
    pub fn aim(&mut self, origin: Point3<f64>, direction: Vector3<f64>) {
        if let Some(p) = ray_plane(origin, direction, self.start, self.normal) {
            self.target = p;
        }
    }

    /// The grabbed point where it is now, world frame.
    pub fn point(&self, sim: &Simulation) -> Result<Point3<f64>> {
        Ok(sim.scene().body(self.object)?.pose() * self.local)
    }

    /// The orientation a torque drag turns the body toward: the start orientation
    /// turned about the axis facing the camera crossed with the mouse's displacement,
    /// by that displacement over the lever (the grabbed point's distance from the
    /// centre), so that the grabbed point roughly follows the mouse.
    pub fn target_rotation(&self, centre: Point3<f64>) -> UnitQuaternion<f64> {
        let lever = (self.start - centre).norm().max(MIN_LEVER);
        let turn = self.normal.cross(&(self.target - self.start)) / lever;
        UnitQuaternion::from_scaled_axis(turn) * self.start_rotation
    }

    /// Pushes the body for the next step, through the safe API: the spring force at the
    /// grabbed point ([`spring_force`]), or the spring torque ([`spring_torque`]).
    pub fn push(&self, sim: &mut Simulation) -> Result<()> {
        let body = sim.scene().body(self.object)?;
        match self.mode {
            DragMode::Force => {
                let point = body.pose() * self.local;
                let force = spring_force(body.mass(), point, body.point_velocity(point), self.target);
                sim.scene_mut().body_mut(self.object)?.add_force_at_point(force, point)
            }
            DragMode::Torque => {
                let goal = self.target_rotation(body.position());
                let error = (goal * body.quaternion().inverse()).scaled_axis();
                let torque = spring_torque(&body.inertia_world(), error, body.angular_velocity());
                sim.scene_mut().body_mut(self.object)?.add_torque(torque)
            }
        }
    }

    /// Moves the body at once (paused): the grabbed point onto the target, or the body
    /// turned to the target rotation.
    pub fn place(&self, sim: &mut Simulation) -> Result<()> {
        let pose = sim.scene().body(self.object)?.pose();
        match self.mode {
            DragMode::Force => {
                let centre = self.target - pose.rotation * self.local.coords;
                sim.scene_mut().set_position(self.object, centre)
            }
            DragMode::Torque => {
                let goal = self.target_rotation(pose.translation.vector.into());
                sim.scene_mut().set_rotation(self.object, goal.to_rotation_matrix())
            }
        }
    }
}

/// The hooks that push a dragged body at every step while the button is held (added
/// when a drag starts, removed when it ends; the window moves its target every frame).
pub(crate) struct Push(pub(crate) Grab);

impl Hooks for Push {
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        // The body may have been removed by the program: then there is nothing to push.
        if sim.scene().body(self.0.object).is_ok() { self.0.push(sim) } else { Ok(()) }
    }
    fn runs_at(&self, point: ars_core::HookPoint) -> bool {
        point == ars_core::HookPoint::PreStep
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ars_core::Mass;

    fn scene() -> (Simulation, ObjectId, ObjectId) {
        let mut sim = Simulation::new().unwrap();
        sim.scene_mut().add_floor_plane(Vector3::y(), 0.0).unwrap();
        let light = sim.scene_mut().add_box([0.5, 0.5, 0.5], [0.0, 0.25, 0.0], Mass::Total(1.0)).unwrap();
        let heavy = sim.scene_mut().add_sphere(0.5, [3.0, 0.5, 0.0], Mass::Total(50.0)).unwrap();
        (sim, light, heavy)
    }

    #[test]
    fn a_ray_picks_the_first_moving_body_and_not_the_floor() {
        let (sim, light, heavy) = scene();
        let down = -Vector3::y();
        let (id, at) = pick(&sim, Point3::new(0.1, 5.0, 0.1), down).unwrap();
        assert_eq!(id, light);
        assert!((at.y - 0.5).abs() < 1e-9, "the top face, got {at}");
        assert_eq!(pick(&sim, Point3::new(3.0, 5.0, 0.0), down).map(|h| h.0), Some(heavy));
        // The floor alone, or nothing at all.
        assert_eq!(pick(&sim, Point3::new(10.0, 5.0, 0.0), down), None);
        assert_eq!(pick(&sim, Point3::new(0.0, 5.0, 0.0), Vector3::y()), None);
        // From the side, the box hides the sphere behind it.
        assert_eq!(pick(&sim, Point3::new(-5.0, 0.3, 0.0), Vector3::x()).map(|h| h.0), Some(light));
        // A direction of zero length picks nothing (no NaN reaches the cast).
        assert_eq!(pick(&sim, Point3::new(0.0, 5.0, 0.0), Vector3::zeros()), None);
    }

    #[test]
    fn the_plane_is_met_in_front_only() {
        let (o, n, p) = (Point3::new(0.0, 0.0, 5.0), Vector3::z(), Point3::new(0.0, 0.0, 1.0));
        let hit = ray_plane(o, Vector3::new(1.0, 0.0, -1.0), p, n).unwrap();
        assert!((hit - Point3::new(4.0, 0.0, 1.0)).norm() < 1e-12);
        assert_eq!(ray_plane(o, Vector3::z(), p, n), None);
        assert_eq!(ray_plane(o, Vector3::x(), p, n), None);
    }

    #[test]
    fn the_spring_scales_with_mass_and_damps_critically() {
        let (p, t) = (Point3::origin(), Point3::new(1.0, 0.0, 0.0));
        let f1 = spring_force(1.0, p, Vector3::zeros(), t);
        let f50 = spring_force(50.0, p, Vector3::zeros(), t);
        assert!((f1 - Vector3::new(SPRING_STIFFNESS, 0.0, 0.0)).norm() < 1e-12);
        assert!((f50 - 50.0 * f1).norm() < 1e-9);
        // Moving toward the target at √k·d / 4 halves the pull; at √k·d / 2 the
        // damping cancels it.
        let v = Vector3::new(SPRING_STIFFNESS.sqrt() / 4.0, 0.0, 0.0);
        assert!((spring_force(1.0, p, v, t) - f1 / 2.0).norm() < 1e-9);
        assert!(spring_force(1.0, p, v * 2.0, t).norm() < 1e-9);
        // Capped, and never NaN.
        assert!(spring_force(1e9, p, Vector3::zeros(), t).norm() <= MAX_PUSH * (1.0 + 1e-12));
        assert_eq!(spring_force(f64::NAN, p, Vector3::zeros(), t), Vector3::zeros());
        let torque = spring_torque(&(Matrix3::identity() * 2.0), Vector3::z(), Vector3::zeros());
        assert!((torque - Vector3::new(0.0, 0.0, 2.0 * SPRING_STIFFNESS)).norm() < 1e-9);
    }

    /// Held for 2 s at 1 m above where they were grabbed, a 1 kg box and a 50 kg ball
    /// both get there (within the sag gravity causes on a spring of 10 rad/s: g/k).
    #[test]
    fn light_and_heavy_bodies_both_follow_the_spring() {
        let (mut sim, light, heavy) = scene();
        for id in [light, heavy] {
            let start = sim.scene().body(id).unwrap().position();
            let mut grab = Grab::new(&sim, id, start, -Vector3::z(), DragMode::Force).unwrap();
            grab.aim(Point3::new(start.x, start.y + 1.0, 10.0), -Vector3::z());
            assert!((grab.target - Point3::new(start.x, start.y + 1.0, 0.0)).norm() < 1e-9);
            let hook = sim.add_hooks(Push(grab)).unwrap();
            sim.run_for(2.0).unwrap();
            sim.remove_hooks(hook).unwrap();
            let p = sim.scene().body(id).unwrap().position();
            let sag = 9.81 / SPRING_STIFFNESS;
            assert!((p.y - (start.y + 1.0 - sag)).abs() < 0.05, "{id:?} at {p}, from {start}");
            assert!((p.x - start.x).abs() < 0.05 && p.z.abs() < 0.05, "{id:?} at {p}");
        }
    }

    #[test]
    fn a_torque_drag_turns_the_body_toward_the_mouse() {
        let mut sim = Simulation::new().unwrap();
        sim.scene_mut().world_mut().set_gravity(Vector3::zeros()).unwrap();
        let cube = sim.scene_mut().add_box([1.0, 1.0, 1.0], [0.0, 0.0, 0.0], Mass::Total(3.0)).unwrap();
        // Grabbed on its front face (toward the camera on +Z), dragged 0.5 m right:
        // a quarter of a radian… about +Y, the front face turning right.
        let mut grab = Grab::new(&sim, cube, Point3::new(0.0, 0.0, 0.5), -Vector3::z(), DragMode::Torque).unwrap();
        grab.aim(Point3::new(0.5, 0.0, 5.0), -Vector3::z());
        let goal = grab.target_rotation(Point3::origin());
        assert!((goal.scaled_axis() - Vector3::new(0.0, 1.0, 0.0)).norm() < 1e-9, "{}", goal.scaled_axis());
        let hook = sim.add_hooks(Push(grab)).unwrap();
        sim.run_for(2.0).unwrap();
        sim.remove_hooks(hook).unwrap();
        let turned = sim.scene().body(cube).unwrap().quaternion().scaled_axis();
        assert!((turned - Vector3::y()).norm() < 0.02, "turned by {turned}");
        assert!(sim.scene().body(cube).unwrap().position().coords.norm() < 1e-6, "a pure torque moved the centre");
    }

    #[test]
    fn paused_the_grabbed_point_goes_to_the_mouse_at_once() {
        let (mut sim, light, _) = scene();
        let at = Point3::new(0.25, 0.4, 0.1);
        let mut grab = Grab::new(&sim, light, at, Vector3::new(0.0, 0.0, -1.0), DragMode::Force).unwrap();
        grab.aim(Point3::new(2.25, 1.4, 5.0), -Vector3::z());
        grab.place(&mut sim).unwrap();
        let moved = grab.point(&sim).unwrap();
        assert!((moved - Point3::new(2.25, 1.4, 0.1)).norm() < 1e-9, "{moved}");
        assert_eq!(sim.scene().time(), 0.0);
    }
}
