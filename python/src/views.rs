//! Named access: `sim.body("arm")` and `sim.joint("r1")`. Every attribute is read when
//! asked and returned as a copy (numpy arrays the caller owns), never a live view.

use ars_core::nalgebra::{Isometry3, Matrix3, Point3, Rotation3, Translation3, UnitQuaternion, Vector3};
use std::sync::{Mutex, PoisonError};

use ars_core::{JointId, ObjectId, Simulation};
use numpy::{PyArray1, PyArray2};
use pyo3::prelude::*;

use crate::errors::Checked;
use crate::simulation::{PySimulation, Vec3};

/// A set-point: a constant, or `(time, value)` breakpoints (a breakpoint that is not
/// a pair is an `ars.InputError`).
pub(crate) enum Setpoint {
    Constant(f64),
    Points(Vec<(f64, f64)>),
}

impl<'py> FromPyObject<'_, 'py> for Setpoint {
    type Error = PyErr;

    fn extract(obj: pyo3::Borrowed<'_, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(value) = obj.extract::<f64>() {
            return Ok(Setpoint::Constant(value));
        }
        obj.extract::<Checked<Vec<(f64, f64)>>>().map(|points| Setpoint::Points(points.0))
    }
}

/// An object of a simulation, by name.
#[pyclass(module = "ars", frozen)]
pub struct Body {
    sim: Py<PySimulation>,
    name: String,
    /// The id its name had when last looked up (see [`by_name`]).
    id: Mutex<Option<ObjectId>>,
}

impl Body {
    pub(crate) fn new(sim: Py<PySimulation>, name: String) -> Self {
        Body { sim, name, id: Mutex::default() }
    }

    fn read<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation, ObjectId) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
        let (name, cached) = (self.name.as_str(), &self.id);
        self.sim.get().with(py, |sim| {
            let id = by_name(
                cached,
                |id| sim.scene().object(id).is_ok_and(|o| o.name() == name),
                || Ok(sim.scene().object(name)?.id()),
            )?;
            f(sim, id)
        })
    }
}

/// The id a view's name has now: the `cached` one while it still has it
/// (`still_named`: alive, with that name; a name removed and made again is another
/// object), else `look_up`'s, then kept. A program reads its bodies and joints every step, and checking an id is
/// cheaper than finding a name.
fn by_name<Id: Copy>(
    cached: &Mutex<Option<Id>>,
    still_named: impl FnOnce(Id) -> bool,
    look_up: impl FnOnce() -> ars_core::Result<Id>,
) -> ars_core::Result<Id> {
    let mut cached = cached.lock().unwrap_or_else(PoisonError::into_inner);
    if let Some(id) = *cached
        && still_named(id)
    {
        return Ok(id);
    }
    let id = look_up()?;
    *cached = Some(id);
    Ok(id)
}

/// A rotation from a 3×3 matrix given in Python: refused unless it is one, so that
/// ODE never gets a shear ([`ars_core::limits::rotation_matrix`]).
pub(crate) fn rotation(m: [[f64; 3]; 3]) -> ars_core::Result<Rotation3<f64>> {
    ars_core::limits::rotation_matrix("rotation", Matrix3::from_fn(|i, j| m[i][j]))
}

/// A pose from a position and an optional 3×3 rotation (identity when `None`).
pub(crate) fn pose(position: Vec3, rot: Option<Checked<[[f64; 3]; 3]>>) -> ars_core::Result<Isometry3<f64>> {
    let r = rot.map(|r| rotation(r.0)).transpose()?.unwrap_or_else(Rotation3::identity);
    Ok(Isometry3::from_parts(Translation3::from(Vector3::from(position)), UnitQuaternion::from_rotation_matrix(&r)))
}

/// Three numbers as a Python tuple.
type Tuple3 = (f64, f64, f64);
/// A 3×3 matrix, row by row, as a flat Python tuple.
type Tuple9 = (f64, f64, f64, f64, f64, f64, f64, f64, f64);

