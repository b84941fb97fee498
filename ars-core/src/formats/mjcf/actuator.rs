//! `<actuator>`: the actuators on joints (`motor`, `position`, `velocity`, `general`)
//! as ARS [`Actuator`]s.

use super::MjcfActuator;
use super::defaults::Attrs;
use super::problem::{Parsed, problem};
use super::read::Reader;
use crate::{Actuator, ActuatorKind, Error};

impl Reader<'_, '_, '_> {
    /// An actuator (the `index`-th), or `None` when skipped.
    pub(super) fn actuator(&mut self, node: roxmltree::Node<'_, '_>, index: usize) -> Parsed<Option<MjcfActuator>> {
        let tag = node.tag_name().name();
        let a = Attrs::new(node, self.defaults, "main");
        for transmission in ["tendon", "site", "jointinparent", "body", "cranksite"] {
            if a.get(transmission).is_some() {
                self.unsupported(&node, &format!("an actuator driving a {transmission} (only joints are)"))?;
                return Ok(None);
            }
        }
        let kind = match tag {
            "motor" => ActuatorKind::Motor,
            "position" => {
                ActuatorKind::Position { kp: a.number("kp")?.unwrap_or(1.0), kv: a.number("kv")?.unwrap_or(0.0) }
            }
            "velocity" => ActuatorKind::Velocity { kv: a.number("kv")?.unwrap_or(1.0) },
            "general" => match general_kind(&a)? {
                Ok(kind) => kind,
                Err(why) => {
                    self.unsupported(&node, &format!("a <general> actuator with {why}"))?;
                    return Ok(None);
                }
            },
            other => {
                self.unsupported(&node, &format!("an actuator of kind <{other}>"))?;
                return Ok(None);
            }
        };
        let joint = a.get("joint").ok_or_else(|| problem(&node, "needs a joint"))?.to_string();
        let name = node.attribute("name").map_or_else(|| format!("actuator{index}"), str::to_string);
        let gear = a.numbers("gear")?.and_then(|g| g.first().copied()).unwrap_or(1.0);
        let to_problem = |e: Error| problem(&node, e.to_string());
        let mut actuator = Actuator::new(&name, kind, gear).map_err(to_problem)?;
        if let Some([lo, hi]) = self.limited(&a, "ctrl")? {
            actuator = actuator.with_ctrl_range(lo, hi).map_err(to_problem)?;
        }
        if let Some([lo, hi]) = self.limited(&a, "force")? {
            actuator = actuator.with_force_range(lo, hi).map_err(to_problem)?;
        }
        Ok(Some(MjcfActuator { name, kind: tag.to_string(), joint, actuator }))
    }
}

/// What a `<general>` actuator (`a`, with its class's defaults) becomes: its fixed
/// gain and affine bias, or (`Err`) what ARS does not model: activation dynamics
/// (`dyntype`), a gain that is not fixed, a bias that is not affine. A class whose
/// default was set by a `<position>` shortcut (its `kp`, `kv`) gives its `<general>`s
/// that servo, as MuJoCo's shared actuator default does. A `<general>` that is a
/// `position` or `velocity` shortcut written out becomes that shortcut.
fn general_kind(a: &Attrs<'_, '_>) -> Parsed<Result<ActuatorKind, String>> {
    for (attribute, plain) in [("dyntype", "none"), ("gaintype", "fixed")] {
        if let Some(value) = a.get(attribute).filter(|v| *v != plain) {
            return Ok(Err(format!("{attribute}=\"{value}\"")));
        }
    }
    let affine = match a.get("biastype") {
        None | Some("none") => false,
        Some("affine") => true,
        Some(other) => return Ok(Err(format!("biastype=\"{other}\""))),
    };
    let (gainprm, biasprm) = (a.numbers("gainprm")?, a.numbers("biasprm")?);
    if gainprm.is_none()
        && biasprm.is_none()
        && a.get("biastype").is_none()
        && let Some(kp) = a.number("kp")?
    {
        return Ok(Ok(ActuatorKind::Position { kp, kv: a.number("kv")?.unwrap_or(0.0) }));
    }
    let gain = gainprm.and_then(|g| g.first().copied()).unwrap_or(1.0);
    let mut bias = [0.0; 3];
    if affine {
        for (b, v) in bias.iter_mut().zip(biasprm.unwrap_or_default()) {
            *b = v;
        }
    }
    // MuJoCo's shortcuts written out are those shortcuts (the same arithmetic as a
    // <position> or <velocity> of the file, so the same bits).
    Ok(Ok(match bias {
        [0.0, b, v] if b == -gain && gain >= 0.0 && v <= 0.0 => ActuatorKind::Position { kp: gain, kv: -v },
        [0.0, 0.0, v] if v == -gain && gain >= 0.0 => ActuatorKind::Velocity { kv: gain },
        _ => ActuatorKind::General { gain, bias },
    }))
}
