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
//! - **`<frame>` and `<replicate>`** in the world body, in bodies and in each other
//!   (`formats/mjcf/frame.rs`). A frame places what it holds, with its `childclass`. A
//!   replicate makes `count` copies, each moved by `offset` and turned by `euler` once
//!   more than the last, every name suffixed with `sep` and the copy's number
//!   (zero-padded to the digits of `count`, as MuJoCo names them); the actuators and
//!   sensors naming a replicated joint, body or site are repeated per copy, after the
//!   others (MuJoCo's order), and so are the equalities, contact exclusions and
//!   `<pair>`s naming a replicated element: in each copy, every name that copy
//!   replicated takes its suffix. (MuJoCo 4.0 refuses such an element when it also
//!   names an element defined after the replicate, and drops an equality that also
//!   names one outside it; ARS repeats both.) A joint directly in a replicate, or in
//!   a frame of one, is refused, as MuJoCo refuses it. At most [`MAX_REPLICATED`]
//!   elements and copies in all.
//! - **Mass.** `<inertial>` (`mass`, `diaginertia` or `fullinertia`, its own frame), or,
//!   without one (or with `<compiler inertiafromgeom="true">`), the mass and inertia of
//!   the body's geoms as MuJoCo's compiler computes them: each geom's `mass`, or its
//!   `density` (1000 kg/m³ by default) times its volume, combined about the centre of
//!   mass. ODE wants the body's frame at the centre of mass: the body is placed there,
//!   turned as the MJCF body, with the full inertia tensor.
//! - **Geoms.** `plane` (static only: an infinite plane), `sphere`, `capsule`,
//!   `cylinder`, `box`, and `ellipsoid` (it collides as the convex hull of 258 points
//!   on it, which reaches within 1.5 % of it along any direction; its mass is the
//!   ellipsoid's);
//!   `mesh` (an `<asset><mesh>`'s STL, OBJ or MuJoCo's legacy `.msh` file, with its `scale`, in `<compiler
//!   meshdir>` or `assetdir`; it collides as its convex hull, as in MuJoCo
//!   ([`Shape::ConvexHull`](crate::Shape::ConvexHull)), and is drawn as its triangles
//!   (the object's visuals); its mass and inertia those of the closed solid it bounds,
//!   as MuJoCo's for a convex mesh; a mesh that encloses no volume (open, or wound
//!   inwards) weighs as its hull, said in `skipped`, and one whose hull is flat is
//!   refused, as MuJoCo refuses it);
//!   `hfield` (an `<asset><hfield>` of `elevation` numbers, a PNG file's grey levels, or
//!   zeros; static terrain only: a triangle mesh of its grid at MuJoCo's heights, see
//!   the `hfield` module; its base box is not made);
//!   `fromto` for capsules and cylinders; `rgba` for the colour (else its
//!   `material`'s, as MuJoCo draws it); `contype` and
//!   `conaffinity` as ODE's category and collide bits (the same rule: two geoms collide
//!   when one's type meets the other's affinity).
//! - **Joints.** `hinge` (a hinge), `slide` (a slider), `ball`, `free` (a free body); a
//!   body without joints is welded to its parent, as in MuJoCo's compiler, which makes
//!   it one rigid body with its parent: it is no object of its own. Its mass (if any) is
//!   combined with its parent's about their common centre, its geoms go onto its
//!   parent's object at their offsets, its sites and children are placed through it,
//!   and [`MjcfModel::welded`] says where it went. A jointless body of the world that
//!   weighs nothing is merged into the world (its geoms static); one with mass is an
//!   object of its own, with its jointless descendants, whose ODE body is kinematic:
//!   nothing moves it, and it adds no constraint row to the step (a fixed joint to the
//!   world would add six to every step of what hangs from it). It is also disabled, so
//!   that ODE neither steps it nor moves its geoms each step, and what touches it is
//!   held as the world holds it (a kinematic body at rest: its contacts are attached to
//!   the world, the same rows, so that a table does not join everything on it into one
//!   island); a joint that joins it to a body that moves enables it again. A moving
//!   body that weighs nothing with its welded descendants (its mass is in bodies that
//!   move on joints of their own) is refused, as MuJoCo refuses it ("mass and inertia
//!   of moving bodies must be larger than mjMINVAL"). `range` (with `limited`, or
//!   `<compiler autolimits>`, on by default) becomes stops, as soft as `solreflimit`
//!   and `solimplimit`'s `dmax` say: their ERP is MuJoCo's reference acceleration as
//!   ODE's spring at the time step the model is made at (0.073 at MuJoCo's defaults and
//!   3 ms; kept if the time step changes later); their CFM stays the world's (MuJoCo's
//!   impedance is not modelled). `damping` is integrated as
//!   MuJoCo integrates it, implicitly (stable at any coefficient): an ODE motor beside
//!   the joint holds the bodies' relative velocity at 0 with constraint force mixing
//!   `1 / damping`, so that ODE solves the damping force from the velocity at the end
//!   of the step. A hinge's or a slide's is the joint's own
//!   ([`SimJoint::set_damping`](crate::SimJoint::set_damping)), on the one motor that
//!   also holds its armature; a ball's (an angular motor about three axes) and a free
//!   joint's (a linear and an angular one) are listed in [`MjcfModel::joint_motors`].
//!   A joint's position is the child's relative to its parent, as in MuJoCo. Several
//!   joints in one body are one joint group
//!   ([`Scene::add_joint_group`](crate::Scene::add_joint_group)), as MuJoCo moves such a
//!   body: hinges through one point about perpendicular axes (a humanoid's hip or
//!   shoulder) are a ball with the rotations they do not allow held, and slides along
//!   perpendicular axes with at most a hinge about their plane's normal (the planar
//!   roots of hopper, walker and half-cheetah: slide x, slide z, hinge y; a point mass)
//!   hold the body in its plane; each joint stays a joint of its own, read as the body's
//!   relative pose gives it. Joints a group cannot take (hinges through different
//!   points or about axes that are not perpendicular, a slide after a hinge, slides of a
//!   body that is not the world's child, a planar body's slides with an armature,
//!   damping or dry friction) are chained through light links at the
//!   body's frame (each of
//!   [`CHAIN_LINK_FRACTION`] of the body's mass and inertia, named `body/joint`, listed
//!   in [`MjcfModel::chain_links`]): the body then moves with up to 0.1 % more inertia
//!   along each joint but the first (and a free joint cannot be chained). A body with
//!   several joints and its parent never touch ([`Scene::exclude_contacts`](crate::Scene::exclude_contacts)), as MuJoCo ignores
//!   the contacts of a body with its parent and ODE those of two bodies one joint joins.
//!   A hinge's or slide's `ref` is its position in the pose the file gives (MuJoCo's
//!   `qpos0`): the joint is made with its child moved back by `ref`, so that ODE,
//!   which measures a joint from where it was made, reads `ref` there, and ranges,
//!   servos and sensors see MuJoCo's positions. `stiffness` about `springref` becomes
//!   a spring ([`SimJoint::set_spring`](crate::SimJoint::set_spring): explicit, from
//!   the position at the start of the step), `frictionloss` dry friction
//!   ([`SimJoint::set_dry_friction`](crate::SimJoint::set_dry_friction): ODE's motor
//!   at speed 0, a hard limit where MuJoCo's is soft; on a ball or free joint a motor
//!   beside it, at speed 0 with that limit about each of three axes: a box of torques
//!   where MuJoCo's bounds each degree of freedom alike). On ball and free joints `ref`
//!   and `stiffness` are unsupported (an error, or skipped with a warning).
//! - **Mocap bodies.** A `mocap="true"` body (a jointless child of the world, as MuJoCo
//!   requires) is a kinematic ODE body with its jointless descendants: gravity and
//!   contacts do not move it, [`Simulation::set_mocap_pose`] does (in the file's
//!   frame, as MuJoCo's `mocap_pos` and `mocap_quat`), and what an `<equality>` joins
//!   to it follows ([`MjcfModel::mocap`]). Like the bodies welded to the world, it
//!   touches neither the world's geoms nor them. A massless one carries ARS's least
//!   mass, which its kinematic body never feels.
//! - **Armature.** A hinge's or slide's `armature` (MuJoCo's rotor inertia on the
//!   joint's own degree of freedom) is the joint's own
//!   ([`SimJoint::set_armature`](crate::SimJoint::set_armature)): an ODE motor beside
//!   the joint resists the change of its rate by `armature · Δrate / h`, implicitly, as
//!   MuJoCo's joint-space armature does; the bodies' masses and inertias stay MuJoCo's.
//!   ODE has no joint coordinate for a ball joint: its `armature · 1` is added to the
//!   inertia of the body it moves ([`MjcfModel::armature`] lists what each object got;
//!   exact for a ball whose parent stays put, and felt by that body's every turn
//!   below moving joints). A free joint's armature (mass along some directions only)
//!   is not modelled and is listed in [`MjcfModel::skipped`].
//! - **Contact parameters.** A geom's `friction`, `condim`, `solref`, `solimp`,
//!   `priority` and `solmix` (MuJoCo's defaults where not given) are its own
//!   ([`Scene::set_geom_contact`](crate::Scene::set_geom_contact)): each pair of geoms
//!   that touch combines them as MuJoCo does and maps them onto ODE's contact, as
//!   [`GeomContact`](crate::GeomContact)'s docs say (Coulomb friction, torsional and
//!   rolling friction by `condim`, soft contacts of MuJoCo's resting depth and
//!   rebound). `margin` and `gap` are read and said unused in [`MjcfModel::skipped`]:
//!   ODE makes contacts only where geoms overlap.
//! - **Defaults.** `<default>` classes with inheritance, `class` and `childclass`.
//! - **Compiler.** `angle`, `eulerseq`, `autolimits`, `inertiafromgeom`,
//!   `inertiagrouprange` (only geoms of those `group`s weigh), `meshdir`,
//!   `assetdir`,
//!   `settotalmass` (every body's mass and inertia scaled by one factor, as MuJoCo
//!   does); `coordinate="global"` is refused.
//! - **Options.** `<option timestep gravity>` are returned in [`MjcfModel`] (the
//!   integrator is ODE's; the caller chooses to use them). `<flag>`s that turn
//!   off `contact`, `gravity`, `equality`, `limit`, `frictionloss` (all four with
//!   `constraint`), `spring` or `damper` turn them off in the model; a flag at MuJoCo's
//!   default (`warmstart="enable"`) changes nothing; any other is said unused.
//! - **Includes.** `<include file>` anywhere (its path relative to the model's own
//!   file, at any depth, as MuJoCo reads it; a cycle is refused): the included file's
//!   top-level elements take its place whatever its root element is called
//!   (`<mujocoinclude>` by convention), and an error in it names that file.
//! - **Keyframes.** `<keyframe>`'s `<key>`s are read into [`MjcfModel::keyframes`]
//!   (name, time, `qpos`, `qvel`, `ctrl`, `mpos`, `mquat` as written) and not applied:
//!   MuJoCo applies none when it compiles a model (its reset goes to `qpos0`), so a
//!   model starts where MuJoCo's starts.
//! - **Ignored without a word** (they change no physics): `<visual>`, `<asset>`
//!   (textures, materials beyond their colour, meshes not used by a geom),
//!   `<statistic>`, `<size>`, `<custom>`, `<light>`, `<camera>`, unnamed `<site>`s
//!   (nothing can name them).
//! - **Sites.** A body's named `<site>`s (`pos` and orientation, `type` `sphere`,
//!   `capsule`, `cylinder`, `box` or `ellipsoid` with its `size`, MuJoCo's 0.005 m
//!   where not given; classes as other elements) are listed in [`MjcfModel::sites`]
//!   with their frames relative to their body's object; `fromto` places one as it
//!   places a geom (centred between its points, its z axis along them, its length
//!   theirs: a rangefinder looks from one to the other). Sites
//!   of the world body are read for their names only: a sensor on one is unsupported.
//! - **Attributes.** Every attribute of the elements read is checked against MuJoCo's
//!   schema (`mjcf/schema.rs`): one MuJoCo does not know (a typo) is an error naming it,
//!   its element and line (or skipped with a warning); one it knows and ARS does not
//!   use is accepted (and said unused where it changes the physics).
//! - **Actuators.** `motor`, `position` (`kp`, `kv`), `velocity` (`kv`) and `general`
//!   (a fixed gain `gainprm[0]` and an affine bias `biasprm[0..3]`, no activation
//!   dynamics: [`ActuatorKind::General`](crate::ActuatorKind::General), or the shortcut it
//!   spells out) on a joint become [`Actuator`]s of the same names driving their joints, with `gear` (its
//!   first number), `ctrlrange`/`ctrllimited` and `forcerange`/`forcelimited` (with
//!   `autolimits`), their defaults from a `<default>` class's actuator (in a class,
//!   `<general>`, `<motor>`, `<position>`... all set the one actuator default, as in
//!   MuJoCo: the attributes merge in the file's order); set a control with [`Scene::set_control`](crate::Scene::set_control), as MuJoCo's
//!   `data.ctrl`, at 0 until set. Other kinds, and actuators on tendons or sites, are
//!   unsupported; a second actuator on one joint is skipped (ARS drives a joint with
//!   one controller).
//! - **Contacts.** `<contact><exclude body1 body2>`: the two bodies never touch
//!   ([`Scene::exclude_contacts`](crate::Scene::exclude_contacts)). `<pair geom1 geom2>`: the two named geoms touch
//!   whatever their `contype` and `conaffinity` say (each pair takes a bit of its own
//!   among ODE's upper 32 category and collide bits, so at most [`MAX_CONTACT_PAIRS`];
//!   `contype` and `conaffinity` must fit in 32 bits, as MuJoCo's do); its own `friction`
//!   (the first sliding, torsional and first rolling of its five), `condim`, `solref`
//!   and `solimp` are its contacts', in place of its geoms' combined, MuJoCo's defaults
//!   for those it does not give
//!   ([`Scene::set_geom_pair_contact`](crate::Scene::set_geom_pair_contact)); its
//!   `margin`, `gap`, `solreffriction` and an anisotropic friction are said unused. Unlike MuJoCo's, a pair does not override
//!   an `<exclude>` or the rule that bodies one joint joins never touch; and a paired
//!   geom also touches what was made outside the model (ARS's own shapes and floors,
//!   URDF robots), whose collide bits take in ODE's upper 32.
//! - **Equality constraints.** `connect` (a ball joint at the anchor), `weld` (a fixed
//!   joint, keeping the pose the file gives) and `joint` of degree 1 (`joint1` follows
//!   `joint2` as a [`Mimic`](crate::scene::Mimic), with their `ref`s as MuJoCo's
//!   `qpos0`), between bodies, sites or a body and the world; listed in
//!   [`MjcfModel::equalities`]. They are hard, not softened by `solref`/`solimp` (said
//!   unused), a coupling is one-way (the leader does not feel the follower's load), and
//!   two bodies an equality joins never touch (ODE's rule for joined bodies). `tendon`
//!   and `flex` equalities, `polycoef` beyond degree 1, a `joint` without `joint2`, a
//!   `relpose` other than the file's pose and inactive equalities are skipped or
//!   refused (see the `equality` module's docs).
//! - **Tendons.** A fixed tendon that does nothing (no limit, spring, damping or
//!   friction) is read and dropped, as it has no effect on the motion; any other tendon
//!   is unsupported (see the `tendon` module's docs).
//! - **Sensors.** `jointpos` and `jointvel` of hinges and slides; `framepos`,
//!   `framelinvel` and `framequat` of a body's inertial frame (`objtype="body"`; for
//!   `framequat` only when its `<inertial>` gives `diaginertia`), a body's frame
//!   (`xbody`) or a site; `accelerometer`, `gyro`, `touch` and `rangefinder` on a site:
//!   made by [`Simulation::load_mjcf`] and listed in
//!   [`MjcfModel::sensors`] ([`MjcfSensor`] says which ARS sensor each becomes and
//!   which of its columns hold MuJoCo's value, in the simulation's Y-up frame). Other
//!   kinds and frames, `reftype`, a `cutoff`, and sensors on the world body's sites are
//!   unsupported; a sensor naming a joint, body or site the model lacks is an error at
//!   its line. A `touch` counts the contacts whose point lies inside the site's volume
//!   (MuJoCo also counts those whose normal, cast as a ray from the point, crosses it).
//!
//! Unnamed bodies and joints are named `body{N}` and `joint{N}` with N MuJoCo's id (the
//! world body is 0, bodies are numbered in the file's order).

