//! Saving a simulation's scene to a readable JSON file and loading it back.
//!
//! What is saved: the parameters (gravity, time step, steps per frame, ERP, CFM,
//! stepper, contact surface and the surfaces of pairs of objects, space), the clock, every object in creation order (name,
//! shape, colour, visuals, and for a body its mass, inertia, pose and velocities, to the
//! last bit), every joint (name, type, its objects, the anchors and axes it was created
//! with, its stops, speed motor, viscous and dry friction, spring, actuator limits and the
//! joint it mimics), the joints made through the world (hinge-2 joints, motors), and the
//! sensors ARS builds from a kind and what they read (GPS, velometer, accelerometer,
//! inclinometer, IMU, contact, energies, joint sensors, joint positions), lidars and
//! depth cameras with their settings, each with its period and its noise; the other
//! sensors (closures, lasers, your own types) are named in `unsaved_sensors`. Not saved: hooks and closure sensors (they are code), sensor
//! records, contact joints (they live within a step).
//!
//! With them, the file holds the exact state of a [`Snapshot`](crate::Snapshot)
//! (`state`, hexadecimal): a scene saved at any step loads into a simulation that steps
//! on bit for bit as the original, its joints made where they were made. The sensors the
//! file does not rebuild (named in `unsaved_sensors`) are left out of that state. When
//! the state cannot be captured (a joint controller of your own type), `state_not_saved`
//! says why, and the scene loads as before the state existed: exact if saved before the
//! first step; saved later, every body comes back to the bit and the joints are made
//! where their anchors and axes are then (universal and hinge-2 joints are then refused).

use nalgebra::{Isometry3, Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::joint::{JointBuilder, JointKind};
use crate::scene::GeomContact;
use crate::scene::{Color, JointType, Visual};
use crate::sensors::SensorSettings;
use crate::shape::Shape;
use crate::simulation::Simulation;
use crate::world::{SpaceKind, Stepper};

mod load;
mod save;

/// The format tag of a scene file.
const FORMAT: &str = "ars-scene/1";

/// A scene as saved (see the [module docs](self)).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SceneFile {
    /// `"ars-scene/1"`.
    pub format: String,
    /// Gravity, m/s².
    pub gravity: Vector3<f64>,
    /// Time step, s.
    pub time_step: f64,
    /// Steps per frame.
    pub steps_per_frame: u32,
    /// Global ERP.
    pub erp: f64,
    /// Global CFM.
    pub cfm: f64,
    /// The stepper.
    pub stepper: Stepper,
    /// The contact surface of every pair.
    pub surface: ContactSurface,
    /// The contact surfaces of pairs of objects (by name) that have their own.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pair_surfaces: Vec<PairSurfaceFile>,
    /// The pairs of objects (by name) that never touch.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub excluded_contacts: Vec<(String, String)>,
    /// The geoms with contact parameters of their own (MJCF's), by object name and
    /// index (see [`Scene::set_geom_contact`](crate::Scene::set_geom_contact)).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub geom_contacts: Vec<GeomContactFile>,
    /// The pairs of geoms with contact parameters of their own (MJCF's `<pair>`s; see
    /// [`Scene::set_geom_pair_contact`](crate::Scene::set_geom_pair_contact)).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub geom_pair_contacts: Vec<GeomPairContactFile>,
    /// The broad-phase space. A file that names none (written by hand, say) loads
    /// with [`SpaceKind::Simple`], the original's (and, before sweep and prune was the
    /// default, every simulation's).
    #[serde(default = "original_space")]
    pub space: SpaceKind,
    /// Simulated time, s.
    pub time: f64,
    /// Steps taken.
    pub step_count: u64,
    /// The objects, in creation order.
    pub objects: Vec<ObjectFile>,
    /// The joints, in creation order.
    pub joints: Vec<JointFile>,
    /// The joints made through the world rather than the scene (hinge-2 joints,
    /// angular and linear motors), in creation order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub world_joints: Vec<WorldJointFile>,
    /// The sensors ARS builds from a name and what they read, in the order added.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub sensors: Vec<SensorFile>,
    /// The other sensors (closures, noise wrappers, scanners, your own types): named
    /// here, not saved.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unsaved_sensors: Vec<String>,
    /// The exact state (see [`Snapshot`](crate::Snapshot)), as the hexadecimal digits
    /// of its bytes: with it, a scene saved at any step loads into a simulation that
    /// steps on to the bit as the original.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state: Option<String>,
    /// Why the exact state could not be saved (a controller of your own type), if so:
    /// the scene then loads as described above the state.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub state_not_saved: Option<String>,
}

