//! Convex hulls of point sets (a mesh's vertices), computed with Qhull, the library
//! MuJoCo computes its mesh hulls with (`qhull Qt`: triangulated output), and the
//! checks a hull handed in from outside must pass before ODE takes it as a convex.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};

use crate::error::{Error, Result};
use crate::limits;
use crate::mesh_mass::{Triangles, mass_properties};

/// Points within this fraction of the set's extent of a line or a plane make no solid.
const FLAT: f64 = 1e-9;

/// How far (as a fraction of the hull's extent) a vertex may stand outside the plane
/// of a neighbouring face of a convex hull. Qhull merges nearly coplanar facets and
/// `Qt` triangulates them: their corners stand up to a few millionths of the extent
/// off a plane (4e-6 m in a 0.2 m link of ABB's Yumi). A concave mesh is off by a
/// part of its size, far beyond.
const CONVEX_SLACK: f64 = 1e-3;

fn invalid(problem: impl Into<String>) -> Error {
    Error::InvalidMesh(problem.into())
}

/// The largest distance between two corners of the points' bounding box.
fn extent(points: &[Point3<f64>]) -> f64 {
    let (mut lo, mut hi) = (points[0], points[0]);
    for p in points {
        lo = lo.inf(p);
        hi = hi.sup(p);
    }
    (hi - lo).norm()
}

/// Refuses points that bound no solid, with the reason: fewer than four distinct
/// points, or all of them (to [`FLAT`] of their extent) on one line or one plane.
fn check_solid(points: &[Point3<f64>]) -> Result<()> {
    let size = extent(points);
    if size.is_nan() || size <= 0.0 {
        return Err(invalid(format!("no convex hull: its {} points are all the same point", points.len())));
    }
    let tolerance = FLAT * size;
    // The farthest point from the first, the farthest from their line, the farthest
    // from their plane: a tetrahedron of volume 0 means flat.
    let far = |score: &dyn Fn(&Point3<f64>) -> f64| {
        points.iter().map(|p| (score(p), *p)).fold((f64::NEG_INFINITY, points[0]), |a, b| if b.0 > a.0 { b } else { a })
    };
    let a = points[0];
    let (_, b) = far(&|p| (p - a).norm());
    let axis = (b - a).normalize();
    let (line_distance, c) = far(&|p| (p - a - axis * (p - a).dot(&axis)).norm());
    if line_distance <= tolerance {
        return Err(invalid(format!("no convex hull: its {} points are all on one line", points.len())));
    }
    let normal = axis.cross(&(c - a)).normalize();
    let (plane_distance, _) = far(&|p| (p - a).dot(&normal).abs());
    if plane_distance <= tolerance {
        return Err(invalid(format!(
            "no convex hull: its {} points are all on one plane, enclosing no volume",
            points.len()
        )));
    }
    Ok(())
}

