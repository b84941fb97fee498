//! `<compiler>` settings, `<default>` classes and an element's attributes with its
//! class's defaults under them; frames and orientations as MuJoCo reads them.

use std::collections::HashMap;

use nalgebra::{Isometry3, Matrix3, Rotation3, Translation3, Unit, UnitQuaternion, Vector3};

use super::include::Tree;
use super::problem::{Parsed, problem};

/// `<compiler>` settings.
#[derive(Clone, Debug)]
pub(super) struct Compiler {
    pub(super) degrees: bool,
    pub(super) eulerseq: [u8; 3],
    /// Extrinsic (capital letters) or intrinsic rotations.
    pub(super) extrinsic: bool,
    pub(super) autolimits: bool,
    /// `inertiafromgeom`: Some(true) always, Some(false) never, None when no inertial.
    pub(super) from_geom: Option<bool>,
    /// `inertiagrouprange`: the geom groups whose geoms make up their bodies' masses.
    pub(super) inertia_groups: [f64; 2],
    /// `settotalmass`: every body's mass and inertia scaled so that they add up to it.
    pub(super) total_mass: Option<f64>,
    /// `meshdir` (else `assetdir`): where mesh files are, relative to the model's folder.
    pub(super) meshdir: Option<String>,
    /// `boundmass` and `boundinertia`: the least mass and principal moment of every
    /// moving body.
    pub(super) bounds: (f64, f64),
}

impl Default for Compiler {
    fn default() -> Self {
        Compiler {
            degrees: true,
            eulerseq: [0, 1, 2],
            extrinsic: false,
            autolimits: true,
            from_geom: None,
            inertia_groups: [0.0, 5.0],
            total_mass: None,
            meshdir: None,
            bounds: (0.0, 0.0),
        }
    }
}

/// The attributes an element gets from its class, by element kind.
pub(super) type Defaults = HashMap<String, HashMap<String, HashMap<String, String>>>;

/// The actuator elements: in a `<default>` class they all set one actuator default, as
/// in MuJoCo (a class's `<general ctrlrange>` applies to its `<motor>`s).
pub(super) const ACTUATOR_KINDS: [&str; 9] =
    ["general", "motor", "position", "velocity", "intvelocity", "damper", "cylinder", "muscle", "adhesion"];

/// Where an element's defaults are kept in a class: under its tag, or under
/// `actuator` for every actuator kind.
pub(super) fn default_kind(tag: &str) -> &str {
    if ACTUATOR_KINDS.contains(&tag) { "actuator" } else { tag }
}

/// Reads `<default>` classes (with inheritance) into `out`.
pub(super) fn read_defaults<'a, 'input>(
    tree: &Tree<'a, 'input>,
    node: roxmltree::Node<'a, 'input>,
    parent: &HashMap<String, HashMap<String, String>>,
    out: &mut Defaults,
) {
    let class = node.attribute("class").unwrap_or("main").to_string();
    let mut mine = parent.clone();
    let children = tree.elements(node);
    for child in children.iter().filter(|c| c.tag_name().name() != "default") {
        let attrs = mine.entry(default_kind(child.tag_name().name()).to_string()).or_default();
        for a in child.attributes() {
            attrs.insert(a.name().to_string(), a.value().to_string());
        }
    }
    for child in children.into_iter().filter(|c| c.tag_name().name() == "default") {
        read_defaults(tree, child, &mine, out);
    }
    out.insert(class, mine);
}

/// An element's attributes with its class's defaults under them.
pub(super) struct Attrs<'a, 'input> {
    pub(super) node: roxmltree::Node<'a, 'input>,
    pub(super) class: Option<&'a HashMap<String, String>>,
}