/// A scene file is read into a [`SceneFile`], which [`build`](SceneFile::build) makes
/// into the simulation it describes (its settings, objects, joints, sensors and, when
/// saved exactly, its state): a whole simulation, not something added to one.
///
/// ```
/// use ars_core::formats::scene_file::SceneFile;
/// use ars_core::{Mass, Simulation};
///
/// let mut sim = Simulation::new()?;
/// sim.scene_mut().add_sphere(0.5, [0.0, 2.0, 0.0], Mass::Total(1.0))?;
/// let file = SceneFile::parse(&sim.save_scene()?, "ball.json")?;
/// let (a, b) = (file.build()?, file.build()?);
/// assert_eq!((a.scene().objects().count(), b.scene().objects().count()), (1, 1));
/// assert!(SceneFile::parse("{", "broken.json").is_err());
/// # Ok::<(), ars_core::Error>(())
/// ```
impl SceneFile {
    /// Reads the scene file at `path` (errors name it).
    pub fn read(path: impl AsRef<std::path::Path>) -> Result<SceneFile> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| Error::io("read the scene file", path, &e))?;
        SceneFile::parse(&text, &path.display().to_string())
    }

    /// Reads a scene file's JSON text; `file` names it in errors, with the line and
    /// column where the text stops being a scene.
    pub fn parse(text: &str, file: &str) -> Result<SceneFile> {
        serde_json::from_str(text).map_err(|e| {
            let message = e.to_string();
            let position = format!(" at line {} column {}", e.line(), e.column());
            let problem = message.strip_suffix(&position).unwrap_or(&message);
            Error::Format {
                format: "scene file",
                file: file.to_string(),
                element: String::new(),
                line: u32::try_from(e.line()).ok(),
                column: u32::try_from(e.column()).ok(),
                problem: format!("not a scene: {problem}"),
            }
        })
    }

    /// The simulation this file describes ([`Simulation::from_scene_file`]), as many
    /// times as asked.
    pub fn build(&self) -> Result<Simulation> {
        Simulation::from_scene_file(self)
    }
}

/// The space of a file that names none: the original's simple space.
fn original_space() -> SpaceKind {
    SpaceKind::Simple
}

/// A sensor as saved: its kind (`"Gps"`, `"JointPositions"`...), the objects or joints
/// it reads, by name, and its period (`None`: every step). Its records are not saved.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct SensorFile {
    /// The sensor's type.
    pub kind: String,
    /// The objects it reads.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub objects: Vec<String>,
    /// The joints it reads.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<String>,
    /// Seconds between samples (`None`: every step).
    pub period: Option<f64>,
    /// Gaussian noise on it ([`Noisy`](crate::sensors::Noisy)): standard deviation and
    /// the generator's state when saved.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub noise: Option<(f64, u64)>,
    /// A lidar's or depth camera's settings.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub settings: Option<SensorSettings>,
}

impl SensorFile {
    /// Adds the sensor to `sim` (its objects and joints looked up by name).
    fn add_to(&self, sim: &mut Simulation) -> Result<()> {
        let objects =
            self.objects.iter().map(|n| Ok(sim.scene().object(n.as_str())?.id())).collect::<Result<Vec<_>>>()?;
        let joints = self.joints.iter().map(|n| Ok(sim.scene().joint(n.as_str())?.id())).collect::<Result<Vec<_>>>()?;
        sim.add_sensor_described(self.kind.parse()?, &objects, &joints, self.period, self.noise, self.settings.as_ref())
            .map(drop)
    }
}

/// A geom's own contact parameters, by its object's name and its index there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeomContactFile {
    /// Its object.
    pub object: String,
    /// Its index among the object's geoms (0: the first).
    pub geom: usize,
    /// Its parameters.
    pub contact: GeomContact,
}

/// A pair of geoms' own contact parameters, each geom by its object's name and its
/// index there.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GeomPairContactFile {
    /// One geom: its object and index.
    pub a: (String, usize),
    /// The other.
    pub b: (String, usize),
    /// Their parameters.
    pub contact: GeomContact,
}

/// The contact surface of a pair of objects, by name.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairSurfaceFile {
    /// One object.
    pub a: String,
    /// The other.
    pub b: String,
    /// Their surface.
    pub surface: ContactSurface,
}

/// An object as saved.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ObjectFile {
    /// Its name.
    pub name: String,
    /// Its shape.
    pub shape: Shape,
    /// Its colour in the viewer.
    pub color: Option<Color>,
    /// Its body (`None`: static).
    pub body: Option<BodyFile>,
    /// The pose of a static object's geom.
    pub pose: Option<Isometry3<f64>>,
    /// What the viewer draws instead of its geom.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub visuals: Vec<Visual>,
    /// The shapes of its other geoms (a robot link's other collision elements); their
    /// offsets from the body are in the exact state.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub extra_shapes: Vec<Shape>,
    /// Whether it has a geom (it collides); a robot link without a collision shape has
    /// none, and its shape is what its mass was computed from.
    #[serde(default = "has_geom", skip_serializing_if = "is_true")]
    pub geom: bool,
}

/// An object of a file that does not say has a geom.
fn has_geom() -> bool {
    true
}

