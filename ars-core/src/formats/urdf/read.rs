//! Reading URDF text into a [`Robot`], as people write it and as PyBullet and ROS's
//! urdfdom read it:
//!
//! - only `<link>`, `<joint>` and `<material>` children of `<robot>` are read; other
//!   elements (`<gazebo>`, `<transmission>`, xacro's) are ignored, and so is what a
//!   read element holds that URDF does not define (a `<material>` inside `<geometry>`,
//!   a `<texture>`), as urdfdom does;
//! - of an element that should be there once (`<inertial>`, `<origin>`, `<axis>`,
//!   `<limit>`, a `<geometry>`'s shape), the first is read; a second `<axis>` is noted;
//! - defaults: no `<inertial>`, no mass; `<origin>` and each of its attributes zero;
//!   `<axis>` (1, 0, 0); each `<limit>` attribute 0 (`effort` and `velocity` 0: no
//!   limit, as PyBullet reads a limit without them; urdfdom refuses it); `<dynamics>`
//!   attributes 0; an `<inertia>` attribute absent, 0;
//! - numbers as [`values`](super::values) reads them (commas, extra numbers,
//!   `$(optenv)`); one that is not a number is refused, naming the link or joint, the
//!   element, the attribute and the line;
//! - a `<visual>` or `<collision>` without a shape, or whose shape ARS does not have
//!   (PyBullet's `<plane>` and `<cdf>`), is skipped with a note (PyBullet loads the
//!   link without what it cannot make);
//! - a `<mimic>` ARS cannot follow (its leader is not in the file, or is not a joint
//!   moving alike: a fixed joint that "follows" a hinge) is dropped with a note:
//!   PyBullet does not read mimics at all.

use roxmltree::Node;

use super::model::{
    Axis, Collision, Color, Dynamics, Geometry, Inertia, Inertial, Joint, JointLimit, JointType, Link, LinkName, Mass,
    Material, Mimic, Pose, Robot, Vec3, Vec4, Visual,
};
use super::values::{Parsed, Problem, Values, line_of, missing, problem};

/// A robot read, and a line for each thing read leniently or skipped.
pub(super) struct Read {
    pub(super) robot: Robot,
    pub(super) notes: Vec<String>,
}

/// Reads a URDF document (see the [module docs](self)).
pub(super) fn read(text: &str) -> Parsed<Read> {
    // NUL bytes after the document (pybullet_data/humanoid/humanoid.urdf ends with one)
    // are no XML, but xml-rs and TinyXML read past them.
    let text = text.trim_end_matches(|c: char| c == '\0' || c.is_whitespace());
    let options = roxmltree::ParsingOptions { allow_dtd: true, ..Default::default() };
    let document = roxmltree::Document::parse_with_options(text, options).map_err(|e| Problem {
        element: "robot".into(),
        line: e.pos().row,
        text: format!("not XML: {e}"),
    })?;
    let root = document.root_element();
    if root.tag_name().name() != "robot" {
        return Err(problem("robot", &root, format!("the root element is <{}>, not <robot>", root.tag_name().name())));
    }
    let mut notes = Vec::new();
    let mut robot = Robot { name: root.attribute("name").unwrap_or_default().to_string(), ..Robot::default() };
    let mut reader = Reader { values: Values { notes: &mut notes } };
    for node in root.children().filter(Node::is_element) {
        match node.tag_name().name() {
            "link" => robot.links.push(reader.link(&node)?),
            "joint" => robot.joints.push(reader.joint(&node)?),
            "material" => robot.materials.push(reader.material("robot", &node)?),
            _ => {}
        }
    }
    drop_unusable_mimics(&mut robot, &mut notes);
    Ok(Read { robot, notes })
}

/// The first child element named `name`.
fn child<'a, 'i>(node: &Node<'a, 'i>, name: &str) -> Option<Node<'a, 'i>> {
    node.children().find(|n| n.is_element() && n.tag_name().name() == name)
}

/// Every child element named `name`.
fn children<'a, 'i>(node: &Node<'a, 'i>, name: &'static str) -> impl Iterator<Item = Node<'a, 'i>> {
    node.children().filter(move |n| n.is_element() && n.tag_name().name() == name)
}

/// An attribute that must be there: its text.
fn text_attribute<'a>(owner: &str, node: &Node<'a, '_>, attribute: &str) -> Parsed<&'a str> {
    node.attribute(attribute).ok_or_else(|| missing(owner, node, attribute))
}

struct Reader<'n> {
    values: Values<'n>,
}

