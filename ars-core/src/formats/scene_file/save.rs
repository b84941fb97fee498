//! Saving: a simulation as a [`SceneFile`] and as JSON text.

use crate::error::{Error, Result};
use crate::joint::{JointKind, JointParam};
use crate::scene::JointType;
use crate::scene::joints::JointData;
use crate::sensors::SensorKind;
use crate::shape::Shape;
use crate::simulation::Simulation;

use super::{
    BodyFile, FORMAT, GeomContactFile, GeomPairContactFile, GroupFile, JointFile, MimicFile, ObjectFile,
    PairSurfaceFile, SceneFile, SensorFile, WorldJointFile, to_hex,
};

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
            geom_contacts: self
                .scene()
                .geom_contacts()
                .into_iter()
                .map(|(object, geom, contact)| {
                    Ok(GeomContactFile { object: self.scene.object(object)?.name().to_string(), geom, contact })
                })
                .collect::<Result<_>>()?,
            geom_pair_contacts: self
                .scene()
                .geom_pair_contacts()
                .into_iter()
                .map(|((a, ka), (b, kb), contact)| {
                    let name = |id| -> Result<String> { Ok(self.scene.object(id)?.name().to_string()) };
                    Ok(GeomPairContactFile { a: (name(a)?, ka), b: (name(b)?, kb), contact })
                })
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
                armature: data.armature.map_or(0.0, |a| a.inertia),
                damping: data.armature.map_or(0.0, |a| a.damping),
                group: self.saved_group(data)?,
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
        if let Some(member) = data.member {
            // Its group is saved with its geometry; here, where the joint is now.
            let (anchor, axis) = self.scene.member_geometry(member)?;
            return Ok(match data.kind {
                JointType::Hinge => JointKind::Hinge { anchor, axis },
                _ => JointKind::Slider { axis },
            });
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

    /// The group a joint is the first of, if it is.
    fn saved_group(&self, data: &JointData) -> Result<Option<GroupFile>> {
        let Some(member) = data.member.filter(|m| m.index == 0) else { return Ok(None) };
        let joints = self
            .scene
            .group_members(member)?
            .iter()
            .map(|id| Ok(self.scene.joint(*id)?.name().to_string()))
            .collect::<Result<_>>()?;
        Ok(Some(GroupFile { joints, rest: self.scene.group_rest(member)? }))
    }

    /// A joint's speed motor, when on: its speed and largest force.
    fn saved_motor(&self, data: &JointData) -> Result<Option<(f64, f64)>> {
        let world = self.scene.world();
        if let Some(member) = data.member {
            return Ok((member.motor.1 > 0.0).then_some(member.motor));
        }
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
        // An armature's motor is its joint's, made again with it.
        let mut owned: Vec<crate::JointHandle> =
            self.scene.joints_in_creation_order().filter_map(|d| d.armature.map(|a| a.motor)).collect();
        // A group's constraint is its joints', made again with them.
        owned.extend(self.scene.group_joints());
        let mut others: Vec<_> = world
            .joints
            .iter()
            .filter(|(h, _)| {
                !scene_handles.contains(&crate::JointHandle(*h)) && !owned.contains(&crate::JointHandle(*h))
            })
            .collect();
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
}
