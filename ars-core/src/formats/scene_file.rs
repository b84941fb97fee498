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

use crate::body::{BodyBuilder, MassSpec};
use crate::contact::ContactSurface;
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{ObjectId, SpaceHandle};
use crate::joint::{JointBuilder, JointKind, JointParam};
use crate::scene::joints::JointData;
use crate::scene::{ActuatorLimits, Color, JointEnd, JointType, Visual};
use crate::sensors::SensorKind;
use crate::sensors::SensorSettings;
use crate::shape::Shape;
use crate::simulation::{Simulation, SimulationBuilder};
use crate::world::{SpaceKind, Stepper};

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

impl Simulation {
    /// The scene as a [`SceneFile`] (see the [`scene_file`](crate::formats::scene_file)
    /// module), with its exact state when it can be saved (otherwise `state_not_saved`
    /// says why).
    pub fn scene_file(&self) -> Result<SceneFile> {
        match self.capture_state() {
            Ok(state) => {
                let mut file = self.scene_structure(true)?;
                file.state = Some(to_hex(&crate::simulation::scene_state::encode(&state)));
                Ok(file)
            }
            Err(Error::NotCapturable { what }) => {
                let mut file = self.scene_structure(false)?;
                file.state_not_saved = Some(what);
                Ok(file)
            }
            Err(e) => Err(e),
        }
    }

    /// The scene without its exact state: with `exact`, the joints as they were made
    /// (the state remakes them where they were made); without, where they stand after
    /// the first step.
    pub(crate) fn scene_structure(&self, exact: bool) -> Result<SceneFile> {
        let world = self.scene.world();
        let objects = self.object_files()?;
        let joints = self.joint_files(exact)?;
        let world_joints = self.world_joint_files()?;
        let (sensors, unsaved_sensors) = self.sensor_files()?;
        Ok(SceneFile {
            format: FORMAT.into(),
            sensors,
            unsaved_sensors,
            state: None,
            state_not_saved: None,
            gravity: world.gravity(),
            time_step: self.scene.time_step(),
            steps_per_frame: self.scene.steps_per_frame(),
            erp: world.erp(),
            cfm: world.cfm(),
            stepper: world.stepper(),
            surface: world.default_surface(),
            pair_surfaces: self
                .scene()
                .contact_surfaces()
                .into_iter()
                .map(|(a, b, surface)| {
                    Ok(PairSurfaceFile {
                        a: self.scene.object(a)?.name().into(),
                        b: self.scene.object(b)?.name().into(),
                        surface,
                    })
                })
                .collect::<Result<_>>()?,
            excluded_contacts: self
                .scene()
                .excluded_contacts()
                .into_iter()
                .map(|(a, b)| Ok((self.scene.object(a)?.name().to_string(), self.scene.object(b)?.name().to_string())))
                .collect::<Result<_>>()?,
            space: self.scene.space_kind(),
            time: self.scene.time(),
            step_count: self.scene.step_count(),
            objects,
            joints,
            world_joints,
        })
    }

    /// Every object as saved, in creation order.
    fn object_files(&self) -> Result<Vec<ObjectFile>> {
        let world = self.scene.world();
        let mut objects = Vec::new();
        for (_, data) in self.scene.objects_in_creation_order() {
            let body = match data.body {
                Some(b) => {
                    let b = world.body(b)?;
                    Some(BodyFile {
                        mass: b.mass(),
                        inertia: b.inertia(),
                        position: b.position(),
                        rotation: b.rotation(),
                        quaternion: b.quaternion(),
                        linear_velocity: b.linear_velocity(),
                        angular_velocity: b.angular_velocity(),
                    })
                }
                None => None,
            };
            let pose = match (&data.body, data.geom, &data.shape) {
                (None, Some(g), shape) if !matches!(shape, Shape::Plane { .. }) => Some(world.geom(g)?.pose()),
                _ => None,
            };
            objects.push(ObjectFile {
                name: data.name.clone(),
                shape: data.shape.clone(),
                color: data.color,
                body,
                pose,
                visuals: data.visuals.clone(),
                extra_shapes: data
                    .extra_geoms
                    .iter()
                    .map(|g| Ok(world.geoms.get(g.0, "geom")?.shape.clone()))
                    .collect::<Result<_>>()?,
                geom: data.geom.is_some(),
            });
        }
        Ok(objects)
    }

