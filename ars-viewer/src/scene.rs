//! Mirrors a simulation into a kiss3d scene: one node per object, posed every frame,
//! added and removed as objects come and go; plus lines for lasers, and on request
//! the world axes, contacts and joints.

use std::collections::HashMap;

use ars_core::nalgebra::{Point3, Vector3};
use ars_core::{ObjectId, RenderQuality, Shape, Simulation, WindowSettings};
use kiss3d::color::Color;
use kiss3d::glamx::{Quat, Vec3};
use kiss3d::light::Light;
use kiss3d::scene::SceneNode3d;
use kiss3d::window::Window;

use crate::convert;
use crate::layout::FramedCamera;
use crate::look::{PLANE_HALF_SIZE, look_of};
use crate::material::{FlatMaterial, SharedMaterial};

struct ObjectNode {
    group: SceneNode3d,
    dynamic: bool,
    /// The colour it is drawn with (its own, or the palette's).
    color: [f32; 3],
}

/// The scene nodes of a simulation's objects.
pub struct SceneMirror {
    nodes: HashMap<ObjectId, ObjectNode>,
    /// Draw the world axes at the origin (X red, Y green, Z blue, 1 m long).
    pub show_axes: bool,
    /// Draw joint anchors and axes.
    pub show_joints: bool,
    /// Draw the contact points of the last step, with their normals.
    pub show_contacts: bool,
    /// Draw the contact forces of the last step as arrows, [`force_scale`](Self::force_scale)
    /// metres per newton. The world must report them
    /// ([`World::set_contact_feedback`](ars_core::World::set_contact_feedback): the window's
    /// Forces button turns it on while they are drawn).
    pub show_forces: bool,
    /// The arrows' length per newton, m/N.
    pub force_scale: f64,
    /// The fast materials (objects, floors), when drawing fast.
    fast: Option<(SharedMaterial, SharedMaterial)>,
}

impl Default for SceneMirror {
    fn default() -> Self {
        SceneMirror {
            nodes: HashMap::new(),
            show_axes: false,
            show_joints: false,
            show_contacts: false,
            show_forces: false,
            force_scale: DEFAULT_FORCE_SCALE,
            fast: None,
        }
    }
}

impl SceneMirror {
    /// An empty mirror.
    pub fn new() -> Self {
        SceneMirror::default()
    }

    /// Whether it draws with the fast materials.
    pub(crate) fn draws_fast(&self) -> bool {
        self.fast.is_some()
    }

    /// Draws with the fast materials (flat shading, checkered floors) from now on.
    /// Needs the rendering context of this thread.
    pub(crate) fn draw_fast(&mut self) {
        self.fast = Some((FlatMaterial::shared(None), FlatMaterial::shared(Some(1.0))));
    }

    /// Forgets every node (after the simulation was rebuilt).
    pub fn clear(&mut self) {
        for (_, mut n) in self.nodes.drain() {
            n.group.remove();
        }
    }

    /// The colour `id` is drawn with (its own, or the one the viewer gave it).
    pub fn drawn_color(&self, id: ObjectId) -> Option<[f32; 3]> {
        self.nodes.get(&id).map(|n| n.color)
    }

    /// Draws `id` anew at the next [`sync`](Self::sync) (after its colour changed).
    pub fn redraw(&mut self, id: ObjectId) {
        if let Some(mut n) = self.nodes.remove(&id) {
            n.group.remove();
        }
    }

    /// Creates nodes for new objects, removes those of removed objects, and poses
    /// every dynamic one.
    pub fn sync(&mut self, sim: &Simulation, scene: &mut SceneNode3d) -> ars_core::Result<()> {
        let live: Vec<(String, ObjectId)> = sim.scene().objects().map(|(n, id)| (n.to_string(), id)).collect();
        self.nodes.retain(|id, node| {
            let keep = live.iter().any(|(_, l)| l == id);
            if !keep {
                node.group.remove();
            }
            keep
        });
        for (_, id) in &live {
            if !self.nodes.contains_key(id) {
                let n = self.nodes.len();
                let node = build_node(sim, *id, scene, n, self.fast.as_ref())?;
                self.nodes.insert(*id, node);
            }
        }
        for (id, node) in &mut self.nodes {
            if node.dynamic {
                node.group.set_pose(convert::pose(&sim.scene().pose(*id)?));
            }
        }
        Ok(())
    }