use std::path::Path;

use nalgebra::{Isometry3, Matrix3, Vector3};

use crate::control::Actuator;
use crate::error::{Error, Result};
use crate::handle::{JointHandle, JointId, ObjectId};
use crate::sensors::{AnySensorId, Mount, TouchZone};
use crate::simulation::Simulation;

mod actuator;
mod build;
mod contact;
mod damper;
mod defaults;
mod equality;
mod flags;
mod frame;
mod group;
mod hfield;
mod include;
mod keyframe;
#[cfg(test)]
mod lean_step_tests;
mod mass;
mod meshes;
mod mocap;
mod model;
mod prefix;
mod problem;
mod read;
mod schema;
mod sensors;
mod tendon;
mod tree;
mod weld;

pub use keyframe::MjcfKeyframe;
pub use mocap::MjcfMocap;

/// How an MJCF model is loaded.
#[derive(Clone, Debug)]
pub struct MjcfOptions {
    /// Where the model's world frame goes in the simulation (after the Z-up to Y-up
    /// turn). Default: the origin.
    pub base_pose: Isometry3<f64>,
    /// Skip what ARS cannot read (with a warning in [`MjcfModel::skipped`]) instead of
    /// refusing the file.
    pub skip_unsupported: bool,
    /// Put before every name of the model (bodies, joints, geoms, sites, actuators,
    /// sensors, and the names ARS makes of them), as MuJoCo's `attach` prefixes an
    /// attached model's: two copies of a model then share a simulation. Default: none.
    pub prefix: String,
}

