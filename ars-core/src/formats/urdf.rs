//! Robots from URDF files: one body per link, one joint per URDF joint, with the
//! file's names.
//!
//! - **Up axis.** URDF is Z-up; a simulation is Y-up. The root link's frame is turned
//!   by one rotation, −90° about X (URDF (x, y, z) → simulation (x, z, −y)), then placed
//!   at [`UrdfOptions::base_pose`]. A file written Y-up is loaded as is with
//!   [`UpAxis::Y`].
//! - **Bodies.** ODE wants a body's frame at its centre of mass: each link's body frame
//!   is its `<inertial>` frame (origin and `rpy`), where the URDF's inertia tensor is
//!   given, so the tensor is used as written. Collision geometry is placed relative to
//!   it (no offset when it shares the inertial frame).
//! - **Mass.** A root link without mass is static (its geometry collides, nothing moves
//!   it), as pybullet does. A massless link fixed to its parent (a tool frame, a
//!   flange: the Panda's `panda_link8`) is merged into the nearest ancestor that is not
//!   one: its geometry and looks join that link's object, [`UrdfRobot::link`] gives that
//!   object for its name, and its fixed joint is not made. Any other link needs a
//!   positive mass.
//! - **Joints.** `revolute` and `continuous` become hinges, `prismatic` sliders,
//!   `fixed` fixed joints, at the joint's origin and about its axis, with the URDF's
//!   sign: a joint's angle (position) is the child's relative to the parent, and a
//!   positive torque (force) turns (pushes) the child that way (ODE's joint then joins
//!   the parent to the child about the negated axis); `revolute` and
//!   `prismatic` limits become joint stops, their `effort` and `velocity` the joint's
//!   [`ActuatorLimits`](crate::scene::ActuatorLimits) (0 or absent: none); `<dynamics damping>`
//!   becomes viscous friction and `friction` dry friction
//!   ([`SimJoint::set_dry_friction`](crate::scene::SimJoint::set_dry_friction)); `<mimic>` a
//!   [`Mimic`](crate::scene::Mimic) (multiplier 1 and offset 0 unless given); `spherical` (an
//!   extension some tools write) becomes a ball joint. `floating` and `planar` joints
//!   are refused.
//! - **Collisions.** Linked bodies never collide (ODE's rule). With
//!   [`UrdfOptions::self_collision`] off (the default) no two links of the robot do.
//! - **Geometry.** Every collision element of a link: `box`, `cylinder` (along the
//!   link's Z, as in ODE), `sphere`, `capsule`, and `mesh` (STL, OBJ, COLLADA, with
//!   `scale`) as a triangle mesh (see [`load_mesh`](crate::formats::mesh::load_mesh)).
//! - **Mesh paths** (the first that exists; the error lists every path tried):
//!   `file://` and absolute paths as written; relative ones in the URDF's folder, then
//!   in [`UrdfOptions::search_paths`]; `package://NAME/REST` in the folder given for
//!   NAME ([`UrdfOptions::package`]), in `ROS_PACKAGE_PATH` and `AMENT_PREFIX_PATH`,
//!   as `NAME/REST` beside the URDF, in a folder named NAME above it, as `REST` beside
//!   it, then in the search paths.
//!
//! - **Looks.** The viewer draws a link's `<visual>` elements (any geometry, meshes
//!   found as above, each in its material's colour: its own `<color>` or the
//!   robot-level material it names) as its [`Visual`](crate::scene::Visual)s; the link's
//!   colour is its first visual's. A link without visuals, or every link with
//!   [`UrdfOptions::ignore_visuals`] (for files whose visual meshes ARS cannot read),
//!   is drawn as its collision geometry.
//!
//! Errors name the file, the element and the problem, and nothing is added to the
//! scene when a file is refused.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};

use crate::body::{BodyBuilder, MassSpec};
use crate::convert::rotation_about_axis;
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{JointId, ObjectId};
use crate::joint::JointBuilder;
use crate::scene::JointEnd;
use crate::scene::Scene;
use crate::scene::objects::multiply;
use crate::shape::Shape;
use crate::simulation::Simulation;

/// The up axis a URDF file is written with.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum UpAxis {
    /// Z up, as URDF specifies: turned −90° about X into the simulation's Y-up frame.
    #[default]
    Z,
    /// Y up, like the simulation: loaded as written.
    Y,
}

/// How to load a URDF file.
#[derive(Clone, Debug, Default)]
#[non_exhaustive]
pub struct UrdfOptions {
    /// Where the root link's frame goes, in the simulation frame (after the up-axis
    /// rotation).
    pub base_pose: Isometry3<f64>,
    /// Fix the root link to the world.
    pub fixed_base: bool,
    /// Let links of the robot collide with each other (never a parent and its child).
    pub self_collision: bool,
    /// The up axis the file is written with.
    pub up_axis: UpAxis,
    /// Folders of ROS packages: `package://NAME/...` resolves in the folder given for NAME.
    pub package_dirs: Vec<(String, PathBuf)>,
    /// More folders where relative mesh paths (and packages) are looked for.
    pub search_paths: Vec<PathBuf>,
    /// Starting positions of joints, by name (rad or m; the others start at 0). The
    /// joints read these positions: the robot is built at zero, joined, then posed.
    pub initial_positions: Vec<(String, f64)>,
    /// Draw the collision geometry rather than the `<visual>` elements (whose meshes
    /// are then not loaded at all).
    pub ignore_visuals: bool,
}