fn array3<'py>(py: Python<'py>, v: &Vector3<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_slice(py, v.as_slice())
}

#[pymethods]
impl Body {
    /// Its name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Position of its centre (of mass), m: a new array.
    #[getter]
    fn position<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let p = self.read(py, |sim, id| sim.scene().position(id))?;
        Ok(array3(py, &p.coords))
    }

    /// Rotation matrix (body to world), 3×3: a new array.
    #[getter]
    fn rotation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let r = self.read(py, |sim, id| sim.scene().rotation(id))?;
        let rows: Vec<Vec<f64>> = (0..3).map(|i| (0..3).map(|j| r[(i, j)]).collect()).collect();
        Ok(PyArray2::from_vec2(py, &rows).expect("3 rows of 3"))
    }

    /// Linear velocity, m/s: a new array.
    #[getter]
    fn linear_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let v = self.read(py, |sim, id| Ok(sim.scene().body(id)?.linear_velocity()))?;
        Ok(array3(py, &v))
    }

    /// Angular velocity, rad/s: a new array.
    #[getter]
    fn angular_velocity<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        let w = self.read(py, |sim, id| Ok(sim.scene().body(id)?.angular_velocity()))?;
        Ok(array3(py, &w))
    }

    /// Mass, kg.
    #[getter]
    fn mass(&self, py: Python<'_>) -> PyResult<f64> {
        self.read(py, |sim, id| Ok(sim.scene().body(id)?.mass()))
    }

    /// Inertia tensor about its centre of mass in its own frame, kg·m²: a new 3×3
    /// array.
    #[getter]
    fn inertia<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let i = self.read(py, |sim, id| Ok(sim.scene().body(id)?.inertia()))?;
        let rows: Vec<Vec<f64>> = (0..3).map(|r| (0..3).map(|c| i[(r, c)]).collect()).collect();
        Ok(PyArray2::from_vec2(py, &rows).expect("3 rows of 3"))
    }

    /// Position of its centre, m, as a tuple: what the original API (`ars.model`)
    /// returns, and no numpy array is made. Methods, not getters, so that `ars.model`
    /// can hand them out as its own bound methods.
    #[pyo3(name = "_position")]
    fn position_tuple(&self, py: Python<'_>) -> PyResult<Tuple3> {
        let p = self.read(py, |sim, id| sim.scene().position(id))?;
        Ok((p.x, p.y, p.z))
    }

    /// Rotation matrix (body to world) as a tuple of 9, row by row (the original API's).
    #[pyo3(name = "_rotation")]
    fn rotation_tuple(&self, py: Python<'_>) -> PyResult<Tuple9> {
        let r = self.read(py, |sim, id| sim.scene().rotation(id))?;
        Ok((r[(0, 0)], r[(0, 1)], r[(0, 2)], r[(1, 0)], r[(1, 1)], r[(1, 2)], r[(2, 0)], r[(2, 1)], r[(2, 2)]))
    }

    /// Linear velocity, m/s, as a tuple (the original API's).
    #[pyo3(name = "_linear_velocity")]
    fn linear_velocity_tuple(&self, py: Python<'_>) -> PyResult<Tuple3> {
        let v = self.read(py, |sim, id| Ok(sim.scene().body(id)?.linear_velocity()))?;
        Ok((v.x, v.y, v.z))
    }

    /// Angular velocity, rad/s, as a tuple (the original API's).
    #[pyo3(name = "_angular_velocity")]
    fn angular_velocity_tuple(&self, py: Python<'_>) -> PyResult<Tuple3> {
        let w = self.read(py, |sim, id| Ok(sim.scene().body(id)?.angular_velocity()))?;
        Ok((w.x, w.y, w.z))
    }

    /// Inertia tensor (as `inertia`) as a tuple of three row tuples (the original API's).
    #[pyo3(name = "_inertia")]
    fn inertia_tuple(&self, py: Python<'_>) -> PyResult<(Tuple3, Tuple3, Tuple3)> {
        let i = self.read(py, |sim, id| Ok(sim.scene().body(id)?.inertia()))?;
        let row = |r: usize| (i[(r, 0)], i[(r, 1)], i[(r, 2)]);
        Ok((row(0), row(1), row(2)))
    }

    /// Moves it to `position` (m).
    fn set_position(&self, py: Python<'_>, position: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().set_position(id, Point3::from(position)))
    }

    /// Sets its linear velocity (m/s).
    fn set_linear_velocity(&self, py: Python<'_>, velocity: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().body_mut(id)?.set_linear_velocity(Vector3::from(velocity)))
    }

    /// Sets its angular velocity (rad/s).
    fn set_angular_velocity(&self, py: Python<'_>, velocity: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().body_mut(id)?.set_angular_velocity(Vector3::from(velocity)))
    }

    /// Adds a force (N, world frame) at its centre of mass for the next step.
    fn add_force(&self, py: Python<'_>, force: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().body_mut(id)?.add_force(Vector3::from(force)))
    }

    /// Sets its orientation to `rotation` (a 3×3 rotation matrix, world frame), about
    /// its centre; refused (`ars.InputError`) if it is not a rotation.
    fn set_rotation(&self, py: Python<'_>, rotation: Checked<[[f64; 3]; 3]>) -> PyResult<()> {
        self.read(py, move |sim, id| sim.scene_mut().set_rotation(id, self::rotation(rotation.0)?))
    }

    /// Moves and turns it at once: its centre to `position`, its orientation to
    /// `rotation` (3×3, identity if not given); velocities are kept.
    #[pyo3(signature = (position, rotation=None))]
    fn set_pose(&self, py: Python<'_>, position: Vec3, rotation: Option<Checked<[[f64; 3]; 3]>>) -> PyResult<()> {
        self.read(py, move |sim, id| sim.scene_mut().set_pose(id, pose(position, rotation)?))
    }

    /// Moves it by the position of the object `other` (the original's
    /// `offset_by_object`).
    fn offset_by_object(&self, py: Python<'_>, other: &str) -> PyResult<()> {
        self.read(py, move |sim, id| {
            let other = sim.scene().object(other)?.id();
            sim.scene_mut().offset_by_object(id, other)
        })
    }

    /// Turns it by `angle` (rad) about the world `axis`, about its centre.
    fn rotate(&self, py: Python<'_>, axis: Vec3, angle: f64) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().rotate(id, Vector3::from(axis), angle))
    }

    /// Moves it by `offset` (m).
    fn offset_by_position(&self, py: Python<'_>, offset: Vec3) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().offset_by_position(id, Vector3::from(offset)))
    }

    /// The colour the viewer draws it with (RGB, each in [0, 1]).
    fn set_color(&self, py: Python<'_>, color: Checked<[f32; 3]>) -> PyResult<()> {
        self.read(py, |sim, id| sim.scene_mut().set_color(id, color.0))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Body {:?}>", self.name)
    }
}

