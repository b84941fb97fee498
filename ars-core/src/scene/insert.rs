//! The importers' way in: the small crate-visible API through which the URDF, MJCF
//! and scene-file readers put what they parsed into a scene.
//!
//! An importer makes its ODE bodies through the world ([`Scene::world_mut`]), then
//! hands each body with its geoms to [`Scene::insert_object`], adds geoms to an object
//! it made with [`Scene::attach_geoms`], and joins objects with
//! [`Scene::insert_sim_joint`]. Nothing else of the scene's bookkeeping (its object
//! and joint tables, their names) is theirs to touch.

use super::Scene;
use super::joints::{ActuatorLimits, JointData, JointEfforts, JointEnd, JointType};
use super::objects::ObjectData;
use crate::error::{Error, Result};
use crate::geom::GeomBuilder;
use crate::handle::{BodyHandle, GeomHandle, JointHandle, JointId, ObjectId};
use crate::joint::{JointBuilder, JointKind};
use crate::shape::Shape;

/// How an inserted object is named.
#[derive(Clone, Copy, Debug)]
pub(crate) enum ObjectName<'a> {
    /// This name, or this name with a number added when it is taken (a robot's links).
    Unique(&'a str),
    /// Exactly this name; an error when it is taken (a saved scene's objects).
    Exact(&'a str),
}

/// What an importer inserts as one object.
pub(crate) struct NewObject<'a> {
    /// Its name.
    pub(crate) name: ObjectName<'a>,
    /// The shape it is drawn as when it has no visuals.
    pub(crate) drawn: Shape,
    /// Its ODE body, made in the scene's world; `None` for a static object. From here
    /// on it is the object's: if the insertion fails, it is removed.
    pub(crate) body: Option<BodyHandle>,
    /// Its own geom, of the shape it is drawn as (a saved scene remakes it so).
    pub(crate) geom: Option<GeomBuilder>,
    /// Its more collision elements (a robot link's others), in order.
    pub(crate) more_geoms: Vec<GeomBuilder>,
}

impl<'a> NewObject<'a> {
    /// An object whose first geom (if any) is its own and the rest its more.
    pub(crate) fn with_geoms(
        name: ObjectName<'a>,
        drawn: Shape,
        body: Option<BodyHandle>,
        geoms: Vec<GeomBuilder>,
    ) -> Self {
        let mut geoms = geoms.into_iter();
        NewObject { name, drawn, body, geom: geoms.next(), more_geoms: geoms.collect() }
    }
}

impl Scene {
    /// Inserts an object: its geoms into the scene's space, then the object under its
    /// name. All or nothing: on an error nothing of it (its body included) is left.
    pub(crate) fn insert_object(&mut self, new: NewObject<'_>) -> Result<ObjectId> {
        let has_own = new.geom.is_some();
        let made = match new.name {
            ObjectName::Exact(name) if self.object_names.contains(name) => {
                Err(Error::DuplicateName { kind: "object", name: name.to_string() })
            }
            _ => self.insert_geoms(new.geom.into_iter().chain(new.more_geoms).collect()),
        };
        let mut geoms = match made {
            Ok(geoms) => geoms,
            Err(e) => {
                if let Some(body) = new.body {
                    self.world.remove_body(body)?;
                }
                return Err(e);
            }
        };
        let base = match new.name {
            ObjectName::Unique(base) | ObjectName::Exact(base) => base,
        };
        let own = if has_own { Some(geoms.remove(0)) } else { None };
        let id = self.register_as(base, new.drawn, new.body, own)?;
        self.objects.get_mut(id.0, ObjectId::KIND)?.extra_geoms = geoms;
        Ok(id)
    }

    /// Adds geoms to an object after its others (a URDF link merged into its parent's).
    /// All or nothing.
    pub(crate) fn attach_geoms(&mut self, id: ObjectId, geoms: Vec<GeomBuilder>) -> Result<()> {
        self.object_data(id)?;
        let made = self.insert_geoms(geoms)?;
        self.objects.get_mut(id.0, ObjectId::KIND)?.extra_geoms.extend(made);
        Ok(())
    }

