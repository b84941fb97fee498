//! A bounding-box tree over a triangle mesh, built once when the mesh's geom is made,
//! so that a ray cast visits the few triangles near the ray instead of all of them (a
//! robot link's mesh has thousands). The nearest hit it finds is the one a test of
//! every triangle finds, bit for bit: the same triangle test, and boxes padded so that
//! rounding never hides a triangle the ray meets.

use nalgebra::{Point3, Vector3};

/// At most this many triangles in a leaf.
const LEAF_TRIANGLES: usize = 4;

/// The deepest a tree gets: each level halves its triangles (median split), and a mesh
/// has fewer than 2³² of them.
const MAX_DEPTH: usize = 33;

/// One box of the tree: a leaf holds `order[first..first + count]`; an inner node
/// (`count == 0`) has its two children at `first` and `first + 1`.
#[derive(Clone, Copy, Debug)]
struct Node {
    lo: Point3<f64>,
    hi: Point3<f64>,
    first: u32,
    count: u32,
}

/// The tree of one mesh. It holds no vertices: a cast passes the mesh it was built from.
#[derive(Debug)]
pub(crate) struct MeshTree {
    nodes: Vec<Node>,
    /// Triangle indices, each leaf's contiguous.
    order: Vec<u32>,
}

impl MeshTree {
    /// The tree of a mesh whose indices are all in range (checked when the geom is made).
    pub(crate) fn new(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Self {
        let corners = |t: &[u32; 3]| t.map(|k| vertices[k as usize]);
        let mut boxes: Vec<(Point3<f64>, Point3<f64>)> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = corners(t);
                (a.inf(&b).inf(&c), a.sup(&b).sup(&c))
            })
            .collect();
        // Pad every box by a billionth of the mesh's largest coordinate (and at least
        // 1 nm): far more than the rounding of a hit point, far less than anything a
        // sensor resolves.
        let largest = boxes.iter().fold(0.0f64, |m, (lo, hi)| m.max(lo.coords.amax()).max(hi.coords.amax()));
        let pad = Vector3::repeat(1e-9 * largest.max(1.0));
        for (lo, hi) in &mut boxes {
            *lo -= pad;
            *hi += pad;
        }
        let centres: Vec<Point3<f64>> = boxes.iter().map(|(lo, hi)| nalgebra::center(lo, hi)).collect();
        let empty = Node { lo: Point3::origin(), hi: Point3::origin(), first: 0, count: 0 };
        let mut tree = MeshTree { nodes: vec![empty], order: (0..triangles.len() as u32).collect() };
        tree.split(0, 0, triangles.len(), &boxes, &centres);
        tree
    }

    /// Makes node `at` the box of `order[from..to]`, splitting it at the median of the
    /// triangles' centres along its longest side until the leaves are small.
    fn split(
        &mut self,
        at: usize,
        from: usize,
        to: usize,
        boxes: &[(Point3<f64>, Point3<f64>)],
        centres: &[Point3<f64>],
    ) {
        let span = &mut self.order[from..to];
        let (mut lo, mut hi) =
            (Point3::from(Vector3::repeat(f64::INFINITY)), Point3::from(Vector3::repeat(f64::NEG_INFINITY)));
        let (mut c_lo, mut c_hi) = (lo, hi);
        for &t in span.iter() {
            let (b_lo, b_hi) = boxes[t as usize];
            lo = lo.inf(&b_lo);
            hi = hi.sup(&b_hi);
            c_lo = c_lo.inf(&centres[t as usize]);
            c_hi = c_hi.sup(&centres[t as usize]);
        }
        if span.len() <= LEAF_TRIANGLES {
            self.nodes[at] = Node { lo, hi, first: from as u32, count: span.len() as u32 };
            return;
        }
        let axis = (c_hi - c_lo).imax();
        let half = span.len() / 2;
        span.select_nth_unstable_by(half, |a, b| centres[*a as usize][axis].total_cmp(&centres[*b as usize][axis]));
        let left = self.nodes.len();
        self.nodes[at] = Node { lo, hi, first: left as u32, count: 0 };
        let empty = self.nodes[at];
        self.nodes.extend([empty, empty]);
        self.split(left, from, from + half, boxes, centres);
        self.split(left + 1, from + half, to, boxes, centres);
    }
}

