//! The mass of the solid a closed triangle mesh bounds: what mesh shapes, their convex
//! hulls and the importers weigh.

use nalgebra::{Point3, Vector3};

/// A mesh's vertices and triangles (three vertex indices each).
pub(crate) type Triangles = (Vec<Point3<f64>>, Vec<[u32; 3]>);

/// The mass properties of the solid a closed triangle mesh bounds (counter-clockwise
/// triangles seen from outside), at a density of 1: its volume, its centre of mass,
/// and its inertia tensor about that centre, in the mesh's frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MeshMass {
    /// Volume, m³ (the mass at a density of 1 kg/m³).
    pub volume: f64,
    /// Centre of mass, m.
    pub centre: Point3<f64>,
    /// Inertia tensor about the centre of mass per kg/m³ of density, kg·m² per kg/m³.
    pub inertia: nalgebra::Matrix3<f64>,
}

/// The [`MeshMass`] of a mesh: `None` when it encloses no volume (open, flat, or wound
/// the wrong way round) or a triangle names a vertex it does not have. Exact for a
/// closed mesh: each triangle's tetrahedron from the origin, with its signed volume and
/// second moments.
///
/// ```
/// use ars_core::shape::mass_properties;
/// use nalgebra::Point3;
/// // The unit cube [0, 1]³, two triangles a face, wound outwards.
/// let v: Vec<Point3<f64>> = (0..8).map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect();
/// let t = [[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
///          [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]];
/// let m = mass_properties(&v, &t).unwrap();
/// assert!((m.volume - 1.0).abs() < 1e-12);
/// assert!((m.centre - Point3::new(0.5, 0.5, 0.5)).norm() < 1e-12);
/// assert!((m.inertia[(0, 0)] - 1.0 / 6.0).abs() < 1e-12 && m.inertia[(0, 1)].abs() < 1e-12);
/// ```
pub fn mass_properties(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Option<MeshMass> {
    use nalgebra::Matrix3;
    // ∫ x xᵀ over a tetrahedron (0, a, b, c) is det/120 · (A·K·Aᵀ) with A = [a b c] and
    // K = [[2,1,1],[1,2,1],[1,1,2]].
    let canonical = Matrix3::new(2.0, 1.0, 1.0, 1.0, 2.0, 1.0, 1.0, 1.0, 2.0);
    let (mut volume, mut first, mut second) = (0.0, Vector3::zeros(), Matrix3::zeros());
    for t in triangles {
        let corner = |k: u32| vertices.get(k as usize).map(|p| p.coords);
        let (a, b, c) = (corner(t[0])?, corner(t[1])?, corner(t[2])?);
        let columns = Matrix3::from_columns(&[a, b, c]);
        let det = columns.determinant();
        volume += det / 6.0;
        first += (a + b + c) * (det / 24.0);
        second += columns * canonical * columns.transpose() * (det / 120.0);
    }
    if !(volume.is_finite() && volume > 0.0) {
        return None;
    }
    let centre = first / volume;
    // Second moments about the centre, then the inertia tensor tr(C)·1 − C.
    let about_centre = second - centre * centre.transpose() * volume;
    let inertia = Matrix3::identity() * about_centre.trace() - about_centre;
    Some(MeshMass { volume, centre: Point3::from(centre), inertia })
}

/// How MuJoCo weighs a mesh: its `<mesh inertia>` attribute.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum MeshInertia {
    /// The solid its convex hull bounds.
    Convex,
    /// The solid it bounds, its triangles' signed volumes (it must be closed and
    /// wound outwards).
    Exact,
    /// MuJoCo's default: each triangle's pyramid from a centre with its volume taken
    /// positive, whatever the triangle's winding (an open mesh weighs something).
    #[default]
    Legacy,
    /// Its surface, of unit thickness: the mass is the area's.
    Shell,
}