impl Default for MjcfOptions {
    fn default() -> Self {
        MjcfOptions { base_pose: Isometry3::identity(), skip_unsupported: false, prefix: String::new() }
    }
}

impl MjcfOptions {
    /// The defaults: at the origin, refusing what cannot be read.
    pub fn new() -> Self {
        Self::default()
    }
    /// Where the model goes.
    #[must_use]
    pub fn base_pose(mut self, pose: Isometry3<f64>) -> Self {
        self.base_pose = pose;
        self
    }
    /// Skip (with a warning) what cannot be read.
    #[must_use]
    pub fn skip_unsupported(mut self, skip: bool) -> Self {
        self.skip_unsupported = skip;
        self
    }
    /// Prefix every name of the model with `prefix` (see [`MjcfOptions::prefix`]).
    #[must_use]
    pub fn prefix(mut self, prefix: impl Into<String>) -> Self {
        self.prefix = prefix.into();
        self
    }
}

/// An actuator of the file, as made: an [`Actuator`] of the same name driving its
/// joint (set its control with [`Scene::set_control`](crate::Scene::set_control)).
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

/// What [`Simulation::load_mjcf`] made.
#[derive(Clone, Debug, Default)]
pub struct MjcfModel {
    /// The model's name (`<mujoco model>`).
    pub name: String,
    /// Every body made an object, by name, in the file's order (not those in
    /// [`welded`](Self::welded)).
    pub bodies: Vec<(String, ObjectId)>,
    /// The jointless bodies merged into the body they are welded to (or into the
    /// world), in the file's order (see the module docs).
    pub welded: Vec<MjcfWeld>,
    /// Every joint made, by name.
    pub joints: Vec<(String, JointId)>,
    /// The ODE motors beside the ball and free joints, by joint name: those that damp
    /// one with a `damping`, and those that hold one with a `frictionloss` (one for a
    /// ball joint, a linear and an angular one for a free joint; see the module docs; a
    /// hinge's or a slide's damping is the joint's own, [`SimJoint::damping`](crate::SimJoint::damping)).
    /// They are joints of the [`World`](crate::World), saved with the scene.
    pub joint_motors: Vec<(String, JointHandle)>,
    /// The static geoms of the world body.
    pub world_geoms: Vec<ObjectId>,
    /// `<option timestep>`, s.
    pub timestep: Option<f64>,
    /// `<option gravity>`, in the simulation's frame, m/s².
    pub gravity: Option<Vector3<f64>>,
    /// `<option magnetic>` (MuJoCo's `(0, −0.5, 0)` when not given), in the simulation's
    /// frame: what the model's magnetometers read.
    pub magnetic: Vector3<f64>,
    /// The actuators read.
    pub actuators: Vec<MjcfActuator>,
    /// What was skipped, and why.
    pub skipped: Vec<String>,
    /// The light links that chain several joints of one body (see the module docs).
    pub chain_links: Vec<ObjectId>,
    /// The inertia added to an object (by name: a body, or a chain link) for the
    /// armature of the ball joint that moves it, in the object's frame, kg·m² (see the
    /// module docs): subtract it to compare the object's inertia with MuJoCo's
    /// `body_inertia`. A hinge's or slide's armature is the joint's own, not here.
    pub armature: Vec<(String, Matrix3<f64>)>,
    /// The sensors read, in the file's order, each with the ARS sensor made of it.
    pub sensors: Vec<MjcfSensor>,
    /// The joints made of the file's `<equality>` constraints (`connect`: a ball joint,
    /// `weld`: a fixed joint), in the file's order; a `joint` equality makes no joint
    /// but a [`Mimic`](crate::scene::Mimic) on its `joint1` (see the module docs).
    pub equalities: Vec<JointId>,
    /// The named `<site>`s of the bodies, in the file's order.
    pub sites: Vec<MjcfSite>,
    /// The `<keyframe>`'s `<key>`s, in the file's order: read, not applied (MuJoCo
    /// applies none when it compiles a model either; its reset goes to `qpos0`).
    pub keyframes: Vec<MjcfKeyframe>,
    /// The mocap bodies, in the file's order: kinematic bodies moved by
    /// [`Simulation::set_mocap_pose`].
    pub mocap: Vec<MjcfMocap>,
}