impl UrdfOptions {
    /// The defaults: floating base at the origin, no self-collision, Z up.
    pub fn new() -> Self {
        Self::default()
    }
    /// The root link's pose.
    #[must_use]
    pub fn base_pose(mut self, pose: Isometry3<f64>) -> Self {
        self.base_pose = pose;
        self
    }
    /// Fix the root link to the world.
    #[must_use]
    pub fn fixed_base(mut self, fixed: bool) -> Self {
        self.fixed_base = fixed;
        self
    }
    /// Let links collide with each other.
    #[must_use]
    pub fn self_collision(mut self, on: bool) -> Self {
        self.self_collision = on;
        self
    }
    /// The file's up axis.
    #[must_use]
    pub fn up_axis(mut self, up: UpAxis) -> Self {
        self.up_axis = up;
        self
    }
    /// Where the ROS package `name` is (for `package://name/...` mesh paths).
    #[must_use]
    pub fn package(mut self, name: &str, dir: impl Into<PathBuf>) -> Self {
        self.package_dirs.push((name.to_string(), dir.into()));
        self
    }
    /// The starting position of joint `name` (rad or m).
    #[must_use]
    pub fn initial_position(mut self, name: &str, position: f64) -> Self {
        self.initial_positions.push((name.to_string(), position));
        self
    }
    /// Draw the collision geometry, not the `<visual>` elements.
    #[must_use]
    pub fn ignore_visuals(mut self, ignore: bool) -> Self {
        self.ignore_visuals = ignore;
        self
    }
    /// A folder to look for meshes (and packages) in.
    #[must_use]
    pub fn search_path(mut self, dir: impl Into<PathBuf>) -> Self {
        self.search_paths.push(dir.into());
        self
    }
}

/// Finds and loads the meshes a file names (each file once).
struct Meshes<'o> {
    options: &'o UrdfOptions,
    /// The URDF file's folder.
    base_dir: Option<PathBuf>,
    loaded: super::MeshCache,
}

impl Meshes<'_> {
    /// The first existing path for a URDF mesh filename, or every path tried.
    fn resolve(&self, filename: &str) -> std::result::Result<PathBuf, String> {
        let name = filename.strip_prefix("file://").unwrap_or(filename);
        let mut tried = Vec::new();
        if let Some(rest) = name.strip_prefix("package://") {
            let (package, rest) = rest.split_once('/').unwrap_or((rest, ""));
            for (p, dir) in &self.options.package_dirs {
                if p == package {
                    tried.push(dir.join(rest));
                }
            }
            for var in ["ROS_PACKAGE_PATH", "AMENT_PREFIX_PATH"] {
                if let Some(paths) = std::env::var_os(var) {
                    for dir in std::env::split_paths(&paths) {
                        tried.push(dir.join(package).join(rest));
                        tried.push(dir.join("share").join(package).join(rest));
                    }
                }
            }
            if let Some(base) = &self.base_dir {
                tried.push(base.join(package).join(rest));
                for ancestor in base.ancestors() {
                    if ancestor.file_name().is_some_and(|n| n == package) {
                        tried.push(ancestor.join(rest));
                    }
                }
                tried.push(base.join(rest));
            }
            for dir in &self.options.search_paths {
                tried.push(dir.join(package).join(rest));
                tried.push(dir.join(rest));
            }
        } else if Path::new(name).is_absolute() {
            tried.push(PathBuf::from(name));
        } else {
            if let Some(base) = &self.base_dir {
                tried.push(base.join(name));
            }
            for dir in &self.options.search_paths {
                tried.push(dir.join(name));
            }
        }
        super::first_file(filename, &tried)
    }

    fn shape(&mut self, geometry: &urdf_rs::Geometry) -> std::result::Result<Shape, String> {
        use urdf_rs::Geometry as G;
        Ok(match geometry {
            G::Box { size } => Shape::Box { edges: Vector3::from(size.0) },
            G::Cylinder { radius, length } => Shape::Cylinder { radius: *radius, length: *length },
            G::Capsule { radius, length } => Shape::Capsule { radius: *radius, length: *length },
            G::Sphere { radius } => Shape::Sphere { radius: *radius },
            G::Mesh { filename, scale } => {
                let path = self.resolve(filename)?;
                let scale = Vector3::from(scale.as_ref().map_or([1.0; 3], |s| s.0));
                self.loaded.load(&path, scale).map_err(|e| e.to_string())?
            }
        })
    }
}

/// What a URDF file added to a scene.
#[derive(Clone, Debug, PartialEq)]
pub struct UrdfRobot {
    /// The robot's name.
    pub name: String,
    /// Each link's object, in file order (named after the link).
    pub links: Vec<(String, ObjectId)>,
    /// Each joint, in file order (named after the URDF joint).
    pub joints: Vec<(String, JointId)>,
    /// The fixed joint holding the root to the world, with [`UrdfOptions::fixed_base`].
    pub base_joint: Option<JointId>,
}

impl UrdfRobot {
    /// The object of a link.
    pub fn link(&self, name: &str) -> Option<ObjectId> {
        self.links.iter().find(|(n, _)| n == name).map(|(_, id)| *id)
    }
    /// A joint by its URDF name.
    pub fn joint(&self, name: &str) -> Option<JointId> {
        self.joints.iter().find(|(n, _)| n == name).map(|(_, id)| *id)
    }
}