impl MeshInertia {
    /// The value of `<mesh inertia>` (`convex`, `exact`, `legacy`, `shell`).
    pub fn from_name(name: &str) -> Option<Self> {
        match name {
            "convex" => Some(MeshInertia::Convex),
            "exact" => Some(MeshInertia::Exact),
            "legacy" => Some(MeshInertia::Legacy),
            "shell" => Some(MeshInertia::Shell),
            _ => None,
        }
    }
}

/// Below this MuJoCo takes an area, a volume or a triangle's size as none (`mjMINVAL`).
const MUJOCO_NOTHING: f64 = 1e-15;

/// A triangle's area, unit normal and centroid; an area of 0 (and any normal) when it is
/// smaller than MuJoCo takes a face to be.
fn face(corners: [Vector3<f64>; 3]) -> (f64, Vector3<f64>, Vector3<f64>) {
    let [a, b, c] = corners;
    let cross = (b - a).cross(&(c - a));
    let length = cross.norm();
    let centre = (a + b + c) / 3.0;
    if length < MUJOCO_NOTHING { (0.0, Vector3::zeros(), centre) } else { (length / 2.0, cross / length, centre) }
}

/// The [`MeshMass`] of a mesh as MuJoCo's compiler computes it with `method` (its
/// `<mesh inertia>`): for a shell `volume` is the area. `hull` (the convex hull's
/// vertices and triangles) is used by [`MeshInertia::Convex`] only.
///
/// MuJoCo's steps: the centre of its faces (their centroids weighted by area); the
/// centre of mass of the pyramids from there to each face (of the hull's faces for
/// `Convex`; their volumes taken positive for `Legacy`; the faces' areas for `Shell`);
/// then the volume and the second moments of the pyramids from that centre of mass.
/// Errors say why MuJoCo refuses the mesh: no area, no (or a negative) volume, or an
/// inertia no rigid body has.
pub fn mujoco_mass_properties(
    (vertices, triangles): (&[Point3<f64>], &[[u32; 3]]),
    hull: (&[Point3<f64>], &[[u32; 3]]),
    method: MeshInertia,
) -> Result<MeshMass, String> {
    let faces_of = |(points, faces): (&[Point3<f64>], &[[u32; 3]])| -> Result<Vec<[Vector3<f64>; 3]>, String> {
        faces
            .iter()
            .map(|t| {
                let corner = |k: u32| points.get(k as usize).map(|p| p.coords);
                match (corner(t[0]), corner(t[1]), corner(t[2])) {
                    (Some(a), Some(b), Some(c)) => Ok([a, b, c]),
                    _ => Err(format!("a triangle {t:?} names a vertex beyond the mesh's {}", points.len())),
                }
            })
            .collect()
    };
    let own = faces_of((vertices, triangles))?;
    let weighed = if method == MeshInertia::Convex { faces_of(hull)? } else { own.clone() };
    // The centre of the faces.
    let (mut area, mut face_centre) = (0.0, Vector3::zeros());
    for corners in &own {
        let (a, _, centre) = face(*corners);
        area += a;
        face_centre += centre * a;
    }
    if area < MUJOCO_NOTHING {
        return Err("its surface area is too small".into());
    }
    face_centre /= area;
    // The centre of mass: of the pyramids from the faces' centre.
    let (total, centre) = pyramids(&weighed, face_centre, method, |_, _| {});
    if total < MUJOCO_NOTHING {
        return Err(if total < 0.0 {
            "its volume is negative (its triangles are wound inwards)".into()
        } else {
            "its volume is too small (MuJoCo weighs such a mesh only with inertia=\"shell\")".into()
        });
    }
    // The volume and the second moments: of the pyramids from the centre of mass.
    let mut second = nalgebra::Matrix3::zeros();
    let denominator = if method == MeshInertia::Shell { 12.0 } else { 20.0 };
    let (volume, _) = pyramids(&weighed, centre, method, |weight, [d, e, f]| {
        let (d, e, f) = (d - centre, e - centre, f - centre);
        let sum = d + e + f;
        // 2 Σ v vᵀ + Σ (vᵢ vⱼᵀ + vⱼ vᵢᵀ) over the pairs = Σ v vᵀ + s sᵀ.
        second += (d * d.transpose() + e * e.transpose() + f * f.transpose() + sum * sum.transpose())
            * (weight / denominator);
    });
    let inertia = nalgebra::Matrix3::identity() * second.trace() - second;
    check_rigid(&inertia)?;
    Ok(MeshMass { volume, centre: Point3::from(centre), inertia })
}

