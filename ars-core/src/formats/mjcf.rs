//! Models from MuJoCo's MJCF files: one body per `<body>`, ARS joints for its joints,
//! the file's names.
//!
//! What is read (the rest is a clear error naming the element and its line, or with
//! [`MjcfOptions::skip_unsupported`] a warning in [`MjcfModel::skipped`]):
//! - **Frames.** `pos` and one of `quat`, `euler` (with `<compiler eulerseq>`),
//!   `axisangle`, `xyaxes`, `zaxis` on bodies, geoms, joints' `pos`/`axis` and
//!   `<inertial>`; angles in degrees unless `<compiler angle="radian">`. MJCF is Z-up:
//!   the model is turned by −90° about X (MuJoCo (x, y, z) → simulation (x, z, −y)), then
//!   placed at [`MjcfOptions::base_pose`].
//! - **Mass.** `<inertial>` (`mass`, `diaginertia` or `fullinertia`, its own frame), or,
//!   without one (or with `<compiler inertiafromgeom="true">`), the mass and inertia of
//!   the body's geoms as MuJoCo's compiler computes them: each geom's `mass`, or its
//!   `density` (1000 kg/m³ by default) times its volume, combined about the centre of
//!   mass. ODE wants the body's frame at the centre of mass: the body is placed there,
//!   turned as the MJCF body, with the full inertia tensor.
//! - **Geoms.** `plane` (static only: an infinite plane), `sphere`, `capsule`,
//!   `cylinder`, `box`, and `ellipsoid` (as a sphere of the same volume, with a warning);
//!   `mesh` (an `<asset><mesh>`'s STL or OBJ file, with its `scale`, in `<compiler
//!   meshdir>` or `assetdir`, as a triangle mesh; its mass and inertia those of the
//!   closed solid it bounds, as MuJoCo's for a convex mesh);
//!   `fromto` for capsules and cylinders; `rgba` for the colour (else its
//!   `material`'s, as MuJoCo draws it); `contype` and
//!   `conaffinity` as ODE's category and collide bits (the same rule: two geoms collide
//!   when one's type meets the other's affinity).
//! - **Joints.** `hinge` (a hinge), `slide` (a slider), `ball`, `free` (a free body); a
//!   body without joints is fixed to its parent. `range` (with `limited`, or
//!   `<compiler autolimits>`, on by default) becomes stops, `damping` viscous friction
//!   (explicit, from the rate at the start of the step: stable while `damping · dt`
//!   stays below the inertia it acts on).
//!   A joint's position is the child's relative to its parent, as in MuJoCo. Several
//!   joints in one body (the planar roots of hopper, walker and half-cheetah: slide x,
//!   slide z, hinge y) are chained through light links at the body's frame (each of
//!   [`CHAIN_LINK_FRACTION`] of the body's mass and inertia, named `body/joint`, listed
//!   in [`MjcfModel::chain_links`]): the body then moves with up to 0.1 % more inertia
//!   along each joint but the first (and a free joint cannot be chained). A chained
//!   body and its parent never touch ([`Scene::exclude_contacts`]), as MuJoCo ignores
//!   the contacts of a body with its parent and ODE those of two bodies one joint joins.
//!   A hinge's or slide's `ref` is its position in the pose the file gives (MuJoCo's
//!   `qpos0`): the joint is made with its child moved back by `ref`, so that ODE,
//!   which measures a joint from where it was made, reads `ref` there, and ranges,
//!   servos and sensors see MuJoCo's positions. `stiffness` about `springref` becomes
//!   a spring ([`SimJoint::set_spring`](crate::SimJoint::set_spring): explicit, from
//!   the position at the start of the step), `frictionloss` dry friction
//!   ([`SimJoint::set_dry_friction`](crate::SimJoint::set_dry_friction): ODE's motor
//!   at speed 0, a hard limit where MuJoCo's is soft). On ball and free joints they
//!   are unsupported (an error, or skipped with a warning).
//! - **Armature.** ODE has no joint-space inertia, so a joint's `armature` (MuJoCo's
//!   rotor inertia on the joint's own degree of freedom) is added to the inertia of
//!   the body the joint moves: `armature · n nᵀ` about a hinge's axis `n`,
//!   `armature · 1` for a ball joint ([`MjcfModel::armature`] lists what each object
//!   got). That is MuJoCo's armature exactly for a joint whose axis stays put in the
//!   world (the first hinge or ball of a fixed base). Below moving joints the added
//!   inertia also turns with the joints above it: it adds `armature · (n·m)` to their
//!   coupling and `armature · (n·m)²` to a joint of axis `m` above, and a gyroscopic
//!   torque MuJoCo's armature has not. When the armature outweighs the body so much
//!   that no rigid body has the sum (a moment above the sum of the other two: links of
//!   grams with an armature of 1, as in Gymnasium's reacher), the smallest inertia
//!   across the axis that makes it one is added too, with a warning in
//!   [`MjcfModel::skipped`]. A slide's or a free joint's armature (mass along some
//!   directions only) is not modelled and is listed there.
//! - **Contact parameters.** A geom's `friction`, `solref`, `solimp`, `condim`,
//!   `margin` and `gap` are read and not used, with a warning in [`MjcfModel::skipped`]:
//!   contacts take ARS's surfaces ([`Scene::set_contact_surface`]).
//! - **Defaults.** `<default>` classes with inheritance, `class` and `childclass`.
//! - **Compiler.** `angle`, `eulerseq`, `autolimits`, `inertiafromgeom`, `meshdir`,
//!   `assetdir`,
//!   `settotalmass` (every body's mass and inertia scaled by one factor, as MuJoCo
//!   does); `coordinate="global"` is refused.
//! - **Options.** `<option timestep gravity>` are returned in [`MjcfModel`] (the
//!   integrator is ODE's; the caller chooses to use them).
//! - **Includes.** `<include file>` anywhere (its path relative to the file that
//!   includes it; a cycle is refused): the included file's top-level elements take its
//!   place, and an error in it names that file.
//! - **Ignored without a word** (they change no physics): `<visual>`, `<asset>`
//!   (textures, materials beyond their colour, meshes not used by a geom),
//!   `<statistic>`, `<size>`, `<custom>`, `<light>`, `<camera>`, unnamed `<site>`s
//!   (nothing can name them).
//! - **Sites.** A body's named `<site>`s (`pos` and orientation, `type` `sphere`,
//!   `capsule`, `cylinder`, `box` or `ellipsoid` with its `size`, MuJoCo's 0.005 m
//!   where not given; classes as other elements) are listed in [`MjcfModel::sites`]
//!   with their frames relative to their body's object; `fromto` is unsupported. Sites
//!   of the world body are read for their names only: a sensor on one is unsupported.
//! - **Attributes.** Every attribute of the elements read is checked against MuJoCo's
//!   schema (`mjcf_schema.rs`): one MuJoCo does not know (a typo) is an error naming it,
//!   its element and line (or skipped with a warning); one it knows and ARS does not
//!   use is accepted (and said unused where it changes the physics).
//! - **Actuators.** `motor`, `position` (`kp`, `kv`) and `velocity` (`kv`) on a joint
//!   become [`Actuator`]s of the same names driving their joints, with `gear` (its
//!   first number), `ctrlrange`/`ctrllimited` and `forcerange`/`forcelimited` (with
//!   `autolimits`), their defaults from a `<default>` class's actuator (in a class,
//!   `<general>`, `<motor>`, `<position>`... all set the one actuator default, as in
//!   MuJoCo: the attributes merge in the file's order); set a control with [`Scene::set_control`], as MuJoCo's
//!   `data.ctrl`, at 0 until set. Other kinds, and actuators on tendons or sites, are
//!   unsupported; a second actuator on one joint is skipped (ARS drives a joint with
//!   one controller).
//! - **Contacts.** `<contact><exclude body1 body2>`: the two bodies never touch
//!   ([`Scene::exclude_contacts`]). `<pair geom1 geom2>`: the two named geoms touch
//!   whatever their `contype` and `conaffinity` say (each pair takes a bit of its own
//!   among ODE's upper 32 category and collide bits, so at most [`MAX_CONTACT_PAIRS`];
//!   `contype` and `conaffinity` must fit in 32 bits, as MuJoCo's do); its contact
//!   parameters are read and said unused. Unlike MuJoCo's, a pair does not override
//!   an `<exclude>` or the rule that bodies one joint joins never touch; and a paired
//!   geom also touches what was made outside the model (ARS's own shapes and floors,
//!   URDF robots), whose collide bits take in ODE's upper 32.
//! - **Sensors.** `jointpos` and `jointvel` of hinges and slides; `framepos`,
//!   `framelinvel` and `framequat` of a body's inertial frame (`objtype="body"`; for
//!   `framequat` only when its `<inertial>` gives `diaginertia`), a body's frame
//!   (`xbody`) or a site; `accelerometer`, `gyro`, `touch` and `rangefinder` on a site:
//!   made by [`Simulation::load_mjcf`](crate::Simulation::load_mjcf) and listed in
//!   [`MjcfModel::sensors`] ([`MjcfSensor`] says which ARS sensor each becomes and
//!   which of its columns hold MuJoCo's value, in the simulation's Y-up frame). Other
//!   kinds and frames, `reftype`, a `cutoff`, and sensors on the world body's sites are
//!   unsupported; a sensor naming a joint, body or site the model lacks is an error at
//!   its line. A `touch` counts the contacts whose point lies inside the site's volume
//!   (MuJoCo also counts those whose normal, cast as a ray from the point, crosses it).
//!
//! Unnamed bodies and joints are named `body{N}` and `joint{N}` with N MuJoCo's id (the
//! world body is 0, bodies are numbered in the file's order).

use std::collections::HashMap;
use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};

use crate::body::{BodyBuilder, MassSpec};
use crate::control::{Actuator, ActuatorKind};
use crate::error::{Error, Result};
use crate::formats::mesh::MeshMass;
use crate::geom::GeomBuilder;
use crate::handle::{GeomHandle, JointId, ObjectId};
use crate::scene::JointEnd;
use crate::scene::Scene;
use crate::sensors::{AnySensorId, Mount, TouchZone};
use crate::shape::Shape;

/// How an MJCF model is loaded.
#[derive(Clone, Debug)]
pub struct MjcfOptions {
    /// Where the model's world frame goes in the simulation (after the Z-up to Y-up
    /// turn). Default: the origin.
    pub base_pose: Isometry3<f64>,
    /// Skip what ARS cannot read (with a warning in [`MjcfModel::skipped`]) instead of
    /// refusing the file.
    pub skip_unsupported: bool,
}

impl Default for MjcfOptions {
    fn default() -> Self {
        MjcfOptions { base_pose: Isometry3::identity(), skip_unsupported: false }
    }
}

impl MjcfOptions {
    /// The defaults: at the origin, refusing what cannot be read.
    pub fn new() -> Self {
        Self::default()
    }
    /// Where the model goes.
    pub fn base_pose(mut self, pose: Isometry3<f64>) -> Self {
        self.base_pose = pose;
        self
    }
    /// Skip (with a warning) what cannot be read.
    pub fn skip_unsupported(mut self, skip: bool) -> Self {
        self.skip_unsupported = skip;
        self
    }
}