/// A joint of a simulation, by name.
#[pyclass(module = "ars", frozen)]
pub struct Joint {
    sim: Py<PySimulation>,
    name: String,
    /// The id its name had when last looked up (see [`by_name`]).
    id: Mutex<Option<JointId>>,
}

impl Joint {
    pub(crate) fn new(sim: Py<PySimulation>, name: String) -> Self {
        Joint { sim, name, id: Mutex::default() }
    }

    fn act<R: Send>(
        &self,
        py: Python<'_>,
        f: impl FnOnce(&mut Simulation, JointId) -> ars_core::Result<R> + Send,
    ) -> PyResult<R> {
        let (name, cached) = (self.name.as_str(), &self.id);
        self.sim.get().with(py, |sim| {
            let id = by_name(
                cached,
                |id| sim.scene().joint(id).is_ok_and(|j| j.name() == name),
                || Ok(sim.scene().joint(name)?.id()),
            )?;
            f(sim, id)
        })
    }
}

#[pymethods]
impl Joint {
    /// Its name.
    #[getter]
    fn name(&self) -> &str {
        &self.name
    }

    /// Angle (rad) of a rotary joint, or position (m) of a slider: its first degree of
    /// freedom.
    #[getter]
    fn angle(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| sim.scene().joint_position(id))
    }

    /// Same as `angle` (the word for sliders).
    #[getter]
    fn position(&self, py: Python<'_>) -> PyResult<f64> {
        self.angle(py)
    }

    /// Rate of `angle`, rad/s (or m/s).
    #[getter]
    fn rate(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| sim.scene().joint_rate(id))
    }

    /// Adds a torque (N·m) about a rotary joint's axis for the next step.
    pub(crate) fn add_torque(&self, py: Python<'_>, torque: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.add_torque(torque))
    }

    /// Adds a force (N) along a slider's axis for the next step.
    fn add_force(&self, py: Python<'_>, force: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.add_force(force))
    }

    /// Drives the joint at `speed` (rad/s or m/s) with at most `max_force` (N·m or N);
    /// `max_force = 0` turns the motor off.
    fn set_speed(&self, py: Python<'_>, speed: f64, max_force: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_speed(speed, max_force))
    }

    /// Sets one of ODE's parameters of its first axis, by name: `"lo_stop"`,
    /// `"hi_stop"`, `"velocity"`, `"max_force"`, `"fudge_factor"`, `"bounce"`, `"cfm"`,
    /// `"stop_erp"`, `"stop_cfm"`; a fixed or ball joint takes only `"erp"` and `"cfm"`.
    fn set_param(&self, py: Python<'_>, name: &str, value: f64) -> PyResult<()> {
        use ars_core::JointParam as P;
        let param = match name {
            "lo_stop" => P::LoStop,
            "hi_stop" => P::HiStop,
            "velocity" => P::Velocity,
            "max_force" => P::MaxForce,
            "fudge_factor" => P::FudgeFactor,
            "bounce" => P::Bounce,
            "cfm" => P::Cfm,
            "stop_erp" => P::StopErp,
            "stop_cfm" => P::StopCfm,
            "erp" => P::Erp,
            other => {
                let known = [
                    "lo_stop",
                    "hi_stop",
                    "velocity",
                    "max_force",
                    "fudge_factor",
                    "bounce",
                    "cfm",
                    "stop_erp",
                    "stop_cfm",
                    "erp",
                ]
                .map(String::from)
                .to_vec();
                let error = ars_core::Error::UnknownKind { what: "joint parameter", name: other.to_string(), known };
                return Err(crate::errors::to_py(py, error));
            }
        };
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_param(param, value))
    }

    /// Viscous friction: `-coefficient · rate` every step (N·m·s/rad or N·s/m; 0: off).
    fn set_viscous_friction(&self, py: Python<'_>, coefficient: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_viscous_friction(coefficient))
    }

    /// A spring: `-stiffness · (angle - rest)` every step (N·m/rad or N/m; 0: off).
    #[pyo3(signature = (stiffness, rest=0.0))]
    fn set_spring(&self, py: Python<'_>, stiffness: f64, rest: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_spring(stiffness, rest))
    }

    /// Drives the joint in native code every step: `kind` is `"torque"` (the torque
    /// follows `setpoint`), `"position"` (a PD servo to `setpoint` with gains `kp`,
    /// `kd`), `"velocity"` (a P servo to `setpoint` with gain `kp`) or `"dc_motor"` (a
    /// DC motor under the voltage `setpoint`, V, with `torque_constant` (N·m/A),
    /// `back_emf_constant` (V·s/rad), `resistance` (Ω), `gear_ratio`, `rotor_inertia`
    /// (kg·m²), `inductance` (H) and rotor `friction` (N·m·s/rad)). `setpoint` is a
    /// number or `(time, value)` breakpoints, linear between them. `None` removes it.
    #[pyo3(signature = (kind, setpoint=None, kp=0.0, kd=0.0, *, torque_constant=None, back_emf_constant=None,
                        resistance=None, gear_ratio=1.0, rotor_inertia=0.0, inductance=0.0, friction=0.0))]
    #[allow(clippy::too_many_arguments)]
    fn set_controller(
        &self,
        py: Python<'_>,
        kind: Option<&str>,
        setpoint: Option<Setpoint>,
        kp: f64,
        kd: f64,
        torque_constant: Option<f64>,
        back_emf_constant: Option<f64>,
        resistance: Option<f64>,
        gear_ratio: f64,
        rotor_inertia: f64,
        inductance: f64,
        friction: f64,
    ) -> PyResult<()> {
        use ars_core::{DcMotor, PositionServo, Profile, TorqueMotor, VelocityServo};
        let needed = |value: Option<f64>, name: &str| {
            value.ok_or_else(|| ars_core::Error::Invalid {
                what: "a DC motor",
                problem: format!("needs its {name} (set_controller(\"dc_motor\", volts, {name}=...))"),
            })
        };
        let profile = |s: Option<Setpoint>| -> ars_core::Result<Profile> {
            match s {
                None => Err(ars_core::Error::Invalid { what: "a controller", problem: "needs a setpoint".into() }),
                Some(Setpoint::Constant(v)) => Profile::constant(v),
                Some(Setpoint::Points(p)) => Profile::new(p),
            }
        };
        let kind = kind.map(str::to_string);
        self.act(py, move |sim, id| {
            let mut joint = sim.scene_mut().joint_mut(id)?;
            match kind.as_deref() {
                None => {
                    joint.clear_controller();
                    Ok(())
                }
                Some("torque") => joint.set_controller(TorqueMotor { torque: profile(setpoint)? }),
                Some("position") => joint.set_controller(PositionServo::pd(profile(setpoint)?, kp, kd)),
                Some("velocity") => joint.set_controller(VelocityServo { setpoint: profile(setpoint)?, gain: kp }),
                Some("dc_motor") => {
                    let motor = DcMotor::new(
                        profile(setpoint)?,
                        needed(torque_constant, "torque_constant")?,
                        needed(back_emf_constant, "back_emf_constant")?,
                        needed(resistance, "resistance")?,
                        gear_ratio,
                        rotor_inertia,
                    )?
                    .with_inductance(inductance)?
                    .with_friction(friction)?;
                    joint.set_controller(motor)
                }
                Some(other) => Err(ars_core::Error::UnknownKind {
                    what: "controller kind",
                    name: other.to_string(),
                    known: ["torque", "position", "velocity", "dc_motor"].map(String::from).to_vec(),
                }),
            }
        })
    }

    /// Its kind: `"hinge"`, `"slider"`, `"universal"`, `"ball"`, `"piston"` or
    /// `"fixed"`.
    #[getter]
    fn kind(&self, py: Python<'_>) -> PyResult<String> {
        self.act(py, |sim, id| Ok(format!("{:?}", sim.scene().joint(id)?.joint_type()).to_lowercase()))
    }

    /// Dry (Coulomb) friction: the joint resists motion with up to `max_effort` (N·m
    /// or N; 0: off).
    fn set_dry_friction(&self, py: Python<'_>, max_effort: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_dry_friction(max_effort))
    }

    /// Its armature: inertia (kg·m², or kg for a slider) that only the joint's own
    /// motion feels, as a motor's rotor through its gearbox (MuJoCo's joint `armature`),
    /// integrated implicitly; 0 removes it. Hinges and sliders.
    fn set_armature(&self, py: Python<'_>, inertia: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_armature(inertia))
    }

    /// Its armature (0: none), kg·m² or kg (see `set_armature`).
    #[getter]
    fn armature(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| Ok(sim.scene_mut().joint_mut(id)?.armature()))
    }

    /// Its damping: a viscous torque (force) of `coefficient` N·m·s/rad (N·s/m) against
    /// the joint's rate at the end of each step, as MuJoCo's joint `damping` (stable at
    /// any coefficient, where `set_viscous_friction`, the original's, takes the rate at
    /// the step's start); 0 removes it. Hinges and sliders.
    fn set_damping(&self, py: Python<'_>, coefficient: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_damping(coefficient))
    }

    /// Its damping (0: none), N·m·s/rad or N·s/m (see `set_damping`).
    #[getter]
    fn damping(&self, py: Python<'_>) -> PyResult<f64> {
        self.act(py, |sim, id| Ok(sim.scene_mut().joint_mut(id)?.damping()))
    }

    /// Limits of its actuator: the largest `effort` (N·m or N) and `velocity` (rad/s
    /// or m/s) its motor and controller may use (`math.inf`: none).
    #[pyo3(signature = (effort=f64::INFINITY, velocity=f64::INFINITY))]
    fn set_actuator_limits(&self, py: Python<'_>, effort: f64, velocity: f64) -> PyResult<()> {
        self.act(py, |sim, id| {
            sim.scene_mut().joint_mut(id)?.set_actuator_limits(ars_core::ActuatorLimits { effort, velocity })
        })
    }

    /// Makes it follow the joint `leader`: its position is held at `multiplier ·
    /// leader + offset` (URDF's `<mimic>`).
    #[pyo3(signature = (leader, multiplier=1.0, offset=0.0))]
    fn set_mimic(&self, py: Python<'_>, leader: &str, multiplier: f64, offset: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_mimic(leader, multiplier, offset))
    }

    /// Stops following a leader (see `set_mimic`).
    fn clear_mimic(&self, py: Python<'_>) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.clear_mimic())
    }

    /// The torques (N·m) or forces (N) put on it this step so far, by where they
    /// came from: a dict with `"added"` (`add_torque`/`add_force`), `"controller"`,
    /// `"friction"` (viscous) and `"total"`.
    #[getter]
    fn efforts<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, pyo3::types::PyDict>> {
        let e = self.act(py, |sim, id| sim.scene().joint_efforts(id))?;
        let dict = pyo3::types::PyDict::new(py);
        dict.set_item("added", e.added)?;
        dict.set_item("controller", e.controller)?;
        dict.set_item("friction", e.friction)?;
        dict.set_item("total", e.total())?;
        Ok(dict)
    }

    /// Stops (limits) of its first degree of freedom (±inf: none).
    fn set_limits(&self, py: Python<'_>, low: f64, high: f64) -> PyResult<()> {
        self.act(py, |sim, id| sim.scene_mut().joint_mut(id)?.set_limits(low, high))
    }

    fn __repr__(&self) -> String {
        format!("<ars.Joint {:?}>", self.name)
    }
}

/// `ars.Simulation`'s views of one body or joint by name: `body` and `joint`.
#[pymethods]
impl PySimulation {
    /// The object named `name` (an unknown name raises `ars.UnknownNameError`, with the
    /// names spelled almost the same). Its attributes are copies, read when asked.
    fn body(slf: Bound<'_, Self>, name: &str) -> PyResult<Body> {
        slf.get().with(slf.py(), |sim| Self::object_id(sim, name))?;
        Ok(Body::new(slf.unbind(), name.to_string()))
    }

    /// The joint named `name`; see `body`.
    fn joint(slf: Bound<'_, Self>, name: &str) -> PyResult<Joint> {
        slf.get().with(slf.py(), |sim| sim.scene().joint(name).map(|_| ()))?;
        Ok(Joint::new(slf.unbind(), name.to_string()))
    }
}
