//! Robots from URDF files: one body per link, one joint per URDF joint, with the
//! file's names.
//!
//! - **Up axis.** URDF is Z-up; a simulation is Y-up. The root link's frame is turned
//!   by one rotation, −90° about X (URDF (x, y, z) → simulation (x, z, −y)), then placed
//!   at [`UrdfOptions::base_pose`]. A file written Y-up is loaded as is with
//!   [`UpAxis::Y`].
//! - **On the floor.** A robot free to move (no [`UrdfOptions::fixed_base`], a root
//!   link with mass) whose collision geometry, at the base pose and initial joint
//!   positions asked for, would reach into a floor of the scene is raised (+Y, nothing
//!   else of the pose changes) just enough for its lowest collision point to rest on
//!   that floor. A robot whose root is massless (static: a `world` link) is raised the
//!   same way when its links with bodies (all but the root and the massless links
//!   fixed to it) reach into a floor, just enough for them to rest on it; its static
//!   geometry is not looked at (nothing static collides with a floor). Either way there is a line
//!   in [`UrdfRobot::adjusted`] saying by how much; so a robot
//!   whose root frame is at its centre, or between its feet, starts standing on the
//!   floor, not buried in it (where ODE would shoot it out). A pose that
//!   reaches into no floor is kept exactly: a robot is never lowered, and one placed
//!   above the floor falls onto it. A floor is a static plane of the scene facing up
//!   (its normal within 45° of +Y: `Simulation::builder().floor_plane`,
//!   [`Scene::add_floor_plane`](crate::scene::Scene::add_floor_plane), Python's
//!   `add_floor`); terrain meshes, heightfields and other objects are not looked at.
//!   [`UrdfOptions::exact_base_pose`] keeps the pose asked for whatever it reaches into
//!   (PyBullet's `loadURDF` never moves a robot); a fixed base is always where it is
//!   asked to be.
//! - **Bodies.** ODE wants a body's frame at its centre of mass: each link's body frame
//!   is its `<inertial>` frame (origin and `rpy`), where the URDF's inertia tensor is
//!   given, so the tensor is used as written. Collision geometry is placed relative to
//!   it (no offset when it shares the inertial frame).
//! - **Mass.** A root link without mass is static (its geometry collides, nothing moves
//!   it), as pybullet does. A massless link fixed to its parent (a tool frame, a
//!   flange: the Panda's `panda_link8`) is merged into the nearest ancestor that is not
//!   one: its geometry and looks join that link's object, [`UrdfRobot::link`] gives that
//!   object for its name, and its fixed joint is not made. A massless link that moves
//!   (between two hinges, as human models' `*_virtual` links) is lent a small mass by
//!   the nearest link with mass, whose mass and inertia shrink alike, so that the total
//!   is the file's (see `massless.rs`; a line in [`UrdfRobot::adjusted`] each); a robot
//!   with no mass at all to lend is refused.
//! - **Inertia.** An inertia no body can have is corrected, with a line naming the link
//!   in [`UrdfRobot::adjusted`], in the tensor's principal frame (mass and centre of
//!   mass untouched): no moment worth the name (a link given only its mass, or moments
//!   below a millionth of the sphere's that follows) becomes a solid sphere of its
//!   mass at water's density, `0.4 m r²` with `r = (3m / 4πρ)^⅓`;
//!   a moment below a millionth of the largest (zero, or negative from rounded
//!   products) is raised to that millionth; a moment above the sum of the other two
//!   sets all three to their mean, as MuJoCo's `balanceinertia` does. With
//!   [`UrdfOptions::strict_inertia`] such a file is refused instead, as before.
//! - **Degenerate visuals.** A `<visual>` box, cylinder, capsule or sphere with a size
//!   that is zero, negative or not finite has nothing to draw: it is skipped, with a
//!   line in [`UrdfRobot::adjusted`]. (A collision element of that kind is refused.)
//! - **Collision meshes** collide as their convex hulls (ODE convexes), as PyBullet
//!   collides a URDF's meshes by default: far fewer contacts than the triangles, and
//!   faster. [`UrdfOptions::triangle_mesh_collisions`] keeps them triangle meshes. A
//!   mesh whose points bound no solid (flat) stays a triangle mesh, with a line in
//!   [`UrdfRobot::adjusted`]. What is drawn is the `<visual>`s, unchanged.
//! - **Joints.** `revolute` and `continuous` become hinges, `prismatic` sliders,
//!   `fixed` fixed joints, at the joint's origin and about its axis, with the URDF's
//!   sign: a joint's angle (position) is the child's relative to the parent, and a
//!   positive torque (force) turns (pushes) the child that way (ODE's joint then joins
//!   the parent to the child about the negated axis); `revolute` and
//!   `prismatic` limits become joint stops (ODE measures a hinge's angle within ±π:
//!   revolute limits beyond ±(π − 0.05) are turned by whole turns and cut to that, or
//!   dropped when they span a turn, each with a line in [`UrdfRobot::adjusted`]), their
//!   `effort` and `velocity` the joint's
//!   [`ActuatorLimits`](crate::scene::ActuatorLimits) (0 or absent: none); `<dynamics damping>`
//!   becomes viscous friction and `friction` dry friction
//!   ([`SimJoint::set_dry_friction`](crate::scene::SimJoint::set_dry_friction)); `<mimic>` a
//!   [`Mimic`](crate::scene::Mimic) (multiplier 1 and offset 0 unless given; a mimic ARS
//!   cannot follow, of a joint not in the file or of a joint that does not move alike,
//!   is dropped with a line in [`UrdfRobot::adjusted`], as PyBullet ignores mimics);
//!   `spherical` (an
//!   extension some tools write) becomes a ball joint. `floating` and `planar` joints
//!   are refused.
//! - **Collisions.** Linked bodies never collide (ODE's rule). With
//!   [`UrdfOptions::self_collision`] off (the default) no two links of the robot do.
//! - **Geometry.** Every collision element of a link: `box`, `cylinder` (along the
//!   link's Z, as in ODE), `sphere`, `capsule`, and `mesh` (STL, OBJ, COLLADA, with
//!   `scale`) as a triangle mesh (see [`load_mesh`](crate::formats::mesh::load_mesh)).
//!   A `<collision>` whose mesh file is not there is skipped, with a line in
//!   [`UrdfRobot::adjusted`] (PyBullet loads the link without it; its `<inertial>`
//!   stays); another shape (PyBullet's `<plane>`, `<cdf>`) is skipped alike.
//! - **Mesh paths** (the first that exists; the error lists every path tried):
//!   `file://` and absolute paths as written; relative ones in the URDF's folder, then
//!   in [`UrdfOptions::search_paths`]; `package://NAME/REST` in the folder given for
//!   NAME ([`UrdfOptions::package`]), in `ROS_PACKAGE_PATH` and `AMENT_PREFIX_PATH`,
//!   as `NAME/REST` beside the URDF, in a folder named NAME above it, as `REST` beside
//!   it, in the search paths, then as `REST` in each folder above the URDF's (a package
//!   whose meshes are in its `_description` folder; `package:///REST`).
//! - **Reading.** The file is read as PyBullet and ROS's urdfdom read what people write
//!   (see `read.rs`): vectors with commas, extra numbers cut (noted), xacro's
//!   `$(optenv NAME default)` as xacro reads it (noted), absent `<limit>` attributes 0,
//!   the first of repeated elements; what URDF does not define is ignored. A number
//!   that is none is an error naming the file, the link or joint, the attribute and
//!   the line.
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