/// An actuator of the file, as made: an [`Actuator`] of the same name driving its
/// joint (set its control with [`Scene::set_control`]).
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfActuator {
    /// Its name (`actuator{N}` when unnamed, N its index among the actuators).
    pub name: String,
    /// `motor`, `position` or `velocity`.
    pub kind: String,
    /// The joint it drives.
    pub joint: String,
    /// The actuator made of it.
    pub actuator: Actuator,
}

/// What [`Simulation::load_mjcf`](crate::Simulation::load_mjcf) made.
#[derive(Clone, Debug, Default)]
pub struct MjcfModel {
    /// The model's name (`<mujoco model>`).
    pub name: String,
    /// Every body, by name, in the file's order.
    pub bodies: Vec<(String, ObjectId)>,
    /// Every joint made, by name.
    pub joints: Vec<(String, JointId)>,
    /// The static geoms of the world body.
    pub world_geoms: Vec<ObjectId>,
    /// `<option timestep>`, s.
    pub timestep: Option<f64>,
    /// `<option gravity>`, in the simulation's frame, m/s².
    pub gravity: Option<Vector3<f64>>,
    /// The actuators read.
    pub actuators: Vec<MjcfActuator>,
    /// What was skipped, and why.
    pub skipped: Vec<String>,
    /// The light links that chain several joints of one body (see the module docs).
    pub chain_links: Vec<ObjectId>,
    /// The inertia added to an object (by name: a body, or a chain link) for the
    /// armature of the joint that moves it, in the object's frame, kg·m² (see the module
    /// docs): subtract it to compare the object's inertia with MuJoCo's `body_inertia`.
    pub armature: Vec<(String, Matrix3<f64>)>,
    /// The sensors read, in the file's order, each with the ARS sensor made of it.
    pub sensors: Vec<MjcfSensor>,
    /// The named `<site>`s of the bodies, in the file's order.
    pub sites: Vec<MjcfSite>,
}

/// A `<site>` of a body: a frame fixed on it (where sensors sit) and the volume a
/// `touch` sensor feels.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfSite {
    /// Its name.
    pub name: String,
    /// The body it is on, by name.
    pub body: String,
    /// The body's object.
    pub object: ObjectId,
    /// The site's frame relative to the object's: ARS keeps a body's frame at its centre
    /// of mass, turned as the MJCF body, so this is the site's `pos` and orientation in
    /// its body less the body's centre of mass (`(site.pos − com, site.quat)` in the MJCF
    /// body's axes).
    pub offset: Isometry3<f64>,
    /// Its volume (`type` and `size`, MuJoCo's half sizes), centred on its frame.
    pub zone: TouchZone,
}

/// A sensor of the file and the ARS sensor made of it.
///
/// Each kind becomes (its record's columns that hold MuJoCo's value; MuJoCo's world
/// (x, y, z) is the simulation's (x, z, −y)):
/// - `jointpos`, `jointvel`: a [`JointPositions`](crate::sensors::JointPositions) or
///   [`JointVelocities`](crate::sensors::JointVelocities) of its joint (its one column).
/// - `framepos`: a [`Gps`](crate::sensors::Gps) at the frame's origin (its columns, in
///   the simulation's world frame).
/// - `framelinvel`: a [`Velometer`](crate::sensors::Velometer) at the frame's origin
///   (its first three columns, world frame). On a jointed body it lags MuJoCo's by
///   about `ω² r dt` (ODE keeps a constrained body's velocity tangent to its path at
///   the start of the step).
/// - `framequat`: an [`Orientation`](crate::sensors::Orientation) of the frame (its
///   quaternion `q` is MuJoCo's `q_mj` turned with the model, `q = q_turn · q_mj`,
///   `q_turn` the −90° turn about X, up to the sign: ARS's has `w ≥ 0`).
/// - `accelerometer`, `gyro`: an [`Imu`](crate::sensors::Imu) at the site, in the
///   site's frame as MuJoCo's (its first three columns, the specific force, are the
///   `accelerometer`; its last three the `gyro`). The acceleration is the change of the
///   site's velocity over the step (MuJoCo's is the acceleration at an instant): they
///   agree as the step shrinks, on a jointed body once ODE's error correction has
///   brought in the centripetal pull (a few steps after a state is set).
/// - `touch`: a [`Touch`](crate::sensors::Touch) on the site's body within the site's
///   volume (its second column, the normal force).
/// - `rangefinder`: a [`Laser`](crate::sensors::Laser) of [`RANGEFINDER_LENGTH`] at the
///   site along its +Z, not seeing the site's body (its first column; empty where MuJoCo
///   reads −1, nothing hit).
///
/// The frame of `objtype="body"` is the body's inertial frame (its centre of mass,
/// turned as its `<inertial>`), of `xbody` the body's own frame, of `site` the site's.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfSensor {
    /// Its name (`sensor{N}` when unnamed, N its index among the sensors).
    pub name: String,
    /// Its element: `jointpos`, `jointvel`, `framepos`, `framelinvel`, `framequat`,
    /// `accelerometer`, `gyro`, `touch` or `rangefinder`.
    pub kind: String,
    /// What its target is: `joint`, `body` (its inertial frame), `xbody` (its frame) or
    /// `site`.
    pub objtype: String,
    /// The joint, body or site it reads, by name.
    pub target: String,
    /// Where it reads, once the model is built: its object and the frame's offset from
    /// the object's origin (the body's centre of mass, turned as the body); `None` for
    /// a joint's sensor.
    pub mount: Option<Mount>,
    /// The ARS sensor made of it (see above); `None` until made.
    pub id: Option<AnySensorId>,
}

/// The length of the ray of a `rangefinder` (MuJoCo's has none), m.
pub const RANGEFINDER_LENGTH: f64 = 1e4;

/// MuJoCo's default size of a site, m.
const SITE_SIZE: f64 = 0.005;

impl MjcfModel {
    /// The object of a body, by name.
    pub fn body(&self, name: &str) -> Option<ObjectId> {
        self.bodies.iter().find(|(n, _)| n == name).map(|(_, id)| *id)
    }
    /// A joint, by name.
    pub fn joint(&self, name: &str) -> Option<JointId> {
        self.joints.iter().find(|(n, _)| n == name).map(|(_, id)| *id)
    }
    /// A site, by name.
    pub fn site(&self, name: &str) -> Option<&MjcfSite> {
        self.sites.iter().find(|s| s.name == name)
    }
}

/// The mass (and inertia) of each light link that chains several joints of one body,
/// as a fraction of the body's.
pub const CHAIN_LINK_FRACTION: f64 = 1e-3;

/// A problem at a place of the file (or of a file it includes).
#[derive(Clone)]
struct Problem {
    element: String,
    line: u32,
    text: String,
    /// The included file it is in, if not the main one (set from `document` when the
    /// problem reaches [`read`]).
    file: Option<String>,
    /// The address of the document its element is in: which file it is.
    document: usize,
}

type Parsed<T> = std::result::Result<T, Problem>;

/// What cannot be read: with `skip` (`MjcfOptions::skip_unsupported`) a line in
/// `skipped` naming its element and line, else the error.
fn skip_or_refuse(p: Problem, skip: bool, skipped: &mut Vec<String>) -> Parsed<()> {
    if !skip {
        return Err(p);
    }
    skipped.push(format!("<{}> at line {}: {}", p.element, p.line, p.text));
    Ok(())
}

fn problem(node: &roxmltree::Node<'_, '_>, text: impl Into<String>) -> Problem {
    let line = node.document().text_pos_at(node.range().start).row;
    let document = std::ptr::from_ref(node.document()) as usize;
    Problem { element: node.tag_name().name().to_string(), line, text: text.into(), file: None, document }
}

/// `<compiler>` settings.
#[derive(Clone, Debug)]
struct Compiler {
    degrees: bool,
    eulerseq: [u8; 3],
    /// Extrinsic (capital letters) or intrinsic rotations.
    extrinsic: bool,
    autolimits: bool,
    /// `inertiafromgeom`: Some(true) always, Some(false) never, None when no inertial.
    from_geom: Option<bool>,
    /// `settotalmass`: every body's mass and inertia scaled so that they add up to it.
    total_mass: Option<f64>,
    /// `meshdir` (else `assetdir`): where mesh files are, relative to the model's folder.
    meshdir: Option<String>,
}

impl Default for Compiler {
    fn default() -> Self {
        Compiler {
            degrees: true,
            eulerseq: [0, 1, 2],
            extrinsic: false,
            autolimits: true,
            from_geom: None,
            total_mass: None,
            meshdir: None,
        }
    }
}

/// The attributes an element gets from its class, by element kind.
type Defaults = HashMap<String, HashMap<String, HashMap<String, String>>>;

/// The actuator elements: in a `<default>` class they all set one actuator default, as
/// in MuJoCo (a class's `<general ctrlrange>` applies to its `<motor>`s).
const ACTUATOR_KINDS: [&str; 9] =
    ["general", "motor", "position", "velocity", "intvelocity", "damper", "cylinder", "muscle", "adhesion"];

/// Where an element's defaults are kept in a class: under its tag, or under
/// `actuator` for every actuator kind.
fn default_kind(tag: &str) -> &str {
    if ACTUATOR_KINDS.contains(&tag) { "actuator" } else { tag }
}

/// Reads `<default>` classes (with inheritance) into `out`.
fn read_defaults<'a, 'input>(
    tree: &Tree<'a, 'input>,
    node: roxmltree::Node<'a, 'input>,
    parent: &HashMap<String, HashMap<String, String>>,
    out: &mut Defaults,
) {
    let class = node.attribute("class").unwrap_or("main").to_string();
    let mut mine = parent.clone();
    let children = tree.elements(node);
    for child in children.iter().filter(|c| c.tag_name().name() != "default") {
        let attrs = mine.entry(default_kind(child.tag_name().name()).to_string()).or_default();
        for a in child.attributes() {
            attrs.insert(a.name().to_string(), a.value().to_string());
        }
    }
    for child in children.into_iter().filter(|c| c.tag_name().name() == "default") {
        read_defaults(tree, child, &mine, out);
    }
    out.insert(class, mine);
}

/// An element's attributes with its class's defaults under them.
struct Attrs<'a, 'input> {
    node: roxmltree::Node<'a, 'input>,
    class: Option<&'a HashMap<String, String>>,
}

impl<'a, 'input> Attrs<'a, 'input> {
    fn new(node: roxmltree::Node<'a, 'input>, defaults: &'a Defaults, class: &str) -> Self {
        let class = node.attribute("class").unwrap_or(class);
        let class = defaults.get(class).and_then(|c| c.get(default_kind(node.tag_name().name())));
        Attrs { node, class }
    }
    fn get(&self, name: &str) -> Option<&str> {
        self.node.attribute(name).or_else(|| self.class.and_then(|c| c.get(name)).map(String::as_str))
    }
    fn numbers(&self, name: &str) -> Parsed<Option<Vec<f64>>> {
        let Some(text) = self.get(name) else { return Ok(None) };
        let values: std::result::Result<Vec<f64>, _> = text.split_whitespace().map(str::parse::<f64>).collect();
        match values {
            Ok(v) if v.iter().all(|x| x.is_finite()) => Ok(Some(v)),
            _ => Err(problem(&self.node, format!("{name}=\"{text}\" is not a list of finite numbers"))),
        }
    }
    fn fixed<const N: usize>(&self, name: &str) -> Parsed<Option<[f64; N]>> {
        match self.numbers(name)? {
            None => Ok(None),
            Some(v) => v
                .try_into()
                .map(Some)
                .map_err(|v: Vec<f64>| problem(&self.node, format!("{name} has {} numbers, {N} expected", v.len()))),
        }
    }
    fn number(&self, name: &str) -> Parsed<Option<f64>> {
        Ok(self.fixed::<1>(name)?.map(|[x]| x))
    }
}