    /// Queues the lines of this frame: laser beams with their hit points, what sensors
    /// draw, and when asked the world axes (`show_axes`), contacts (`show_contacts`)
    /// and joint anchors and axes (`show_joints`).
    pub fn draw_overlays(&self, sim: &Simulation, window: &mut Window) {
        if self.show_axes {
            let o = Vec3::ZERO;
            window.draw_line(o, Vec3::X, Color::new(1.0, 0.0, 0.0, 1.0), 3.0, false);
            window.draw_line(o, Vec3::Y, Color::new(0.0, 0.7, 0.0, 1.0), 3.0, false);
            window.draw_line(o, Vec3::Z, Color::new(0.0, 0.0, 1.0, 1.0), 3.0, false);
        }
        let world = sim.scene().world();
        for g in world.geoms() {
            let Ok(geom) = world.geom(g) else { continue };
            let (Shape::Ray { length }, Some((start, dir))) = (geom.shape(), geom.ray()) else { continue };
            let red = Color::new(1.0, 0.0, 0.0, 1.0);
            match world.closest_ray_hit(g) {
                Some(hit) => {
                    window.draw_line(convert::point(&start), convert::point(&hit.position), red, 2.0, false);
                    window.draw_point(convert::point(&hit.position), Color::new(1.0, 1.0, 0.0, 1.0), 8.0);
                }
                // Before the first step no hit has been computed yet: draw nothing
                // rather than a ray through what it will hit.
                None if sim.scene().step_count() == 0 => {}
                None => {
                    let end = start + dir * length.min(50.0);
                    window.draw_line(convert::point(&start), convert::point(&end), red, 1.0, false);
                }
            }
        }
        // What sensors draw: a lidar's beams to their hits.
        for (a, b) in sim.sensor_lines() {
            window.draw_line(convert::point(&a), convert::point(&b), Color::new(0.1, 0.8, 0.2, 1.0), 1.0, false);
        }
        if self.show_contacts {
            // The normal, 1 m both ways from the point: the point itself is usually
            // hidden inside the bodies that touch, the line shows outside them.
            let orange = Color::new(1.0, 0.5, 0.0, 1.0);
            for c in world.contacts() {
                let (a, b) = (c.position - c.normal * 1.0, c.position + c.normal * 1.0);
                window.draw_point(convert::point(&c.position), orange, 12.0);
                window.draw_line(convert::point(&a), convert::point(&b), orange, 3.0, false);
            }
        }
        if self.show_forces {
            let cyan = Color::new(0.0, 0.75, 0.85, 1.0);
            for c in world.contacts() {
                for (a, b) in force_arrow(c, self.force_scale) {
                    window.draw_line(convert::point(&a), convert::point(&b), cyan, 3.0, false);
                }
            }
            // The joints' reaction forces, where they report them.
            let amber = Color::new(1.0, 0.6, 0.0, 1.0);
            for (a, b) in world.joints().flat_map(|j| joint_force_arrow(world, j, self.force_scale)) {
                window.draw_line(convert::point(&a), convert::point(&b), amber, 3.0, false);
            }
        }
        if self.show_joints {
            for (_, j) in sim.scene().joints() {
                let Ok(joint) = sim.scene().joint(j).and_then(|j| j.ode()) else { continue };
                if let Ok(anchor) = joint.anchor() {
                    // A big magenta dot at the anchor and the axis through it, both ways.
                    window.draw_point(convert::point(&anchor), Color::new(1.0, 0.0, 1.0, 1.0), 16.0);
                    if let Ok(axis) = joint.axis() {
                        let (a, b) = (anchor - axis * 0.5, anchor + axis * 0.5);
                        let magenta = Color::new(1.0, 0.0, 1.0, 1.0);
                        window.draw_line(convert::point(&a), convert::point(&b), magenta, 5.0, false);
                    }
                }
            }
        }
    }
}

/// The default length of the contact-force arrows per newton, m/N (a 1 kg body
/// resting on four contact points: four arrows of 12 cm).
pub const DEFAULT_FORCE_SCALE: f64 = 0.05;