use std::path::{Path, PathBuf};

use nalgebra::Isometry3;

use crate::error::{Error, Result};
use crate::handle::{JointId, ObjectId};
use crate::simulation::Simulation;

mod build;
mod description;
mod frame;
mod fuse;
mod massless;
mod meshes;
mod model;
mod place;
mod read;
mod stops;
mod values;

pub use description::{LinkFrame, RobotDescription, TreeJoint};

use build::plan;
use meshes::Meshes;

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
    /// rotation); a floating robot that would reach into a floor there is raised onto
    /// it, unless [`exact_base_pose`](Self::exact_base_pose) (see [the module
    /// docs](self)).
    pub base_pose: Isometry3<f64>,
    /// Place the root at [`base_pose`](Self::base_pose) exactly, even where the robot's
    /// collision geometry then reaches into a floor, rather than raise it to rest on the
    /// floor (see [the module docs](self)).
    pub exact_base_pose: bool,
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
    /// Starting positions of joints, by name (rad or m). The others start at 0, but
    /// a joint whose limits exclude 0, which starts at its limit nearest 0 (a line in
    /// [`UrdfRobot::adjusted`]), and a mimic follower, which starts at `multiplier ·
    /// leader + offset`. The joints read these positions: the robot is built at zero,
    /// joined, then posed.
    pub initial_positions: Vec<(String, f64)>,
    /// Draw the collision geometry rather than the `<visual>` elements (whose meshes
    /// are then not loaded at all).
    pub ignore_visuals: bool,
    /// Refuse an inertia no body can have (not positive definite, or breaking the
    /// triangle inequality) rather than correct it with a line in
    /// [`UrdfRobot::adjusted`] (see [the module docs](self)).
    pub strict_inertia: bool,
    /// Make each link with mass on a fixed joint a body of its own, held by a fixed
    /// joint, rather than fuse it into the body it is fixed to (the default, as
    /// MuJoCo's `fusestatic` does; see `fuse.rs`).
    pub keep_fixed_links: bool,
    /// Collide `<collision>` meshes as triangle meshes rather than as their convex
    /// hulls (the default, as PyBullet does; see [the module docs](self)).
    pub triangle_mesh_collisions: bool,
}

