//! The attributes of the MJCF elements ARS reads, as MuJoCo's own schema (MuJoCo 4.0,
//! `mujoco.mj_printSchema`) gives them. An attribute MuJoCo does not know is refused
//! with its element and line, as MuJoCo refuses it; one it knows and ARS does not use
//! is accepted (and, where it changes physics, said unused where it is read).
//! `python/tests/test_mjcf.py` holds this list against MuJoCo's schema.

use super::include::Tree;
use super::problem::{Parsed, problem, skip_or_refuse};

/// The sections of the file whose elements ARS reads and checks.
pub(super) const READ_SECTIONS: [&str; 9] =
    ["compiler", "option", "default", "asset", "worldbody", "contact", "actuator", "sensor", "keyframe"];

/// The attributes every sensor has, besides its own.
const SENSOR_ATTRIBUTES: [&str; 8] = ["cutoff", "delay", "interp", "interval", "name", "noise", "nsample", "user"];

/// Each element's attributes (a world body's are a body's; a sensor's add to
/// [`SENSOR_ATTRIBUTES`]).
#[rustfmt::skip]
const ATTRIBUTES: &[(&str, &[&str])] = &[
    ("mujoco", &["model"]),
    ("include", &["file"]),
    ("keyframe", &[]),
    ("key", &["name", "time", "qpos", "qvel", "act", "ctrl", "mpos", "mquat", "plastic"]),
    ("default", &["class"]),
    ("compiler", &[
        "alignfree", "angle", "assetdir", "autolimits", "balanceinertia", "boundinertia",
        "boundmass", "conflict", "coordinate", "discardvisual", "eulerseq", "fitaabb",
        "fusestatic", "inertiafromgeom", "inertiagrouprange", "meshdir", "passthrough",
        "savecanonical", "savecompiled", "saveinertial", "settotalmass", "strippath",
        "texturedir", "usethread"
    ]),
    ("option", &[
        "actuatorgroupdisable", "ccd_iterations", "ccd_tolerance", "cone", "density", "gravity",
        "impratio", "integrator", "iterations", "jacobian", "ls_iterations", "ls_tolerance",
        "magnetic", "noslip_iterations", "noslip_tolerance", "o_friction", "o_margin", "o_solimp",
        "o_solref", "sdf_initpoints", "sdf_iterations", "sleep_tolerance", "solver", "timestep",
        "tolerance", "viscosity", "wind"
    ]),
    ("body", &[
        "axisangle", "childclass", "euler", "fuse", "gravcomp", "mocap", "name", "pos", "quat",
        "simple", "sleep", "user", "xyaxes", "zaxis"
    ]),
    ("inertial", &[
        "axisangle", "diaginertia", "euler", "fullinertia", "mass", "pos", "quat", "xyaxes",
        "zaxis"
    ]),
    ("joint", &[
        "actuatorfrclimited", "actuatorfrcrange", "actuatorgravcomp", "armature", "axis", "class",
        "damping", "frictionloss", "group", "limited", "margin", "name", "pos", "range", "ref",
        "solimpfriction", "solimplimit", "solreffriction", "solreflimit", "springdamper",
        "springref", "springyield", "stiffness", "type", "user"
    ]),
    ("freejoint", &["align", "group", "name"]),
    ("geom", &[
        "adhesion", "axisangle", "castshadow", "class", "conaffinity", "condim", "contype",
        "density", "euler", "fitscale", "fluidcoef", "fluidshape", "friction", "fromto", "gap",
        "group", "hfield", "margin", "mass", "material", "mesh", "name", "pos", "priority", "quat",
        "rgba", "shellinertia", "size", "solimp", "solmix", "solref", "surfacevel", "type", "user",
        "xyaxes", "zaxis"
    ]),
    ("site", &[
        "axisangle", "class", "euler", "fromto", "group", "material", "mesh", "name", "pos", "quat",
        "rgba", "size", "type", "user", "xyaxes", "zaxis"
    ]),
    ("mesh", &[
        "builtin", "class", "content_type", "face", "file", "inertia", "material", "maxhullvert",
        "name", "normal", "params", "refpos", "refquat", "scale", "smoothnormal", "texcoord",
        "vertex"
    ]),
    ("material", &[
        "class", "emission", "metallic", "name", "reflectance", "rgba", "roughness",
        "shininess", "specular", "texrepeat", "texture", "texuniform"
    ]),
    ("pair", &[
        "adhesion", "class", "condim", "friction", "gap", "geom1", "geom2", "margin", "name",
        "solimp", "solref", "solreffriction"
    ]),
    ("exclude", &["body1", "body2", "name"]),
    ("motor", &[
        "armature", "class", "cranklength", "cranksite", "ctrllimited", "ctrlrange", "damping",
        "delay", "forcelimited", "forcerange", "gear", "group", "interp", "joint", "jointinparent",
        "lengthrange", "name", "nsample", "refsite", "site", "slidersite", "tendon", "user"
    ]),
    ("position", &[
        "armature", "class", "cranklength", "cranksite", "ctrllimited", "ctrlrange", "damping",
        "dampratio", "delay", "forcelimited", "forcerange", "gear", "group", "inheritrange",
        "interp", "joint", "jointinparent", "kp", "kv", "lengthrange", "name", "nsample",
        "refsite", "site", "slidersite", "tendon", "timeconst", "user"
    ]),
    ("velocity", &[
        "armature", "class", "cranklength", "cranksite", "ctrllimited", "ctrlrange", "damping",
        "delay", "forcelimited", "forcerange", "gear", "group", "interp", "joint",
        "jointinparent", "kv", "lengthrange", "name", "nsample", "refsite", "site",
        "slidersite", "tendon", "user"
    ]),
    ("general", &[
        "actdim", "actearly", "actlimited", "actrange", "armature", "biasprm", "biastype",
        "body", "class", "cranklength", "cranksite", "ctrllimited", "ctrlrange", "damping",
        "delay", "dynprm", "dyntype", "ffrange", "forcelimited", "forcerange", "gainprm",
        "gaintype", "gear", "group", "inheritrange", "input", "interp", "joint", "jointinparent",
        "lengthrange", "name", "nsample", "refsite", "site", "slidersite", "tendon", "user",
        "velrange"
    ]),
    ("jointpos", &["joint"]),
    ("jointvel", &["joint"]),
    ("framepos", &["objname", "objtype", "refname", "reftype"]),
    ("framequat", &["objname", "objtype", "refname", "reftype"]),
    ("framelinvel", &["objname", "objtype", "refname", "reftype"]),
    ("accelerometer", &["site"]),
    ("gyro", &["site"]),
    ("touch", &["site"]),
    ("rangefinder", &["camera", "data", "site"]),
];