/// A mesh with its tree, as a ray cast reads it.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TreeMesh<'a> {
    pub(crate) vertices: &'a [Point3<f64>],
    pub(crate) triangles: &'a [[u32; 3]],
    pub(crate) tree: &'a MeshTree,
}

impl TreeMesh<'_> {
    /// The distance along the unit `d` from `o` to the nearest triangle (either side)
    /// within `reach`, as [`triangle_distance`] measures it.
    pub(crate) fn nearest(&self, o: &Point3<f64>, d: &Vector3<f64>, reach: f64) -> Option<f64> {
        if self.triangles.is_empty() {
            return None;
        }
        let nodes = &self.tree.nodes;
        let enter = |n: u32, limit: f64| box_entry(o, d, limit, &nodes[n as usize].lo, &nodes[n as usize].hi);
        let mut best: Option<f64> = None;
        // Boxes still to search, with where the ray enters each (each box is tested once).
        let mut stack = [(0u32, 0.0f64); 2 * MAX_DEPTH];
        let mut len = 0;
        if let Some(t) = enter(0, reach) {
            stack[0] = (0, t);
            len = 1;
        }
        while len > 0 {
            len -= 1;
            let (index, entry) = stack[len];
            let limit = best.unwrap_or(reach);
            if entry > limit {
                continue; // entered beyond a hit found since it was pushed
            }
            let node = nodes[index as usize];
            if node.count == 0 {
                // The nearer child is searched first (pushed last): its hits shorten the reach.
                let [a, b] = [node.first, node.first + 1].map(|n| (n, enter(n, limit)));
                let nearer_first = a.1.unwrap_or(f64::INFINITY) <= b.1.unwrap_or(f64::INFINITY);
                for (n, t) in if nearer_first { [b, a] } else { [a, b] } {
                    if let Some(t) = t {
                        stack[len] = (n, t);
                        len += 1;
                    }
                }
                continue;
            }
            for &t in &self.tree.order[node.first as usize..(node.first + node.count) as usize] {
                let [a, b, c] = self.triangles[t as usize].map(|k| self.vertices[k as usize]);
                if let Some(dist) = triangle_distance(o, d, &a, &b, &c)
                    && best.is_none_or(|b| dist < b)
                {
                    best = Some(dist);
                }
            }
        }
        best.filter(|b| *b <= reach)
    }
}

/// Where the segment from `o` along the unit `d` for `len` enters the box [lo, hi]
/// (0 when it starts inside), if it meets it.
pub(crate) fn box_entry(
    o: &Point3<f64>,
    d: &Vector3<f64>,
    len: f64,
    lo: &Point3<f64>,
    hi: &Point3<f64>,
) -> Option<f64> {
    let (mut t0, mut t1) = (0.0f64, len);
    for i in 0..3 {
        if d[i].abs() < 1e-300 {
            if o[i] < lo[i] || o[i] > hi[i] {
                return None;
            }
            continue;
        }
        let (a, b) = ((lo[i] - o[i]) / d[i], (hi[i] - o[i]) / d[i]);
        t0 = t0.max(a.min(b));
        t1 = t1.min(a.max(b));
        if t0 > t1 {
            return None;
        }
    }
    Some(t0)
}