/// The convex hull of `points`: its corners (the points it keeps, in their order) and
/// its faces, triangles wound counter-clockwise seen from outside. `Err` names the
/// problem: no points, a coordinate that is not finite or beyond
/// [`MAX_COORDINATE`](limits::MAX_COORDINATE), points that bound no solid (fewer than
/// four, or all on a line or a plane), or Qhull's own failure.
pub(crate) fn convex_hull(points: &[Point3<f64>]) -> Result<Triangles> {
    if points.len() < 4 {
        return Err(invalid(format!("no convex hull: it needs at least 4 points, got {}", points.len())));
    }
    for (i, p) in points.iter().enumerate() {
        if let Err(e) = limits::point("hull point", p) {
            return Err(invalid(format!("point {i}: {e}")));
        }
    }
    check_solid(points)?;
    let limit = i32::MAX as usize / 3;
    if points.len() > limit {
        return Err(invalid("too many points for a convex hull"));
    }
    let coordinates: Vec<f64> = points.iter().flat_map(|p| [p.x, p.y, p.z]).collect();
    // Qhull reports its errors (a precision failure) through its captured error stream;
    // the builder panics only when it cannot make the temporary file for that stream.
    let built = std::panic::catch_unwind(move || {
        let qh = qhull::Qh::builder()
            .qhull_args(["Qt"])
            .map_err(|e| format!("{e:?}"))?
            .build_managed(3, coordinates)
            .map_err(|e| e.to_string())?;
        let mut faces = Vec::new();
        for facet in qh.facets() {
            let normal = facet.normal().map(|n| Vector3::new(n[0], n[1], n[2]));
            let corners: Option<Vec<usize>> =
                facet.vertices().map(|set| set.iter().filter_map(|v| v.index(&qh)).collect());
            match (normal, corners) {
                (Some(n), Some(c)) if c.len() == 3 => faces.push(([c[0], c[1], c[2]], n)),
                _ => return Err("Qhull returned a facet that is not a triangle".to_string()),
            }
        }
        Ok(faces)
    });
    let faces = match built {
        Ok(Ok(faces)) => faces,
        Ok(Err(e)) => return Err(invalid(format!("no convex hull: Qhull failed: {}", e.trim()))),
        Err(_) => return Err(invalid("no convex hull: Qhull could not start (no temporary file for its messages)")),
    };
    // Keep the points the hull uses, in their order; wind each face outwards.
    let mut used: Vec<usize> = faces.iter().flat_map(|(c, _)| *c).collect();
    used.sort_unstable();
    used.dedup();
    let new_index: HashMap<usize, u32> = used.iter().enumerate().map(|(k, &i)| (i, k as u32)).collect();
    let vertices: Vec<Point3<f64>> = used.iter().map(|&i| points[i]).collect();
    let triangles: Vec<[u32; 3]> = faces
        .iter()
        .map(|([a, b, c], n)| {
            let (pa, pb, pc) = (points[*a], points[*b], points[*c]);
            let t = [new_index[a], new_index[b], new_index[c]];
            if (pb - pa).cross(&(pc - pa)).dot(n) < 0.0 { [t[0], t[2], t[1]] } else { t }
        })
        .collect();
    let hull = (vertices, triangles);
    check_convex(&hull.0, &hull.1)?;
    Ok(hull)
}