/// Whether a flag is set (a geom, as nearly every object has, is not written).
fn is_true(flag: &bool) -> bool {
    *flag
}

/// A body's mass and state, exactly.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BodyFile {
    /// Mass, kg.
    pub mass: f64,
    /// Inertia tensor in the body frame, kg·m².
    pub inertia: Matrix3<f64>,
    /// Position of the centre of mass, m.
    pub position: Point3<f64>,
    /// Rotation matrix (body to world).
    pub rotation: Rotation3<f64>,
    /// Orientation as ODE's quaternion (ODE keeps both).
    pub quaternion: UnitQuaternion<f64>,
    /// Linear velocity, m/s.
    pub linear_velocity: Vector3<f64>,
    /// Angular velocity, rad/s.
    pub angular_velocity: Vector3<f64>,
}

/// A joint as saved.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct JointFile {
    /// Its name.
    pub name: String,
    /// Its type.
    pub joint_type: JointType,
    /// The kind with the anchors and axes it was created with.
    pub kind: JointKind,
    /// The name of its first object.
    pub object1: String,
    /// The name of its second object (`None`: the world).
    pub object2: Option<String>,
    /// Its stops.
    pub limits: Option<(f64, f64)>,
    /// Viscous friction coefficient.
    pub friction: f64,
    /// Dry friction, N·m or N (0: none).
    #[serde(default)]
    pub dry_friction: f64,
    /// Its spring: stiffness (N·m/rad or N/m) and rest position (`None`: none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub spring: Option<(f64, f64)>,
    /// Effort limit of its actuator (`None`: unlimited).
    #[serde(default)]
    pub effort_limit: Option<f64>,
    /// Velocity limit of its actuator (`None`: unlimited).
    #[serde(default)]
    pub velocity_limit: Option<f64>,
    /// The joint it follows, if any.
    #[serde(default)]
    pub mimic: Option<MimicFile>,
    /// Its speed motor, when on: speed (rad/s or m/s) and largest force (N·m or N).
    #[serde(default)]
    pub motor: Option<(f64, f64)>,
    /// Its armature, kg·m² or kg (0: none; see
    /// [`SimJoint::set_armature`](crate::SimJoint::set_armature)).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub armature: f64,
    /// Its implicit damping, N·m·s/rad or N·s/m (0: none; see
    /// [`SimJoint::set_damping`](crate::SimJoint::set_damping)).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub damping: f64,
    /// On the first joint of a joint group (see
    /// [`Scene::add_joint_group`](crate::Scene::add_joint_group)): the group (the
    /// group's other joints are saved after it, each with its own settings).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<GroupFile>,
}

/// A joint group as saved: its joints' names in order and its geometry.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct GroupFile {
    /// Its joints, in order (slides first).
    pub joints: Vec<String>,
    /// Where its joints read 0.
    pub rest: crate::scene::GroupRest,
}

fn is_zero(value: &f64) -> bool {
    *value == 0.0
}

/// A joint made through the [`World`](crate::World) between objects' bodies, as saved.
/// Its parameters are in the exact state.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct WorldJointFile {
    /// Its kind, with the anchors and axes it was made with.
    pub kind: JointKind,
    /// The object whose body is its first body.
    pub object1: String,
    /// The object whose body is its second (`None`: the world).
    pub object2: Option<String>,
    /// How many of the scene's joints were made before it.
    pub after: usize,
}

impl WorldJointFile {
    /// Makes the joint in `sim`.
    fn add_to(&self, sim: &mut Simulation) -> Result<()> {
        let body = |name: &str| -> Result<crate::BodyHandle> {
            let object = sim.scene().object(name)?;
            object.body_handle().ok_or_else(|| Error::NoBody { operation: "a joint", object: name.to_string() })
        };
        let builder = JointBuilder::new(self.kind.clone());
        let builder = match &self.object2 {
            Some(o) => builder.between(body(&self.object1)?, body(o)?),
            None => builder.to_world(body(&self.object1)?),
        };
        sim.scene_mut().world_mut().insert_joint(builder).map(drop)
    }
}

/// A mimic joint's leader, by name, and its coefficients.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MimicFile {
    /// The name of the joint followed.
    pub leader: String,
    /// Follower position per leader position.
    pub multiplier: f64,
    /// Follower position when the leader is at 0.
    pub offset: f64,
}

/// Lower-case hexadecimal digits of `bytes`.
fn to_hex(bytes: &[u8]) -> String {
    bytes.iter().map(|b| format!("{b:02x}")).collect()
}

/// The bytes of hexadecimal digits, if they are.
fn from_hex(text: &str) -> Option<Vec<u8>> {
    if !text.len().is_multiple_of(2) {
        return None;
    }
    (0..text.len()).step_by(2).map(|i| u8::from_str_radix(text.get(i..i + 2)?, 16).ok()).collect()
}
