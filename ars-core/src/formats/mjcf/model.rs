//! The model as read from the file, before anything is built: bodies, geoms, joints,
//! sites.

use nalgebra::{Isometry3, Matrix3, UnitQuaternion, Vector3};

use super::problem::Problem;
use super::{MjcfActuator, MjcfSensor};
use crate::sensors::TouchZone;
use crate::shape::MeshMass;
use crate::shape::Shape;

/// A geom's shape, MuJoCo's way (half sizes).
#[derive(Clone, Debug)]
pub(super) enum GeomKind {
    Mesh(std::sync::Arc<MeshGeom>),
    /// A height field: static, made as the triangle mesh of its grid.
    Hfield(std::sync::Arc<super::hfield::Hfield>),
    Plane,
    Sphere(f64),
    Capsule(f64, f64),
    Cylinder(f64, f64),
    Box(Vector3<f64>),
    Ellipsoid(Vector3<f64>),
}

/// A mesh asset as a geom uses it: its triangles (scaled), what it collides as (their
/// convex hull, as in MuJoCo) and its mass properties (MuJoCo's: see
/// [`mujoco_mass_properties`](crate::mesh_mass::mujoco_mass_properties)).
#[derive(Debug)]
pub(super) struct MeshGeom {
    /// The triangles, as drawn.
    pub(super) shape: Shape,
    /// Their convex hull, as collided; `None` when they are flat (MuJoCo builds no hull
    /// for a mesh no geom collides with, and refuses a flat one that does).
    pub(super) hull: Option<Shape>,
    pub(super) mass: MeshMass,
}

#[derive(Clone, Debug)]
pub(super) struct Geom {
    pub(super) kind: GeomKind,
    /// Relative to its body.
    pub(super) frame: Isometry3<f64>,
    pub(super) mass: Option<f64>,
    pub(super) density: f64,
    pub(super) rgba: Option<[f64; 4]>,
    /// `contype` and `conaffinity`: ODE's category and collide bits, the same rule.
    pub(super) bits: (u64, u64),
    /// `friction`, `condim`, `solref`, `solimp`, `priority`, `solmix`.
    pub(super) contact: crate::scene::GeomContact,
    /// Its name, for `<contact><pair>`.
    pub(super) name: Option<String>,
}

#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) enum JointKind {
    Hinge,
    Slide,
    Ball,
    Free,
}

#[derive(Clone, Debug)]
pub(super) struct Joint {
    pub(super) name: String,
    pub(super) kind: JointKind,
    /// Anchor and axis in the body's frame.
    pub(super) pos: Vector3<f64>,
    pub(super) axis: Vector3<f64>,
    pub(super) range: Option<(f64, f64)>,
    pub(super) damping: f64,
    pub(super) armature: f64,
    /// `ref`: its position in the pose the file gives (MuJoCo's `qpos0`).
    pub(super) reference: f64,
    /// `stiffness` and `springref`: a spring.
    pub(super) spring: (f64, f64),
    /// `frictionloss`: dry friction.
    pub(super) frictionloss: f64,
    /// `solreflimit` and `solimplimit`'s `dmax`: how soft its stops are.
    pub(super) limit_softness: ([f64; 2], f64),
}

impl Joint {
    /// The ERP of its stops at time step `h` ([`reference_erp`] of `solreflimit` and
    /// `solimplimit`'s `dmax`). With MuJoCo's defaults (0.02 s, 1, dmax 0.95) and h =
    /// 3 ms: 0.073, where ODE's world ERP (0.2) threw the humanoid's knees, which start
    /// 2° outside their range, back at 2.3 rad/s.
    pub(super) fn stop_erp(&self, h: f64) -> Option<f64> {
        let (solref, dmax) = self.limit_softness;
        reference_erp(solref, dmax, h)
    }
}

/// MuJoCo's reference acceleration of a soft constraint, `−b·v − k·r` (`solref`
/// `(timeconst, dampratio)`: `b = 2 / (dmax·timeconst)`, `k = 1 / (dmax²·timeconst²·
/// dampratio²)`; negative: `(−stiffness, −damping)`, `k = stiffness / dmax²`, `b =
/// damping / dmax`), as ODE's spring at time step `h`: the ERP `h·k / (h·k + b)`, with
/// which ODE's hard constraint lags a moving target as MuJoCo's does (`b / k` per m/s).
/// `None` when the numbers make no spring (then the world's ERP).
pub(super) fn reference_erp(solref: [f64; 2], dmax: f64, h: f64) -> Option<f64> {
    let [s0, s1] = solref;
    let dmax = dmax.clamp(1e-4, 1.0 - 1e-4);
    let (k, b) = if s0 > 0.0 && s1 > 0.0 {
        (1.0 / (dmax * dmax * s0 * s0 * s1 * s1), 2.0 / (dmax * s0))
    } else if s0 < 0.0 && s1 <= 0.0 {
        (-s0 / (dmax * dmax), -s1 / dmax)
    } else {
        return None;
    };
    let erp = h * k / (h * k + b);
    (erp.is_finite() && erp > 0.0).then_some(erp.min(1.0))
}