/// The frame an element's `pos` and orientation attributes give, relative to its parent.
fn frame(a: &Attrs<'_, '_>, compiler: &Compiler) -> Parsed<Isometry3<f64>> {
    let pos = Vector3::from(a.fixed::<3>("pos")?.unwrap_or([0.0; 3]));
    Ok(Isometry3::from_parts(Translation3::from(pos), orientation(a, compiler)?))
}

fn orientation(a: &Attrs<'_, '_>, compiler: &Compiler) -> Parsed<UnitQuaternion<f64>> {
    let angle = |x: f64| if compiler.degrees { x.to_radians() } else { x };
    let given: Vec<&str> = ["quat", "euler", "axisangle", "xyaxes", "zaxis"]
        .into_iter()
        .filter(|n| a.node.attribute(*n).is_some())
        .collect();
    if given.len() > 1 {
        return Err(problem(&a.node, format!("has more than one orientation: {}", given.join(", "))));
    }
    if let Some([w, x, y, z]) = a.fixed::<4>("quat")? {
        let q = nalgebra::Quaternion::new(w, x, y, z);
        if q.norm() == 0.0 {
            return Err(problem(&a.node, "quat is zero"));
        }
        return Ok(UnitQuaternion::from_quaternion(q));
    }
    if let Some([x, y, z, t]) = a.fixed::<4>("axisangle")? {
        let axis =
            Unit::try_new(Vector3::new(x, y, z), 1e-12).ok_or_else(|| problem(&a.node, "axisangle's axis is zero"))?;
        return Ok(UnitQuaternion::from_axis_angle(&axis, angle(t)));
    }
    if let Some(e) = a.fixed::<3>("euler")? {
        let mut q = UnitQuaternion::identity();
        for (i, axis) in compiler.eulerseq.iter().enumerate() {
            let unit = match axis {
                0 => Vector3::x_axis(),
                1 => Vector3::y_axis(),
                _ => Vector3::z_axis(),
            };
            let turn = UnitQuaternion::from_axis_angle(&unit, angle(e[i]));
            q = if compiler.extrinsic { turn * q } else { q * turn };
        }
        return Ok(q);
    }
    if let Some(v) = a.fixed::<6>("xyaxes")? {
        let x = Vector3::new(v[0], v[1], v[2]);
        let y = Vector3::new(v[3], v[4], v[5]);
        let x = x.try_normalize(1e-12).ok_or_else(|| problem(&a.node, "xyaxes' x axis is zero"))?;
        let y =
            (y - x * x.dot(&y)).try_normalize(1e-12).ok_or_else(|| problem(&a.node, "xyaxes' axes are parallel"))?;
        let m = Matrix3::from_columns(&[x, y, x.cross(&y)]);
        return Ok(UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m)));
    }
    if let Some(z) = a.fixed::<3>("zaxis")? {
        let z = Vector3::from(z);
        return UnitQuaternion::rotation_between(&Vector3::z(), &z)
            .or_else(|| (z.z < 0.0).then(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)))
            .ok_or_else(|| problem(&a.node, "zaxis is zero"));
    }
    Ok(UnitQuaternion::identity())
}

/// A geom's shape, MuJoCo's way (half sizes).
#[derive(Clone, Debug)]
enum GeomKind {
    Mesh(std::sync::Arc<MeshGeom>),
    Plane,
    Sphere(f64),
    Capsule(f64, f64),
    Cylinder(f64, f64),
    Box(Vector3<f64>),
    Ellipsoid(Vector3<f64>),
}

/// A mesh asset as a geom uses it: its triangles (scaled) and their mass properties.
#[derive(Debug)]
struct MeshGeom {
    shape: Shape,
    mass: MeshMass,
}

#[derive(Clone, Debug)]
struct Geom {
    kind: GeomKind,
    /// Relative to its body.
    frame: Isometry3<f64>,
    mass: Option<f64>,
    density: f64,
    rgba: Option<[f64; 4]>,
    /// `contype` and `conaffinity`: ODE's category and collide bits, the same rule.
    bits: (u64, u64),
    /// Its name, for `<contact><pair>`.
    name: Option<String>,
}

impl Geom {
    fn volume(&self) -> f64 {
        use std::f64::consts::PI;
        match &self.kind {
            GeomKind::Mesh(mesh) => mesh.mass.volume,
            GeomKind::Plane => 0.0,
            GeomKind::Sphere(r) => 4.0 / 3.0 * PI * r.powi(3),
            GeomKind::Capsule(r, h) => PI * r * r * 2.0 * h + 4.0 / 3.0 * PI * r.powi(3),
            GeomKind::Cylinder(r, h) => PI * r * r * 2.0 * h,
            GeomKind::Box(s) => 8.0 * s.x * s.y * s.z,
            GeomKind::Ellipsoid(s) => 4.0 / 3.0 * PI * s.x * s.y * s.z,
        }
    }

    fn mass(&self) -> f64 {
        self.mass.unwrap_or(self.density * self.volume())
    }

    /// Its centre of mass and its inertia tensor about it, in its frame.
    fn mass_distribution(&self) -> (Vector3<f64>, Matrix3<f64>) {
        match &self.kind {
            GeomKind::Mesh(mesh) => (mesh.mass.centre.coords, mesh.mass.inertia * (self.mass() / mesh.mass.volume)),
            _ => (Vector3::zeros(), Matrix3::from_diagonal(&self.inertia())),
        }
    }

    /// Principal moments about the geom's centre, in its frame, as MuJoCo computes them
    /// (a mesh's are [`mass_distribution`](Self::mass_distribution)'s).
    fn inertia(&self) -> Vector3<f64> {
        let m = self.mass();
        match &self.kind {
            GeomKind::Plane | GeomKind::Mesh(_) => Vector3::zeros(),
            GeomKind::Sphere(r) => Vector3::repeat(0.4 * m * r * r),
            GeomKind::Capsule(r, h) => {
                let height = 2.0 * h;
                let sphere_mass = m * 4.0 * r / (4.0 * r + 3.0 * height);
                let cylinder_mass = m - sphere_mass;
                let across = cylinder_mass * (3.0 * r * r + height * height) / 12.0
                    + 0.4 * sphere_mass * r * r
                    + sphere_mass * height * (3.0 * r + 2.0 * height) / 8.0;
                Vector3::new(across, across, cylinder_mass * r * r / 2.0 + 0.4 * sphere_mass * r * r)
            }
            GeomKind::Cylinder(r, h) => {
                let across = m * (3.0 * r * r + 4.0 * h * h) / 12.0;
                Vector3::new(across, across, m * r * r / 2.0)
            }
            GeomKind::Box(s) => {
                Vector3::new(s.y * s.y + s.z * s.z, s.x * s.x + s.z * s.z, s.x * s.x + s.y * s.y) * (m / 3.0)
            }
            GeomKind::Ellipsoid(s) => {
                Vector3::new(s.y * s.y + s.z * s.z, s.x * s.x + s.z * s.z, s.x * s.x + s.y * s.y) * (m / 5.0)
            }
        }
    }

    /// The ODE shape (an ellipsoid as the sphere of its volume).
    fn shape(&self) -> Shape {
        match &self.kind {
            GeomKind::Mesh(mesh) => mesh.shape.clone(),
            GeomKind::Plane => Shape::Plane { normal: Vector3::z(), distance: 0.0 },
            GeomKind::Sphere(r) => Shape::Sphere { radius: *r },
            GeomKind::Capsule(r, h) => Shape::Capsule { radius: *r, length: 2.0 * h },
            GeomKind::Cylinder(r, h) => Shape::Cylinder { radius: *r, length: 2.0 * h },
            GeomKind::Box(s) => Shape::Box { edges: *s * 2.0 },
            GeomKind::Ellipsoid(s) => Shape::Sphere { radius: (s.x * s.y * s.z).cbrt() },
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq)]
enum JointKind {
    Hinge,
    Slide,
    Ball,
    Free,
}

#[derive(Clone, Debug)]
struct Joint {
    name: String,
    kind: JointKind,
    /// Anchor and axis in the body's frame.
    pos: Vector3<f64>,
    axis: Vector3<f64>,
    range: Option<(f64, f64)>,
    damping: f64,
    armature: f64,
    /// `ref`: its position in the pose the file gives (MuJoCo's `qpos0`).
    reference: f64,
    /// `stiffness` and `springref`: a spring.
    spring: (f64, f64),
    /// `frictionloss`: dry friction.
    frictionloss: f64,
}

#[derive(Clone, Debug)]
struct Body {
    name: String,
    /// Relative to its parent.
    frame: Isometry3<f64>,
    /// Mass, centre of mass in the body's frame, inertia about it in the body's frame.
    mass: Option<(f64, Vector3<f64>, Matrix3<f64>)>,
    geoms: Vec<Geom>,
    joints: Vec<Joint>,
    children: Vec<Body>,
    /// Its named sites.
    sites: Vec<Site>,
    /// The turn of its inertial frame from its frame, when its `<inertial>` gives it
    /// (`diaginertia`, used for its mass).
    principal: Option<UnitQuaternion<f64>>,
}

/// A named `<site>`.
#[derive(Clone, Debug)]
struct Site {
    name: String,
    /// Relative to its body.
    frame: Isometry3<f64>,
    zone: TouchZone,
}

/// Everything read from the file before anything is built.
struct Model {
    name: String,
    world_geoms: Vec<Geom>,
    bodies: Vec<Body>,
    timestep: Option<f64>,
    gravity: Option<Vector3<f64>>,
    actuators: Vec<MjcfActuator>,
    /// `<contact><exclude>`: pairs of bodies, by name, that never touch.
    excluded: Vec<(String, String)>,
    /// `<contact><pair>`: pairs of geoms, by name, that touch whatever their bits say.
    pairs: Vec<(String, String)>,
    sensors: Vec<MjcfSensor>,
    /// Where each sensor is in the file (for errors found once the whole file is read).
    sensor_places: Vec<Problem>,
    /// The sites of the world body, by name.
    world_sites: Vec<String>,
    skipped: Vec<String>,
}

/// Reads the model's elements.
struct Reader<'d, 'a, 'input> {
    tree: &'d Tree<'a, 'input>,
    compiler: Compiler,
    defaults: &'d Defaults,
    skip: bool,
    skipped: Vec<String>,
    bodies: usize,
    joints: usize,
    /// The `<asset><mesh>`es by name: their file (as written) and scale.
    meshes: HashMap<String, (String, Vector3<f64>)>,
    /// The meshes loaded so far, by name.
    loaded: HashMap<String, std::sync::Arc<MeshGeom>>,
    /// The `<asset><material>`s' colours, by name.
    materials: HashMap<String, [f64; 4]>,
    /// Their files, each read once.
    files: super::MeshCache,
    /// The main file's folder.
    dir: std::path::PathBuf,
}

