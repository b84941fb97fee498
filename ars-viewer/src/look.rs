//! What an object looks like, with no GPU: the shapes it is drawn as (each posed
//! relative to the object, each with its colour), its colour and whether it moves.
//! The window's and the off-screen renderer's scene nodes ([`crate::scene`]) and the
//! browser replay ([`crate::replay`]) are built from this one description.

use ars_core::nalgebra::Isometry3;
use ars_core::{ObjectId, Shape, Simulation};

/// Colours given to objects that have none, in creation order.
const PALETTE: [[f32; 3]; 6] =
    [[0.8, 0.1, 0.1], [0.1, 0.3, 0.8], [0.9, 0.7, 0.1], [0.1, 0.6, 0.2], [0.6, 0.2, 0.7], [0.9, 0.4, 0.1]];
/// The floor's colour (the original's 0.7 grey).
const FLOOR: [f32; 3] = [0.7, 0.7, 0.7];
/// Half the side of the square drawn for an infinite floor plane, m.
pub(crate) const PLANE_HALF_SIZE: f32 = 25.0;

/// One shape an object is drawn as.
pub(crate) struct Part {
    /// The shape, in its own frame.
    pub(crate) shape: Shape,
    /// Its pose relative to the object's.
    pub(crate) local: Isometry3<f64>,
    /// Its colour, RGB in [0, 1].
    pub(crate) color: [f32; 3],
}

/// How an object is drawn.
pub(crate) struct Look {
    /// Whether it has a body (it moves; a static object keeps the pose it was made at).
    pub(crate) dynamic: bool,
    /// Whether it is a floor (a static plane or mesh): checkered when drawn fast.
    pub(crate) floor: bool,
    /// The colour it is drawn with (its own, or the palette's).
    pub(crate) color: [f32; 3],
    /// Its pose now.
    pub(crate) pose: Isometry3<f64>,
    /// What it is drawn as.
    pub(crate) parts: Vec<Part>,
}

/// How `id` is drawn, `index` being the number of objects drawn before it (objects
/// without a colour take the palette's in that order).
pub(crate) fn look_of(sim: &Simulation, id: ObjectId, index: usize) -> ars_core::Result<Look> {
    let object = sim.scene().object(id)?;
    let dynamic = object.body_handle().is_some();
    let flat = matches!(object.shape(), Shape::Plane { .. } | Shape::TriMesh { .. });
    let default = if flat { FLOOR } else { PALETTE[index % PALETTE.len()] };
    let color = object.color().unwrap_or(default);
    let pose = sim.scene().pose(id).unwrap_or(Isometry3::identity());
    // Its visuals if it has any (a robot link's <visual>s), else each of its geoms
    // where it is relative to the object (a robot link may have several, offset from
    // its body); an object without either is drawn as its shape.
    let world = sim.scene().world();
    let mut parts: Vec<Part> = if object.visuals().is_empty() {
        object
            .geoms()
            .filter_map(|g| world.geom(g).ok())
            .map(|g| {
                let local = match g.shape() {
                    Shape::Plane { .. } => Isometry3::identity(),
                    _ => pose.inverse() * g.pose(),
                };
                Part { shape: g.shape().clone(), local, color }
            })
            .collect()
    } else {
        object
            .visuals()
            .iter()
            .map(|v| Part { shape: v.shape.clone(), local: v.offset, color: v.color.unwrap_or(color) })
            .collect()
    };
    if parts.is_empty() {
        parts.push(Part { shape: object.shape().clone(), local: Isometry3::identity(), color });
    }
    Ok(Look { dynamic, floor: !dynamic && flat, color, pose, parts })
}