#[derive(Clone, Debug)]
pub(super) struct Body {
    pub(super) name: String,
    /// Relative to its parent.
    pub(super) frame: Isometry3<f64>,
    /// Mass, centre of mass in the body's frame, inertia about it in the body's frame.
    pub(super) mass: Option<(f64, Vector3<f64>, Matrix3<f64>)>,
    pub(super) geoms: Vec<Geom>,
    pub(super) joints: Vec<Joint>,
    pub(super) children: Vec<Body>,
    /// Its named sites.
    pub(super) sites: Vec<Site>,
    /// The turn of its inertial frame from its frame, when its `<inertial>` gives it
    /// (`diaginertia`, used for its mass).
    pub(super) principal: Option<UnitQuaternion<f64>>,
    /// `mocap="true"`: a jointless child of the world that the user moves
    /// ([`Simulation::set_mocap_pose`](crate::Simulation::set_mocap_pose)); a kinematic body.
    pub(super) mocap: bool,
}

impl Body {
    /// Its centre of mass in its frame (its origin when it weighs nothing): where its
    /// object's frame is.
    pub(super) fn centre_of_mass(&self) -> Vector3<f64> {
        self.mass.map_or(Vector3::zeros(), |(_, com, _)| com)
    }
}

/// A named `<site>`.
#[derive(Clone, Debug)]
pub(super) struct Site {
    pub(super) name: String,
    /// Relative to its body.
    pub(super) frame: Isometry3<f64>,
    pub(super) zone: TouchZone,
    /// The massless body it was read in, when that body was welded into the one that
    /// holds it now (see [`Welded`]).
    pub(super) welded_from: Option<String>,
}

/// A jointless body merged into the body it is welded to (or into the world), as
/// MuJoCo welds it: its geoms, sites and children went there (see
/// [`weld_jointless`](super::weld::weld_jointless)).
#[derive(Clone, Debug)]
pub(super) struct Welded {
    pub(super) name: String,
    /// The body that holds its geoms now; `None`: the world (its geoms are static).
    pub(super) into: Option<String>,
    /// Its frame relative to `into`'s (or to the model's world frame).
    pub(super) frame: Isometry3<f64>,
    /// Its own mass (in its frame), when it had one (merged into a massless moving body).
    pub(super) mass: Option<(f64, Vector3<f64>, Matrix3<f64>)>,
    /// Its `<inertial>`'s turn, as [`Body::principal`].
    pub(super) principal: Option<UnitQuaternion<f64>>,
}

/// A `<contact><pair>`: two geoms by name, and the parameters their contacts take (its
/// own, MuJoCo's defaults where it gives none: not the geoms').
#[derive(Clone, Debug)]
pub(super) struct Pair {
    pub(super) geom1: String,
    pub(super) geom2: String,
    pub(super) contact: crate::scene::GeomContact,
}

/// Everything read from the file before anything is built.
#[derive(Clone, Debug, Default)]
pub(super) struct Model {
    pub(super) name: String,
    pub(super) world_geoms: Vec<Geom>,
    pub(super) bodies: Vec<Body>,
    pub(super) timestep: Option<f64>,
    pub(super) gravity: Option<Vector3<f64>>,
    /// `<option magnetic>` (MuJoCo's default if not given), in the file's frame.
    pub(super) magnetic: Vector3<f64>,
    pub(super) actuators: Vec<MjcfActuator>,
    /// `<contact><exclude>`: pairs of bodies, by name, that never touch.
    pub(super) excluded: Vec<(String, String)>,
    /// `<contact><pair>`: pairs of geoms, by name, that touch whatever their bits say,
    /// with their own contact parameters.
    pub(super) pairs: Vec<Pair>,
    pub(super) sensors: Vec<MjcfSensor>,
    /// Where each sensor is in the file (for errors found once the whole file is read).
    pub(super) sensor_places: Vec<Problem>,
    /// The sites of the world body (and of the bodies welded into it), by name.
    pub(super) world_sites: Vec<String>,
    /// The jointless bodies merged into others, in the file's order.
    pub(super) welded: Vec<Welded>,
    /// `<equality>`: its `connect`, `weld` and `joint` elements, in the file's order.
    pub(super) equalities: Vec<Equality>,
    /// `<keyframe>`'s keys, read and kept (not applied, as MuJoCo applies none).
    pub(super) keyframes: Vec<super::keyframe::MjcfKeyframe>,
    pub(super) skipped: Vec<String>,
}

/// Where an end of a `connect` or `weld` is: a body (or `world`), or a site.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Place {
    Body(String),
    Site(String),
}

#[derive(Clone, Debug, PartialEq)]
pub(super) enum EqualityKind {
    /// A shared point: `anchor` in `first`'s frame (unused for sites: site1's origin).
    Connect { first: Place, second: Option<Place>, anchor: Vector3<f64> },
    /// A kept relative pose; `relpose`: the pose of `second` in `first`'s frame, when
    /// the file gives one.
    Weld { first: Place, second: Option<Place>, relpose: Option<Isometry3<f64>> },
    /// `follower − ref = polycoef[0] + polycoef[1]·(leader − ref) + …`.
    Joint { follower: String, leader: Option<String>, polycoef: [f64; 5] },
}

/// An `<equality>` element as read.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Equality {
    pub(super) name: Option<String>,
    pub(super) kind: EqualityKind,
    /// `solref`, and `solimp`'s `dmin` and `dmax` (MuJoCo's defaults 0.02 s, 1, and
    /// 0.9, 0.95, when not given).
    pub(super) softness: ([f64; 2], [f64; 2]),
    /// Its tag and line, for what is said about it.
    pub(super) tag: String,
    pub(super) line: u32,
}