impl<'a, 'input> Reader<'_, 'a, 'input> {
    fn unsupported(&mut self, node: &roxmltree::Node<'_, '_>, what: &str) -> Parsed<()> {
        skip_or_refuse(problem(node, format!("{what} is not supported")), self.skip, &mut self.skipped)
    }

    fn geom(&mut self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<Option<Geom>> {
        let a = Attrs::new(node, self.defaults, class);
        let kind_name = a.get("type").unwrap_or("sphere");
        let size = a.numbers("size")?.unwrap_or_default();
        let fromto = a.fixed::<6>("fromto")?;
        let size_at = |i: usize| -> Parsed<f64> {
            match size.get(i) {
                Some(s) if *s > 0.0 => Ok(*s),
                Some(s) => Err(problem(&node, format!("size {s} must be positive"))),
                None => Err(problem(&node, format!("a {kind_name} needs {} size numbers", i + 1))),
            }
        };
        let mut frame = frame(&a, &self.compiler)?;
        let kind = match kind_name {
            "mesh" => GeomKind::Mesh(self.mesh(&node, a.get("mesh"))?),
            "plane" => GeomKind::Plane,
            "sphere" => GeomKind::Sphere(size_at(0)?),
            "capsule" | "cylinder" => {
                let (r, h) = match fromto {
                    Some(f) => {
                        let (from, to) = (Vector3::new(f[0], f[1], f[2]), Vector3::new(f[3], f[4], f[5]));
                        let along = to - from;
                        if along.norm() == 0.0 {
                            return Err(problem(&node, "fromto's two points are the same"));
                        }
                        let turn = UnitQuaternion::rotation_between(&Vector3::z(), &along).unwrap_or_else(|| {
                            UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)
                        });
                        frame = Isometry3::from_parts(Translation3::from((from + to) / 2.0), turn);
                        (size_at(0)?, along.norm() / 2.0)
                    }
                    None => (size_at(0)?, size_at(1)?),
                };
                if kind_name == "capsule" { GeomKind::Capsule(r, h) } else { GeomKind::Cylinder(r, h) }
            }
            "box" => GeomKind::Box(Vector3::new(size_at(0)?, size_at(1)?, size_at(2)?)),
            "ellipsoid" => {
                self.skipped.push(format!(
                    "<geom> at line {}: an ellipsoid collides as the sphere of its volume",
                    problem(&node, "").line
                ));
                GeomKind::Ellipsoid(Vector3::new(size_at(0)?, size_at(1)?, size_at(2)?))
            }
            other => {
                self.unsupported(&node, &format!("a geom of type {other:?}"))?;
                return Ok(None);
            }
        };
        let mass = a.number("mass")?;
        if mass.is_some_and(|m| m < 0.0) {
            return Err(problem(&node, "mass must not be negative"));
        }
        let density = a.number("density")?.unwrap_or(1000.0);
        if density < 0.0 {
            return Err(problem(&node, "density must not be negative"));
        }
        let bits = |name: &str| -> Parsed<u64> {
            match a.get(name) {
                None => Ok(1),
                // MuJoCo's are 32 bits; ODE's upper 32 are left for `<contact><pair>`.
                Some(v) => v
                    .parse::<u32>()
                    .map(u64::from)
                    .map_err(|_| problem(&node, format!("{name}=\"{v}\" is not a whole number of at most 32 bits"))),
            }
        };
        let bits = (bits("contype")?, bits("conaffinity")?);
        // MuJoCo's contact model is not ODE's: its parameters are read and said unused.
        let contact: Vec<&str> = ["friction", "solref", "solimp", "condim", "margin", "gap"]
            .into_iter()
            .filter(|k| a.get(k).is_some())
            .collect();
        contact_parameters_unused(&node, &contact, &mut self.skipped);
        let name = node.attribute("name").map(str::to_string);
        // Its own rgba (or its class's), else its material's colour, as MuJoCo draws it.
        let rgba = match a.fixed::<4>("rgba")? {
            Some(rgba) => Some(rgba),
            None => a.get("material").and_then(|m| self.materials.get(m)).copied(),
        };
        Ok(Some(Geom { kind, frame, mass, density, rgba, bits, name }))
    }

    fn joint(&mut self, node: roxmltree::Node<'_, '_>, class: &str, free: bool) -> Parsed<Joint> {
        self.joints += 1;
        let a = Attrs::new(node, self.defaults, class);
        let kind = match (free, a.get("type").unwrap_or("hinge")) {
            (true, _) | (_, "free") => JointKind::Free,
            (_, "hinge") => JointKind::Hinge,
            (_, "slide") => JointKind::Slide,
            (_, "ball") => JointKind::Ball,
            (_, other) => return Err(problem(&node, format!("a joint of type {other:?} is not supported"))),
        };
        let name = a.node.attribute("name").map_or_else(|| format!("joint{}", self.joints - 1), str::to_string);
        let axis = Vector3::from(a.fixed::<3>("axis")?.unwrap_or([0.0, 0.0, 1.0]));
        if axis.norm() == 0.0 {
            return Err(problem(&node, "axis is zero"));
        }
        // A hinge's positions are angles, in the compiler's unit.
        let angle = if kind == JointKind::Hinge && self.compiler.degrees { 1f64.to_radians() } else { 1.0 };
        let limited = match a.get("limited") {
            Some("true") => true,
            Some("false") => false,
            _ => self.compiler.autolimits && a.get("range").is_some(),
        };
        let range = match (limited, a.fixed::<2>("range")?) {
            (true, Some([lo, hi])) => {
                if lo > hi {
                    return Err(problem(&node, format!("range {lo} {hi} is reversed")));
                }
                Some((lo * angle, hi * angle))
            }
            (true, None) => return Err(problem(&node, "is limited but has no range")),
            _ => None,
        };
        let damping = a.number("damping")?.unwrap_or(0.0);
        if damping < 0.0 {
            return Err(problem(&node, "damping must not be negative"));
        }
        let armature = a.number("armature")?.unwrap_or(0.0);
        if armature < 0.0 {
            return Err(problem(&node, "armature must not be negative"));
        }
        let mut reference = a.number("ref")?.unwrap_or(0.0) * angle;
        let mut spring = (a.number("stiffness")?.unwrap_or(0.0), a.number("springref")?.unwrap_or(0.0) * angle);
        let mut frictionloss = a.number("frictionloss")?.unwrap_or(0.0);
        if spring.0 < 0.0 || frictionloss < 0.0 {
            return Err(problem(&node, "stiffness and frictionloss must not be negative"));
        }
        // A ball's or a free joint's has no one position: ARS's springs, dry friction
        // and reference positions are of hinges and slides.
        if matches!(kind, JointKind::Ball | JointKind::Free) {
            for (attribute, value) in [("ref", reference), ("stiffness", spring.0), ("frictionloss", frictionloss)] {
                if value != 0.0 {
                    self.unsupported(&node, &format!("{attribute} on a ball or free joint"))?;
                }
            }
            (reference, spring, frictionloss) = (0.0, (0.0, 0.0), 0.0);
        }
        Ok(Joint {
            name,
            kind,
            pos: Vector3::from(a.fixed::<3>("pos")?.unwrap_or([0.0; 3])),
            axis: axis.normalize(),
            range,
            damping,
            armature,
            reference,
            spring,
            frictionloss,
        })
    }

    fn body(&mut self, node: roxmltree::Node<'a, 'input>, class: &str) -> Parsed<Body> {
        self.bodies += 1;
        let index = self.bodies;
        let a = Attrs::new(node, self.defaults, class);
        let class = node.attribute("childclass").unwrap_or(class).to_string();
        let name = node.attribute("name").map_or_else(|| format!("body{index}"), str::to_string);
        let mut body = Body {
            name,
            frame: frame(&a, &self.compiler)?,
            mass: None,
            geoms: Vec::new(),
            joints: Vec::new(),
            children: Vec::new(),
            sites: Vec::new(),
            principal: None,
        };
        let mut inertial = None;
        let mut principal = None;
        for child in self.tree.elements(node) {
            match child.tag_name().name() {
                "geom" => body.geoms.extend(self.geom(child, &class)?),
                "joint" => body.joints.push(self.joint(child, &class, false)?),
                "freejoint" => body.joints.push(self.joint(child, &class, true)?),
                "body" => body.children.push(self.body(child, &class)?),
                "inertial" => {
                    inertial = Some(self.inertial(child, &class)?);
                    principal = self.principal_axes(child, &class)?;
                }
                "site" => body.sites.extend(self.site(child, &class)?),
                "camera" | "light" => {}
                other => self.unsupported(&child, &format!("<{other}> in a body"))?,
            }
        }
        let from_geoms = match self.compiler.from_geom {
            Some(always) => always,
            None => inertial.is_none(),
        };
        body.mass = if from_geoms { mass_of_geoms(&body.geoms) } else { inertial };
        body.principal = if from_geoms { None } else { principal };
        if body.joints.len() > 1 && body.joints.iter().any(|j| j.kind == JointKind::Free) {
            return Err(problem(&node, "a free joint cannot be combined with other joints in one body"));
        }
        // A slide's or a free joint's armature would be mass along some directions
        // only: ODE's mass is the same along all.
        for j in body.joints.iter().filter(|j| j.armature > 0.0 && matches!(j.kind, JointKind::Slide | JointKind::Free))
        {
            self.skipped.push(format!(
                "<joint> {:?} in body {:?}: the armature {} of a {} joint is not modelled (ODE's mass is the same in every direction)",
                j.name,
                body.name,
                j.armature,
                if j.kind == JointKind::Slide { "slide" } else { "free" }
            ));
        }
        Ok(body)
    }

    /// The mesh asset `name` (loaded once), for a geom at `node`.
    fn mesh(&mut self, node: &roxmltree::Node<'_, '_>, name: Option<&str>) -> Parsed<std::sync::Arc<MeshGeom>> {
        let name = name.ok_or_else(|| problem(node, "a mesh geom needs a mesh"))?;
        if let Some(mesh) = self.loaded.get(name) {
            return Ok(mesh.clone());
        }
        let (file, scale) =
            self.meshes.get(name).ok_or_else(|| problem(node, format!("no <mesh> asset is called {name:?}")))?;
        let dir = match &self.compiler.meshdir {
            Some(meshdir) => self.dir.join(meshdir),
            None => self.dir.clone(),
        };
        let path = super::first_file(file, &[dir.join(file)]).map_err(|e| problem(node, e))?;
        let shape = self.files.load(&path, *scale).map_err(|e| problem(node, e.to_string()))?;
        let Shape::TriMesh { vertices, triangles } = &shape else {
            return Err(problem(node, format!("the mesh {name:?} is not a triangle mesh")));
        };
        let mass = crate::formats::mesh::mass_properties(vertices, triangles).ok_or_else(|| {
            problem(node, format!("the mesh {name:?} encloses no volume (it must be closed and wound outwards)"))
        })?;
        let mesh = std::sync::Arc::new(MeshGeom { shape, mass });
        self.loaded.insert(name.to_string(), mesh.clone());
        Ok(mesh)
    }

    /// A `<site>`, or `None` when it has no name (no sensor can name it) or is skipped.
    fn site(&mut self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<Option<Site>> {
        let a = Attrs::new(node, self.defaults, class);
        let Some(name) = node.attribute("name") else { return Ok(None) };
        if a.get("fromto").is_some() {
            self.unsupported(&node, "a site placed by fromto")?;
            return Ok(None);
        }
        let size = a.numbers("size")?.unwrap_or_default();
        if let Some(s) = size.iter().find(|s| **s <= 0.0) {
            return Err(problem(&node, format!("size {s} must be positive")));
        }
        let at = |i: usize| size.get(i).copied().unwrap_or(SITE_SIZE);
        let zone = match a.get("type").unwrap_or("sphere") {
            "sphere" => TouchZone::Sphere { radius: at(0) },
            "capsule" => TouchZone::Capsule { radius: at(0), half_length: at(1) },
            "cylinder" => TouchZone::Cylinder { radius: at(0), half_length: at(1) },
            "box" => TouchZone::Box { half_extents: Vector3::new(at(0), at(1), at(2)) },
            "ellipsoid" => TouchZone::Ellipsoid { radii: Vector3::new(at(0), at(1), at(2)) },
            other => {
                self.unsupported(&node, &format!("a site of type {other:?}"))?;
                return Ok(None);
            }
        };
        Ok(Some(Site { name: name.to_string(), frame: frame(&a, &self.compiler)?, zone }))
    }

    /// The turn of an `<inertial>`'s principal axes from its body's frame: its
    /// orientation when it gives `diaginertia` (MuJoCo's `body_iquat`), `None` for a
    /// `fullinertia` (MuJoCo diagonalises it).
    fn principal_axes(&self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<Option<UnitQuaternion<f64>>> {
        let a = Attrs::new(node, self.defaults, class);
        if a.get("diaginertia").is_none() {
            return Ok(None);
        }
        Ok(Some(orientation(&a, &self.compiler)?))
    }

    /// A sensor (the `index`-th), or `None` when skipped.
    fn sensor(&mut self, node: roxmltree::Node<'_, '_>, index: usize) -> Parsed<Option<MjcfSensor>> {
        let kind = node.tag_name().name();
        let a = Attrs::new(node, self.defaults, "main");
        let needs = |what: &str| a.get(what).ok_or_else(|| problem(&node, format!("needs a {what}")));
        let (objtype, target) = match kind {
            "jointpos" | "jointvel" => ("joint", needs("joint")?),
            "accelerometer" | "gyro" | "touch" | "rangefinder" => ("site", needs("site")?),
            "framepos" | "framelinvel" | "framequat" => {
                let objtype = match a.get("objtype") {
                    Some(t @ ("body" | "xbody" | "site")) => t,
                    other => {
                        let what = other.unwrap_or("(none)");
                        self.unsupported(
                            &node,
                            &format!("a {kind} of objtype {what} (ARS reads objtype body, xbody and site)"),
                        )?;
                        return Ok(None);
                    }
                };
                if a.get("reftype").is_some() {
                    self.unsupported(&node, &format!("a {kind} relative to another frame (reftype)"))?;
                    return Ok(None);
                }
                (objtype, needs("objname")?)
            }
            other => {
                self.unsupported(&node, &format!("a sensor of kind <{other}>"))?;
                return Ok(None);
            }
        };
        // A rangefinder reads its distance from a site (MuJoCo's can cast from a camera
        // and give other data).
        if kind == "rangefinder" && (a.get("camera").is_some() || a.get("data").is_some_and(|d| d != "dist")) {
            self.unsupported(&node, "a rangefinder on a camera or with data other than \"dist\"")?;
            return Ok(None);
        }
        // MuJoCo's noise is not applied in simulation either; a cutoff clamps readings.
        if a.number("cutoff")?.is_some_and(|c| c != 0.0) {
            self.unsupported(&node, "a sensor's cutoff")?;
            return Ok(None);
        }
        let name = node.attribute("name").map_or_else(|| format!("sensor{index}"), str::to_string);
        Ok(Some(MjcfSensor {
            name,
            kind: kind.to_string(),
            objtype: objtype.to_string(),
            target: target.to_string(),
            mount: None,
            id: None,
        }))
    }

    /// Checks that the sensors' targets are in the model, once it is read; a sensor ARS
    /// cannot make there is skipped (with a warning) or refused.
    fn check_sensors(&mut self, model: &mut Model) -> Parsed<()> {
        let mut kept = Vec::new();
        let places = std::mem::take(&mut model.sensor_places);
        for (sensor, place) in std::mem::take(&mut model.sensors).into_iter().zip(places) {
            let at = |text: String| Problem { text, ..place.clone() };
            let missing =
                || at(format!("reads the {} {:?}, which the model does not have", sensor.objtype, sensor.target));
            let body = |name: &str| find_body(&model.bodies, &|b| b.name == name);
            let unsupported = match sensor.objtype.as_str() {
                "joint" => {
                    find_body(&model.bodies, &|b| b.joints.iter().any(|j| j.name == sensor.target))
                        .ok_or_else(missing)?;
                    None
                }
                "site" => match find_body(&model.bodies, &|b| b.sites.iter().any(|s| s.name == sensor.target)) {
                    Some(_) => None,
                    None if model.world_sites.contains(&sensor.target) => {
                        Some(format!("a {} on a site of the world body (ARS reads sites on bodies)", sensor.kind))
                    }
                    None => return Err(missing()),
                },
                _ => match body(&sensor.target).ok_or_else(missing)? {
                    b if sensor.kind == "framequat" && sensor.objtype == "body" && b.principal.is_none() => Some(
                        "a framequat of a body's inertial frame when its <inertial> gives no diaginertia (the \
                         principal axes MuJoCo computes are not read; objtype=\"xbody\" reads the body's frame)"
                            .to_string(),
                    ),
                    _ => None,
                },
            };
            match unsupported {
                None => kept.push(sensor),
                Some(what) => skip_or_refuse(at(format!("{what} is not supported")), self.skip, &mut self.skipped)?,
            }
        }
        model.sensors = kept;
        Ok(())
    }

    /// An actuator (the `index`-th), or `None` when skipped.
    fn actuator(&mut self, node: roxmltree::Node<'_, '_>, index: usize) -> Parsed<Option<MjcfActuator>> {
        let tag = node.tag_name().name();
        let a = Attrs::new(node, self.defaults, "main");
        for transmission in ["tendon", "site", "jointinparent", "body", "cranksite"] {
            if a.get(transmission).is_some() {
                self.unsupported(&node, &format!("an actuator driving a {transmission} (only joints are)"))?;
                return Ok(None);
            }
        }
        let kind = match tag {
            "motor" => ActuatorKind::Motor,
            "position" => {
                ActuatorKind::Position { kp: a.number("kp")?.unwrap_or(1.0), kv: a.number("kv")?.unwrap_or(0.0) }
            }
            "velocity" => ActuatorKind::Velocity { kv: a.number("kv")?.unwrap_or(1.0) },
            other => {
                self.unsupported(&node, &format!("an actuator of kind <{other}>"))?;
                return Ok(None);
            }
        };
        let joint = a.get("joint").ok_or_else(|| problem(&node, "needs a joint"))?.to_string();
        let name = node.attribute("name").map_or_else(|| format!("actuator{index}"), str::to_string);
        let gear = a.numbers("gear")?.and_then(|g| g.first().copied()).unwrap_or(1.0);
        let to_problem = |e: Error| problem(&node, e.to_string());
        let mut actuator = Actuator::new(&name, kind, gear).map_err(to_problem)?;
        if let Some([lo, hi]) = self.limited(&a, "ctrl")? {
            actuator = actuator.with_ctrl_range(lo, hi).map_err(to_problem)?;
        }
        if let Some([lo, hi]) = self.limited(&a, "force")? {
            actuator = actuator.with_force_range(lo, hi).map_err(to_problem)?;
        }
        Ok(Some(MjcfActuator { name, kind: tag.to_string(), joint, actuator }))
    }

    /// `{what}range` when `{what}limited` says it applies ("true", or "auto" with a
    /// range and `<compiler autolimits>`).
    fn limited(&self, a: &Attrs<'_, '_>, what: &str) -> Parsed<Option<[f64; 2]>> {
        let range = a.fixed::<2>(&format!("{what}range"))?;
        Ok(match a.get(&format!("{what}limited")).unwrap_or("auto") {
            "true" => Some(range.ok_or_else(|| problem(&a.node, format!("{what}limited needs a {what}range")))?),
            "auto" if self.compiler.autolimits => range,
            _ => None,
        })
    }

    fn inertial(&mut self, node: roxmltree::Node<'_, '_>, class: &str) -> Parsed<(f64, Vector3<f64>, Matrix3<f64>)> {
        let a = Attrs::new(node, self.defaults, class);
        let mass = a.number("mass")?.ok_or_else(|| problem(&node, "needs a mass"))?;
        if mass <= 0.0 {
            return Err(problem(&node, format!("mass {mass} must be positive")));
        }
        let frame = frame(&a, &self.compiler)?;
        let local = match (a.fixed::<3>("diaginertia")?, a.fixed::<6>("fullinertia")?) {
            (Some(d), None) => Matrix3::from_diagonal(&Vector3::from(d)),
            (None, Some(f)) => super::inertia_tensor(f),
            _ => return Err(problem(&node, "needs one of diaginertia and fullinertia")),
        };
        let r = frame.rotation.to_rotation_matrix();
        Ok((mass, frame.translation.vector, super::turned_inertia(&r, &local)))
    }
}

/// The first body of the tree (depth first, in the file's order) that `wanted` accepts.
fn find_body<'b>(bodies: &'b [Body], wanted: &dyn Fn(&Body) -> bool) -> Option<&'b Body> {
    bodies.iter().find_map(|b| if wanted(b) { Some(b) } else { find_body(&b.children, wanted) })
}