/// A rigid frame; `identity` rotations are kept apart so that composing with them does
/// no arithmetic (a file's frames then give exactly the numbers written).
#[derive(Clone, Copy, Debug)]
struct Frame {
    rotation: Option<Matrix3<f64>>,
    translation: Vector3<f64>,
}

impl Frame {
    const IDENTITY: Frame = Frame { rotation: None, translation: Vector3::new(0.0, 0.0, 0.0) };

    fn from_pose(pose: &urdf_rs::Pose) -> Frame {
        Frame { rotation: rpy_matrix(pose.rpy.0), translation: Vector3::from(pose.xyz.0) }
    }

    fn from_isometry(pose: &Isometry3<f64>) -> Frame {
        let identity = pose.rotation == UnitQuaternion::identity();
        Frame {
            rotation: (!identity).then(|| *pose.rotation.to_rotation_matrix().matrix()),
            translation: pose.translation.vector,
        }
    }

    fn rotate(&self, v: &Vector3<f64>) -> Vector3<f64> {
        match &self.rotation {
            None => *v,
            Some(r) => Vector3::new(
                r[(0, 0)] * v.x + r[(0, 1)] * v.y + r[(0, 2)] * v.z,
                r[(1, 0)] * v.x + r[(1, 1)] * v.y + r[(1, 2)] * v.z,
                r[(2, 0)] * v.x + r[(2, 1)] * v.y + r[(2, 2)] * v.z,
            ),
        }
    }

    /// `self ∘ child`: the child frame, given relative to this one.
    fn then(&self, child: &Frame) -> Frame {
        let rotation = match (&self.rotation, &child.rotation) {
            (None, r) | (r, None) => *r,
            (Some(a), Some(b)) => Some(multiply(a, b)),
        };
        Frame { rotation, translation: self.translation + self.rotate(&child.translation) }
    }

    /// `self⁻¹ ∘ other`: `other` relative to this frame.
    fn relative(&self, other: &Frame) -> Isometry3<f64> {
        let a = self.isometry();
        a.inverse() * other.isometry()
    }

    fn same_as(&self, other: &Frame) -> bool {
        self.rotation == other.rotation && self.translation == other.translation
    }

    fn rotation3(&self) -> Rotation3<f64> {
        Rotation3::from_matrix_unchecked(self.rotation.unwrap_or_else(Matrix3::identity))
    }

    fn isometry(&self) -> Isometry3<f64> {
        Isometry3::from_parts(
            Translation3::from(self.translation),
            UnitQuaternion::from_rotation_matrix(&self.rotation3()),
        )
    }
}

/// `Rz(yaw) · Ry(pitch) · Rx(roll)`, URDF's fixed-axis convention; `None` for no turn.
fn rpy_matrix([roll, pitch, yaw]: [f64; 3]) -> Option<Matrix3<f64>> {
    let turns = [(Vector3::z(), yaw), (Vector3::y(), pitch), (Vector3::x(), roll)];
    turns.iter().filter(|(_, angle)| *angle != 0.0).fold(None, |acc, (axis, angle)| {
        let turn = *rotation_about_axis(axis, *angle).matrix();
        Some(match acc {
            None => turn,
            Some(m) => multiply(&m, &turn),
        })
    })
}

/// A problem with a link (the file is named by the caller; urdf-rs gives no line).
fn link_error(link: &urdf_rs::Link, problem: String) -> Error {
    Error::Format {
        format: "URDF",
        file: String::new(),
        element: format!("link {:?}", link.name),
        line: None,
        column: None,
        problem,
    }
}

/// −90° about X, exactly: URDF (x, y, z) → simulation (x, z, −y).
fn z_up_to_y_up() -> Frame {
    Frame { rotation: Some(super::z_up_to_y_up().into_inner()), translation: Vector3::zeros() }
}

/// A robot checked before anything is built.
struct Plan<'r> {
    robot: &'r urdf_rs::Robot,
    /// Index of the root link.
    root: usize,
    /// World frame of each link (at zero joint positions).
    link_frames: Vec<Frame>,
    /// World frame of each joint.
    joint_frames: Vec<Frame>,
    /// World frame of each link at the initial joint positions, if any were given.
    posed_link_frames: Option<Vec<Frame>>,
}

/// A URDF file as read: its robot, not yet in a simulation. [`insert`](Self::insert)
/// makes its links and joints, as many times as asked.
///
/// ```
/// use ars_core::formats::urdf::{UrdfFile, UrdfOptions};
/// use ars_core::Simulation;
///
/// let text = r#"<robot name="one"><link name="base"><inertial><mass value="1"/>
///   <inertia ixx="0.1" iyy="0.1" izz="0.1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>"#;
/// let file = UrdfFile::parse(text, "one.urdf")?;
/// let mut sim = Simulation::new()?;
/// let robot = file.insert(&mut sim, &UrdfOptions::new())?;
/// assert_eq!(robot.name, "one");
/// assert!(robot.link("base").is_some());
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct UrdfFile {
    robot: urdf_rs::Robot,
    /// The file's name, in errors; its folder is where relative mesh paths start.
    file: String,
}