    /// Every joint of the scene as saved, in the order ODE made them (with `exact`, each
    /// as it was made).
    fn joint_files(&self, exact: bool) -> Result<Vec<JointFile>> {
        let world = self.scene.world();
        let mut joints = Vec::new();
        let serial = |h: crate::JointHandle| world.joints.get(h.0, "joint").map_or(u64::MAX, |j| j.serial);
        let mut scene_joints: Vec<_> = self.scene.joints_in_creation_order().collect();
        scene_joints.sort_by_key(|d| serial(d.handle));
        for data in scene_joints {
            let name_of = |o| self.scene.object(o).map(|v| v.name().to_string());
            let kind = self.saved_joint_kind(data, exact)?;
            let motor = self.saved_motor(data)?;
            joints.push(JointFile {
                name: data.name.clone(),
                joint_type: data.kind,
                kind,
                object1: name_of(data.object1)?,
                object2: data.object2.map(name_of).transpose()?,
                limits: data.limits,
                friction: data.friction,
                dry_friction: data.dry_friction,
                spring: (data.spring.0 != 0.0).then_some(data.spring),
                effort_limit: Some(data.actuator.effort).filter(|e| e.is_finite()),
                velocity_limit: Some(data.actuator.velocity).filter(|v| v.is_finite()),
                mimic: data
                    .mimic
                    .map(|m| -> Result<MimicFile> {
                        let leader = self.scene.joint(m.leader)?.name().to_string();
                        Ok(MimicFile { leader, multiplier: m.multiplier, offset: m.offset })
                    })
                    .transpose()?,
                motor,
            });
        }
        Ok(joints)
    }

    /// The kind a joint is saved as, with its anchors and axes. Before any step (or
    /// with `exact`), the joint as it was created (the same ODE calls again); after,
    /// where its anchor and axis are now.
    fn saved_joint_kind(&self, data: &JointData, exact: bool) -> Result<JointKind> {
        if self.scene.step_count() == 0 || exact {
            return Ok(data.creation.clone());
        }
        let ode = self.scene.world().joint(data.handle)?;
        Ok(match &data.creation {
            JointKind::Fixed => JointKind::Fixed,
            JointKind::Hinge { .. } => JointKind::Hinge { anchor: ode.anchor()?, axis: ode.axis()? },
            JointKind::Slider { .. } => JointKind::Slider { axis: ode.axis()? },
            JointKind::Ball { .. } => JointKind::Ball { anchor: ode.anchor()? },
            JointKind::Piston { .. } => JointKind::Piston { anchor: ode.anchor()?, axis: ode.axis()? },
            other => {
                return Err(Error::Invalid {
                    what: "the scene",
                    problem: format!(
                        "cannot be saved: joint {:?} is {} joint, which can be saved only before the scene steps",
                        data.name,
                        crate::error::article(other.name())
                    ),
                });
            }
        })
    }

    /// A joint's speed motor, when on: its speed and largest force.
    fn saved_motor(&self, data: &JointData) -> Result<Option<(f64, f64)>> {
        let world = self.scene.world();
        Ok(match data.kind {
            JointType::Fixed | JointType::Ball => None,
            _ => {
                let ode = world.joint(data.handle)?;
                let max_force = ode.param(JointParam::MaxForce, 0)?;
                (max_force > 0.0).then_some((ode.param(JointParam::Velocity, 0)?, max_force))
            }
        })
    }