/// The distance along `d` from `o` to the triangle `a b c` (either side), if the ray
/// meets it (Möller–Trumbore).
pub(crate) fn triangle_distance(
    o: &Point3<f64>,
    d: &Vector3<f64>,
    a: &Point3<f64>,
    b: &Point3<f64>,
    c: &Point3<f64>,
) -> Option<f64> {
    let (e1, e2) = (b - a, c - a);
    let p = d.cross(&e2);
    let det = e1.dot(&p);
    if det.abs() < 1e-300 {
        return None;
    }
    let s = o - a;
    let u = s.dot(&p) / det;
    if !(0.0..=1.0).contains(&u) {
        return None;
    }
    let q = s.cross(&e1);
    let v = d.dot(&q) / det;
    if v < 0.0 || u + v > 1.0 {
        return None;
    }
    let dist = e2.dot(&q) / det;
    (dist >= 0.0).then_some(dist)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::random::SplitMix64;

    /// Every triangle tested: what the tree must reproduce.
    fn every_triangle(
        o: &Point3<f64>,
        d: &Vector3<f64>,
        vertices: &[Point3<f64>],
        triangles: &[[u32; 3]],
    ) -> Option<f64> {
        triangles
            .iter()
            .filter_map(|t| {
                let [a, b, c] = t.map(|k| vertices[k as usize]);
                triangle_distance(o, d, &a, &b, &c)
            })
            .reduce(f64::min)
    }

    /// A closed UV sphere of `rings` × `segments` quads, radius `r`, bumped by `noise`.
    fn bumpy_sphere(rings: u32, segments: u32, r: f64, noise: &mut SplitMix64) -> (Vec<Point3<f64>>, Vec<[u32; 3]>) {
        let mut vertices = Vec::new();
        for i in 0..=rings {
            let polar = std::f64::consts::PI * f64::from(i) / f64::from(rings);
            for j in 0..segments {
                let azimuth = std::f64::consts::TAU * f64::from(j) / f64::from(segments);
                let radius = r * (1.0 + 0.05 * noise.uniform());
                vertices.push(Point3::new(
                    radius * polar.sin() * azimuth.cos(),
                    radius * polar.cos(),
                    radius * polar.sin() * azimuth.sin(),
                ));
            }
        }
        let mut triangles = Vec::new();
        for i in 0..rings {
            for j in 0..segments {
                let k = |i: u32, j: u32| i * segments + j % segments;
                triangles.push([k(i, j), k(i + 1, j), k(i + 1, j + 1)]);
                triangles.push([k(i, j), k(i + 1, j + 1), k(i, j + 1)]);
            }
        }
        (vertices, triangles)
    }

    #[test]
    fn the_tree_finds_the_nearest_hit_of_every_triangle_bit_for_bit() {
        let mut random = SplitMix64::new(7);
        let (vertices, triangles) = bumpy_sphere(16, 24, 0.8, &mut random);
        let tree = MeshTree::new(&vertices, &triangles);
        let mesh = TreeMesh { vertices: &vertices, triangles: &triangles, tree: &tree };
        let mut point = || Vector3::new(random.uniform() - 0.5, random.uniform() - 0.5, random.uniform() - 0.5);
        let mut hits = 0;
        for i in 0..1500 {
            // Rays from outside and inside, every other one aimed at a point near the
            // sphere (some grazing its surface), the others anywhere.
            let o = Point3::from(point() * 4.0);
            let d = if i % 2 == 0 { point() * 1.8 - o.coords } else { point() }.normalize();
            let expected = every_triangle(&o, &d, &vertices, &triangles).filter(|t| *t <= 3.0);
            let found = mesh.nearest(&o, &d, 3.0);
            assert_eq!(found.map(f64::to_bits), expected.map(f64::to_bits), "ray from {o} along {d}");
            hits += usize::from(found.is_some());
        }
        assert!(hits > 500, "only {hits} of 1500 rays hit the sphere");
        // A ray through a vertex shared by six triangles.
        let at = vertices[5 * 24 + 7];
        let o = Point3::origin();
        let d = at.coords.normalize();
        let expected = every_triangle(&o, &d, &vertices, &triangles);
        assert!(expected.is_some());
        assert_eq!(mesh.nearest(&o, &d, 5.0), expected);
    }

    #[test]
    fn flat_and_tiny_meshes_are_found_too() {
        // A flat square (every box has no depth along Y) and a single triangle.
        let square = vec![
            Point3::new(-1.0, 0.0, -1.0),
            Point3::new(1.0, 0.0, -1.0),
            Point3::new(1.0, 0.0, 1.0),
            Point3::new(-1.0, 0.0, 1.0),
        ];
        let down = Vector3::new(0.0, -1.0, 0.0);
        let cast = |triangles: &[[u32; 3]], from: Point3<f64>, reach: f64| {
            let tree = MeshTree::new(&square, triangles);
            TreeMesh { vertices: &square, triangles, tree: &tree }.nearest(&from, &down, reach)
        };
        let two = [[0, 1, 2], [0, 2, 3]];
        assert_eq!(cast(&two, Point3::new(0.3, 2.0, 0.4), 10.0), Some(2.0));
        assert_eq!(cast(&two, Point3::new(0.3, 2.0, 0.4), 1.5), None);
        assert_eq!(cast(&two, Point3::new(3.0, 2.0, 0.4), 10.0), None);
        assert_eq!(cast(&[[0, 1, 2]], Point3::new(0.9, 1.0, 0.0), 10.0), Some(1.0));
        assert_eq!(cast(&[], Point3::origin(), 10.0), None);
    }
}
