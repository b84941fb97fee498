//! A URDF robot as read: links, joints and materials, with the numbers the file gives
//! (and the defaults it leaves to the reader). The types keep the shape of the
//! `urdf-rs` crate's, which ARS read URDF with before [`read`](super::read): the
//! builder consumes them unchanged.

/// Three numbers: a position, angles, a direction, a size or a scale.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Vec3(pub(super) [f64; 3]);

/// Four numbers: a colour's red, green, blue and alpha.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Vec4(pub(super) [f64; 4]);

/// An `<origin>`: a translation `xyz` and fixed-axis angles `rpy` (roll about X, pitch
/// about Y, yaw about Z), both zero when absent.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Pose {
    pub(super) xyz: Vec3,
    pub(super) rpy: Vec3,
}

/// A link's `<mass value>`, kg.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Mass {
    pub(super) value: f64,
}

/// A link's inertia tensor about its centre of mass, in its inertial frame, kg·m².
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Inertia {
    pub(super) ixx: f64,
    pub(super) ixy: f64,
    pub(super) ixz: f64,
    pub(super) iyy: f64,
    pub(super) iyz: f64,
    pub(super) izz: f64,
}

/// A link's `<inertial>`: all zero (no mass) when the link has none.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Inertial {
    pub(super) origin: Pose,
    pub(super) mass: Mass,
    pub(super) inertia: Inertia,
}

/// A shape of a `<visual>` or `<collision>`.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Geometry {
    /// Full edge lengths.
    Box {
        size: Vec3,
    },
    /// Along the element's Z.
    Cylinder {
        radius: f64,
        length: f64,
    },
    /// Along the element's Z; `length` excludes the caps.
    Capsule {
        radius: f64,
        length: f64,
    },
    Sphere {
        radius: f64,
    },
    /// A mesh file (`package://`, `file://`, absolute or relative), scaled.
    Mesh {
        filename: String,
        scale: Option<Vec3>,
    },
}

/// A colour: red, green, blue, alpha, from 0 to 1.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Color {
    pub(super) rgba: Vec4,
}

/// A `<material>`: of the robot (named, for visuals to refer to), or of a visual (its
/// own colour, or the name of the robot's material).
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Material {
    pub(super) name: String,
    pub(super) color: Option<Color>,
}

/// A `<visual>`: what is drawn.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Visual {
    pub(super) origin: Pose,
    pub(super) geometry: Geometry,
    pub(super) material: Option<Material>,
}

/// A `<collision>`: what collides.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Collision {
    pub(super) origin: Pose,
    pub(super) geometry: Geometry,
}

/// A `<link>`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Link {
    pub(super) name: String,
    pub(super) inertial: Inertial,
    pub(super) visual: Vec<Visual>,
    pub(super) collision: Vec<Collision>,
    /// The line of its `<link>` tag, from 1.
    pub(super) line: u32,
}

/// A joint's kind (`type`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum JointType {
    Revolute,
    Continuous,
    Prismatic,
    Fixed,
    Floating,
    Planar,
    /// Not in the URDF specification; written by some tools (PyBullet reads it).
    Spherical,
}

/// A link a joint names (`<parent link>`, `<child link>`).
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct LinkName {
    pub(super) link: String,
}

/// A joint's `<axis xyz>`: (1, 0, 0) when absent.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Axis {
    pub(super) xyz: Vec3,
}

impl Default for Axis {
    fn default() -> Self {
        Axis { xyz: Vec3([1.0, 0.0, 0.0]) }
    }
}

/// A joint's `<limit>`: each attribute 0 when absent (effort and velocity 0: no limit).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct JointLimit {
    pub(super) lower: f64,
    pub(super) upper: f64,
    pub(super) effort: f64,
    pub(super) velocity: f64,
}

/// A joint's `<dynamics>`: viscous (`damping`) and dry (`friction`) friction.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(super) struct Dynamics {
    pub(super) damping: f64,
    pub(super) friction: f64,
}

/// A joint's `<mimic>`: it follows `joint` as `multiplier · q + offset`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Mimic {
    pub(super) joint: String,
    pub(super) multiplier: Option<f64>,
    pub(super) offset: Option<f64>,
}

/// A `<joint>`.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Joint {
    pub(super) name: String,
    pub(super) joint_type: JointType,
    pub(super) origin: Pose,
    pub(super) parent: LinkName,
    pub(super) child: LinkName,
    pub(super) axis: Axis,
    pub(super) limit: JointLimit,
    pub(super) dynamics: Option<Dynamics>,
    pub(super) mimic: Option<Mimic>,
    /// The line of its `<joint>` tag, from 1.
    pub(super) line: u32,
}

/// A `<robot>`.
#[derive(Clone, Debug, Default, PartialEq)]
pub(super) struct Robot {
    pub(super) name: String,
    pub(super) links: Vec<Link>,
    pub(super) joints: Vec<Joint>,
    /// The robot-level materials, which visuals name.
    pub(super) materials: Vec<Material>,
}