impl UrdfOptions {
    /// The defaults: floating base at the origin (raised onto a floor it would reach
    /// into), no self-collision, Z up.
    pub fn new() -> Self {
        Self::default()
    }
    /// The root link's pose.
    #[must_use]
    pub fn base_pose(mut self, pose: Isometry3<f64>) -> Self {
        self.base_pose = pose;
        self
    }
    /// Keep the base pose exactly, even in a floor (see
    /// [`exact_base_pose`](Self::exact_base_pose)).
    #[must_use]
    pub fn exact_base_pose(mut self, exact: bool) -> Self {
        self.exact_base_pose = exact;
        self
    }
    /// Keep links with mass on fixed joints as bodies of their own (see
    /// [`keep_fixed_links`](Self::keep_fixed_links)).
    #[must_use]
    pub fn keep_fixed_links(mut self, keep: bool) -> Self {
        self.keep_fixed_links = keep;
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
    /// Refuse inertias no body can have rather than correct them.
    #[must_use]
    pub fn strict_inertia(mut self, strict: bool) -> Self {
        self.strict_inertia = strict;
        self
    }
    /// Collide collision meshes as triangle meshes, not as their convex hulls.
    #[must_use]
    pub fn triangle_mesh_collisions(mut self, triangles: bool) -> Self {
        self.triangle_mesh_collisions = triangles;
        self
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
    /// Each link's frame in its object's frame, in the order of [`links`](Self::links)
    /// (a link's object is a body at its inertial frame, or the body it was merged into).
    pub link_offsets: Vec<Isometry3<f64>>,
    /// What was read leniently, corrected or skipped to load the file, a sentence each
    /// naming its link or joint (an inertia no body can have, unless
    /// [`UrdfOptions::strict_inertia`]; a visual with nothing to draw; a collision mesh
    /// not found; mass lent to a massless moving link; a mimic dropped; extra numbers;
    /// revolute limits beyond ±π) or the robot (raised onto a floor, unless
    /// [`UrdfOptions::exact_base_pose`]); see [the module docs](self).
    pub adjusted: Vec<String>,
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
    robot: model::Robot,
    /// The file's name, in errors; its folder is where relative mesh paths start.
    file: String,
    /// What was read leniently or skipped, a line each (for [`UrdfRobot::adjusted`]).
    notes: Vec<String>,
    /// The text as read (a scene keeps it in its [`RobotDescription`]s).
    text: std::sync::Arc<str>,
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
        let read = read::read(text).map_err(|p| Error::Format {
            format: "URDF",
            file: file.to_string(),
            element: p.element,
            line: Some(p.line),
            column: None,
            problem: p.text,
        })?;
        Ok(UrdfFile { robot: read.robot, file: file.to_string(), notes: read.notes, text: text.into() })
    }

    /// The robot's name.
    pub fn name(&self) -> &str {
        &self.robot.name
    }

    /// Makes the robot's links and joints in `sim` (see the [module docs](self)); on an
    /// error nothing of it is left.
    pub fn insert(&self, sim: &mut Simulation, options: &UrdfOptions) -> Result<UrdfRobot> {
        let bad = |element: String, problem: String| {
            let line = self.line_of(&element);
            Error::Format { format: "URDF", file: self.file.clone(), element, line, column: None, problem }
        };
        let (corrected, mut adjusted) = self.corrected(options);
        let robot = corrected.as_ref().unwrap_or(&self.robot);
        let fused = (!options.keep_fixed_links).then(|| fuse::fuse_fixed_links(robot)).flatten();
        let robot = match &fused {
            Some((fused, line)) => {
                adjusted.push(line.clone());
                fused
            }
            None => robot,
        };
        let plan = plan(robot, options).map_err(|(element, problem)| bad(element, problem))?;
        let base_dir = Path::new(&self.file).parent().filter(|d| !d.as_os_str().is_empty()).map(Path::to_path_buf);
        let mut meshes = Meshes { options, base_dir, loaded: super::MeshCache::default(), notes: Vec::new() };
        let mut made = sim.scene.build_urdf(&plan, options, &mut meshes).map_err(|(element, error)| match error {
            Error::Format { format: "URDF", element, problem, .. } => bad(element, problem),
            other => bad(element, other.to_string()),
        })?;
        let mut notes = self.notes.clone();
        notes.extend(adjusted);
        let placed = std::mem::replace(&mut made.adjusted, notes);
        made.adjusted.append(&mut meshes.notes);
        made.adjusted.extend(placed);
        sim.scene.robot_descriptions.push(self.description(&made));
        Ok(made)
    }

    /// What the scene keeps of the robot `made` from this file.
    fn description(&self, made: &UrdfRobot) -> RobotDescription {
        let links = made
            .links
            .iter()
            .zip(&made.link_offsets)
            .map(|((name, object), offset)| LinkFrame { name: name.clone(), object: *object, offset: *offset })
            .collect();
        let joints = self
            .robot
            .joints
            .iter()
            .map(|j| TreeJoint {
                name: j.name.clone(),
                parent: j.parent.link.clone(),
                child: j.child.link.clone(),
                fixed: j.joint_type == model::JointType::Fixed,
            })
            .collect();
        let children: Vec<&str> = self.robot.joints.iter().map(|j| j.child.link.as_str()).collect();
        let root = self.robot.links.iter().find(|l| !children.contains(&l.name.as_str()));
        RobotDescription {
            name: made.name.clone(),
            urdf: Some(self.text.clone()),
            links,
            joints,
            roots: root.map(|l| l.name.clone()).into_iter().collect(),
        }
    }

    /// The line of the link or joint an error names (`link "arm"`, `joint "elbow"`).
    fn line_of(&self, element: &str) -> Option<u32> {
        let links = self.robot.links.iter().map(|l| (format!("link {:?}", l.name), l.line));
        let joints = self.robot.joints.iter().map(|j| (format!("joint {:?}", j.name), j.line));
        links.chain(joints).find(|(name, _)| name == element).map(|(_, line)| line)
    }

    /// The robot with what ARS corrects corrected (see the [module docs](self)), if
    /// anything was, and a line per correction: inertias no body can have (unless
    /// [`UrdfOptions::strict_inertia`]) and visuals with nothing to draw.
    fn corrected(&self, options: &UrdfOptions) -> (Option<model::Robot>, Vec<String>) {
        let (lent, mut adjusted) = match massless::lend_masses(&self.robot) {
            Some((lent, notes)) => (Some(lent), notes),
            None => (None, Vec::new()),
        };
        let original = lent.as_ref().unwrap_or(&self.robot);
        let mut robot = lent.clone();
        for (k, link) in original.links.iter().enumerate() {
            let degenerate = |v: &model::Visual| degenerate(&v.geometry);
            if link.visual.iter().any(degenerate) && !options.ignore_visuals {
                for v in link.visual.iter().filter(|v| degenerate(v)) {
                    adjusted.push(format!(
                        "link {:?}: a <visual> {:?} has nothing to draw: skipped",
                        link.name, v.geometry
                    ));
                }
                robot.get_or_insert_with(|| original.clone()).links[k].visual.retain(|v| !degenerate(v));
            }
            if options.strict_inertia {
                continue;
            }
            let i = &link.inertial.inertia;
            let tensor = crate::formats::inertia_tensor([i.ixx, i.iyy, i.izz, i.ixy, i.ixz, i.iyz]);
            let Some(b) = crate::formats::balance::balance_inertia(link.inertial.mass.value, &tensor) else {
                continue;
            };
            adjusted.push(format!("link {:?}: {}", link.name, b.note));
            let fixed = &mut robot.get_or_insert_with(|| original.clone()).links[k].inertial.inertia;
            let m = b.inertia;
            (fixed.ixx, fixed.iyy, fixed.izz) = (m[(0, 0)], m[(1, 1)], m[(2, 2)]);
            (fixed.ixy, fixed.ixz, fixed.iyz) = (m[(0, 1)], m[(0, 2)], m[(1, 2)]);
        }
        (robot, adjusted)
    }
}

/// Whether a primitive has nothing to draw: a shape ARS refuses (a size zero, negative
/// or not finite; [`Shape`](crate::Shape)'s own check). A mesh is checked when it is
/// loaded.
fn degenerate(geometry: &model::Geometry) -> bool {
    meshes::primitive_shape(geometry).is_some_and(|shape| shape.validate().is_err())
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