    /// The sensors ARS rebuilds from a kind, as saved, and the kinds of the others (not
    /// saved).
    fn sensor_files(&self) -> Result<(Vec<SensorFile>, Vec<String>)> {
        let (mut sensors, mut unsaved_sensors) = (Vec::new(), Vec::new());
        for d in self.sensors.descriptions() {
            let Some(kind) = SensorKind::of_type_name(&d.kind) else {
                unsaved_sensors.push(d.kind);
                continue;
            };
            let objects =
                d.objects.iter().map(|o| Ok(self.scene.object(*o)?.name().to_string())).collect::<Result<_>>()?;
            let joints =
                d.joints.iter().map(|j| Ok(self.scene.joint(*j)?.name().to_string())).collect::<Result<_>>()?;
            sensors.push(SensorFile {
                kind: kind.to_string(),
                objects,
                joints,
                period: d.period,
                noise: d.noise,
                settings: d.settings,
            });
        }
        Ok((sensors, unsaved_sensors))
    }

    /// The joints made through the world (hinge-2 joints, motors...), not the scene.
    fn world_joint_files(&self) -> Result<Vec<WorldJointFile>> {
        let world = self.scene.world();
        let scene_handles: Vec<crate::JointHandle> = self.scene.joints_in_creation_order().map(|d| d.handle).collect();
        let mut scene_serials: Vec<u64> =
            scene_handles.iter().filter_map(|h| world.joints.get(h.0, "joint").ok().map(|j| j.serial)).collect();
        scene_serials.sort_unstable();
        let mut others: Vec<_> =
            world.joints.iter().filter(|(h, _)| !scene_handles.contains(&crate::JointHandle(*h))).collect();
        others.sort_by_key(|(_, j)| j.serial);
        let object_of = |body: crate::BodyHandle| -> Result<String> {
            self.scene
                .objects_in_creation_order()
                .find(|(_, d)| d.body == Some(body))
                .map(|(_, d)| d.name.clone())
                .ok_or_else(|| Error::Invalid {
                    what: "the scene",
                    problem: "cannot be saved: a joint made through the world joins a body that is not an object"
                        .into(),
                })
        };
        others
            .into_iter()
            .map(|(_, j)| {
                Ok(WorldJointFile {
                    kind: j.kind.clone(),
                    object1: object_of(j.body1.expect("a joint has a first body"))?,
                    object2: j.body2.map(object_of).transpose()?,
                    after: scene_serials.iter().filter(|s| **s < j.serial).count(),
                })
            })
            .collect()
    }

    /// The scene as JSON text (see the [`scene_file`](crate::formats::scene_file) module).
    pub fn save_scene(&self) -> Result<String> {
        serde_json::to_string_pretty(&self.scene_file()?)
            .map_err(|e| Error::Invalid { what: "the scene", problem: format!("cannot be written as JSON: {e}") })
    }

    /// A simulation built from JSON text written by [`save_scene`](Self::save_scene).
    pub fn load_scene(text: &str) -> Result<Simulation> {
        Simulation::load_scene_named(text, "<string>")
    }

    /// [`load_scene`](Self::load_scene) of the text of `file` (named in errors):
    /// [`SceneFile::parse`], then [`SceneFile::build`].
    fn load_scene_named(text: &str, file: &str) -> Result<Simulation> {
        Simulation::built_as(&SceneFile::parse(text, file)?, file)
    }

    /// [`SceneFile::build`], its errors naming the file `file`.
    fn built_as(scene: &SceneFile, file: &str) -> Result<Simulation> {
        scene.build().map_err(|e| match e {
            Error::Format { format: "scene file", element, line, column, problem, .. } => {
                Error::Format { format: "scene file", file: file.to_string(), element, line, column, problem }
            }
            other => other,
        })
    }