impl<'a, 'input> Attrs<'a, 'input> {
    pub(super) fn new(node: roxmltree::Node<'a, 'input>, defaults: &'a Defaults, class: &str) -> Self {
        let class = node.attribute("class").unwrap_or(class);
        let class = defaults.get(class).and_then(|c| c.get(default_kind(node.tag_name().name())));
        Attrs { node, class }
    }
    pub(super) fn get(&self, name: &str) -> Option<&str> {
        self.node.attribute(name).or_else(|| self.class.and_then(|c| c.get(name)).map(String::as_str))
    }
    pub(super) fn numbers(&self, name: &str) -> Parsed<Option<Vec<f64>>> {
        let Some(text) = self.get(name) else { return Ok(None) };
        let values: std::result::Result<Vec<f64>, _> = text.split_whitespace().map(str::parse::<f64>).collect();
        match values {
            Ok(v) if v.iter().all(|x| x.is_finite()) => Ok(Some(v)),
            _ => Err(problem(&self.node, format!("{name}=\"{text}\" is not a list of finite numbers"))),
        }
    }
    pub(super) fn fixed<const N: usize>(&self, name: &str) -> Parsed<Option<[f64; N]>> {
        match self.numbers(name)? {
            None => Ok(None),
            Some(v) => v
                .try_into()
                .map(Some)
                .map_err(|v: Vec<f64>| problem(&self.node, format!("{name} has {} numbers, {N} expected", v.len()))),
        }
    }
    pub(super) fn number(&self, name: &str) -> Parsed<Option<f64>> {
        Ok(self.fixed::<1>(name)?.map(|[x]| x))
    }
}

/// The frame an element's `pos` and orientation attributes give, relative to its parent.
pub(super) fn frame(a: &Attrs<'_, '_>, compiler: &Compiler) -> Parsed<Isometry3<f64>> {
    let pos = Vector3::from(a.fixed::<3>("pos")?.unwrap_or([0.0; 3]));
    Ok(Isometry3::from_parts(Translation3::from(pos), orientation(a, compiler)?))
}

/// The turn of Euler angles `e`, in the compiler's unit and sequence.
pub(super) fn euler_turn(e: [f64; 3], compiler: &Compiler) -> UnitQuaternion<f64> {
    let mut q = UnitQuaternion::identity();
    for (i, axis) in compiler.eulerseq.iter().enumerate() {
        let unit = match axis {
            0 => Vector3::x_axis(),
            1 => Vector3::y_axis(),
            _ => Vector3::z_axis(),
        };
        let angle = if compiler.degrees { e[i].to_radians() } else { e[i] };
        let turn = UnitQuaternion::from_axis_angle(&unit, angle);
        q = if compiler.extrinsic { turn * q } else { q * turn };
    }
    q
}

pub(super) fn orientation(a: &Attrs<'_, '_>, compiler: &Compiler) -> Parsed<UnitQuaternion<f64>> {
    let angle = |x: f64| if compiler.degrees { x.to_radians() } else { x };
    let given: Vec<&str> = ["quat", "euler", "axisangle", "xyaxes", "zaxis"]
        .into_iter()
        .filter(|n| a.node.attribute(*n).is_some())
        .collect();
    if given.len() > 1 {
        return Err(problem(&a.node, format!("has more than one orientation: {}", given.join(", "))));
    }
    if let Some([w, x, y, z]) = a.fixed::<4>("quat")? {
        let q = nalgebra::Quaternion::new(w, x, y, z);
        if q.norm() == 0.0 {
            return Err(problem(&a.node, "quat is zero"));
        }
        return Ok(UnitQuaternion::from_quaternion(q));
    }
    if let Some([x, y, z, t]) = a.fixed::<4>("axisangle")? {
        let axis =
            Unit::try_new(Vector3::new(x, y, z), 1e-12).ok_or_else(|| problem(&a.node, "axisangle's axis is zero"))?;
        return Ok(UnitQuaternion::from_axis_angle(&axis, angle(t)));
    }
    if let Some(e) = a.fixed::<3>("euler")? {
        return Ok(euler_turn(e, compiler));
    }
    if let Some(v) = a.fixed::<6>("xyaxes")? {
        let x = Vector3::new(v[0], v[1], v[2]);
        let y = Vector3::new(v[3], v[4], v[5]);
        let x = x.try_normalize(1e-12).ok_or_else(|| problem(&a.node, "xyaxes' x axis is zero"))?;
        let y =
            (y - x * x.dot(&y)).try_normalize(1e-12).ok_or_else(|| problem(&a.node, "xyaxes' axes are parallel"))?;
        let m = Matrix3::from_columns(&[x, y, x.cross(&y)]);
        return Ok(UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m)));
    }
    if let Some(z) = a.fixed::<3>("zaxis")? {
        let z = Vector3::from(z);
        return UnitQuaternion::rotation_between(&Vector3::z(), &z)
            .or_else(|| (z.z < 0.0).then(|| UnitQuaternion::from_axis_angle(&Vector3::x_axis(), std::f64::consts::PI)))
            .ok_or_else(|| problem(&a.node, "zaxis is zero"));
    }
    Ok(UnitQuaternion::identity())
}