/// The segments of the arrow drawing a contact's force, `scale` metres per newton: the
/// force on the moving body of the pair (on the first geom's body, or, when that one is
/// static, on the second's), from the contact point, with a head of two strokes a
/// fifth of its length. No segments for a force of zero (not reported, or no push).
pub fn force_arrow(contact: &ars_core::ContactPoint, scale: f64) -> Vec<(Point3<f64>, Point3<f64>)> {
    let force = if contact.pair.body1.is_some() { contact.force } else { -contact.force };
    arrow(contact.position, force * scale)
}

/// The segments of an arrow from `start` along `shaft`, with a head of two strokes a
/// fifth of its length; none for a shaft of (nearly) zero length.
fn arrow(start: Point3<f64>, shaft: Vector3<f64>) -> Vec<(Point3<f64>, Point3<f64>)> {
    let length = shaft.norm();
    if !(length.is_finite() && length > 1e-9) {
        return Vec::new();
    }
    let tip = start + shaft;
    // Any direction across the shaft, for the head.
    let across =
        shaft.cross(&Vector3::x()).try_normalize(1e-9).unwrap_or_else(|| shaft.cross(&Vector3::y()).normalize());
    let back = tip - shaft * 0.2;
    vec![(start, tip), (tip, back + across * length * 0.1), (tip, back - across * length * 0.1)]
}

/// Asks `world` to report the forces the viewer draws: the contacts' and every joint's
/// (reporting them changes no result).
pub(crate) fn report_forces(world: &mut ars_core::World) {
    world.set_contact_feedback(true);
    let joints: Vec<_> = world.joints().collect();
    for joint in joints {
        if let Ok(mut joint) = world.joint_mut(joint) {
            joint.enable_feedback();
        }
    }
}

/// The segments of the arrow drawing the force a joint puts on its first body, `scale`
/// metres per newton, from its anchor: none when the joint has no anchor (a slider, a
/// fixed joint) or does not report its forces ([`JointMut::enable_feedback`]).
///
/// [`JointMut::enable_feedback`]: ars_core::joint::JointMut::enable_feedback
pub fn joint_force_arrow(
    world: &ars_core::World,
    joint: ars_core::JointHandle,
    scale: f64,
) -> Vec<(Point3<f64>, Point3<f64>)> {
    let Ok(joint) = world.joint(joint) else { return Vec::new() };
    match (joint.feedback(), joint.anchor()) {
        (Some(feedback), Ok(anchor)) => arrow(anchor, feedback.force1 * scale),
        _ => Vec::new(),
    }
}

/// The rotation taking kiss3d's +Y-aligned round primitives to ODE's +Z.
fn y_to_z() -> Quat {
    Quat::from_rotation_arc(Vec3::Y, Vec3::Z)
}

fn build_node(
    sim: &Simulation,
    id: ObjectId,
    scene: &mut SceneNode3d,
    index: usize,
    fast: Option<&(SharedMaterial, SharedMaterial)>,
) -> ars_core::Result<ObjectNode> {
    let look = look_of(sim, id, index)?;
    let mut group = scene.add_group();
    for part in &look.parts {
        let mut placed = group.add_group();
        placed.set_pose(convert::pose(&part.local));
        let mut node = add_shape(&mut placed, &part.shape);
        node.set_color(convert::color(part.color));
        if let Some((object_material, floor_material)) = fast {
            // Floors (planes, static meshes) are checkered when drawn fast.
            node.set_material(if look.floor { floor_material.clone() } else { object_material.clone() });
        }
    }
    group.set_pose(convert::pose(&look.pose));
    Ok(ObjectNode { group, dynamic: look.dynamic, color: look.color })
}