/// The mass, centre of mass and inertia about it (body frame) of `geoms`, as MuJoCo's
/// compiler combines them; `None` when they weigh nothing.
fn mass_of_geoms(geoms: &[Geom]) -> Option<(f64, Vector3<f64>, Matrix3<f64>)> {
    let solid: Vec<&Geom> = geoms.iter().filter(|g| !matches!(g.kind, GeomKind::Plane)).collect();
    let mass: f64 = solid.iter().map(|g| g.mass()).sum();
    if mass <= 0.0 {
        return None;
    }
    // Each geom's centre of mass and inertia about it, in the body's frame.
    let parts: Vec<(f64, Vector3<f64>, Matrix3<f64>)> = solid
        .iter()
        .map(|g| {
            let (centre, inertia) = g.mass_distribution();
            let r = g.frame.rotation.to_rotation_matrix();
            (g.mass(), (g.frame * nalgebra::Point3::from(centre)).coords, super::turned_inertia(&r, &inertia))
        })
        .collect();
    let com = parts.iter().map(|(m, c, _)| c * *m).sum::<Vector3<f64>>() / mass;
    let mut inertia = Matrix3::zeros();
    for (m, c, about_centre) in parts {
        let d = c - com;
        inertia += about_centre + (Matrix3::identity() * d.norm_squared() - d * d.transpose()) * m;
    }
    Some((mass, com, inertia))
}