impl UrdfFile {
    /// Reads and parses the URDF file at `path`.
    pub fn read(path: impl AsRef<Path>) -> Result<UrdfFile> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| Error::io("read the URDF file", path, &e))?;
        UrdfFile::parse(&text, &path.display().to_string())
    }

    /// Parses URDF text; `file` names it in errors and its folder is where relative
    /// mesh paths start.
    pub fn parse(text: &str, file: &str) -> Result<UrdfFile> {
        let bad = |problem: String| format_error(file, "robot".into(), problem);
        // The parser is a dependency: a panic in it must not reach the caller either.
        let parsed = std::panic::catch_unwind(|| urdf_rs::read_from_string(text))
            .map_err(|_| bad("the URDF parser failed on this text".into()))?;
        let robot = parsed.map_err(|e| bad(format!("not valid URDF: {e}")))?;
        Ok(UrdfFile { robot, file: file.to_string() })
    }

    /// The robot's name.
    pub fn name(&self) -> &str {
        &self.robot.name
    }

    /// Makes the robot's links and joints in `sim` (see the [module docs](self)); on an
    /// error nothing of it is left.
    pub fn insert(&self, sim: &mut Simulation, options: &UrdfOptions) -> Result<UrdfRobot> {
        let bad = |element: String, problem: String| format_error(&self.file, element, problem);
        let plan = plan(&self.robot, options).map_err(|(element, problem)| bad(element, problem))?;
        let base_dir = Path::new(&self.file).parent().filter(|d| !d.as_os_str().is_empty()).map(Path::to_path_buf);
        let mut meshes = Meshes { options, base_dir, loaded: super::MeshCache::default() };
        sim.scene.build_urdf(&plan, options, &mut meshes).map_err(|(element, error)| match error {
            Error::Format { format: "URDF", element, problem, .. } => bad(element, problem),
            other => bad(element, other.to_string()),
        })
    }
}

/// A problem of the URDF file `file` at `element`.
fn format_error(file: &str, element: String, problem: String) -> Error {
    Error::Format { format: "URDF", file: file.to_string(), element, line: None, column: None, problem }
}

/// Loads URDF robots: a [`UrdfFile`] read and inserted.
impl Simulation {
    /// Loads the robot of a URDF file: [`UrdfFile::read`], then
    /// [`insert`](UrdfFile::insert).
    pub fn load_urdf(&mut self, path: impl AsRef<Path>, options: &UrdfOptions) -> Result<UrdfRobot> {
        UrdfFile::read(path)?.insert(self, options)
    }

    /// Loads a robot from URDF text; `file` names it in errors.
    pub fn load_urdf_text(&mut self, text: &str, file: &str, options: &UrdfOptions) -> Result<UrdfRobot> {
        UrdfFile::parse(text, file)?.insert(self, options)
    }
}

