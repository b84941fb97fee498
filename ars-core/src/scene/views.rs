//! Named access: an object or a joint looked up by name or by id, as a view that reads
//! it (MuJoCo's `data.body("arm")`): `sim.object("arm")?.position()`,
//! `sim.joint("r1")?.state()?`.

use nalgebra::{Isometry3, Point3, Rotation3};

use super::Scene;
use super::joints::{ActuatorLimits, JointData, JointEfforts, JointType, Mimic};
use super::objects::{Color, ObjectData, Visual};
use crate::body::BodyRef;
use crate::control::JointState;
use crate::error::Result;
use crate::handle::{BodyHandle, GeomHandle, JointId, ObjectId};
use crate::joint::{JointFeedback, JointRef};
use crate::shape::Shape;

/// What finds an object: its name (`"arm"`) or its id.
pub trait ObjectKey {
    /// The object's id (a name is looked up; an id is checked when it is used).
    fn object_id(&self, scene: &Scene) -> Result<ObjectId>;
}

impl ObjectKey for ObjectId {
    fn object_id(&self, _: &Scene) -> Result<ObjectId> {
        Ok(*self)
    }
}

impl ObjectKey for &str {
    fn object_id(&self, scene: &Scene) -> Result<ObjectId> {
        scene.object_names.get(self)
    }
}

impl ObjectKey for &String {
    fn object_id(&self, scene: &Scene) -> Result<ObjectId> {
        scene.object_names.get(self)
    }
}

/// What finds a joint: its name (`"r1"`) or its id.
pub trait JointKey {
    /// The joint's id (a name is looked up; an id is checked when it is used).
    fn joint_id(&self, scene: &Scene) -> Result<JointId>;
}

impl JointKey for JointId {
    fn joint_id(&self, _: &Scene) -> Result<JointId> {
        Ok(*self)
    }
}

impl JointKey for &str {
    fn joint_id(&self, scene: &Scene) -> Result<JointId> {
        scene.joint_names.get(self)
    }
}

impl JointKey for &String {
    fn joint_id(&self, scene: &Scene) -> Result<JointId> {
        scene.joint_names.get(self)
    }
}

/// An object of a scene, read: from [`Scene::object`].
#[derive(Clone, Copy)]
pub struct ObjectView<'s> {
    scene: &'s Scene,
    id: ObjectId,
    data: &'s ObjectData,
}

impl std::fmt::Debug for ObjectView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ObjectView").field("id", &self.id).field("name", &self.data.name).finish()
    }
}

impl<'s> ObjectView<'s> {
    /// Its id (to keep, and to reach it without a name lookup).
    pub fn id(&self) -> ObjectId {
        self.id
    }
    /// Its name.
    pub fn name(&self) -> &'s str {
        &self.data.name
    }
    /// Its shape, in its own frame.
    pub fn shape(&self) -> &'s Shape {
        &self.data.shape
    }
    /// The colour the viewer draws it with (`None`: the viewer's default).
    pub fn color(&self) -> Option<Color> {
        self.data.color
    }
    /// What the viewer draws for it instead of its geoms (empty: the geoms).
    pub fn visuals(&self) -> &'s [Visual] {
        &self.data.visuals
    }
    /// Its body, if it is dynamic (`None` for a static object).
    pub fn body_handle(&self) -> Option<BodyHandle> {
        self.data.body
    }
    /// Its (first) geom.
    pub fn geom_handle(&self) -> Option<GeomHandle> {
        self.data.geom
    }
    /// All its geoms: the first, then any more (a robot link's other collision
    /// elements), each placed relative to its body.
    pub fn geoms(&self) -> impl Iterator<Item = GeomHandle> + 's {
        self.data.geom.into_iter().chain(self.data.extra_geoms.iter().copied())
    }
    /// Its body (pose, velocities, mass...); an error for a static object.
    pub fn body(&self) -> Result<BodyRef<'s>> {
        self.scene.body(self.id)
    }
    /// World pose (a plane's is the identity).
    pub fn pose(&self) -> Result<Isometry3<f64>> {
        self.scene.pose(self.id)
    }
    /// World position.
    pub fn position(&self) -> Result<Point3<f64>> {
        self.scene.position(self.id)
    }
    /// Rotation (body to world).
    pub fn rotation(&self) -> Result<Rotation3<f64>> {
        self.scene.rotation(self.id)
    }
}

