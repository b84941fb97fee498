//! Loading: a [`SceneFile`] built into a simulation, from JSON text or a file.

use crate::body::{BodyBuilder, MassSpec};
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::ObjectId;
use crate::joint::JointBuilder;
use crate::scene::{ActuatorLimits, JointEnd, NewObject, ObjectName};
use crate::sensors::SensorKind;
use crate::shape::Shape;
use crate::simulation::{Simulation, SimulationBuilder};

use super::{BodyFile, FORMAT, JointFile, ObjectFile, SceneFile, from_hex};

impl Simulation {
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
        for o in &file.objects {
            o.add_to(&mut sim)?;
        }
        for (i, j) in file.joints.iter().enumerate() {
            for w in file.world_joints.iter().filter(|w| w.after == i) {
                w.add_to(&mut sim)?;
            }
            j.add_to(&mut sim, &file.joints)?;
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
        for g in &file.geom_contacts {
            let object = sim.scene().object(g.object.as_str())?.id();
            sim.scene_mut().set_geom_contact(object, g.geom, g.contact)?;
        }
        for p in &file.geom_pair_contacts {
            let (a, b) = (sim.scene().object(p.a.0.as_str())?.id(), sim.scene().object(p.b.0.as_str())?.id());
            sim.scene_mut().set_geom_pair_contact((a, p.a.1), (b, p.b.1), p.contact)?;
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
    /// Makes the object in `sim`, with its colour and visuals.
    fn add_to(&self, sim: &mut Simulation) -> Result<()> {
        let id = match &self.body {
            Some(b) => self.add_body_to(sim, b)?,
            None => self.add_static_to(sim)?,
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
    fn add_body_to(&self, sim: &mut Simulation, b: &BodyFile) -> Result<ObjectId> {
        let spec = MassSpec::Custom { mass: b.mass, inertia: b.inertia };
        let world = sim.scene.world_mut();
        let body = world.insert_body(BodyBuilder::new().mass(spec).position(b.position))?;
        {
            let mut m = world.body_mut(body)?;
            // Both ODE's quaternion and its rotation matrix, to the bit.
            m.restore_orientation(&b.quaternion, &b.rotation)?;
            m.set_linear_velocity(b.linear_velocity)?;
            m.set_angular_velocity(b.angular_velocity)?;
        }
        let on_body = |shape: &Shape| GeomBuilder::new(shape.clone()).attached_to(body);
        sim.scene.insert_object(NewObject {
            name: ObjectName::Exact(&self.name),
            drawn: self.shape.clone(),
            body: Some(body),
            geom: self.geom.then(|| on_body(&self.shape)),
            more_geoms: self.extra_shapes.iter().map(on_body).collect(),
        })
    }

    /// Makes the static object: its geom at its pose (a plane's is in its shape) and
    /// its other geoms.
    fn add_static_to(&self, sim: &mut Simulation) -> Result<ObjectId> {
        let geom = GeomBuilder::new(self.shape.clone());
        let geom = match (&self.shape, self.pose) {
            (Shape::Plane { .. }, _) | (_, None) => geom,
            (_, Some(pose)) => geom.pose(pose),
        };
        sim.scene.insert_object(NewObject {
            name: ObjectName::Exact(&self.name),
            drawn: self.shape.clone(),
            body: None,
            geom: Some(geom),
            more_geoms: self.extra_shapes.iter().map(|shape| GeomBuilder::new(shape.clone())).collect(),
        })
    }
}

impl JointFile {
    /// Makes the joint in `sim` (its objects looked up by name) with its stops,
    /// friction, actuator limits, spring and motor; not its mimic (its leader may be
    /// made later).
    fn add_to(&self, sim: &mut Simulation, all: &[JointFile]) -> Result<()> {
        let object1 = sim.scene().object(self.object1.as_str())?.id();
        let object2 = match &self.object2 {
            Some(name) => JointEnd::Object(sim.scene().object(name.as_str())?.id()),
            None => JointEnd::World,
        };
        // A joint of a group after its first is made with the group.
        let made_with_group = match sim.scene().joint(self.name.as_str()) {
            Ok(j) => sim.scene.joint_data(j.id())?.member.is_some(),
            Err(_) => false,
        };
        let id = if let Some(group) = &self.group {
            // The whole group, its first joint's settings here, the others' with them.
            let named = group
                .joints
                .iter()
                .map(|name| {
                    let j = all.iter().find(|j| &j.name == name).ok_or_else(|| Error::Invalid {
                        what: "a scene file",
                        problem: format!(
                            "its joint group of {:?} names joint {name:?}, which it does not have",
                            self.name
                        ),
                    })?;
                    Ok((j.name.clone(), j.joint_type, j.kind.clone()))
                })
                .collect::<Result<Vec<_>>>()?;
            let ids = sim.scene.make_group(object1, object2, &named, group.rest.clone())?;
            ids.into_iter().find(|id| sim.scene().joint(*id).is_ok_and(|j| j.name() == self.name)).ok_or_else(|| {
                Error::Invalid {
                    what: "a scene file",
                    problem: format!("its joint group of {:?} does not name that joint", self.name),
                }
            })?
        } else if made_with_group {
            sim.scene().joint(self.name.as_str())?.id()
        } else {
            sim.scene.insert_sim_joint(
                &self.name,
                self.joint_type,
                object1,
                object2,
                JointBuilder::new(self.kind.clone()),
            )?
        };
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
        if self.armature != 0.0 {
            // Right after its joint, as it was made: the world's joints keep their order.
            joint.set_armature(self.armature)?;
        }
        if self.damping != 0.0 {
            // On the armature's motor, or on one made here as it was.
            joint.set_damping(self.damping)?;
        }
        if let Some((speed, max_force)) = self.motor {
            // As it was, whatever the limits (the speed was held to them when set).
            sim.scene.set_joint_motor(id, speed, max_force)?;
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