/// A node drawing `shape` in its own frame.
fn add_shape(group: &mut SceneNode3d, shape: &Shape) -> SceneNode3d {
    match shape {
        Shape::Sphere { radius } => group.add_sphere(*radius as f32),
        Shape::Box { edges } => group.add_cube(edges.x as f32, edges.y as f32, edges.z as f32),
        Shape::Cylinder { length, radius } => group.add_cylinder(*radius as f32, *length as f32).set_rotation(y_to_z()),
        Shape::Capsule { length, radius } => group.add_capsule(*radius as f32, *length as f32).set_rotation(y_to_z()),
        Shape::Cone { height, radius } => {
            // kiss3d's cone is centred on half its height; ours on its centre of mass,
            // a quarter of the height above the base.
            let mut c = group.add_cone(*radius as f32, *height as f32).set_rotation(y_to_z());
            c.set_position(Vec3::new(0.0, 0.0, (*height / 4.0) as f32));
            c
        }
        Shape::Plane { normal, distance } => {
            // A large square in the plane, centred where the plane meets its normal.
            let n = normal.normalize();
            let mut q = group.add_quad(2.0 * PLANE_HALF_SIZE, 2.0 * PLANE_HALF_SIZE, 1, 1);
            q.set_rotation(Quat::from_rotation_arc(Vec3::Z, convert::vector(&n)));
            q.set_position(convert::vector(&(n * *distance)));
            q
        }
        Shape::TriMesh { vertices, triangles } | Shape::ConvexHull { vertices, triangles } => {
            let v = vertices.iter().map(convert::point).collect();
            group.add_trimesh(v, triangles.clone(), Vec3::ONE, true)
        }
        _ => group.add_sphere(0.05),
    }
}

/// What every viewer draws from: the scene graph (with its lights), the camera of the
/// program's view settings, and the mirror of the simulation's objects.
pub(crate) struct DrawnScene {
    pub(crate) scene: SceneNode3d,
    /// The orbit camera, its image shifted off the panel in a window.
    pub(crate) camera: FramedCamera,
    pub(crate) mirror: SceneMirror,
    /// The object the camera follows, by name (the view settings', or chosen with `f`).
    pub(crate) follow: Option<String>,
    /// Whether it follows now.
    pub(crate) following: bool,
}

impl DrawnScene {
    /// The view of `settings`, drawn into `window` (whose shadows it sets). Needs the
    /// rendering context of this thread.
    pub(crate) fn new(settings: &WindowSettings, window: &mut Window) -> Self {
        let mut scene = SceneNode3d::empty();
        add_lights(&mut scene, settings);
        let camera =
            FramedCamera::new(convert::point(&settings.camera_position), convert::point(&settings.camera_target));
        let mut mirror = SceneMirror::new();
        if draws_fast(settings.quality) {
            mirror.draw_fast();
            // No shadows, and the smallest shadow atlas (2048² × 16 layers otherwise,
            // hundreds of megabytes of memory without a GPU).
            window.set_shadows_enabled(false);
            window.set_shadow_atlas_layers(1);
            window.set_shadow_resolution(64);
        }
        let follow = settings.follow.clone();
        DrawnScene { scene, camera, mirror, following: follow.is_some(), follow }
    }

    /// Brings the scene up to date with `sim`, moves the camera with the object it
    /// follows, and queues this frame's lines.
    pub(crate) fn update(&mut self, sim: &Simulation, window: &mut Window) -> ars_core::Result<()> {
        self.mirror.sync(sim, &mut self.scene)?;
        if self.following
            && let Some(name) = &self.follow
            && let Ok(p) = sim.scene().object(name.as_str()).and_then(|o| o.position())
        {
            self.camera.orbit.set_at(convert::point(&p));
        }
        self.mirror.draw_overlays(sim, window);
        Ok(())
    }

    /// Starts or stops following: the object of the view settings, or else the first
    /// moving object.
    pub(crate) fn toggle_follow(&mut self, sim: &Simulation) {
        if self.follow.is_none() {
            let first = sim.scene().bodies().next().and_then(|(id, _)| sim.scene().object(id).ok());
            self.follow = first.map(|o| o.name().to_string());
        }
        self.following = !self.following && self.follow.is_some();
    }
}

/// Whether to draw fast: asked for, or left to the machine and it has no GPU (the
/// adapter is a software rasteriser).
pub(crate) fn draws_fast(quality: RenderQuality) -> bool {
    fast_for(quality, || kiss3d::context::Context::get().adapter.get_info().device_type == wgpu::DeviceType::Cpu)
}

/// Whether `quality` means drawing fast, `software` telling (when asked) whether the
/// adapter is a software rasteriser.
pub(crate) fn fast_for(quality: RenderQuality, software: impl FnOnce() -> bool) -> bool {
    match quality {
        RenderQuality::Fast => true,
        RenderQuality::Fine => false,
        _ => software(),
    }
}