impl Scene {
    // The element with the error: internal, and only on the error path, so its size
    // costs nothing on a robot that loads.
    #[allow(clippy::result_large_err)]
    fn build_urdf(
        &mut self,
        plan: &Plan<'_>,
        options: &UrdfOptions,
        meshes: &mut Meshes<'_>,
    ) -> std::result::Result<UrdfRobot, (String, Error)> {
        let robot = plan.robot;
        let link_element = |name: &str| format!("link {name:?}");
        // Self-collision off: the robot's geoms share one category they do not collide with.
        let bits = if options.self_collision { None } else { Some(self.next_robot_bit()) };
        let mut links = Vec::new();
        let mut created: Vec<(ObjectId, Option<crate::handle::BodyHandle>)> = Vec::new();
        let undo = |scene: &mut Scene, created: &[(ObjectId, Option<crate::handle::BodyHandle>)]| {
            for (id, _) in created.iter().rev() {
                let _ = scene.remove_object_with_joints(*id);
            }
        };
        let hosts = merge_hosts(robot, plan.root);
        let mut made: Vec<Option<(ObjectId, Option<crate::handle::BodyHandle>)>> = vec![None; robot.links.len()];
        for (i, link) in robot.links.iter().enumerate() {
            if hosts[i].is_some() {
                continue;
            }
            let frame = plan.link_frames[i];
            let result = self.add_link(robot, link, &frame, i == plan.root, bits, meshes);
            let result = result.and_then(|(id, body)| {
                if let Some(color) = link_color(robot, link) {
                    self.set_color(id, color)?;
                }
                Ok((id, body))
            });
            match result {
                Ok(made_link) => {
                    created.push(made_link);
                    made[i] = Some(made_link);
                }
                Err(e) => {
                    undo(self, &created);
                    return Err((link_element(&link.name), e));
                }
            }
        }
        for (i, link) in robot.links.iter().enumerate() {
            let Some(host) = hosts[i] else { continue };
            let host_made = made[host].expect("a host is made in the first pass");
            let host_frame = match host_made.1 {
                Some(_) => plan.link_frames[host].then(&Frame::from_pose(&robot.links[host].inertial.origin)),
                None => plan.link_frames[host],
            };
            let result = self.merge_link(robot, link, &plan.link_frames[i], host_made, &host_frame, bits, meshes);
            if let Err(e) = result {
                undo(self, &created);
                return Err((link_element(&link.name), e));
            }
            made[i] = Some(host_made);
        }
        let made: Vec<(ObjectId, Option<crate::handle::BodyHandle>)> =
            made.into_iter().map(|m| m.expect("every link is made or merged")).collect();
        for (link, (id, _)) in robot.links.iter().zip(&made) {
            links.push((link.name.clone(), *id));
        }
        let mut joints = Vec::new();
        for (j, joint) in robot.joints.iter().enumerate() {
            let parent = robot.links.iter().position(|l| l.name == joint.parent.link).expect("checked");
            let child = robot.links.iter().position(|l| l.name == joint.child.link).expect("checked");
            if hosts[child].is_some() {
                continue; // merged: its link is part of its parent's body
            }
            match self.add_urdf_joint(joint, &plan.joint_frames[j], made[child], made[parent]) {
                Ok(id) => joints.push((joint.name.clone(), id)),
                Err(e) => {
                    undo(self, &created);
                    return Err((format!("joint {:?}", joint.name), e));
                }
            }
        }
        for joint in &robot.joints {
            let Some(mimic) = &joint.mimic else { continue };
            let find = |name: &str| joints.iter().find(|(n, _)| n == name).map(|(_, id)| *id).expect("checked");
            let (follower, leader) = (find(&joint.name), find(&mimic.joint));
            let (multiplier, offset) = (mimic.multiplier.unwrap_or(1.0), mimic.offset.unwrap_or(0.0));
            if let Err(e) = self.joint_mut(follower).and_then(|mut j| j.set_mimic(leader, multiplier, offset)) {
                undo(self, &created);
                return Err((format!("joint {:?}", joint.name), e));
            }
        }
        let base_joint = match (options.fixed_base, made[plan.root]) {
            (true, (root, Some(_))) => {
                let name = format!("{}/base", robot.name);
                match self.insert_sim_joint(
                    &name,
                    crate::scene::JointType::Fixed,
                    root,
                    JointEnd::World,
                    JointBuilder::fixed(),
                ) {
                    Ok(id) => Some(id),
                    Err(e) => {
                        undo(self, &created);
                        return Err(("robot".into(), e));
                    }
                }
            }
            _ => None,
        };
        if let Some(posed) = &plan.posed_link_frames {
            for (i, link) in robot.links.iter().enumerate() {
                let Some(body) = made[i].1.filter(|_| hosts[i].is_none()) else { continue };
                let at = posed[i].then(&Frame::from_pose(&link.inertial.origin));
                let result = self.world.body_mut(body).and_then(|mut b| {
                    b.set_position(Point3::from(at.translation))?;
                    b.set_rotation(at.rotation3())
                });
                if let Err(e) = result {
                    undo(self, &created);
                    return Err((link_element(&link.name), e));
                }
            }
        }
        Ok(UrdfRobot { name: robot.name.clone(), links, joints, base_joint })
    }

    /// A category bit no other robot of this scene uses (1 to 62; 63 is everything else).
    fn next_robot_bit(&mut self) -> u64 {
        self.robots_loaded = (self.robots_loaded % 62) + 1;
        1u64 << self.robots_loaded
    }

    fn add_link(
        &mut self,
        robot: &urdf_rs::Robot,
        link: &urdf_rs::Link,
        frame: &Frame,
        root: bool,
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
    ) -> Result<(ObjectId, Option<crate::handle::BodyHandle>)> {
        let (collisions, looks) = link_geometry(robot, link, frame, meshes)?;
        let urdf_err = |problem: String| link_error(link, problem);
        // The visuals relative to the object's pose.
        let visuals = |object_pose: Isometry3<f64>| -> Vec<crate::scene::Visual> {
            let to_object = object_pose.inverse();
            looks
                .iter()
                .map(|(shape, at, color)| crate::scene::Visual {
                    shape: shape.clone(),
                    offset: to_object * at,
                    color: *color,
                })
                .collect()
        };
        let mass = link.inertial.mass.value;
        let inertial = frame.then(&Frame::from_pose(&link.inertial.origin));
        let with_bits = |g: GeomBuilder| match bits {
            Some(b) => g.category_bits(b).collide_bits(!b),
            None => g,
        };
        // A link without collision geometry is drawn as a small sphere and collides with nothing.
        let drawn = collisions.first().map_or(Shape::Sphere { radius: 1e-3 }, |(shape, _)| shape.clone());
        let mut geoms = Vec::new();
        if mass == 0.0 && root {
            // A massless root is static: its geometry collides, nothing moves it.
            for (shape, at) in collisions {
                let g = GeomBuilder::new(shape).pose(at.isometry());
                match self.world.insert_geom(self.space(), with_bits(g)) {
                    Ok(g) => geoms.push(g),
                    Err(e) => {
                        geoms.into_iter().try_for_each(|g| self.world.remove_geom(g))?;
                        return Err(e);
                    }
                }
            }
            let id = self.register_as(&link.name, drawn, None, geoms.first().copied())?;
            self.objects.get_mut(id.0, ObjectId::KIND)?.extra_geoms = geoms.into_iter().skip(1).collect();
            let object_pose = self.pose(id).unwrap_or_else(|_| Isometry3::identity());
            self.set_visuals(id, visuals(object_pose))?;
            return Ok((id, None));
        }
        if mass.is_nan() || mass <= 0.0 {
            return Err(urdf_err(format!(
                "mass {mass}: a moving link needs a positive mass (a massless link is merged into its parent \
                 only when a fixed joint holds it)"
            )));
        }
        let i = &link.inertial.inertia;
        let inertia = super::inertia_tensor([i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz]);
        let spec = MassSpec::Custom { mass, inertia };
        let mut builder = BodyBuilder::new().mass(spec).position(Point3::from(inertial.translation));
        if inertial.rotation.is_some() {
            builder = builder.rotation(inertial.rotation3());
        }
        let body = self.world.insert_body(builder)?;
        for (shape, at) in collisions {
            let mut g = GeomBuilder::new(shape).attached_to(body);
            if !at.same_as(&inertial) {
                g = g.offset(inertial.relative(&at));
            }
            match self.world.insert_geom(self.space(), with_bits(g)) {
                Ok(g) => geoms.push(g),
                Err(e) => {
                    self.world.remove_body(body)?;
                    return Err(e);
                }
            }
        }
        let id = self.register_as(&link.name, drawn, Some(body), geoms.first().copied())?;
        self.objects.get_mut(id.0, ObjectId::KIND)?.extra_geoms = geoms.into_iter().skip(1).collect();
        self.set_visuals(id, visuals(inertial.isometry()))?;
        Ok((id, Some(body)))
    }