/// The total weight (volume, or area for a shell) of the pyramids from `apex` to each
/// face and the centre of their masses (the apex when they weigh nothing); `each` is
/// given every face's weight and corners.
fn pyramids(
    faces: &[[Vector3<f64>; 3]],
    apex: Vector3<f64>,
    method: MeshInertia,
    mut each: impl FnMut(f64, [Vector3<f64>; 3]),
) -> (f64, Vector3<f64>) {
    let (mut total, mut first) = (0.0, Vector3::zeros());
    for corners in faces {
        let (area, normal, centre) = face(*corners);
        let weight = match method {
            MeshInertia::Shell => area,
            MeshInertia::Legacy => ((centre - apex).dot(&normal) * area / 3.0).abs(),
            MeshInertia::Exact | MeshInertia::Convex => (centre - apex).dot(&normal) * area / 3.0,
        };
        total += weight;
        first += (centre * 0.75 + apex * 0.25) * weight;
        each(weight, *corners);
    }
    (total, if total >= MUJOCO_NOTHING { first / total } else { apex })
}

/// MuJoCo's check of a mesh's inertia: its largest principal moment positive, and each
/// at most the sum of the others (to a millionth, and 1e-9 absolute).
fn check_rigid(inertia: &nalgebra::Matrix3<f64>) -> Result<(), String> {
    let moments = inertia.symmetric_eigenvalues();
    if !moments.iter().all(|m| m.is_finite()) || moments.max() <= 0.0 {
        return Err("its inertia has no positive principal moment".into());
    }
    let sum = moments.sum();
    if moments.iter().any(|&m| sum - m < m * (1.0 - 1e-6) - 1e-9) {
        return Err(format!("its principal moments {moments:?} break A + B ≥ C"));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A U-shaped prism 1 m deep (the profile (0,0) (3,0) (3,3) (2,3) (2,1) (1,1) (1,3)
    /// (0,3), a 1 m notch in a 3 m square), wound outwards: closed, but not star-shaped
    /// from its centre, so that MuJoCo's legacy inertia weighs more than the solid.
    fn u_prism() -> Triangles {
        let profile = [(0, 0), (3, 0), (3, 3), (2, 3), (2, 1), (1, 1), (1, 3), (0, 3)];
        let n = profile.len() as u32;
        let at = |(x, y): (i32, i32), z: f64| Point3::new(f64::from(x), f64::from(y), z);
        let vertices: Vec<_> = profile.iter().map(|p| at(*p, 0.0)).chain(profile.iter().map(|p| at(*p, 1.0))).collect();
        let mut triangles = Vec::new();
        for [a, b, c] in [[0, 1, 4], [0, 4, 5], [1, 2, 3], [1, 3, 4], [0, 5, 6], [0, 6, 7]] {
            triangles.push([a, c, b]);
            triangles.push([a + n, b + n, c + n]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            triangles.push([i, j, j + n]);
            triangles.push([i, j + n, i + n]);
        }
        (vertices, triangles)
    }

    fn weighed(mesh: &Triangles, method: MeshInertia) -> Result<MeshMass, String> {
        let hull = crate::hull::convex_hull(&mesh.0).unwrap();
        mujoco_mass_properties((&mesh.0, &mesh.1), (&hull.0, &hull.1), method)
    }

    fn assert_close(what: &str, ours: f64, mujocos: f64) {
        assert!((ours - mujocos).abs() <= 1e-9 * mujocos.abs().max(1e-9), "{what}: {ours} vs MuJoCo's {mujocos}");
    }

    /// Volume, centre and principal moments (smallest first) as MuJoCo 4.0.0 compiles
    /// the mesh in a free body of density 1 (`body_mass`, `body_ipos`, `body_inertia`).
    fn assert_mujocos(m: &MeshMass, volume: f64, centre: [f64; 3], moments: [f64; 3]) {
        assert_close("volume", m.volume, volume);
        for (ours, mujocos) in m.centre.iter().zip(centre) {
            assert_close("centre", *ours, mujocos);
        }
        let mut ours: Vec<f64> = m.inertia.symmetric_eigenvalues().iter().copied().collect();
        ours.sort_by(f64::total_cmp);
        for (ours, mujocos) in ours.iter().zip(moments) {
            assert_close("principal moment", *ours, mujocos);
        }
    }

    /// MuJoCo 4.0.0's numbers for the U prism given as `<mesh vertex face inertia>`.
    #[test]
    fn each_inertia_method_weighs_a_concave_mesh_as_mujoco_does() {
        let u = u_prism();
        let legacy = weighed(&u, MeshInertia::Legacy).unwrap();
        assert_mujocos(
            &legacy,
            8.617540091638032,
            [1.5, 1.4263101374570448, 0.5],
            [6.699129129016179, 7.4617540091638, 12.832462462349513],
        );
        let exact = weighed(&u, MeshInertia::Exact).unwrap();
        assert_mujocos(
            &exact,
            7.0,
            [1.5, 1.3571428571428574, 0.5],
            [6.023809523809523, 7.166666666666664, 12.02380952380952],
        );
        let convex = weighed(&u, MeshInertia::Convex).unwrap();
        assert_mujocos(&convex, 9.0, [1.5, 1.5, 0.5], [7.5, 7.5, 13.5]);
        let shell = weighed(&u, MeshInertia::Shell).unwrap();
        assert_mujocos(&shell, 30.0, [1.5, 1.433333333333334, 0.5], [34.2, 37.0, 61.533333333333324]);
        // The exact method is the solid's, as `mass_properties` weighs it.
        let solid = mass_properties(&u.0, &u.1).unwrap();
        assert_close("solid", solid.volume, exact.volume);
    }

    /// A cube wound inwards: MuJoCo's legacy inertia weighs it as the cube (1 m³,
    /// moments 1/6), the exact one refuses it ("mesh volume is negative").
    #[test]
    fn a_mesh_wound_inwards_weighs_as_legacy_and_is_refused_as_exact() {
        let (vertices, triangles) = crate::hull::convex_hull(
            &(0..8)
                .map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2)))
                .collect::<Vec<_>>(),
        )
        .unwrap();
        let inwards: Vec<[u32; 3]> = triangles.iter().map(|t| [t[0], t[2], t[1]]).collect();
        let mesh = (vertices, inwards);
        let legacy = weighed(&mesh, MeshInertia::Legacy).unwrap();
        assert_mujocos(&legacy, 1.0, [0.5; 3], [1.0 / 6.0; 3]);
        assert!(weighed(&mesh, MeshInertia::Exact).unwrap_err().contains("negative"));
    }

    /// One triangle: no volume (MuJoCo: "mesh volume is too small ... Try setting
    /// inertia to shell"); as a shell it weighs its area.
    #[test]
    fn a_flat_mesh_weighs_only_as_a_shell() {
        let vertices = vec![Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
        let triangles = [[0, 1, 2]];
        let weigh = |method| mujoco_mass_properties((&vertices, &triangles), (&[], &[]), method);
        assert!(weigh(MeshInertia::Legacy).unwrap_err().contains("too small"));
        assert_close("area", weigh(MeshInertia::Shell).unwrap().volume, 0.5);
        assert!(weigh(MeshInertia::Convex).is_err(), "no hull, no volume");
    }
}