/// Lights that show every side: a point light above and behind the camera, and a
/// dimmer one from the other side.
fn add_lights(scene: &mut SceneNode3d, view: &WindowSettings) {
    let eye = view.camera_position;
    scene.add_light(Light::point(200.0)).set_position(kiss3d::glamx::Vec3::new(
        eye.x as f32,
        eye.y as f32 + 10.0,
        eye.z as f32,
    ));
    scene.add_light(Light::point(200.0).with_intensity(1.5)).set_position(kiss3d::glamx::Vec3::new(
        -eye.x as f32,
        eye.y as f32 + 5.0,
        -eye.z as f32,
    ));
}

#[cfg(test)]
mod tests {
    use super::*;
    use ars_core::{Mass, Simulation};

    /// A 2 kg box resting on the floor: its contact forces, drawn at 0.05 m/N, point up
    /// (the floor pushes the box) and their lengths add up to 2 g × 0.05 m.
    #[test]
    fn force_arrows_point_from_the_contacts_by_the_force_on_the_body() {
        let mut sim = Simulation::new().unwrap();
        let floor = sim.scene_mut().add_floor_plane(Vector3::y(), 0.0).unwrap();
        sim.scene_mut().add_box([0.5, 0.5, 0.5], [0.0, 0.25, 0.0], Mass::Total(2.0)).unwrap();
        sim.scene_mut().world_mut().set_contact_feedback(true);
        sim.run_for(1.0).unwrap();
        let contacts = sim.scene().world().contacts().to_vec();
        assert!(!contacts.is_empty());
        let mut total = 0.0;
        for c in &contacts {
            let arrow = force_arrow(c, 0.05);
            assert_eq!(arrow.len(), 3);
            let (start, tip) = arrow[0];
            assert_eq!(start, c.position);
            assert!(tip.y > start.y, "the floor pushes the box up: {start} to {tip}");
            total += (tip - start).y;
            // The head's strokes end a fifth of the way back, either side of the shaft.
            for (from, end) in &arrow[1..] {
                assert_eq!(*from, tip);
                assert!(((tip - end).y - 0.2 * (tip - start).y).abs() < 1e-9);
            }
        }
        let g = sim.scene().gravity().norm();
        assert!((total - 2.0 * g * 0.05).abs() < 0.01 * 2.0 * g * 0.05, "arrows add up to {total} m");
        // The floor's id is not a body: whichever geom comes first, the arrow is the
        // force on the box.
        assert!(sim.scene().object(floor).unwrap().body_handle().is_none());
        // No force reported, no arrow.
        let mut quiet = contacts[0];
        quiet.force = Vector3::zeros();
        assert!(force_arrow(&quiet, 0.05).is_empty());
    }

    #[test]
    fn a_hanging_pendulum_pulls_its_pivot_by_its_weight() {
        use ars_core::JointEnd;
        let mut sim = Simulation::new().unwrap();
        let bob = sim.scene_mut().add_sphere(0.1, [0.0, 0.5, 0.0], Mass::Total(3.0)).unwrap();
        let pivot = sim
            .scene_mut()
            .add_hinge_joint("pivot", bob, JointEnd::World, Some([0.0, 1.0, 0.0].into()), Vector3::z())
            .unwrap();
        let handle = sim.scene().joint(pivot).unwrap().ode().unwrap().handle();
        assert!(joint_force_arrow(sim.scene().world(), handle, 0.05).is_empty(), "no feedback asked for: no arrow");
        sim.scene_mut().world_mut().joint_mut(handle).unwrap().enable_feedback();
        sim.run_for(0.5).unwrap();
        let arrow = joint_force_arrow(sim.scene().world(), handle, 0.05);
        assert_eq!(arrow.len(), 3);
        let (start, tip) = arrow[0];
        // From the anchor, as ODE reports it from the bob (the joint's error: 1e-11 m).
        assert!((start - Point3::new(0.0, 1.0, 0.0)).norm() < 1e-9, "from the anchor: {start}");
        // The joint holds the bob up: 3 kg × g, upwards, at rest.
        let expected = 3.0 * sim.scene().gravity().norm() * 0.05;
        assert!(((tip - start).y - expected).abs() < 1e-6 * expected, "{start} to {tip}");
        assert!((tip - start).xz().norm() < 1e-9);
    }
}
