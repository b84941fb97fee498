//! Heightfield terrains for [`Simulation::add_trimesh_floor`](super::Scene::add_trimesh_floor),
//! with the original's vertex and face layout.

use nalgebra::Point3;

use crate::error::{Error, Result};

/// Faces of a `size_x × size_z` grid of vertices (vertex index `size_z · x + z`), two
/// triangles per cell, all facing +Y, with the original's alternating diagonals:
/// the cell's type is its vertex index, plus one when `size_z` is even; an even type
/// gives `(i00, i11, i10), (i00, i01, i11)`, an odd one `(i00, i01, i10), (i01, i11, i10)`.
///
/// The grid may hold at most [`MAX_GRID_VERTICES`] vertices.
///
/// ```
/// let faces = ars_core::heightfield_triangles(2, 4)?;
/// assert_eq!(faces, [[0, 1, 4], [1, 5, 4], [1, 6, 5], [1, 2, 6], [2, 3, 6], [3, 7, 6]]);
/// # Ok::<(), ars_core::Error>(())
/// ```
pub fn heightfield_triangles(size_x: u32, size_z: u32) -> Result<Vec<[u32; 3]>> {
    check_grid(size_x, size_z)?;
    Ok(grid_faces(size_x, size_z))
}

/// Most vertices of a heightfield grid (a 2048 × 2048 grid): its faces and vertices
/// then take a few hundred megabytes, and every index fits ODE's.
pub const MAX_GRID_VERTICES: u64 = 1 << 22;

fn check_grid(size_x: u32, size_z: u32) -> Result<()> {
    if u64::from(size_x) * u64::from(size_z) > MAX_GRID_VERTICES {
        return Err(Error::OutOfRange {
            what: "heightfield size",
            detail: format!("must be at most {MAX_GRID_VERTICES} vertices, got {size_x} × {size_z}"),
        });
    }
    Ok(())
}

/// [`heightfield_triangles`] of a grid already checked.
fn grid_faces(size_x: u32, size_z: u32) -> Vec<[u32; 3]> {
    let mut faces = Vec::new();
    let index = |x: u32, z: u32| size_z * x + z;
    for x in 0..size_x.saturating_sub(1) {
        for z in 0..size_z.saturating_sub(1) {
            let (i00, i01, i10, i11) = (index(x, z), index(x, z + 1), index(x + 1, z), index(x + 1, z + 1));
            let face_type = index(x, z) + u32::from(size_z.is_multiple_of(2));
            if face_type.is_multiple_of(2) {
                faces.push([i00, i11, i10]);
                faces.push([i00, i01, i11]);
            } else {
                faces.push([i00, i01, i10]);
                faces.push([i01, i11, i10]);
            }
        }
    }
    faces
}

/// Heights on a 1 m grid of `num_x × num_z` vertices, x-major, as the original's
/// terrain generators made them.
#[derive(Clone, Debug, PartialEq)]
pub struct Heightfield {
    num_x: u32,
    num_z: u32,
    heights: Vec<f64>,
}

impl Heightfield {
    /// A grid whose height at `(x, z)` is `height(x, z)`.
    pub fn from_fn(num_x: u32, num_z: u32, mut height: impl FnMut(f64, f64) -> f64) -> Result<Self> {
        if num_x < 2 || num_z < 2 {
            return Err(Error::OutOfRange {
                what: "heightfield size",
                detail: format!("must be at least 2 × 2 vertices, got {num_x} × {num_z}"),
            });
        }
        check_grid(num_x, num_z)?;
        let mut heights = Vec::with_capacity((num_x * num_z) as usize);
        for x in 0..num_x {
            for z in 0..num_z {
                let h = height(f64::from(x), f64::from(z));
                if !h.is_finite() {
                    return Err(Error::NotFinite { what: "heightfield height", value: h.to_string() });
                }
                heights.push(h);
            }
        }
        Ok(Heightfield { num_x, num_z, heights })
    }

    /// `y = sin(x · frequency_x) · height_scale` (frequency in rad per metre).
    pub fn sinusoidal(num_x: u32, num_z: u32, height_scale: f64, frequency_x: f64) -> Result<Self> {
        Self::from_fn(num_x, num_z, |x, _| (x * frequency_x).sin() * height_scale)
    }

    /// Heights drawn uniformly from `[0, scale)` by a generator seeded with `seed`
    /// (the same seed gives the same terrain).
    pub fn random(num_x: u32, num_z: u32, scale: f64, seed: u64) -> Result<Self> {
        let mut rng = crate::random::SplitMix64::new(seed);
        Self::from_fn(num_x, num_z, |_, _| rng.uniform() * scale)
    }

    /// A flat grid at `height`.
    pub fn constant(num_x: u32, num_z: u32, height: f64) -> Result<Self> {
        Self::from_fn(num_x, num_z, |_, _| height)
    }

    /// The vertices `(x, height, z)`, x-major.
    pub fn vertices(&self) -> Vec<Point3<f64>> {
        let mut v = Vec::with_capacity(self.heights.len());
        for x in 0..self.num_x {
            for z in 0..self.num_z {
                v.push(Point3::new(f64::from(x), self.heights[(x * self.num_z + z) as usize], f64::from(z)));
            }
        }
        v
    }

    /// The triangles, see [`heightfield_triangles`].
    pub fn triangles(&self) -> Vec<[u32; 3]> {
        grid_faces(self.num_x, self.num_z)
    }

    /// Height at grid vertex `(x, z)`.
    pub fn height(&self, x: u32, z: u32) -> Option<f64> {
        (x < self.num_x && z < self.num_z).then(|| self.heights[(x * self.num_z + z) as usize])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_point_up() {
        let field = Heightfield::constant(4, 5, 0.0).unwrap();
        let v = field.vertices();
        for [a, b, c] in field.triangles() {
            let n = (v[b as usize] - v[a as usize]).cross(&(v[c as usize] - v[a as usize]));
            assert!(n.y > 0.0, "face {a} {b} {c} faces down");
        }
        assert_eq!(field.triangles().len(), 2 * 3 * 4);
    }

    #[test]
    fn generators() {
        let s = Heightfield::sinusoidal(40, 20, 0.7, 0.5).unwrap();
        assert_eq!(s.height(3, 7), Some((3.0f64 * 0.5).sin() * 0.7));
        let r1 = Heightfield::random(5, 5, 2.0, 42).unwrap();
        assert_eq!(r1, Heightfield::random(5, 5, 2.0, 42).unwrap());
        assert_ne!(r1, Heightfield::random(5, 5, 2.0, 43).unwrap());
        assert!(r1.vertices().iter().all(|p| (0.0..2.0).contains(&p.y)));
        assert!(Heightfield::constant(1, 5, 0.0).is_err());
    }
}