/// Checks that `triangles` over `vertices` are a convex hull ODE can collide: a closed
/// surface (every edge shared by exactly two triangles, wound oppositely), of one
/// piece without holes (Euler's V − E + F = 2), locally convex at every edge (to
/// [`CONVEX_SLACK`] of its extent), enclosing a positive volume (wound outwards).
/// Indices and coordinates were checked already.
pub(crate) fn check_convex(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Result<()> {
    if triangles.len() < 4 {
        return Err(invalid(format!("a convex hull has at least 4 faces, this one {}", triangles.len())));
    }
    // Each directed edge names the triangle it belongs to.
    let mut edges: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * triangles.len());
    for (i, t) in triangles.iter().enumerate() {
        if t[0] == t[1] || t[1] == t[2] || t[0] == t[2] {
            return Err(invalid(format!("the convex hull's triangle {i} repeats a vertex")));
        }
        for k in 0..3 {
            if edges.insert((t[k], t[(k + 1) % 3]), i).is_some() {
                return Err(invalid(format!(
                    "the convex hull is not a closed surface: its edge {}–{} is wound the same way by two triangles",
                    t[k],
                    t[(k + 1) % 3]
                )));
            }
        }
    }
    let mut used: Vec<u32> = triangles.iter().flatten().copied().collect();
    used.sort_unstable();
    used.dedup();
    let euler = used.len() as i64 - (edges.len() / 2) as i64 + triangles.len() as i64;
    let used_points: Vec<Point3<f64>> = used.iter().map(|&i| vertices[i as usize]).collect();
    let slack = CONVEX_SLACK * extent(&used_points);
    for (&(a, b), &i) in &edges {
        let Some(&j) = edges.get(&(b, a)) else {
            return Err(invalid(format!("the convex hull is not a closed surface: its edge {a}–{b} has one triangle")));
        };
        // The corner of the neighbour opposite the shared edge is behind this face.
        let t = triangles[i].map(|k| vertices[k as usize]);
        let normal = (t[1] - t[0]).cross(&(t[2] - t[0]));
        let length = normal.norm();
        if length.is_nan() || length <= 0.0 {
            continue; // a sliver of no area: its neighbours decide
        }
        let Some(&opposite) = triangles[j].iter().find(|&&k| k != a && k != b) else { continue };
        let height = (vertices[opposite as usize] - t[0]).dot(&normal) / length;
        if height > slack {
            return Err(invalid(format!(
                "the convex hull is not convex: vertex {opposite} is {height:e} m outside the face of triangle {i}"
            )));
        }
    }
    if euler != 2 || !edges.len().is_multiple_of(2) {
        return Err(invalid("the convex hull is not one closed surface without holes (V − E + F ≠ 2)"));
    }
    if mass_properties(vertices, triangles).is_none() {
        return Err(invalid(
            "the convex hull encloses no volume (its triangles must be wound counter-clockwise seen from outside)",
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cube_corners() -> Vec<Point3<f64>> {
        (0..8).map(|i| Point3::new(f64::from(i & 1), f64::from(i >> 1 & 1), f64::from(i >> 2))).collect()
    }

    #[test]
    fn a_cubes_hull_is_the_cube() {
        let mut points = cube_corners();
        points.push(Point3::new(0.5, 0.5, 0.5)); // inside: dropped
        points.push(Point3::new(0.5, 0.0, 0.5)); // on a face: dropped
        let (vertices, triangles) = convex_hull(&points).unwrap();
        assert_eq!(vertices.len(), 8);
        assert_eq!(triangles.len(), 12);
        let mass = mass_properties(&vertices, &triangles).unwrap();
        assert!((mass.volume - 1.0).abs() < 1e-12, "{}", mass.volume);
        assert!((mass.centre - Point3::new(0.5, 0.5, 0.5)).norm() < 1e-12);
    }

    #[test]
    fn points_that_bound_no_solid_are_refused_by_name() {
        let message = |points: &[Point3<f64>]| convex_hull(points).unwrap_err().to_string();
        assert!(message(&cube_corners()[..3]).contains("at least 4 points"));
        let flat: Vec<_> = cube_corners().into_iter().filter(|p| p.z == 0.0).collect();
        assert!(message(&flat).contains("one plane"), "{}", message(&flat));
        let line: Vec<_> = (0..5).map(|i| Point3::new(f64::from(i), 2.0 * f64::from(i), 0.0)).collect();
        assert!(message(&line).contains("one line"));
        assert!(message(&[Point3::new(1.0, 1.0, 1.0); 6]).contains("same point"));
        let mut nan = cube_corners();
        nan[3].y = f64::NAN;
        assert!(message(&nan).contains("point 3"), "{}", message(&nan));
        let mut far = cube_corners();
        far[5].x = 1e12;
        assert!(message(&far).contains("point 5"));
    }

    #[test]
    fn a_concave_or_open_surface_is_no_hull() {
        let (vertices, mut triangles) = convex_hull(&cube_corners()).unwrap();
        // Dent a corner inwards: no longer convex.
        let mut dented = vertices.clone();
        let corner = dented.iter().position(|p| *p == Point3::new(1.0, 1.0, 1.0)).unwrap();
        dented[corner] = Point3::new(0.6, 0.6, 0.6);
        assert!(check_convex(&dented, &triangles).unwrap_err().to_string().contains("not convex"));
        triangles.pop();
        assert!(check_convex(&vertices, &triangles).unwrap_err().to_string().contains("closed"));
        let inside_out: Vec<[u32; 3]> =
            convex_hull(&cube_corners()).unwrap().1.iter().map(|t| [t[0], t[2], t[1]]).collect();
        assert!(check_convex(&vertices, &inside_out).is_err());
    }
}