    /// Adds a merged link's geometry and looks to its host's object: geoms on the host's
    /// body (static with a static host), visuals relative to the host object's pose.
    /// `host_frame` is the host body's frame (its inertial frame), or the static host
    /// link's frame.
    #[allow(clippy::too_many_arguments)]
    fn merge_link(
        &mut self,
        robot: &urdf_rs::Robot,
        link: &urdf_rs::Link,
        frame: &Frame,
        (host, body): (ObjectId, Option<crate::handle::BodyHandle>),
        host_frame: &Frame,
        bits: Option<u64>,
        meshes: &mut Meshes<'_>,
    ) -> Result<()> {
        let (collisions, looks) = link_geometry(robot, link, frame, meshes)?;
        let mut geoms = Vec::new();
        for (shape, at) in collisions {
            let mut g = GeomBuilder::new(shape);
            g = match body {
                Some(body) => g.attached_to(body).offset(host_frame.relative(&at)),
                None => g.pose(at.isometry()),
            };
            if let Some(b) = bits {
                g = g.category_bits(b).collide_bits(!b);
            }
            match self.world.insert_geom(self.space(), g) {
                Ok(g) => geoms.push(g),
                Err(e) => {
                    geoms.into_iter().try_for_each(|g| self.world.remove_geom(g))?;
                    return Err(e);
                }
            }
        }
        self.objects.get_mut(host.0, ObjectId::KIND)?.extra_geoms.extend(geoms);
        if !looks.is_empty() {
            let host_pose = match body {
                Some(_) => host_frame.isometry(),
                None => self.pose(host).unwrap_or_else(|_| Isometry3::identity()),
            };
            let to_host = host_pose.inverse();
            let mut visuals = self.object(host)?.visuals().to_vec();
            visuals.extend(looks.into_iter().map(|(shape, at, color)| crate::scene::Visual {
                shape,
                offset: to_host * at,
                color,
            }));
            self.set_visuals(host, visuals)?;
        }
        Ok(())
    }

    fn add_urdf_joint(
        &mut self,
        joint: &urdf_rs::Joint,
        frame: &Frame,
        child: (ObjectId, Option<crate::handle::BodyHandle>),
        parent: (ObjectId, Option<crate::handle::BodyHandle>),
    ) -> Result<JointId> {
        let anchor = Point3::from(frame.translation);
        let axis = frame.rotate(&Vector3::from(joint.axis.xyz.0));
        // ODE measures a hinge's angle (a slider's position) as body 1 relative to body
        // 2 about (along) the axis; URDF as the child relative to the parent. Between
        // two bodies: parent first, about the negated axis, so that ODE's angle is the
        // URDF position and a positive effort turns the child positively.
        let (object1, object2, axis) = match (child, parent) {
            ((c, Some(_)), (p, Some(_))) => (p, JointEnd::Object(c), -axis),
            ((c, Some(_)), (_, None)) => (c, JointEnd::World, axis),
            ((_, None), _) => {
                return Err(Error::Invalid { what: "the joint's child link", problem: "has no mass".into() });
            }
        };
        use urdf_rs::JointType as U;
        let (kind, builder) = match joint.joint_type {
            U::Revolute | U::Continuous => (crate::scene::JointType::Hinge, JointBuilder::hinge(anchor, axis)),
            U::Prismatic => (crate::scene::JointType::Slider, JointBuilder::slider(axis)),
            U::Fixed => (crate::scene::JointType::Fixed, JointBuilder::fixed()),
            U::Spherical => (crate::scene::JointType::Ball, JointBuilder::ball(anchor)),
            _ => unreachable!("refused when planned"),
        };
        let id = self.insert_sim_joint(&joint.name, kind, object1, object2, builder)?;
        let limited = matches!(joint.joint_type, U::Revolute | U::Prismatic);
        let (lower, upper) = (joint.limit.lower, joint.limit.upper);
        if limited && (lower != 0.0 || upper != 0.0) && lower <= upper {
            self.joint_mut(id)?.set_limits(lower, upper)?;
        }
        let moving = matches!(joint.joint_type, U::Revolute | U::Continuous | U::Prismatic);
        if let Some(d) = &joint.dynamics
            && moving
        {
            if d.damping > 0.0 {
                self.joint_mut(id)?.set_viscous_friction(d.damping)?;
            }
            if d.friction > 0.0 {
                self.joint_mut(id)?.set_dry_friction(d.friction)?;
            }
        }
        // URDF requires effort and velocity on revolute and prismatic joints; a 0 (or
        // an absent <limit>, for continuous joints) reads as no limit, as in pybullet.
        let positive_or_none = |x: f64| if x > 0.0 { x } else { f64::INFINITY };
        let (effort, velocity) = (positive_or_none(joint.limit.effort), positive_or_none(joint.limit.velocity));
        if moving && (effort.is_finite() || velocity.is_finite()) {
            self.joint_mut(id)?.set_actuator_limits(crate::scene::ActuatorLimits { effort, velocity })?;
        }
        Ok(id)
    }
}