/// The inertia a joint's armature adds to the object it moves, in that object's frame
/// (whose rotation is the MJCF body's): `armature · n nᵀ` about a hinge's axis `n`,
/// `armature · 1` for a ball; nothing for slides and free joints (listed as skipped).
///
/// When `inertia` plus `armature · n nᵀ` is no rigid body's (a light link with a large
/// armature: the moment about the axis exceeds the sum of the other two), the smallest
/// inertia `t (1 − n nᵀ)` across the axis that makes it one is added too (at most
/// `armature`: a thin disc's is `armature / 2`); returned as the second number.
fn armature_inertia(inertia: &Matrix3<f64>, joint: &Joint) -> (Matrix3<f64>, f64) {
    let a = joint.armature;
    if a <= 0.0 {
        return (Matrix3::zeros(), 0.0);
    }
    match joint.kind {
        JointKind::Ball => (Matrix3::identity() * a, 0.0),
        JointKind::Hinge => {
            let axial = joint.axis * joint.axis.transpose() * a;
            let across = (Matrix3::identity() - joint.axis * joint.axis.transpose()) * a;
            // A rigid body's principal moments: the largest at most the sum of the
            // others, without the rounding slack of ARS's own check (`limits::inertia`),
            // so that the body made with the sum passes it whatever the rounding.
            let rigid = |t: f64| {
                let moments = (inertia + axial + across * t).symmetric_eigenvalues();
                let largest = moments.max();
                largest <= moments.sum() - largest
            };
            if rigid(0.0) {
                return (axial, 0.0);
            }
            // Rigid at t = 1 (an isotropic term keeps the inequality strict): bisect.
            let (mut lo, mut hi) = (0.0, 1.0);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if rigid(mid) {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            (axial + across * hi, hi * a)
        }
        JointKind::Slide | JointKind::Free => (Matrix3::zeros(), 0.0),
    }
}

/// Checks every element ARS reads against MuJoCo's schema
/// ([`mjcf_schema`](super::mjcf_schema)): an unknown attribute is an error naming it, its
/// element and line (with `skip`, a line in `skipped`).
fn check_attributes(
    tree: &Tree<'_, '_>,
    root: roxmltree::Node<'_, '_>,
    skip: bool,
    skipped: &mut Vec<String>,
) -> Parsed<()> {
    fn walk(
        tree: &Tree<'_, '_>,
        node: roxmltree::Node<'_, '_>,
        in_sensor: bool,
        skip: bool,
        skipped: &mut Vec<String>,
    ) -> Parsed<()> {
        let tag = node.tag_name().name();
        for attribute in node.attributes() {
            let name = attribute.name();
            if super::mjcf_schema::is_unknown(tag, name, in_sensor) {
                {
                    let p =
                        problem(&node, format!("unknown attribute {name:?} (MuJoCo's <{tag}> has no such attribute)"));
                    skip_or_refuse(p, skip, skipped)?;
                }
            }
        }
        // Into the sections ARS reads, and the bodies and classes in them; not into the
        // others (a tendon's <joint> is not a body's) nor below the elements read.
        let holds_elements = match tag {
            "mujoco" => node.parent().is_some_and(|p| p.is_root()),
            "body" | "worldbody" | "default" => true,
            _ => {
                super::mjcf_schema::READ_SECTIONS.contains(&tag)
                    && node.parent_element().is_some_and(|p| p.has_tag_name("mujoco"))
            }
        };
        if holds_elements {
            for child in tree.elements(node) {
                walk(tree, child, in_sensor || tag == "sensor", skip, skipped)?;
            }
        }
        Ok(())
    }
    walk(tree, root, false, skip, skipped)?;
    Ok(())
}

/// A mass below ARS's least ([`MIN_MASS`](crate::limits::MIN_MASS): a marker of a
/// few milligrams, as in Gymnasium's pusher) raised to it, the inertia scaled alike,
/// with a warning in `skipped`; any other mass as it is.
fn at_least_ars_least_mass(
    what: &str,
    mass: f64,
    inertia: Matrix3<f64>,
    skipped: &mut Vec<String>,
) -> (f64, Matrix3<f64>) {
    let least = crate::limits::MIN_MASS;
    if mass > 0.0 && mass < least {
        skipped.push(format!(
            "{what}: a mass of {mass:e} kg is below ARS's least ({least:e} kg): raised to it, the inertia scaled alike"
        ));
        (least, inertia * (least / mass))
    } else {
        (mass, inertia)
    }
}

/// Says which of a geom's or a pair's contact parameters (MuJoCo's contact model, not
/// ODE's) are read and not used, if any.
fn contact_parameters_unused(node: &roxmltree::Node<'_, '_>, names: &[&str], skipped: &mut Vec<String>) {
    if !names.is_empty() {
        skipped.push(format!(
            "<{}> at line {}: {} not used (contacts take ARS's surface: Scene::set_contact_surface)",
            node.tag_name().name(),
            problem(node, "").line,
            names.join(", ")
        ));
    }
}

/// Most `<contact><pair>`s a model may have: each takes one of the upper 32 of ODE's
/// 64 category and collide bits (MuJoCo's `contype` and `conaffinity` take the lower).
pub const MAX_CONTACT_PAIRS: usize = 32;

/// A file and its text: the model's, then those it includes, in the order met.
type Files = Vec<(String, String)>;

/// Where each `<include>` leads: (its file's index, its byte offset there) → the
/// included file's index.
type Includes = HashMap<(usize, usize), usize>;

/// Deepest chain of `<include>`s followed.
const MAX_INCLUDE_DEPTH: usize = 32;

/// Reads the files that `text` (the file `name`) includes, wherever their `<include>`
/// is, depth first, into `files` after it; `stack` is the chain of files being read (a
/// cycle is refused). Returns the file's index.
fn gather(
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
    if root.tag_name().name() != "mujoco" {
        return Err(in_file(problem(&root, "the root element must be <mujoco>")));
    }
    let mut found = Vec::new();
    for node in root.descendants().filter(|c| c.is_element() && c.tag_name().name() == "include") {
        let file = node.attribute("file").ok_or_else(|| in_file(problem(&node, "needs a file")))?;
        let path = Path::new(name).parent().unwrap_or(Path::new("")).join(file);
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
struct Tree<'a, 'input> {
    documents: &'a [roxmltree::Document<'input>],
    includes: &'a Includes,
}

impl<'a, 'input> Tree<'a, 'input> {
    /// The index of the file `node` is in.
    fn file_of(&self, node: &roxmltree::Node<'a, 'input>) -> usize {
        self.file_at(std::ptr::from_ref(node.document()) as usize).unwrap_or(0)
    }

    /// The index of the file whose document is at `address` (a [`Problem`]'s).
    fn file_at(&self, address: usize) -> Option<usize> {
        self.documents.iter().position(|d| std::ptr::from_ref(d) as usize == address)
    }

    /// `node`'s child elements, each `<include>` replaced by the included file's
    /// top-level elements (MuJoCo reads an include in place, wherever it is).
    fn elements(&self, node: roxmltree::Node<'a, 'input>) -> Vec<roxmltree::Node<'a, 'input>> {
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

/// Reads the model from the text of a file (`name` resolves its includes).
fn read(name: &str, text: &str, options: &MjcfOptions) -> Parsed<Model> {
    let mut files = Files::new();
    let mut includes = Includes::new();
    gather(name, text.to_string(), &mut files, &mut includes, &mut vec![name.to_string()])?;
    let documents = files
        .iter()
        .map(|(_, text)| roxmltree::Document::parse(text).expect("parsed once already"))
        .collect::<Vec<_>>();
    let tree = Tree { documents: &documents, includes: &includes };
    read_nodes(name, &tree, options).map_err(|mut p| {
        // A problem in an included file names it.
        if p.file.is_none()
            && let Some(index) = tree.file_at(p.document).filter(|&i| i > 0)
        {
            p.file = Some(files[index].0.clone());
        }
        p
    })
}

/// Reads the model from its files.
fn read_nodes(name: &str, tree: &Tree<'_, '_>, options: &MjcfOptions) -> Parsed<Model> {
    let root = tree.documents[0].root_element();
    let nodes = tree.elements(root);
    let mut compiler = Compiler::default();
    let mut defaults = Defaults::new();
    let mut timestep = None;
    let mut gravity = None;
    let mut meshes = HashMap::new();
    let mut material_nodes = Vec::new();
    let mut schema_skips = Vec::new();
    check_attributes(tree, root, options.skip_unsupported, &mut schema_skips)?;
    for &node in &nodes {
        let mut first_pass = || -> Parsed<()> {
            match node.tag_name().name() {
                "compiler" => {
                    if let Some(angle) = node.attribute("angle") {
                        compiler.degrees = angle != "radian";
                    }
                    if let Some(seq) = node.attribute("eulerseq") {
                        let axes: Vec<u8> = seq
                            .chars()
                            .filter_map(|c| match c.to_ascii_lowercase() {
                                'x' => Some(0),
                                'y' => Some(1),
                                'z' => Some(2),
                                _ => None,
                            })
                            .collect();
                        compiler.eulerseq = axes
                            .try_into()
                            .map_err(|_| problem(&node, format!("eulerseq {seq:?} must be three of x, y, z")))?;
                        compiler.extrinsic = seq.chars().all(|c| c.is_ascii_uppercase());
                    }
                    if let Some(auto) = node.attribute("autolimits") {
                        compiler.autolimits = auto == "true";
                    }
                    if let Some(v) = node.attribute("inertiafromgeom") {
                        compiler.from_geom = match v {
                            "true" => Some(true),
                            "false" => Some(false),
                            _ => None,
                        };
                    }
                    if let Some(total) = node.attribute("settotalmass") {
                        compiler.total_mass = match total.parse::<f64>() {
                            Ok(m) if m > 0.0 && m.is_finite() => Some(m),
                            Ok(_) => None,
                            Err(_) => return Err(problem(&node, format!("settotalmass {total:?} is not a number"))),
                        };
                    }
                    if let Some(dir) = node.attribute("meshdir").or(node.attribute("assetdir")) {
                        compiler.meshdir = Some(dir.to_string());
                    }
                    if node.attribute("coordinate").is_some_and(|c| c != "local") {
                        return Err(problem(&node, "coordinate=\"global\" is not supported (MuJoCo removed it too)"));
                    }
                }
                "default" => read_defaults(tree, node, &HashMap::new(), &mut defaults),
                "asset" => {
                    for mesh in tree.elements(node).into_iter().filter(|c| c.has_tag_name("mesh")) {
                        let file = mesh.attribute("file").ok_or_else(|| problem(&mesh, "needs a file"))?;
                        let name = match mesh.attribute("name") {
                            Some(name) => name.to_string(),
                            None => Path::new(file)
                                .file_stem()
                                .map(|s| s.to_string_lossy().into_owned())
                                .unwrap_or_default(),
                        };
                        let a = Attrs { node: mesh, class: None };
                        let scale = a.fixed::<3>("scale")?.map_or(Vector3::repeat(1.0), Vector3::from);
                        meshes.insert(name, (file.to_string(), scale));
                    }
                    material_nodes.extend(tree.elements(node).into_iter().filter(|c| c.has_tag_name("material")));
                }
                "option" => {
                    let a = Attrs { node, class: None };
                    timestep = a.number("timestep")?;
                    gravity = a.fixed::<3>("gravity")?.map(Vector3::from);
                }
                _ => {}
            }
            Ok(())
        };
        first_pass()?;
    }
    // Materials' colours, with their classes' defaults (read by now, wherever they are).
    let mut materials = HashMap::new();
    for node in material_nodes {
        let a = Attrs::new(node, &defaults, "main");
        if let (Some(name), Some(rgba)) = (node.attribute("name"), a.fixed::<4>("rgba")?) {
            materials.insert(name.to_string(), rgba);
        }
    }
    let mut reader = Reader {
        compiler,
        defaults: &defaults,
        skip: options.skip_unsupported,
        skipped: schema_skips,
        bodies: 0,
        joints: 0,
        meshes,
        materials,
        loaded: HashMap::new(),
        files: super::MeshCache::default(),
        tree,
        dir: Path::new(name).parent().map(Path::to_path_buf).unwrap_or_default(),
    };
    let mut model = Model {
        name: root.attribute("model").unwrap_or("").to_string(),
        world_geoms: Vec::new(),
        bodies: Vec::new(),
        timestep,
        gravity,
        actuators: Vec::new(),
        excluded: Vec::new(),
        pairs: Vec::new(),
        sensors: Vec::new(),
        sensor_places: Vec::new(),
        world_sites: Vec::new(),
        skipped: Vec::new(),
    };
    for &node in &nodes {
        let mut second_pass = || -> Parsed<()> {
            match node.tag_name().name() {
                "worldbody" => {
                    for child in tree.elements(node) {
                        match child.tag_name().name() {
                            "geom" => model.world_geoms.extend(reader.geom(child, "main")?),
                            "body" => model.bodies.push(reader.body(child, "main")?),
                            "site" => model.world_sites.extend(reader.site(child, "main")?.map(|s| s.name)),
                            "camera" | "light" => {}
                            other => reader.unsupported(&child, &format!("<{other}> in the world body"))?,
                        }
                    }
                }
                "actuator" => {
                    for (i, child) in tree.elements(node).into_iter().enumerate() {
                        if let Some(actuator) = reader.actuator(child, i)? {
                            model.actuators.push(actuator);
                        }
                    }
                }
                "compiler" | "default" | "option" | "visual" | "asset" | "statistic" | "size" | "custom" => {}
                "contact" => {
                    for child in tree.elements(node) {
                        let needs = |attr: &str| {
                            child
                                .attribute(attr)
                                .map(str::to_string)
                                .ok_or_else(|| problem(&child, format!("needs a {attr}")))
                        };
                        match child.tag_name().name() {
                            "exclude" => model.excluded.push((needs("body1")?, needs("body2")?)),
                            "pair" => {
                                if model.pairs.len() == MAX_CONTACT_PAIRS {
                                    reader.unsupported(
                                        &child,
                                        &format!("a contact pair beyond the first {MAX_CONTACT_PAIRS}"),
                                    )?;
                                    continue;
                                }
                                model.pairs.push((needs("geom1")?, needs("geom2")?));
                                let unused: Vec<&str> = child
                                    .attributes()
                                    .map(|a| a.name())
                                    .filter(|n| !["geom1", "geom2", "name", "class"].contains(n))
                                    .collect();
                                contact_parameters_unused(&child, &unused, &mut reader.skipped);
                            }
                            other => reader.unsupported(&child, &format!("<{other}> in <contact>"))?,
                        }
                    }
                }
                "sensor" => {
                    for (i, child) in tree.elements(node).into_iter().enumerate() {
                        if let Some(sensor) = reader.sensor(child, i)? {
                            model.sensors.push(sensor);
                            model.sensor_places.push(problem(&child, ""));
                        }
                    }
                }
                other => reader.unsupported(&node, &format!("<{other}>"))?,
            }
            Ok(())
        };
        second_pass()?;
    }
    reader.check_sensors(&mut model)?;
    model.skipped = reader.skipped;
    if let Some(total) = reader.compiler.total_mass {
        fn sum(bodies: &[Body]) -> f64 {
            bodies.iter().map(|b| b.mass.map_or(0.0, |m| m.0) + sum(&b.children)).sum()
        }
        fn scale(bodies: &mut [Body], factor: f64) {
            for b in bodies {
                if let Some((mass, _, inertia)) = b.mass.as_mut() {
                    *mass *= factor;
                    *inertia *= factor;
                }
                scale(&mut b.children, factor);
            }
        }
        let now = sum(&model.bodies);
        if now > 0.0 {
            scale(&mut model.bodies, total / now);
        }
    }
    Ok(model)
}

/// MuJoCo (x, y, z) → simulation (x, z, −y), then the base pose.
fn placement(options: &MjcfOptions) -> Isometry3<f64> {
    let turn = UnitQuaternion::from_rotation_matrix(&super::z_up_to_y_up());
    options.base_pose * Isometry3::from_parts(Translation3::identity(), turn)
}

impl Scene {
    /// Makes the bodies, joints and actuators of an MJCF model from its text, not its
    /// sensors (a scene has none); `file` names it in errors.
    pub(crate) fn insert_mjcf_text(&mut self, text: &str, file: &str, options: &MjcfOptions) -> Result<MjcfModel> {
        let model = read(file, text, options).map_err(|p| Error::Format {
            format: "MJCF",
            file: p.file.unwrap_or_else(|| file.to_string()),
            element: format!("<{}>", p.element),
            line: Some(p.line),
            column: None,
            problem: p.text,
        })?;
        // Built in one go; on an error everything made so far is removed.
        let mut made = MjcfModel {
            name: model.name.clone(),
            timestep: model.timestep,
            gravity: model.gravity.map(|g| placement(options).rotation * g),
            actuators: model.actuators.clone(),
            skipped: model.skipped.clone(),
            ..MjcfModel::default()
        };
        let built = self.build_mjcf(&model, options, &mut made);
        if let Err(e) = built {
            let ids: Vec<ObjectId> = made
                .bodies
                .iter()
                .map(|(_, id)| *id)
                .chain(made.chain_links.iter().copied())
                .chain(made.world_geoms.iter().copied())
                .collect();
            for id in ids.into_iter().rev() {
                // Its joints go with it; what was made is removed whatever the error.
                let _ = self.remove_object_with_joints(id);
            }
            return Err(e);
        }
        Ok(made)
    }

    fn build_mjcf(&mut self, model: &Model, options: &MjcfOptions, made: &mut MjcfModel) -> Result<()> {
        let world = placement(options);
        // Geoms by name, for `<contact><pair>`.
        let mut named = HashMap::new();
        for g in &model.world_geoms {
            let pose = world * g.frame;
            let id = match g.kind {
                GeomKind::Plane => {
                    let normal = pose.rotation * Vector3::z();
                    self.add_static(Shape::Plane { normal, distance: normal.dot(&pose.translation.vector) }, pose)?
                }
                _ => self.add_static(g.shape(), pose)?,
            };
            if let Some(c) = g.rgba {
                self.set_color(id, [c[0] as f32, c[1] as f32, c[2] as f32])?;
            }
            if let Some(handle) = self.object(id)?.geom_handle() {
                let mut geom = self.world.geom_mut(handle)?;
                geom.set_category_bits(g.bits.0);
                geom.set_collide_bits(g.bits.1);
                if let Some(name) = &g.name {
                    named.insert(name.clone(), (handle, g.bits));
                }
            }
            made.world_geoms.push(id);
        }
        for body in &model.bodies {
            self.add_mjcf_body(body, &world, None, made, &mut named)?;
        }
        for (k, (a, b)) in model.pairs.iter().enumerate() {
            let unknown = |name: &str| Error::Invalid {
                what: "an MJCF contact pair",
                problem: format!("names the geom {name:?}, which the model does not have"),
            };
            // A bit of its own in one's category and the other's collide bits: these
            // two touch, and nothing else gains a contact.
            let bit = 1u64 << (32 + k);
            let (first, bits) = named.get_mut(a).ok_or_else(|| unknown(a))?;
            bits.0 |= bit;
            let (first, category) = (*first, bits.0);
            let (second, bits) = named.get_mut(b).ok_or_else(|| unknown(b))?;
            bits.1 |= bit;
            let (second, collide) = (*second, bits.1);
            self.world.geom_mut(first)?.set_category_bits(category);
            self.world.geom_mut(second)?.set_collide_bits(collide);
        }
        self.place_mjcf_sensors(model, made)?;
        for (a, b) in &model.excluded {
            let body = |name: &str| {
                made.body(name).ok_or_else(|| Error::Invalid {
                    what: "an MJCF contact exclusion",
                    problem: format!("names the body {name:?}, which the model does not have"),
                })
            };
            self.exclude_contacts(body(a)?, body(b)?)?;
        }
        for a in &model.actuators {
            let joint = made.joint(&a.joint).ok_or_else(|| Error::Invalid {
                what: "an MJCF actuator",
                problem: format!("{:?} drives the joint {:?}, which the model does not have", a.name, a.joint),
            })?;
            if self.actuators().any(|(_, j)| j == joint) {
                made.skipped.push(format!(
                    "actuator {:?}: the joint {:?} has an actuator already (ARS drives a joint with one)",
                    a.name, a.joint
                ));
                continue;
            }
            self.joint_mut(joint)?.set_controller(a.actuator.clone()).map_err(|e| Error::Invalid {
                what: "an MJCF actuator",
                problem: format!("{:?} on the joint {:?}: {e}", a.name, a.joint),
            })?;
        }
        Ok(())
    }

    /// Lists the bodies' sites and places the sensors on their objects (their targets
    /// were checked when the file was read).
    fn place_mjcf_sensors(&self, model: &Model, made: &mut MjcfModel) -> Result<()> {
        fn sites(bodies: &[Body], made: &mut MjcfModel) -> Result<()> {
            for body in bodies {
                let object = made.body(&body.name).ok_or_else(|| unknown_target(&body.name))?;
                // From the body's frame to the object's (at the centre of mass, turned
                // as the body).
                let com = body.mass.map_or(Vector3::zeros(), |(_, com, _)| com);
                for site in &body.sites {
                    made.sites.push(MjcfSite {
                        name: site.name.clone(),
                        body: body.name.clone(),
                        object,
                        offset: Isometry3::from(-com) * site.frame,
                        zone: site.zone,
                    });
                }
                sites(&body.children, made)?;
            }
            Ok(())
        }
        sites(&model.bodies, made)?;
        let mut sensors = model.sensors.clone();
        for sensor in &mut sensors {
            sensor.mount = match sensor.objtype.as_str() {
                "joint" => None,
                "site" => {
                    let site = made.sites.iter().find(|s| s.name == sensor.target);
                    let site = site.ok_or_else(|| unknown_target(&sensor.target))?;
                    Some(Mount::Object(site.object, site.offset))
                }
                objtype => {
                    let body = find_body(&model.bodies, &|b| b.name == sensor.target);
                    let (body, object) =
                        body.zip(made.body(&sensor.target)).ok_or_else(|| unknown_target(&sensor.target))?;
                    let offset = if objtype == "xbody" {
                        Isometry3::from(-body.mass.map_or(Vector3::zeros(), |(_, com, _)| com))
                    } else {
                        Isometry3::from_parts(Translation3::identity(), body.principal.unwrap_or_default())
                    };
                    Some(Mount::Object(object, offset))
                }
            };
        }
        made.sensors = sensors;
        Ok(())
    }

    fn add_mjcf_body(
        &mut self,
        body: &Body,
        parent_frame: &Isometry3<f64>,
        parent: Option<ObjectId>,
        made: &mut MjcfModel,
        named: &mut HashMap<String, (GeomHandle, (u64, u64))>,
    ) -> Result<()> {
        let frame = parent_frame * body.frame;
        let invalid = |problem: String| Error::Invalid { what: "an MJCF body", problem };
        let (mass, com, inertia) = body
            .mass
            .ok_or_else(|| invalid(format!("{:?} has no mass (no inertial and no geom with mass)", body.name)))?;
        let (link_mass, link_inertia) = if body.joints.len() > 1 {
            let what = format!("the light links chaining {:?}", body.name);
            at_least_ars_least_mass(&what, mass * CHAIN_LINK_FRACTION, inertia * CHAIN_LINK_FRACTION, &mut made.skipped)
        } else {
            (mass * CHAIN_LINK_FRACTION, inertia * CHAIN_LINK_FRACTION)
        };
        let (mass, inertia) = at_least_ars_least_mass(&format!("{:?}", body.name), mass, inertia, &mut made.skipped);
        // The body is moved by its last joint, a chain link by its joint: each carries
        // its joint's armature.
        let mut armature = |object: &str, inertia: &Matrix3<f64>, joint: Option<&Joint>| -> Matrix3<f64> {
            let Some(joint) = joint.filter(|j| j.armature > 0.0) else { return Matrix3::zeros() };
            let (added, across) = armature_inertia(inertia, joint);
            if added != Matrix3::zeros() {
                made.armature.push((object.to_string(), added));
            }
            if across > 0.0 {
                made.skipped.push(format!(
                    "<joint> {:?}: its armature {} outweighs {object:?}'s inertia; {across:e} kg·m² was added across its axis too, to keep {object:?} a rigid body",
                    joint.name, joint.armature
                ));
            }
            added
        };
        let links_armature: Vec<Matrix3<f64>> = body.joints[..body.joints.len().saturating_sub(1)]
            .iter()
            .map(|j| armature(&format!("{}/{}", body.name, j.name), &link_inertia, Some(j)))
            .collect();
        let inertia = inertia + armature(&body.name, &inertia, body.joints.last());
        // The ODE body at the centre of mass, turned as the MJCF body.
        let body_frame = Isometry3::from_parts(Translation3::from(frame * nalgebra::Point3::from(com)), frame.rotation);
        let handle = self
            .world
            .insert_body(
                BodyBuilder::new()
                    .mass(MassSpec::Custom { mass, inertia })
                    .position(nalgebra::Point3::from(body_frame.translation.vector))
                    .rotation(body_frame.rotation.to_rotation_matrix()),
            )
            .map_err(|e| invalid(format!("{:?}: {e}", body.name)))?;
        let mut geoms = Vec::new();
        for g in body.geoms.iter().filter(|g| !matches!(g.kind, GeomKind::Plane)) {
            let offset = body_frame.inverse() * frame * g.frame;
            let geom = GeomBuilder::new(g.shape()).attached_to(handle).category_bits(g.bits.0).collide_bits(g.bits.1);
            let geom = if offset == Isometry3::identity() { geom } else { geom.offset(offset) };
            let handle = self.world.insert_geom(self.space(), geom)?;
            if let Some(name) = &g.name {
                named.insert(name.clone(), (handle, g.bits));
            }
            geoms.push(handle);
        }
        let drawn = body.geoms.first().map_or(Shape::Sphere { radius: 0.01 }, Geom::shape);
        let id = self.register_as(&body.name, drawn, Some(handle), geoms.first().copied())?;
        self.set_extra_geoms(id, geoms.into_iter().skip(1).collect())?;
        if let Some(c) = body.geoms.iter().find_map(|g| g.rgba) {
            self.set_color(id, [c[0] as f32, c[1] as f32, c[2] as f32])?;
        }
        made.bodies.push((self.object(id)?.name().to_string(), id));
        let mut end = parent.map_or(JointEnd::World, JointEnd::Object);
        // MuJoCo ignores contacts between a body and its parent (filterparent). ODE
        // skips them for bodies one joint joins; a chain's links hide that.
        if let (Some(parent), true) = (parent, body.joints.len() > 1) {
            self.exclude_contacts(parent, id)?;
        }
        if body.joints.is_empty() {
            let name = format!("{}_weld", body.name);
            self.add_fixed_joint(&name, id, end)?;
        }
        for (k, j) in body.joints.iter().enumerate() {
            if j.kind == JointKind::Free {
                continue;
            }
            // Several joints in one body: a chain through light links at the body's
            // frame, the first joint nearest the parent (MuJoCo's order).
            let child = if k + 1 < body.joints.len() {
                let name = format!("{}/{}", body.name, j.name);
                let link = self
                    .world
                    .insert_body(
                        BodyBuilder::new()
                            .mass(MassSpec::Custom { mass: link_mass, inertia: link_inertia + links_armature[k] })
                            .position(nalgebra::Point3::from(body_frame.translation.vector))
                            .rotation(body_frame.rotation.to_rotation_matrix()),
                    )
                    .map_err(|e| invalid(format!("{name:?}, the light link chaining {:?}: {e}", j.name)))?;
                self.register_as(&name, Shape::Sphere { radius: 0.01 }, Some(link), None)?
            } else {
                id
            };
            let anchor = frame * nalgebra::Point3::from(j.pos);
            let axis = frame.rotation * j.axis;
            // ODE measures a joint from where its bodies are when it is made: made with
            // the child moved back by `ref`, it reads `ref` in the file's pose.
            let moved = self.object(child)?.body_handle().filter(|_| j.reference != 0.0);
            let before = match moved {
                Some(b) => {
                    let body = self.world.body(b)?;
                    let (position, rotation) = (body.position(), body.rotation());
                    let back = match j.kind {
                        JointKind::Hinge => {
                            let turn = UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), -j.reference);
                            Isometry3::rotation_wrt_point(turn, anchor)
                        }
                        _ => Isometry3::from_parts(Translation3::from(axis * -j.reference), UnitQuaternion::identity()),
                    };
                    let mut body = self.world.body_mut(b)?;
                    body.set_position(back * position)?;
                    body.set_rotation(back.rotation.to_rotation_matrix() * rotation)?;
                    Some((b, position, rotation))
                }
                None => None,
            };
            let joint = match j.kind {
                JointKind::Hinge => self.add_hinge_joint(&j.name, child, end, Some(anchor), axis),
                JointKind::Slide => self.add_slider_joint(&j.name, child, end, axis),
                _ => self.add_ball_joint(&j.name, child, end, Some(anchor)),
            };
            if let Some((b, position, rotation)) = before {
                // Put back as it was made: ODE keeps the rotation matrix as set.
                let mut body = self.world.body_mut(b)?;
                body.set_position(position)?;
                body.set_rotation(rotation)?;
            }
            let joint = joint?;
            if let Some((lo, hi)) = j.range {
                self.joint_mut(joint)?.set_limits(lo, hi)?;
            }
            if j.damping > 0.0 {
                self.joint_mut(joint)?.set_viscous_friction(j.damping)?;
            }
            if j.spring.0 > 0.0 {
                self.joint_mut(joint)?.set_spring(j.spring.0, j.spring.1)?;
            }
            if j.frictionloss > 0.0 {
                self.joint_mut(joint)?.set_dry_friction(j.frictionloss)?;
            }
            made.joints.push((j.name.clone(), joint));
            if child != id {
                made.chain_links.push(child);
            }
            end = JointEnd::Object(child);
        }
        for child in &body.children {
            self.add_mjcf_body(child, &frame, Some(id), made, named)?;
        }
        Ok(())
    }
}

/// Loads MJCF models with their sensors.
impl crate::Simulation {
    /// Loads the MJCF model in `path` (see the [module docs](self)) with its sensors
    /// ([`MjcfModel::sensors`]), sampled after every step.
    pub fn load_mjcf(&mut self, path: impl AsRef<Path>, options: &MjcfOptions) -> Result<MjcfModel> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| Error::io("read the MJCF file", path, &e))?;
        self.load_mjcf_text(&text, &path.display().to_string(), options)
    }

    /// Loads an MJCF model from its text with its sensors (see
    /// [`load_mjcf`](Self::load_mjcf)); `file` names it in errors.
    pub fn load_mjcf_text(&mut self, text: &str, file: &str, options: &MjcfOptions) -> Result<MjcfModel> {
        let model = self.scene.insert_mjcf_text(text, file, options)?;
        self.make_mjcf_sensors(model)
    }

    fn make_mjcf_sensors(&mut self, mut model: MjcfModel) -> Result<MjcfModel> {
        use crate::sensors::{Gps, Imu, JointPositions, JointVelocities, Laser, Orientation, Touch, Velometer};
        for i in 0..model.sensors.len() {
            let sensor = &model.sensors[i];
            let (kind, target) = (sensor.kind.as_str(), sensor.target.as_str());
            // The targets were checked while the model was read and placed while it was built.
            let mounted = || match sensor.mount {
                Some(Mount::Object(object, offset)) => Ok((object, offset)),
                _ => Err(unknown_target(target)),
            };
            let id: AnySensorId = match kind {
                "jointpos" | "jointvel" => {
                    let joint = model.joint(target).ok_or_else(|| unknown_target(target))?;
                    if kind == "jointpos" {
                        self.add_sensor(JointPositions::new(&self.scene, &[joint])?)?.into()
                    } else {
                        self.add_sensor(JointVelocities::new(&self.scene, &[joint])?)?.into()
                    }
                }
                _ => {
                    let (object, offset) = mounted()?;
                    let point = offset.translation.vector;
                    match kind {
                        "framepos" => self.add_sensor(Gps::new(object).at(point))?.into(),
                        "framelinvel" => self.add_sensor(Velometer::new(object).at(point))?.into(),
                        "framequat" => self.add_sensor(Orientation::new(object).at(offset.rotation))?.into(),
                        "accelerometer" | "gyro" => self.add_sensor(Imu::new(object).at(offset))?.into(),
                        "touch" => {
                            let zone = model.site(target).ok_or_else(|| unknown_target(target))?.zone;
                            self.add_sensor(Touch::new(object).within(zone, offset))?.into()
                        }
                        _ => self.add_sensor(Laser::new(RANGEFINDER_LENGTH).mounted_on(object, offset))?.into(),
                    }
                }
            };
            model.sensors[i].id = Some(id);
        }
        Ok(model)
    }
}

/// A sensor target the model does not have (checked before: not expected).
fn unknown_target(target: &str) -> Error {
    Error::Invalid { what: "an MJCF sensor", problem: format!("reads {target:?}, which the model does not have") }
}