    /// A simulation built from a [`SceneFile`].
    pub fn from_scene_file(file: &SceneFile) -> Result<Simulation> {
        if file.format != FORMAT {
            return Err(Error::Format {
                format: "scene file",
                file: "<string>".into(),
                element: "\"format\"".into(),
                line: None,
                column: None,
                problem: format!("is {:?}, expected {FORMAT:?}", file.format),
            });
        }
        let mut sim = SimulationBuilder::default()
            .gravity(file.gravity)
            .time_step(file.time_step)
            .steps_per_frame(file.steps_per_frame)
            .erp(file.erp)
            .cfm(file.cfm)
            .stepper(file.stepper)
            .contact_surface(file.surface)
            .space(file.space)
            .build()?;
        let space = sim.scene().space();
        for o in &file.objects {
            o.add_to(&mut sim, space)?;
        }
        for (i, j) in file.joints.iter().enumerate() {
            for w in file.world_joints.iter().filter(|w| w.after == i) {
                w.add_to(&mut sim)?;
            }
            j.add_to(&mut sim)?;
        }
        for w in file.world_joints.iter().filter(|w| w.after >= file.joints.len()) {
            w.add_to(&mut sim)?;
        }
        // Leaders may come later in creation order than their followers.
        for j in &file.joints {
            if let Some(m) = &j.mimic {
                sim.scene_mut().joint_mut(j.name.as_str())?.set_mimic(m.leader.as_str(), m.multiplier, m.offset)?;
            }
        }
        sim.scene.set_clock(file.time, file.step_count);
        // After the clock: periodic sensors count their periods from the saved time.
        for pair in &file.pair_surfaces {
            let (a, b) = (sim.scene().object(pair.a.as_str())?.id(), sim.scene().object(pair.b.as_str())?.id());
            sim.scene_mut().set_contact_surface(a, b, pair.surface)?;
        }
        for (a, b) in &file.excluded_contacts {
            let (a, b) = (sim.scene().object(a.as_str())?.id(), sim.scene().object(b.as_str())?.id());
            sim.scene_mut().exclude_contacts(a, b)?;
        }
        for sensor in &file.sensors {
            sensor.add_to(&mut sim)?;
        }
        if let Some(hex) = &file.state {
            sim.restore_saved_state(hex)?;
        }
        Ok(sim)
    }

    /// Restores the exact state a scene file holds (`hex`, hexadecimal digits), but
    /// that of the sensors it does not rebuild.
    fn restore_saved_state(&mut self, hex: &str) -> Result<()> {
        let corrupt = |problem: String| Error::Format {
            format: "scene file",
            file: "<string>".into(),
            element: "\"state\"".into(),
            line: None,
            column: None,
            problem,
        };
        let bytes = from_hex(hex).ok_or_else(|| corrupt("is not hexadecimal digits".into()))?;
        let mut state: crate::simulation::scene_state::SceneState =
            crate::simulation::scene_state::decode(&bytes).map_err(|e| corrupt(e.to_string()))?;
        // The sensors a scene file does not rebuild (named in `unsaved_sensors`) have
        // no place for their state.
        state.keep_sensors(|kind| SensorKind::of_type_name(kind).is_some());
        self.restore_state(&state)
    }
}

impl ObjectFile {
    /// Makes the object in `sim`, its geoms in `space`, with its colour and visuals.
    fn add_to(&self, sim: &mut Simulation, space: SpaceHandle) -> Result<()> {
        let id = match &self.body {
            Some(b) => self.add_body_to(sim, b, space)?,
            None => self.add_static_to(sim, space)?,
        };
        if let Some(c) = self.color {
            sim.scene_mut().set_color(id, c)?;
        }
        if !self.visuals.is_empty() {
            sim.scene_mut().set_visuals(id, self.visuals.clone())?;
        }
        Ok(())
    }

    /// Makes the object with its body `b` (restored to the bit) and its geoms.
    fn add_body_to(&self, sim: &mut Simulation, b: &BodyFile, space: SpaceHandle) -> Result<ObjectId> {
        let geom = GeomBuilder::new(self.shape.clone());
        let spec = MassSpec::Custom { mass: b.mass, inertia: b.inertia };
        let body = sim.scene.world.insert_body(BodyBuilder::new().mass(spec).position(b.position))?;
        let g = if self.geom { Some(sim.scene.world.insert_geom(space, geom.attached_to(body))?) } else { None };
        {
            let mut m = sim.scene.world.body_mut(body)?;
            // Both ODE's quaternion and its rotation matrix, to the bit.
            m.restore_orientation(&b.quaternion, &b.rotation)?;
            m.set_linear_velocity(b.linear_velocity)?;
            m.set_angular_velocity(b.angular_velocity)?;
        }
        let id = sim.scene.register_object(&self.name, self.shape.clone(), Some(body), g)?;
        let extra = self
            .extra_shapes
            .iter()
            .map(|shape| sim.scene.world.insert_geom(space, GeomBuilder::new(shape.clone()).attached_to(body)))
            .collect::<Result<Vec<_>>>()?;
        sim.scene.set_extra_geoms(id, extra)?;
        Ok(id)
    }

