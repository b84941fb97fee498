//! MJCF sensors: read and checked against the model, placed on what was built, and
//! made as ARS sensors.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};

use super::defaults::Attrs;
use super::mass::find_body;
use super::model::{Body, Model};
use super::problem::{Parsed, Problem, problem, skip_or_refuse};
use super::read::Reader;
use super::{MjcfModel, MjcfSensor, MjcfSite, RANGEFINDER_LENGTH};
use crate::error::{Error, Result};
use crate::handle::ObjectId;
use crate::scene::Scene;
use crate::sensors::{Laser, Mount, SensorKind, SensorSettings, SensorTarget};

impl Reader<'_, '_, '_> {
    /// A sensor (the `index`-th), or `None` when skipped.
    pub(super) fn sensor(&mut self, node: roxmltree::Node<'_, '_>, index: usize) -> Parsed<Option<MjcfSensor>> {
        let kind = node.tag_name().name();
        let a = Attrs::new(node, self.defaults, "main");
        let needs = |what: &str| a.get(what).ok_or_else(|| problem(&node, format!("needs a {what}")));
        let (objtype, target) = match kind {
            "jointpos" | "jointvel" => ("joint", needs("joint")?),
            "accelerometer" | "gyro" | "velocimeter" | "touch" | "rangefinder" | "magnetometer" => {
                ("site", needs("site")?)
            }
            "subtreecom" | "subtreelinvel" | "subtreeangmom" => ("subtree", needs("body")?),
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
            subtree: Vec::new(),
            id: None,
        }))
    }

    /// Checks that the sensors' targets are in the model, once it is read; a sensor ARS
    /// cannot make there is skipped (with a warning) or refused.
    pub(super) fn check_sensors(&mut self, model: &mut Model) -> Parsed<()> {
        let mut kept = Vec::new();
        let places = std::mem::take(&mut model.sensor_places);
        for (sensor, place) in std::mem::take(&mut model.sensors).into_iter().zip(places) {
            let at = |text: String| Problem { text, ..place.clone() };
            let missing =
                || at(format!("reads the {} {:?}, which the model does not have", sensor.objtype, sensor.target));
            let unsupported = match sensor.objtype.as_str() {
                "joint" => {
                    find_body(&model.bodies, &|b| b.joints.iter().any(|j| j.name == sensor.target))
                        .ok_or_else(missing)?;
                    None
                }
                "subtree" if find_body(&model.bodies, &|b| b.name == sensor.target).is_some() => None,
                "subtree" if sensor.target == "world" => Some(format!("a {} of the world body", sensor.kind)),
                "subtree" if model.welded.iter().any(|w| w.name == sensor.target) => Some(format!(
                    "a {} of {:?}, a body merged into the one it is welded to (its own mass is not told apart \
                     there),",
                    sensor.kind, sensor.target
                )),
                "subtree" => return Err(missing()),
                "site" => match find_body(&model.bodies, &|b| b.sites.iter().any(|s| s.name == sensor.target)) {
                    Some(_) => None,
                    None if model.world_sites.contains(&sensor.target) => {
                        Some(format!("a {} on a site of the world body (ARS reads sites on bodies)", sensor.kind))
                    }
                    None => return Err(missing()),
                },
                _ => match frame_of(model, &sensor.target).ok_or_else(missing)? {
                    (_, None) => Some(format!("a {} of a body welded to the world (its geoms static)", sensor.kind)),
                    _ if sensor.objtype == "body"
                        && model.welded.iter().any(|w| w.name == sensor.target && w.mass.is_none()) =>
                    {
                        Some(format!(
                            "a {} of a massless body's inertial frame (objtype=\"xbody\" reads its frame)",
                            sensor.kind
                        ))
                    }
                    (principal, _) if sensor.kind == "framequat" && sensor.objtype == "body" && principal.is_none() => {
                        Some(
                            "a framequat of a body's inertial frame when its <inertial> gives no diaginertia (the \
                         principal axes MuJoCo computes are not read; objtype=\"xbody\" reads the body's frame)"
                                .to_string(),
                        )
                    }
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
}

impl Scene {
    /// Lists the bodies' sites and places the sensors on their objects (their targets
    /// were checked when the file was read).
    pub(super) fn place_mjcf_sensors(&self, model: &Model, made: &mut MjcfModel) -> Result<()> {
        fn sites(bodies: &[Body], made: &mut MjcfModel) -> Result<()> {
            for body in bodies {
                let object = made.body(&body.name).ok_or_else(|| unknown_target(&body.name))?;
                // From the body's frame to the object's (at the centre of mass, turned
                // as the body).
                let com = body.centre_of_mass();
                for site in &body.sites {
                    made.sites.push(MjcfSite {
                        name: site.name.clone(),
                        body: site.welded_from.clone().unwrap_or_else(|| body.name.clone()),
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
            if sensor.objtype == "subtree" {
                let body = find_body(&model.bodies, &|b| b.name == sensor.target);
                let body = body.ok_or_else(|| unknown_target(&sensor.target))?;
                sensor.subtree = subtree_objects(body, made)?;
                continue;
            }
            sensor.mount = match sensor.objtype.as_str() {
                "joint" => None,
                "site" => {
                    let site = made.sites.iter().find(|s| s.name == sensor.target);
                    let site = site.ok_or_else(|| unknown_target(&sensor.target))?;
                    Some(Mount::Object(site.object, site.offset))
                }
                objtype => {
                    let object = made.body(&sensor.target).ok_or_else(|| unknown_target(&sensor.target))?;
                    // The frame of the body's object in the body's, and the body's in
                    // the one holding it (itself, unless it was welded into another).
                    let (body, frame) = match model.welded.iter().find(|w| w.name == sensor.target) {
                        Some(w) => {
                            let into = w.into.as_deref().unwrap_or_default();
                            (find_body(&model.bodies, &|b| b.name == into), w.frame)
                        }
                        None => (find_body(&model.bodies, &|b| b.name == sensor.target), Isometry3::identity()),
                    };
                    let body = body.ok_or_else(|| unknown_target(&sensor.target))?;
                    let (principal, _) =
                        frame_of(model, &sensor.target).ok_or_else(|| unknown_target(&sensor.target))?;
                    let own = if objtype == "xbody" {
                        Isometry3::identity()
                    } else {
                        let com = mass_centre(model, &sensor.target);
                        Isometry3::from_parts(Translation3::from(com), principal.unwrap_or_default())
                    };
                    Some(Mount::Object(object, Isometry3::from(-body.centre_of_mass()) * frame * own))
                }
            };
        }
        made.sensors = sensors;
        Ok(())
    }
}

impl MjcfSensor {
    /// The ARS sensor kind this sensor became (see [`MjcfSensor`]); `None` for a
    /// `rangefinder`, which becomes a [`Laser`].
    pub fn ars_kind(&self) -> Option<SensorKind> {
        ars_kind(&self.kind)
    }
}

/// The ARS sensor kind an MJCF sensor element becomes (see [`MjcfSensor`]); `None` for
/// a `rangefinder`, which becomes a [`Laser`], a sensor a scene file does not rebuild.
pub(super) fn ars_kind(element: &str) -> Option<SensorKind> {
    Some(match element {
        "jointpos" => SensorKind::JointPositions,
        "jointvel" => SensorKind::JointVelocities,
        "framepos" => SensorKind::Gps,
        "framelinvel" => SensorKind::Velometer,
        "framequat" => SensorKind::Orientation,
        "accelerometer" | "gyro" => SensorKind::Imu,
        "velocimeter" => SensorKind::Velocimeter,
        "touch" => SensorKind::Touch,
        "magnetometer" => SensorKind::Magnetometer,
        "subtreecom" | "subtreelinvel" | "subtreeangmom" => SensorKind::Momentum,
        _ => return None,
    })
}

impl crate::Simulation {
    pub(super) fn make_mjcf_sensors(&mut self, mut model: MjcfModel) -> Result<MjcfModel> {
        for i in 0..model.sensors.len() {
            let sensor = &model.sensors[i];
            let target = sensor.target.as_str();
            // The targets were checked while the model was read and placed while it was built.
            let mounted = || match sensor.mount {
                Some(Mount::Object(object, offset)) => Ok((object, offset)),
                _ => Err(unknown_target(target)),
            };
            let id = match ars_kind(&sensor.kind) {
                Some(kind) if kind.target() == SensorTarget::Joints => {
                    let joint = model.joint(target).ok_or_else(|| unknown_target(target))?;
                    self.add_sensor_described(kind, &[], &[joint], None, None, None)?
                }
                Some(kind) if kind.target() == SensorTarget::Objects => {
                    self.add_sensor_described(kind, &sensor.subtree, &[], None, None, None)?
                }
                Some(kind) => {
                    let (object, pose) = mounted()?;
                    let settings = match kind {
                        SensorKind::Touch => {
                            let zone = model.site(target).ok_or_else(|| unknown_target(target))?.zone;
                            SensorSettings::Touch { zone, pose }
                        }
                        SensorKind::Magnetometer => SensorSettings::Magnetometer { field: model.magnetic, pose },
                        _ => SensorSettings::Offset { pose },
                    };
                    self.add_sensor_described(kind, &[object], &[], None, None, Some(&settings))?
                }
                None => {
                    let (object, offset) = mounted()?;
                    self.add_sensor(Laser::new(RANGEFINDER_LENGTH).mounted_on(object, offset))?.into()
                }
            };
            model.sensors[i].id = Some(id);
        }
        Ok(model)
    }
}

/// The objects of `body` and of the bodies below it (not the light links chaining a
/// body's joints, which MuJoCo does not have), each once.
fn subtree_objects(body: &Body, made: &MjcfModel) -> Result<Vec<ObjectId>> {
    let mut objects = Vec::new();
    let mut stack = vec![body];
    while let Some(b) = stack.pop() {
        let object = made.body(&b.name).ok_or_else(|| unknown_target(&b.name))?;
        if !objects.contains(&object) {
            objects.push(object);
        }
        stack.extend(b.children.iter());
    }
    Ok(objects)
}

/// A body's `<inertial>` turn (when known) and the body it is made in (itself, or the
/// one it was welded into; `Some(None)`: the world), by name; `None` if there is none.
fn frame_of(model: &Model, name: &str) -> Option<(Option<UnitQuaternion<f64>>, Option<String>)> {
    if let Some(b) = find_body(&model.bodies, &|b| b.name == name) {
        return Some((b.principal, Some(b.name.clone())));
    }
    let w = model.welded.iter().find(|w| w.name == name)?;
    Some((w.principal, w.into.clone()))
}

/// A body's own centre of mass in its frame (welded or not; its origin when massless).
fn mass_centre(model: &Model, name: &str) -> Vector3<f64> {
    match model.welded.iter().find(|w| w.name == name) {
        Some(w) => w.mass.map_or(Vector3::zeros(), |(_, com, _)| com),
        None => find_body(&model.bodies, &|b| b.name == name).map_or(Vector3::zeros(), Body::centre_of_mass),
    }
}

/// A sensor target the model does not have (checked before: not expected).
pub(super) fn unknown_target(target: &str) -> Error {
    Error::Invalid { what: "an MJCF sensor", problem: format!("reads {target:?}, which the model does not have") }
}