impl Reader<'_> {
    fn link(&mut self, node: &Node<'_, '_>) -> Parsed<Link> {
        let name = text_attribute("<link>", node, "name")?.to_string();
        let owner = format!("link {name:?}");
        let inertial = match child(node, "inertial") {
            Some(n) => self.inertial(&owner, &n)?,
            None => Inertial::default(),
        };
        let mut visual = Vec::new();
        for v in children(node, "visual") {
            let Some(geometry) = self.geometry(&owner, &v)? else { continue };
            let material = child(&v, "material").map(|m| self.material(&owner, &m)).transpose()?;
            visual.push(Visual { origin: self.origin(&owner, &v)?, geometry, material });
        }
        let mut collision = Vec::new();
        for c in children(node, "collision") {
            let Some(geometry) = self.geometry(&owner, &c)? else { continue };
            collision.push(Collision { origin: self.origin(&owner, &c)?, geometry });
        }
        Ok(Link { name, inertial, visual, collision, line: line_of(node) })
    }

    fn inertial(&mut self, owner: &str, node: &Node<'_, '_>) -> Parsed<Inertial> {
        let origin = self.origin(owner, node)?;
        let mass = match child(node, "mass") {
            Some(m) => self.values.number_or(owner, &m, "value", 0.0)?,
            None => 0.0,
        };
        let mut inertia = Inertia::default();
        if let Some(i) = child(node, "inertia") {
            let mut get = |attribute| self.values.number_or(owner, &i, attribute, 0.0);
            inertia = Inertia {
                ixx: get("ixx")?,
                ixy: get("ixy")?,
                ixz: get("ixz")?,
                iyy: get("iyy")?,
                iyz: get("iyz")?,
                izz: get("izz")?,
            };
        }
        Ok(Inertial { origin, mass: Mass { value: mass }, inertia })
    }

    /// The `<origin>` child of `node` (zero when absent).
    fn origin(&mut self, owner: &str, node: &Node<'_, '_>) -> Parsed<Pose> {
        let Some(o) = child(node, "origin") else { return Ok(Pose::default()) };
        let xyz = self.values.vector::<3>(owner, &o, "xyz")?.unwrap_or_default();
        let rpy = self.values.vector::<3>(owner, &o, "rpy")?.unwrap_or_default();
        Ok(Pose { xyz: Vec3(xyz), rpy: Vec3(rpy) })
    }

    /// The shape of a `<visual>` or `<collision>`; `None` (with a note) when it has none
    /// or one ARS does not have.
    fn geometry(&mut self, owner: &str, element: &Node<'_, '_>) -> Parsed<Option<Geometry>> {
        let kind = element.tag_name().name();
        let shape = child(element, "geometry").and_then(|g| g.children().find(Node::is_element));
        let Some(shape) = shape else {
            let line = line_of(element);
            self.values.notes.push(format!("{owner}: the <{kind}> at line {line} has no shape: skipped"));
            return Ok(None);
        };
        let v = &mut self.values;
        let geometry = match shape.tag_name().name() {
            "box" => {
                let size = v.vector::<3>(owner, &shape, "size")?.ok_or_else(|| missing(owner, &shape, "size"))?;
                Geometry::Box { size: Vec3(size) }
            }
            "cylinder" => Geometry::Cylinder {
                radius: v.required(owner, &shape, "radius")?,
                length: v.required(owner, &shape, "length")?,
            },
            "capsule" => Geometry::Capsule {
                radius: v.required(owner, &shape, "radius")?,
                length: v.required(owner, &shape, "length")?,
            },
            "sphere" => Geometry::Sphere { radius: v.required(owner, &shape, "radius")? },
            "mesh" => Geometry::Mesh {
                filename: text_attribute(owner, &shape, "filename")?.to_string(),
                scale: v.vector::<3>(owner, &shape, "scale")?.map(Vec3),
            },
            other => {
                let line = line_of(&shape);
                v.notes.push(format!(
                    "{owner}: the <{kind}>'s <{other}> at line {line}: ARS has no such shape: skipped \
                     (ARS reads box, cylinder, capsule, sphere and mesh)"
                ));
                return Ok(None);
            }
        };
        Ok(Some(geometry))
    }

    /// A `<material>`: its name and its own `<color>`, if any.
    fn material(&mut self, owner: &str, node: &Node<'_, '_>) -> Parsed<Material> {
        let name = node.attribute("name").unwrap_or_default().to_string();
        let color = match child(node, "color") {
            Some(c) => self.values.vector::<4>(owner, &c, "rgba")?.map(|rgba| Color { rgba: Vec4(rgba) }),
            None => None,
        };
        Ok(Material { name, color })
    }

    fn joint(&mut self, node: &Node<'_, '_>) -> Parsed<Joint> {
        let name = text_attribute("<joint>", node, "name")?.to_string();
        let owner = format!("joint {name:?}");
        let joint_type = joint_type(&owner, node)?;
        let link_of = |tag: &str| -> Parsed<LinkName> {
            let n = child(node, tag).ok_or_else(|| problem(&owner, node, format!("<joint> needs a <{tag}>")))?;
            Ok(LinkName { link: text_attribute(&owner, &n, "link")?.to_string() })
        };
        let (parent, child_link) = (link_of("parent")?, link_of("child")?);
        let mut axes = children(node, "axis");
        let axis = match axes.next() {
            Some(a) => Axis { xyz: Vec3(self.values.vector::<3>(&owner, &a, "xyz")?.unwrap_or([1.0, 0.0, 0.0])) },
            None => Axis::default(),
        };
        if let Some(second) = axes.next() {
            let line = line_of(&second);
            self.values.notes.push(format!(
                "{owner}: a second <axis> at line {line} is ignored: the first is read, as urdfdom and PyBullet do"
            ));
        }
        let limit = match child(node, "limit") {
            Some(l) => self.limit(&owner, &l)?,
            None => JointLimit::default(),
        };
        let dynamics = match child(node, "dynamics") {
            Some(d) => Some(Dynamics {
                damping: self.values.number_or(&owner, &d, "damping", 0.0)?,
                friction: self.values.number_or(&owner, &d, "friction", 0.0)?,
            }),
            None => None,
        };
        let mimic = match child(node, "mimic") {
            Some(m) => Some(Mimic {
                joint: text_attribute(&owner, &m, "joint")?.to_string(),
                multiplier: self.values.number(&owner, &m, "multiplier")?,
                offset: self.values.number(&owner, &m, "offset")?,
            }),
            None => None,
        };
        let origin = self.origin(&owner, node)?;
        let line = line_of(node);
        Ok(Joint { name, joint_type, origin, parent, child: child_link, axis, limit, dynamics, mimic, line })
    }

    fn limit(&mut self, owner: &str, node: &Node<'_, '_>) -> Parsed<JointLimit> {
        Ok(JointLimit {
            lower: self.values.number_or(owner, node, "lower", 0.0)?,
            upper: self.values.number_or(owner, node, "upper", 0.0)?,
            effort: self.values.number_or(owner, node, "effort", 0.0)?,
            velocity: self.values.number_or(owner, node, "velocity", 0.0)?,
        })
    }
}

