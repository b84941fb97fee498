//! `<option><flag>`s as MuJoCo reads them: those that turn off what ARS builds
//! (contacts, gravity, every constraint or one kind of them, springs, dampers) turn it
//! off in the model read; one at MuJoCo's default changes nothing; any other is said
//! unused.

use nalgebra::Vector3;

use super::model::{Body, Model};
use super::problem::problem;

/// MuJoCo 4.0's `<flag>`s that are on unless disabled (`mjtDisableBit`).
#[rustfmt::skip]
const DISABLE_FLAGS: [&str; 20] = [
    "actuation", "autoreset", "clampctrl", "constraint", "contact", "damper", "equality",
    "eulerdamp", "filterparent", "frictionloss", "gravity", "island", "limit", "midphase",
    "multiccd", "nativeccd", "refsafe", "sensor", "spring", "warmstart",
];

/// MuJoCo 4.0's `<flag>`s that are off unless enabled (`mjtEnableBit`).
const ENABLE_FLAGS: [&str; 8] =
    ["diagexact", "energy", "fwdinv", "invdiscrete", "ipc", "override", "sleep", "speculative"];

/// What a model's `<flag>`s turn off, and those ARS does not apply.
#[derive(Debug, Default)]
pub(super) struct Flags {
    /// `contact` (or `constraint`) disabled: no contact at all.
    contact: bool,
    /// `gravity` disabled.
    gravity: bool,
    /// `equality` (or `constraint`) disabled: no equality constraint.
    equality: bool,
    /// `limit` (or `constraint`) disabled: no joint range.
    limit: bool,
    /// `frictionloss` (or `constraint`) disabled: no joint's dry friction.
    frictionloss: bool,
    /// `spring` disabled: no joint's stiffness.
    spring: bool,
    /// `damper` disabled: no joint's damping.
    damper: bool,
    /// The `<flag>`s read and not used, one line each.
    unused: Vec<String>,
}

impl Flags {
    /// Reads a `<flag>` element's attributes.
    pub(super) fn read(&mut self, flag: roxmltree::Node<'_, '_>) {
        for attribute in flag.attributes() {
            match (attribute.name(), attribute.value()) {
                ("contact", "disable") => self.contact = true,
                ("gravity", "disable") => self.gravity = true,
                ("equality", "disable") => self.equality = true,
                ("limit", "disable") => self.limit = true,
                ("frictionloss", "disable") => self.frictionloss = true,
                ("spring", "disable") => self.spring = true,
                ("damper", "disable") => self.damper = true,
                // MuJoCo's constraints: equalities, dry friction, limits and contacts.
                ("constraint", "disable") => {
                    (self.contact, self.equality, self.limit, self.frictionloss) = (true, true, true, true);
                }
                // MuJoCo's own default: nothing changes.
                (name, "enable") if DISABLE_FLAGS.contains(&name) => {}
                (name, "disable") if ENABLE_FLAGS.contains(&name) => {}
                (name, value) => self
                    .unused
                    .push(format!("<flag> at line {}: {name}=\"{value}\" is not used", problem(&flag, "").line)),
            }
        }
    }

    /// Turns off in `model` what the flags turn off; the unused ones go to its
    /// `skipped` list.
    pub(super) fn apply(self, model: &mut Model) {
        if self.contact {
            for geom in &mut model.world_geoms {
                geom.bits = (0, 0);
            }
            model.pairs.clear();
        }
        if self.gravity {
            model.gravity = Some(Vector3::zeros());
        }
        if self.equality {
            model.equalities.clear();
        }
        each_body(&mut model.bodies, &mut |body| {
            if self.contact {
                body.geoms.iter_mut().for_each(|g| g.bits = (0, 0));
            }
            for joint in &mut body.joints {
                if self.limit {
                    joint.range = None;
                }
                if self.frictionloss {
                    joint.frictionloss = 0.0;
                }
                if self.spring {
                    joint.spring.0 = 0.0;
                }
                if self.damper {
                    joint.damping = 0.0;
                }
            }
        });
        model.skipped.extend(self.unused);
    }
}

/// Calls `f` on each of `bodies` and every body below them.
fn each_body(bodies: &mut [Body], f: &mut impl FnMut(&mut Body)) {
    for body in bodies {
        f(body);
        each_body(&mut body.children, f);
    }
}
