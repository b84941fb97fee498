//! Fewer contact points for a pair, chosen as a contact manifold is reduced: when a
//! collider finds more points than a hook-chosen surface allows
//! ([`ContactSurface::max_contacts`](super::contact::ContactSurface::max_contacts)),
//! the deepest is kept, then the one farthest from it, then the one that spans the
//! largest triangle with those two, then the one farthest outside that triangle, then
//! each next farthest from those already kept. ODE's colliders would otherwise stop at
//! their first points in their own order: a convex hull on a plane keeps the first
//! vertices of its list that lie below the plane, which may all sit on one side of its
//! footprint.

use nalgebra::Vector3;
use ode_sys as ffi;

fn point(c: &ffi::dContactGeom) -> Vector3<f64> {
    Vector3::new(c.pos[0], c.pos[1], c.pos[2])
}

/// The index in `points` (not yet `kept`) that maximises `score`; `None` when every
/// point is kept.
fn best(points: &[ffi::dContactGeom], kept: &[usize], score: impl Fn(Vector3<f64>) -> f64) -> Option<usize> {
    (0..points.len())
        .filter(|i| !kept.contains(i))
        .map(|i| (i, score(point(&points[i]))))
        .filter(|(_, s)| s.is_finite())
        .fold(None, |acc: Option<(usize, f64)>, (i, s)| match acc {
            Some((_, best)) if best >= s => acc,
            _ => Some((i, s)),
        })
        .map(|(i, _)| i)
}

/// Keeps at most `most` (at least 1) of `points`, spread as the module docs say, at the
/// front of the slice in their original order; returns how many.
pub(super) fn keep_spread(points: &mut [ffi::dContactGeom], most: usize) -> usize {
    let most = most.max(1);
    if points.len() <= most {
        return points.len();
    }
    let mut kept: Vec<usize> = Vec::with_capacity(most);
    // The deepest (the first of equals).
    kept.push((0..points.len()).fold(0, |b, i| if points[i].depth > points[b].depth { i } else { b }));
    // The kept points' positions, beside their indices.
    let mut chosen: Vec<Vector3<f64>> = Vec::with_capacity(most);
    chosen.push(point(&points[kept[0]]));
    while kept.len() < most {
        let next = match chosen.len() {
            1 => best(points, &kept, |p| (p - chosen[0]).norm_squared()),
            2 => best(points, &kept, |p| (chosen[1] - chosen[0]).cross(&(p - chosen[0])).norm_squared()),
            3 => best(points, &kept, |p| {
                let area = |a: Vector3<f64>, b: Vector3<f64>| (b - a).cross(&(p - a)).norm();
                area(chosen[0], chosen[1]) + area(chosen[1], chosen[2]) + area(chosen[2], chosen[0])
            }),
            _ => best(points, &kept, |p| chosen.iter().map(|c| (p - c).norm_squared()).fold(f64::INFINITY, f64::min)),
        };
        match next {
            Some(i) => {
                kept.push(i);
                chosen.push(point(&points[i]));
            }
            None => break,
        }
    }
    kept.sort_unstable();
    for (slot, &i) in kept.iter().enumerate() {
        points[slot] = points[i];
    }
    kept.len()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, y: f64, depth: f64) -> ffi::dContactGeom {
        ffi::dContactGeom { pos: [x, y, 0.0, 0.0], depth, ..Default::default() }
    }

    #[test]
    fn the_deepest_and_the_corners_of_a_footprint_are_kept() {
        // Sixteen points around a unit circle, listed from one side, and the deepest
        // among them; then four points in the middle.
        let mut points: Vec<ffi::dContactGeom> = (0..16)
            .map(|k| {
                let a = f64::from(k) * std::f64::consts::TAU / 16.0;
                at(a.cos(), a.sin(), if k == 5 { 0.02 } else { 0.01 })
            })
            .collect();
        points.extend((0..4).map(|k| at(0.1 * f64::from(k), 0.0, 0.015)));
        let n = keep_spread(&mut points, 4);
        assert_eq!(n, 4);
        let kept = &points[..4];
        assert!(kept.iter().any(|c| c.depth == 0.02), "the deepest is kept");
        // Spread over the circle: every kept point on it, and they span it both ways.
        assert!(kept.iter().all(|c| (c.pos[0].hypot(c.pos[1]) - 1.0).abs() < 1e-9));
        let span = |axis: usize| {
            let v = kept.iter().map(|c| c.pos[axis]);
            v.clone().fold(f64::MIN, f64::max) - v.fold(f64::MAX, f64::min)
        };
        assert!(span(0) > 1.5 && span(1) > 1.5, "{} {}", span(0), span(1));
    }

    #[test]
    fn few_points_stay_as_they_are() {
        let mut points = vec![at(0.0, 0.0, 0.01), at(1.0, 0.0, 0.02)];
        let before = points.clone();
        assert_eq!(keep_spread(&mut points, 4), 2);
        assert_eq!(points.iter().map(|c| c.pos).collect::<Vec<_>>(), before.iter().map(|c| c.pos).collect::<Vec<_>>());
        let mut many: Vec<_> = (0..10).map(|k| at(f64::from(k), 0.0, 0.01)).collect();
        assert_eq!(keep_spread(&mut many, 2), 2);
        assert_eq!((many[0].pos[0], many[1].pos[0]), (0.0, 9.0), "the first deepest and the farthest from it");
    }
}