    /// Makes the static object: its geom at its pose (a plane's is in its shape) and
    /// its other geoms.
    fn add_static_to(&self, sim: &mut Simulation, space: SpaceHandle) -> Result<ObjectId> {
        let geom = GeomBuilder::new(self.shape.clone());
        let geom = match (&self.shape, self.pose) {
            (Shape::Plane { .. }, _) | (_, None) => geom,
            (_, Some(pose)) => geom.pose(pose),
        };
        let g = sim.scene.world.insert_geom(space, geom)?;
        let id = sim.scene.register_object(&self.name, self.shape.clone(), None, Some(g))?;
        let extra = self
            .extra_shapes
            .iter()
            .map(|shape| sim.scene.world.insert_geom(space, GeomBuilder::new(shape.clone())))
            .collect::<Result<Vec<_>>>()?;
        sim.scene.set_extra_geoms(id, extra)?;
        Ok(id)
    }
}

impl JointFile {
    /// Makes the joint in `sim` (its objects looked up by name) with its stops,
    /// friction, actuator limits, spring and motor; not its mimic (its leader may be
    /// made later).
    fn add_to(&self, sim: &mut Simulation) -> Result<()> {
        let object1 = sim.scene().object(self.object1.as_str())?.id();
        let object2 = match &self.object2 {
            Some(name) => JointEnd::Object(sim.scene().object(name.as_str())?.id()),
            None => JointEnd::World,
        };
        let id = sim.scene.insert_sim_joint(
            &self.name,
            self.joint_type,
            object1,
            object2,
            JointBuilder::new(self.kind.clone()),
        )?;
        if let Some((low, high)) = self.limits {
            sim.scene_mut().joint_mut(id)?.set_limits(low, high)?;
        }
        let mut joint = sim.scene_mut().joint_mut(id)?;
        if self.friction != 0.0 {
            joint.set_viscous_friction(self.friction)?;
        }
        if self.effort_limit.is_some() || self.velocity_limit.is_some() {
            let unlimited = f64::INFINITY;
            joint.set_actuator_limits(ActuatorLimits {
                effort: self.effort_limit.unwrap_or(unlimited),
                velocity: self.velocity_limit.unwrap_or(unlimited),
            })?;
        }
        if self.dry_friction != 0.0 {
            joint.set_dry_friction(self.dry_friction)?;
        }
        if let Some((stiffness, rest)) = self.spring {
            joint.set_spring(stiffness, rest)?;
        }
        if let Some((speed, max_force)) = self.motor {
            // As it was, whatever the limits (the speed was held to them when set).
            let handle = sim.scene.joint_data(id)?.handle;
            sim.scene.world.joint_mut(handle)?.set_motor(0, speed, max_force)?;
        }
        Ok(())
    }
}

/// Reads and writes scene files at paths.
impl Simulation {
    /// Saves the scene as JSON to `path`.
    pub fn save_scene_to(&self, path: impl AsRef<std::path::Path>) -> Result<()> {
        let path = path.as_ref();
        std::fs::write(path, self.save_scene()?).map_err(|e| Error::io("write the scene file", path, &e))
    }

    /// Loads a scene saved with [`save_scene_to`](Self::save_scene_to).
    pub fn load_scene_from(path: impl AsRef<std::path::Path>) -> Result<Simulation> {
        let path = path.as_ref();
        Simulation::built_as(&SceneFile::read(path)?, &path.display().to_string())
    }
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