/// A jointless body of the file merged into the body it is welded to: it is
/// no object of its own.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfWeld {
    /// Its name.
    pub body: String,
    /// The body whose object holds its geoms, by name; `None`: the world (its geoms
    /// are static objects, in [`MjcfModel::world_geoms`]).
    pub into: Option<String>,
    /// That body's object.
    pub object: Option<ObjectId>,
    /// Its frame relative to that object's (the body's centre of mass, turned as the
    /// body), or its pose in the simulation when welded to the world.
    pub offset: Isometry3<f64>,
}

/// A `<site>` of a body: a frame fixed on it (where sensors sit) and the volume a
/// `touch` sensor feels.
#[derive(Clone, Debug, PartialEq)]
pub struct MjcfSite {
    /// Its name.
    pub name: String,
    /// The body it is on, by name (in the file: a body in [`MjcfModel::welded`] too).
    pub body: String,
    /// The body's object (for a body welded into another, that one's).
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
/// - `velocimeter`: a [`Velocimeter`](crate::sensors::Velocimeter) at the site, in the
///   site's frame (its first three columns; it lags on a jointed body as `framelinvel`).
/// - `touch`: a [`Touch`](crate::sensors::Touch) on the site's body within the site's
///   volume (its second column, the normal force).
/// - `magnetometer`: a [`Magnetometer`](crate::sensors::Magnetometer) at the site, in
///   the site's frame, in the model's [`magnetic`](MjcfModel::magnetic) field (its
///   three columns).
/// - `subtreecom`, `subtreelinvel`, `subtreeangmom`: a
///   [`Momentum`](crate::sensors::Momentum) of the body's object and those of the bodies
///   below it (its columns `x y z`, `vx vy vz` and `Lx Ly Lz`, world frame). A body
///   merged into the body it is welded to has no object of its own: its subtree sensors
///   are skipped.
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
    /// `accelerometer`, `gyro`, `velocimeter`, `touch`, `rangefinder`, `magnetometer`, `subtreecom`,
    /// `subtreelinvel` or `subtreeangmom`.
    pub kind: String,
    /// What its target is: `joint`, `body` (its inertial frame), `xbody` (its frame),
    /// `site`, or `subtree` (a body and the bodies below it).
    pub objtype: String,
    /// The joint, body or site it reads, by name.
    pub target: String,
    /// Where it reads, once the model is built: its object and the frame's offset from
    /// the object's origin (the body's centre of mass, turned as the body); `None` for
    /// a joint's sensor.
    pub mount: Option<Mount>,
    /// What a `subtreecom`, `subtreelinvel` or `subtreeangmom` reads: the objects of its
    /// body and of the bodies below it; empty for the other kinds.
    pub subtree: Vec<ObjectId>,
    /// The ARS sensor made of it (see above); `None` until made.
    pub id: Option<AnySensorId>,
}