/// A link's collision shapes with their world frames, and its looks (shape, world
/// pose, colour) unless visuals are ignored.
#[allow(clippy::type_complexity)]
fn link_geometry(
    robot: &urdf_rs::Robot,
    link: &urdf_rs::Link,
    frame: &Frame,
    meshes: &mut Meshes<'_>,
) -> Result<(Vec<(Shape, Frame)>, Vec<(Shape, Isometry3<f64>, Option<crate::scene::Color>)>)> {
    let urdf_err = |problem: String| link_error(link, problem);
    let mut collisions = Vec::new();
    for c in &link.collision {
        let shape = meshes.shape(&c.geometry).map_err(urdf_err)?;
        collisions.push((shape, frame.then(&Frame::from_pose(&c.origin))));
    }
    let mut looks = Vec::new();
    if !meshes.options.ignore_visuals {
        for v in &link.visual {
            let shape = meshes.shape(&v.geometry).map_err(|problem| {
                urdf_err(format!(
                    "{problem} (a <visual>: UrdfOptions::ignore_visuals draws the collision geometry instead)"
                ))
            })?;
            // Checked before anything is created, so that setting them cannot fail.
            shape.validate().map_err(|e| urdf_err(format!("a <visual>: {e}")))?;
            let color = v.material.as_ref().and_then(|m| material_color(robot, m));
            looks.push((shape, frame.then(&Frame::from_pose(&v.origin)).isometry(), color));
        }
    }
    Ok((collisions, looks))
}

/// For each link, the link it is merged into: a massless link fixed to its parent goes
/// into the nearest ancestor that is not such a link (`None`: it is made itself).
fn merge_hosts(robot: &urdf_rs::Robot, root: usize) -> Vec<Option<usize>> {
    let index: HashMap<&str, usize> = robot.links.iter().enumerate().map(|(i, l)| (l.name.as_str(), i)).collect();
    let mut parent: Vec<Option<(usize, bool)>> = vec![None; robot.links.len()];
    for joint in &robot.joints {
        let fixed = matches!(joint.joint_type, urdf_rs::JointType::Fixed);
        parent[index[joint.child.link.as_str()]] = Some((index[joint.parent.link.as_str()], fixed));
    }
    let merged = |i: usize| i != root && robot.links[i].inertial.mass.value == 0.0 && parent[i].is_some_and(|p| p.1);
    (0..robot.links.len())
        .map(|i| {
            let mut host = i;
            // The tree has no loop (checked): this walk ends at the root at the latest.
            while merged(host) {
                host = parent[host].expect("merged links have a parent").0;
            }
            (host != i).then_some(host)
        })
        .collect()
}

/// The world frame of every link and of every joint, from the root outwards, with the
/// joints at positions `q` (at zero when `None`: then no motion is composed at all, so
/// the frames are the file's numbers exactly).
fn frames(
    robot: &urdf_rs::Robot,
    link_index: &HashMap<&str, usize>,
    root: usize,
    root_frame: Frame,
    q: Option<&[f64]>,
) -> (Vec<Frame>, Vec<Frame>) {
    let mut links: Vec<Option<Frame>> = vec![None; robot.links.len()];
    let mut joints = vec![Frame::IDENTITY; robot.joints.len()];
    links[root] = Some(root_frame);
    let mut queue = vec![root];
    while let Some(parent) = queue.pop() {
        let parent_frame = links[parent].expect("set before queued");
        for (j, joint) in robot.joints.iter().enumerate() {
            if joint.parent.link != robot.links[parent].name {
                continue;
            }
            let child = link_index[joint.child.link.as_str()];
            let frame = parent_frame.then(&Frame::from_pose(&joint.origin));
            joints[j] = frame;
            let position = q.map_or(0.0, |q| q[j]);
            let axis = Vector3::from(joint.axis.xyz.0).normalize();
            links[child] = Some(match joint.joint_type {
                _ if position == 0.0 => frame,
                urdf_rs::JointType::Prismatic => frame.then(&Frame { rotation: None, translation: axis * position }),
                urdf_rs::JointType::Spherical | urdf_rs::JointType::Fixed => frame,
                _ => frame.then(&Frame {
                    rotation: Some(*rotation_about_axis(&axis, position).matrix()),
                    translation: Vector3::zeros(),
                }),
            });
            queue.push(child);
        }
    }
    (links.into_iter().map(|f| f.expect("a tree reaches every link")).collect(), joints)
}