/// A joint's `type`, which must be one URDF (or PyBullet's `spherical`) has.
fn joint_type(owner: &str, node: &Node<'_, '_>) -> Parsed<JointType> {
    Ok(match text_attribute(owner, node, "type")? {
        "revolute" => JointType::Revolute,
        "continuous" => JointType::Continuous,
        "prismatic" => JointType::Prismatic,
        "fixed" => JointType::Fixed,
        "floating" => JointType::Floating,
        "planar" => JointType::Planar,
        "spherical" => JointType::Spherical,
        other => {
            return Err(problem(
                owner,
                node,
                format!(
                    "type {other:?} is not a URDF joint type (revolute, continuous, prismatic, fixed, floating, \
                     planar; or spherical)"
                ),
            ));
        }
    })
}

/// Drops each `<mimic>` ARS cannot follow, with a note: its leader is not in the file,
/// is the joint itself, or does not move alike (both must be hinges — revolute,
/// continuous — or both prismatic).
fn drop_unusable_mimics(robot: &mut Robot, notes: &mut Vec<String>) {
    let types: Vec<(String, JointType)> = robot.joints.iter().map(|j| (j.name.clone(), j.joint_type)).collect();
    let rotation = |t: JointType| match t {
        JointType::Revolute | JointType::Continuous => Some(true),
        JointType::Prismatic => Some(false),
        _ => None,
    };
    for joint in &mut robot.joints {
        let Some(mimic) = &joint.mimic else { continue };
        let leader = types.iter().find(|(name, _)| *name == mimic.joint).map(|(_, t)| *t);
        let why = match leader {
            None => format!("names joint {:?}, which is not in the file", mimic.joint),
            Some(_) if mimic.joint == joint.name => "names the joint itself".to_string(),
            Some(t) if rotation(t).is_none() || rotation(t) != rotation(joint.joint_type) => format!(
                "a {} joint cannot follow joint {:?}, a {} joint (a rotation follows a rotation, a translation a \
                 translation)",
                type_name(joint.joint_type),
                mimic.joint,
                type_name(t)
            ),
            Some(_) => continue,
        };
        notes.push(format!(
            "joint {:?} (line {}): its <mimic> {why}: dropped (PyBullet ignores mimics)",
            joint.name, joint.line
        ));
        joint.mimic = None;
    }
}

/// A joint type as URDF writes it.
fn type_name(t: JointType) -> &'static str {
    match t {
        JointType::Revolute => "revolute",
        JointType::Continuous => "continuous",
        JointType::Prismatic => "prismatic",
        JointType::Fixed => "fixed",
        JointType::Floating => "floating",
        JointType::Planar => "planar",
        JointType::Spherical => "spherical",
    }
}