/// Most `<contact><pair>`s a model may have: each takes one of the upper 32 of ODE's
/// 64 category and collide bits (MuJoCo's `contype` and `conaffinity` take the lower).
pub const MAX_CONTACT_PAIRS: usize = 32;

pub use frame::MAX_REPLICATED;

/// How a skipped line about a geom's or a pair's unused contact parameters ends.
pub(crate) const CONTACT_PARAMETERS_UNUSED: &str =
    "not used (ODE makes contacts where geoms overlap, with the touching geoms' own parameters)";

/// The length of the ray of a `rangefinder` (MuJoCo's has none), m.
pub const RANGEFINDER_LENGTH: f64 = 1e4;

/// MuJoCo's default size of a site, m.
const SITE_SIZE: f64 = 0.005;

impl MjcfModel {
    /// The object of a body, by name: its own, or for a body in
    /// [`welded`](Self::welded) the object it was merged into (`None` for the world).
    pub fn body(&self, name: &str) -> Option<ObjectId> {
        let own = self.bodies.iter().find(|(n, _)| n == name).map(|(_, id)| *id);
        own.or_else(|| self.welded.iter().find(|w| w.body == name).and_then(|w| w.object))
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

/// MuJoCo's time step when a model gives none (`<option timestep>`'s default), s.
pub const MUJOCO_TIMESTEP: f64 = 0.002;

/// An MJCF file as read: its model, not yet in a simulation. [`insert`](Self::insert)
/// makes its bodies, joints, actuators and sensors, as many times as asked.
///
/// ```
/// use ars_core::formats::mjcf::{MjcfFile, MjcfOptions};
/// use ars_core::Simulation;
///
/// let text = r#"<mujoco model="one"><worldbody><body name="ball" pos="0 0 1">
///   <freejoint/><geom type="sphere" size="0.1"/></body></worldbody></mujoco>"#;
/// let file = MjcfFile::parse(text, "one.xml", &MjcfOptions::new())?;
/// let (mut a, mut b) = (Simulation::new()?, Simulation::new()?);
/// let model = file.insert(&mut a, &MjcfOptions::new())?;
/// file.insert(&mut b, &MjcfOptions::new())?;
/// assert_eq!((model.name.as_str(), a.scene().objects().count()), ("one", b.scene().objects().count()));
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct MjcfFile {
    model: model::Model,
}

impl MjcfFile {
    /// Reads the MJCF model in `path` (and the files it includes and the meshes it
    /// names), as `options` say: what cannot be read is an error, or with
    /// [`MjcfOptions::skip_unsupported`] a line in [`skipped`](Self::skipped).
    pub fn read(path: impl AsRef<Path>, options: &MjcfOptions) -> Result<MjcfFile> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| Error::io("read the MJCF file", path, &e))?;
        Self::parse(&text, &path.display().to_string(), options)
    }