/// A joint of a scene, read: from [`Scene::joint`] (to act on it, [`Scene::joint_mut`]).
#[derive(Clone, Copy)]
pub struct JointView<'s> {
    scene: &'s Scene,
    id: JointId,
    data: &'s JointData,
}

impl std::fmt::Debug for JointView<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("JointView").field("id", &self.id).field("name", &self.data.name).finish()
    }
}

impl<'s> JointView<'s> {
    /// Its id.
    pub fn id(&self) -> JointId {
        self.id
    }
    /// Its name.
    pub fn name(&self) -> &'s str {
        &self.data.name
    }
    /// Its type.
    pub fn joint_type(&self) -> JointType {
        self.data.kind
    }
    /// The objects it connects (`None`: the static world).
    pub fn objects(&self) -> (ObjectId, Option<ObjectId>) {
        (self.data.object1, self.data.object2)
    }
    /// Position (angle, rad, or slider position, m) and rate of its first degree of
    /// freedom; an error for a fixed or ball joint.
    pub fn state(&self) -> Result<JointState> {
        self.scene.joint_state(self.id)
    }
    /// The torques (or forces) put on it during the step being taken.
    pub fn efforts(&self) -> JointEfforts {
        self.data.efforts
    }
    /// Forces and torques it applied on its objects in the last step.
    pub fn reaction(&self) -> Result<JointFeedback> {
        Ok(self.ode()?.feedback().expect("simulation joints record feedback"))
    }
    /// What its actuator can put out.
    pub fn actuator_limits(&self) -> ActuatorLimits {
        self.data.actuator
    }
    /// The most torque (force) its dry friction holds it with (0: none).
    pub fn dry_friction(&self) -> f64 {
        self.data.dry_friction
    }
    /// Its spring's stiffness (N·m/rad or N/m; 0: none) and rest position, as set with
    /// [`SimJoint::set_spring`](crate::SimJoint::set_spring).
    pub fn spring(&self) -> (f64, f64) {
        self.data.spring
    }
    /// Its viscous friction coefficient (N·m·s/rad or N·s/m; 0: none), as set with
    /// [`SimJoint::set_viscous_friction`](crate::SimJoint::set_viscous_friction).
    pub fn viscous_friction(&self) -> f64 {
        self.data.friction
    }
    /// The limits of its first degree of freedom set with
    /// [`SimJoint::set_limits`](crate::SimJoint::set_limits) (or a scene file), if any.
    pub fn limits(&self) -> Option<(f64, f64)> {
        self.data.limits
    }
    /// The joint it follows, if any.
    pub fn mimic(&self) -> Option<Mimic> {
        self.data.mimic
    }
    /// The underlying ODE joint (anchors, axes, angles, parameters).
    pub fn ode(&self) -> Result<JointRef<'s>> {
        self.scene.world.joint(self.data.handle)
    }
}

impl Scene {
    /// An object, by name (an unknown name is an error listing close matches) or id.
    pub fn object(&self, key: impl ObjectKey) -> Result<ObjectView<'_>> {
        let id = key.object_id(self)?;
        Ok(ObjectView { scene: self, id, data: self.object_data(id)? })
    }

    /// A joint, by name (an unknown name is an error listing close matches) or id.
    pub fn joint(&self, key: impl JointKey) -> Result<JointView<'_>> {
        let id = key.joint_id(self)?;
        Ok(JointView { scene: self, id, data: self.joint_data(id)? })
    }
}