    /// Puts geoms into the scene's space, in order; on an error removes those made.
    fn insert_geoms(&mut self, builders: Vec<GeomBuilder>) -> Result<Vec<GeomHandle>> {
        let mut made = Vec::with_capacity(builders.len());
        for builder in builders {
            match self.world.insert_geom(self.space(), builder) {
                Ok(g) => made.push(g),
                Err(e) => {
                    for g in made {
                        self.world.remove_geom(g)?;
                    }
                    return Err(e);
                }
            }
        }
        Ok(made)
    }

    /// Registers an object under `base`, made unique.
    pub(super) fn register_as(
        &mut self,
        base: &str,
        shape: Shape,
        body: Option<BodyHandle>,
        geom: Option<GeomHandle>,
    ) -> Result<ObjectId> {
        let name = self.object_names.unique(base);
        let id = ObjectId(self.objects.insert(ObjectData {
            name: name.clone(),
            shape,
            body,
            geom,
            extra_geoms: Vec::new(),
            visuals: Vec::new(),
            color: None,
        }));
        self.object_names.insert(name, id)?;
        Ok(id)
    }

    /// Joins `object1` to `object2` (or the world) with the joint `builder` makes, named
    /// `name` (or the kind's default name, made unique, when empty).
    pub(crate) fn insert_sim_joint(
        &mut self,
        name: &str,
        kind: JointType,
        object1: ObjectId,
        object2: JointEnd,
        builder: JointBuilder,
    ) -> Result<JointId> {
        let first = self.object_data(object1)?;
        let body1 = first
            .body
            .ok_or_else(|| Error::NoBody { operation: "the first object of a joint", object: first.name.clone() })?;
        let (object2, body2) = match object2 {
            JointEnd::World => (None, None),
            JointEnd::Object(o) => {
                if o == object1 {
                    return Err(Error::SelfJoint {
                        joint: kind.default_name(),
                        body: format!("object {:?}", self.object_data(o)?.name),
                    });
                }
                (Some(o), self.object_data(o)?.body)
            }
        };
        if !name.is_empty() {
            // Check before creating anything.
            if self.joint_names.get(name).is_ok() {
                return Err(Error::DuplicateName { kind: "joint", name: name.to_string() });
            }
        }
        let builder = match body2 {
            Some(b2) => builder.between(body1, b2),
            None => builder.to_world(body1),
        };
        let creation = builder.kind().clone();
        let handle = self.world.insert_joint(builder.feedback())?;
        self.name_joint(name, kind, handle, (object1, object2), creation, None)
    }

    /// Names a new joint `name` (empty: the kind's default name, made unique) and keeps
    /// its data: ODE's `handle` joining `objects` (`None`: the world), made as
    /// `creation`, in a group's place `member` if any.
    pub(crate) fn name_joint(
        &mut self,
        name: &str,
        kind: JointType,
        handle: JointHandle,
        (object1, object2): (ObjectId, Option<ObjectId>),
        creation: JointKind,
        member: Option<super::joint_group::GroupMember>,
    ) -> Result<JointId> {
        let name = if name.is_empty() { self.joint_names.unique(kind.default_name()) } else { name.to_string() };
        let data = JointData {
            name: name.clone(),
            kind,
            handle,
            object1,
            object2,
            friction: 0.0,
            controller: None,
            efforts: JointEfforts::default(),
            creation,
            limits: None,
            actuator: ActuatorLimits::default(),
            dry_friction: 0.0,
            mimic: None,
            spring: (0.0, 0.0),
            armature: None,
            member,
        };
        let id = JointId(self.joints.insert(data));
        self.joint_names.insert(name, id)?;
        Ok(id)
    }
}