    /// Reads an MJCF model from its text (see [`read`](Self::read)); `file` names it in
    /// errors, and its folder is where included files and meshes are found.
    pub fn parse(text: &str, file: &str, options: &MjcfOptions) -> Result<MjcfFile> {
        Ok(MjcfFile { model: build::read_mjcf(text, file, options)? })
    }

    /// The model's name (`<mujoco model>`).
    pub fn name(&self) -> &str {
        &self.model.name
    }

    /// What reading skipped or adjusted, and why (what it could not read only when read
    /// with `skip_unsupported`).
    pub fn skipped(&self) -> &[String] {
        &self.model.skipped
    }

    /// The model's time step (`<option timestep>`), s, if it gives one (MuJoCo's
    /// default is [`MUJOCO_TIMESTEP`]).
    pub fn timestep(&self) -> Option<f64> {
        self.model.timestep
    }

    /// Makes the model in `sim` at `options.base_pose`, with its sensors
    /// ([`MjcfModel::sensors`]), sampled after every step; returns what was made. On an
    /// error nothing is left in the simulation. `options.skip_unsupported` plays no part
    /// here: it decides how the file is read ([`read`](Self::read)).
    pub fn insert(&self, sim: &mut Simulation, options: &MjcfOptions) -> Result<MjcfModel> {
        let made = sim.scene.insert_mjcf_model(&self.model, options)?;
        sim.make_mjcf_sensors(made)
    }
}

