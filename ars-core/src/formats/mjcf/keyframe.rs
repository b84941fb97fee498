//! `<keyframe>`: named states of a model, read and kept, not applied (MuJoCo applies
//! none when it compiles a model; its reset goes to `qpos0`).

use super::problem::{Parsed, problem};

/// A `<key>` of a `<keyframe>`: a named state of the model in MuJoCo's coordinates
/// (`qpos`, `qvel` in its joints' order; `ctrl` in its actuators'), kept as the file
/// gives it. Each list is empty where the key leaves it out.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct MjcfKeyframe {
    /// Its name (`key{N}` when unnamed, N its index).
    pub name: String,
    /// `time`, s.
    pub time: f64,
    /// `qpos`: joint positions (a free joint's 3 + 4, a ball's 4).
    pub qpos: Vec<f64>,
    /// `qvel`: joint velocities (a free joint's 6, a ball's 3).
    pub qvel: Vec<f64>,
    /// `ctrl`: the actuators' controls.
    pub ctrl: Vec<f64>,
    /// `mpos`: the mocap bodies' positions, 3 each.
    pub mpos: Vec<f64>,
    /// `mquat`: the mocap bodies' orientations, 4 each.
    pub mquat: Vec<f64>,
}

/// A `<keyframe>`'s `<key>` (the `index`th), its numbers as written.
pub(super) fn keyframe(node: roxmltree::Node<'_, '_>, index: usize) -> Parsed<MjcfKeyframe> {
    if !node.has_tag_name("key") {
        return Err(problem(&node, format!("<{}> in <keyframe> (MuJoCo's holds <key>s)", node.tag_name().name())));
    }
    let numbers = |attribute: &str| -> Parsed<Vec<f64>> {
        let Some(text) = node.attribute(attribute) else { return Ok(Vec::new()) };
        text.split_whitespace()
            .map(|n| match n.parse::<f64>() {
                Ok(v) if v.is_finite() => Ok(v),
                _ => Err(problem(&node, format!("{attribute}: {n:?} is not a finite number"))),
            })
            .collect()
    };
    let time = match numbers("time")?.as_slice() {
        [] => 0.0,
        [t] => *t,
        _ => return Err(problem(&node, "time must be one number")),
    };
    Ok(MjcfKeyframe {
        name: node.attribute("name").map_or_else(|| format!("key{index}"), str::to_string),
        time,
        qpos: numbers("qpos")?,
        qvel: numbers("qvel")?,
        ctrl: numbers("ctrl")?,
        mpos: numbers("mpos")?,
        mquat: numbers("mquat")?,
    })
}