/// Whether `attribute` is unknown to MuJoCo on an element `tag` (inside `<sensor>`
/// when `in_sensor`); `false` for elements ARS does not check.
pub(super) fn is_unknown(tag: &str, attribute: &str, in_sensor: bool) -> bool {
    let tag = if tag == "worldbody" { "body" } else { tag };
    match ATTRIBUTES.iter().find(|(t, _)| *t == tag) {
        Some((_, known)) => !(known.contains(&attribute) || in_sensor && SENSOR_ATTRIBUTES.contains(&attribute)),
        None => false,
    }
}

/// Checks every element ARS reads against MuJoCo's schema
/// ([`schema`](super::schema)): an unknown attribute is an error naming it, its
/// element and line (with `skip`, a line in `skipped`).
pub(super) fn check_attributes(
    tree: &Tree<'_, '_>,
    root: roxmltree::Node<'_, '_>,
    skip: bool,
    skipped: &mut Vec<String>,
) -> Parsed<()> {
    pub(super) fn walk(
        tree: &Tree<'_, '_>,
        node: roxmltree::Node<'_, '_>,
        in_sensor: bool,
        skip: bool,
        skipped: &mut Vec<String>,
    ) -> Parsed<()> {
        let tag = node.tag_name().name();
        for attribute in node.attributes() {
            let name = attribute.name();
            if is_unknown(tag, name, in_sensor) {
                {
                    let p =
                        problem(&node, format!("unknown attribute {name:?} (MuJoCo's <{tag}> has no such attribute)"));
                    skip_or_refuse(p, skip, skipped)?;
                }
            }
        }
        // Into the sections ARS reads, and the bodies and classes in them; not into the
        // others (a tendon's <joint> is not a body's) nor below the elements read.
        let holds_elements = match tag {
            "mujoco" => node.parent().is_some_and(|p| p.is_root()),
            "body" | "worldbody" | "default" | "frame" | "replicate" => true,
            _ => READ_SECTIONS.contains(&tag) && node.parent_element().is_some_and(|p| p.has_tag_name("mujoco")),
        };
        if holds_elements {
            for child in tree.elements(node) {
                walk(tree, child, in_sensor || tag == "sensor", skip, skipped)?;
            }
        }
        Ok(())
    }
    walk(tree, root, false, skip, skipped)?;
    Ok(())
}