/// Loads MJCF models with their sensors.
impl Simulation {
    /// Loads the MJCF model in `path` (see the [module docs](self)) with its sensors
    /// ([`MjcfModel::sensors`]), sampled after every step: [`MjcfFile::read`], then
    /// [`MjcfFile::insert`].
    pub fn load_mjcf(&mut self, path: impl AsRef<Path>, options: &MjcfOptions) -> Result<MjcfModel> {
        MjcfFile::read(path, options)?.insert(self, options)
    }

    /// Loads an MJCF model from its text with its sensors (see
    /// [`load_mjcf`](Self::load_mjcf)); `file` names it in errors.
    pub fn load_mjcf_text(&mut self, text: &str, file: &str, options: &MjcfOptions) -> Result<MjcfModel> {
        MjcfFile::parse(text, file, options)?.insert(self, options)
    }
}

/// Moves MJCF models' mocap bodies.
impl Simulation {
    /// The mocap bodies of the MJCF models loaded, in the order loaded.
    pub fn mocap_bodies(&self) -> &[MjcfMocap] {
        &self.scene.mocap_bodies
    }

    /// Puts the mocap body `body` (its name in the file, with the model's prefix) at
    /// `position`, turned by `quaternion` (w, x, y, z), in the file's world frame: what
    /// MuJoCo's `data.mocap_pos` and `data.mocap_quat` hold. It stays there, still,
    /// until moved again. Errors: an unknown name, a non-finite number, a zero
    /// quaternion; nothing is moved then.
    pub fn set_mocap_pose(&mut self, body: &str, position: [f64; 3], quaternion: [f64; 4]) -> Result<()> {
        let mocap = self.mocap(body)?;
        let (object, pose) = (mocap.object, mocap.object_pose(position, quaternion)?);
        self.scene.set_pose(object, pose)
    }

    /// Where the mocap body `body` is: its position and quaternion (w, x, y, z) in the
    /// file's world frame.
    pub fn mocap_pose(&self, body: &str) -> Result<([f64; 3], [f64; 4])> {
        let mocap = self.mocap(body)?;
        Ok(mocap.body_pose(&self.scene.pose(mocap.object)?))
    }

    fn mocap(&self, body: &str) -> Result<&MjcfMocap> {
        self.scene.mocap_bodies.iter().find(|m| m.body == body).ok_or_else(|| Error::UnknownName {
            kind: "mocap body",
            name: body.to_string(),
            close_matches: crate::scene::names::close_matches(
                body,
                self.scene.mocap_bodies.iter().map(|m| m.body.as_str()),
            ),
        })
    }
}