/// The colour of a link's first visual with a material: its own `<color>`, or that of
/// the robot-level material it names (URDF allows both).
fn link_color(robot: &urdf_rs::Robot, link: &urdf_rs::Link) -> Option<crate::scene::Color> {
    link.visual.iter().filter_map(|v| v.material.as_ref()).find_map(|m| material_color(robot, m))
}

/// A material's colour: its own `<color>`, or that of the robot-level material it names.
fn material_color(robot: &urdf_rs::Robot, m: &urdf_rs::Material) -> Option<crate::scene::Color> {
    let rgba = match &m.color {
        Some(c) => c.rgba.0,
        None => robot.materials.iter().find(|r| r.name == m.name)?.color.as_ref()?.rgba.0,
    };
    Some([rgba[0], rgba[1], rgba[2]].map(|c| c.clamp(0.0, 1.0) as f32))
}

/// Checks the tree (names, parents, one root, no loop, supported joints) and computes
/// every frame.
fn plan<'r>(robot: &'r urdf_rs::Robot, options: &UrdfOptions) -> std::result::Result<Plan<'r>, (String, String)> {
    let mut link_index = HashMap::new();
    for (i, link) in robot.links.iter().enumerate() {
        if link_index.insert(link.name.as_str(), i).is_some() {
            return Err((format!("link {:?}", link.name), "two links have this name".into()));
        }
    }
    if robot.links.is_empty() {
        return Err(("robot".into(), "it has no link".into()));
    }
    let mut joint_names = HashMap::new();
    let mut parent_joint = vec![None; robot.links.len()];
    for (j, joint) in robot.joints.iter().enumerate() {
        let element = format!("joint {:?}", joint.name);
        if joint_names.insert(joint.name.as_str(), j).is_some() {
            return Err((element, "two joints have this name".into()));
        }
        let Some(&parent) = link_index.get(joint.parent.link.as_str()) else {
            return Err((element, format!("its parent link {:?} is not in the file", joint.parent.link)));
        };
        let Some(&child) = link_index.get(joint.child.link.as_str()) else {
            return Err((element, format!("its child link {:?} is not in the file", joint.child.link)));
        };
        if parent == child {
            return Err((element, format!("link {:?} is both its parent and its child", joint.parent.link)));
        }
        if let Some(other) = parent_joint[child] {
            let other: &urdf_rs::Joint = &robot.joints[other];
            return Err((
                element,
                format!("link {:?} is already the child of joint {:?}: a loop", joint.child.link, other.name),
            ));
        }
        parent_joint[child] = Some(j);
        use urdf_rs::JointType as U;
        match joint.joint_type {
            U::Revolute | U::Continuous | U::Prismatic | U::Fixed | U::Spherical => {}
            ref other => {
                return Err((
                    element,
                    format!("type {other:?}: ARS loads revolute, continuous, prismatic, fixed and spherical joints"),
                ));
            }
        }
        if let Some(mimic) = &joint.mimic
            && !robot.joints.iter().any(|j| j.name == mimic.joint)
        {
            return Err((element, format!("<mimic> names joint {:?}, which is not in the file", mimic.joint)));
        }
        let axis = Vector3::from(joint.axis.xyz.0);
        let directed = axis.iter().all(|x| x.is_finite()) && axis.norm() > 1e-9;
        if !matches!(joint.joint_type, U::Fixed | U::Spherical) && !directed {
            return Err((element, format!("axis {:?} has no direction", joint.axis.xyz.0)));
        }
    }
    let roots: Vec<usize> = (0..robot.links.len()).filter(|&i| parent_joint[i].is_none()).collect();
    let root = match roots[..] {
        [root] => root,
        [] => return Err(("robot".into(), "every link has a parent: the joints form a loop".into())),
        _ => {
            let names: Vec<&str> = roots.iter().map(|&i| robot.links[i].name.as_str()).collect();
            return Err(("robot".into(), format!("several root links ({}): one tree is needed", names.join(", "))));
        }
    };
    for link in &robot.links {
        let element = format!("link {:?}", link.name);
        let m = link.inertial.mass.value;
        if !m.is_finite() || m < 0.0 {
            return Err((element, format!("mass {m}: must be positive")));
        }
    }
    // Frames, from the root outwards.
    let base = Frame::from_isometry(&options.base_pose);
    let root_frame = match options.up_axis {
        UpAxis::Z => base.then(&z_up_to_y_up()),
        UpAxis::Y => base,
    };
    let (link_frames, joint_frames) = frames(robot, &link_index, root, root_frame, None);
    let posed_link_frames = if options.initial_positions.is_empty() {
        None
    } else {
        let mut q = vec![0.0; robot.joints.len()];
        for (name, value) in &options.initial_positions {
            let element = format!("joint {name:?}");
            let Some(&j) = joint_names.get(name.as_str()) else {
                return Err((element, "an initial position is given, but the file has no such joint".into()));
            };
            let fixed = matches!(robot.joints[j].joint_type, urdf_rs::JointType::Fixed | urdf_rs::JointType::Spherical);
            if fixed || !value.is_finite() {
                return Err((element, format!("initial position {value}: needs a moving joint and a finite value")));
            }
            q[j] = *value;
        }
        Some(frames(robot, &link_index, root, root_frame, Some(&q)).0)
    };
    Ok(Plan { robot, root, link_frames, joint_frames, posed_link_frames })
}
