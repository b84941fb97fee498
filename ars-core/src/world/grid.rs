//! The grid broad phase ([`SpaceKind::Grid`](super::SpaceKind::Grid)): ARS's own, in
//! Rust, over the geoms of a simple ODE space. Each collision puts every geom's
//! bounding box in the cells of a uniform grid (the cell twice the median geom's
//! size) and reports the pairs that share a cell and whose boxes overlap, once each, in
//! the order of the geoms' creation. Geoms much larger than a cell (and planes, whose
//! boxes are infinite) are tested against every other geom. Its cost grows with the
//! number of geoms and of touching pairs, not with their square: ODE's hash space
//! clears a table of one bit per pair of geoms at every collision, and its sweep and
//! prune sorts along one axis only, so a scene spread over the ground costs it n·√n.
//!
//! It applies ODE's own rules for which pairs a space reports: geoms enabled, not on
//! the same body, and whose category and collide bits match.

use ode_sys as ffi;

use super::World;
use crate::handle::SpaceHandle;

/// A geom as the grid sees it.
struct Entry {
    raw: ffi::dGeomID,
    body: ffi::dBodyID,
    category: u64,
    collide: u64,
    aabb: [f64; 6],
}

impl Entry {
    fn extent(&self) -> f64 {
        (self.aabb[1] - self.aabb[0]).max(self.aabb[3] - self.aabb[2]).max(self.aabb[5] - self.aabb[4])
    }

    fn overlaps(&self, other: &Entry) -> bool {
        (0..3).all(|a| self.aabb[2 * a] <= other.aabb[2 * a + 1] && other.aabb[2 * a] <= self.aabb[2 * a + 1])
    }

    /// ODE's rules (`collideAABBs`): not on one body, bits that match, boxes that
    /// overlap.
    fn may_touch(&self, other: &Entry) -> bool {
        (self.body.is_null() || self.body != other.body)
            && ((self.category & other.collide) != 0 || (other.category & self.collide) != 0)
            && self.overlaps(other)
    }
}

/// A geom's box larger than this many cells is tested against all the others.
const LARGE: f64 = 2.0;

/// A cell's key: its coordinates, 21 bits each (cells 2 million apart share a key,
/// which only makes more candidates).
fn key(c: [i64; 3]) -> u64 {
    let bits = |v: i64| (v as u64) & 0x1F_FFFF;
    bits(c[0]) | bits(c[1]) << 21 | bits(c[2]) << 42
}

fn cell(x: f64, size: f64) -> i64 {
    // Coordinates are finite (infinite boxes are large); `as` saturates far away.
    (x / size).floor() as i64
}

/// The grid's buffers, kept by the world from one collision to the next so that a
/// step allocates nothing once the scene has stopped growing. The raw ODE ids they
/// hold between collisions are never read there: each collision lists them anew from
/// the world that owns them.
#[derive(Default)]
pub(crate) struct Grid {
    entries: Vec<Entry>,
    extents: Vec<f64>,
    small: Vec<usize>,
    large: Vec<usize>,
    covered: Vec<(u64, u32)>,
    starts: Vec<u32>,
    next: Vec<u32>,
    grouped: Vec<(u64, u32)>,
    found: Vec<(usize, usize)>,
    pairs: Vec<(ffi::dGeomID, ffi::dGeomID)>,
}

impl Grid {
    /// The pairs of geoms of `space` that may touch, in the order of the geoms'
    /// creation.
    pub(crate) fn candidate_pairs(&mut self, world: &World, space: SpaceHandle) -> &[(ffi::dGeomID, ffi::dGeomID)] {
        let Grid { entries, extents, small, large, covered, starts, next, grouped, found, pairs } = self;
        gather_entries(entries, world, space);
        let size = cell_size(entries, extents);
        small.clear();
        large.clear();
        for (i, e) in entries.iter().enumerate() {
            let e_ext = e.extent();
            if e_ext.is_finite() && e_ext <= LARGE * size && e.aabb.iter().all(|c| c.abs() < 1e15) {
                small.push(i);
            } else {
                large.push(i);
            }
        }
        cover_cells(entries, small, size, covered);
        group_by_cell(covered, starts, next, grouped);
        found.clear();
        pairs_in_cells(entries, starts, grouped, size, found);
        for (n, &i) in large.iter().enumerate() {
            for &j in small.iter().chain(&large[n + 1..]) {
                if entries[i].may_touch(&entries[j]) {
                    found.push((i.min(j), i.max(j)));
                }
            }
        }
        // In the order of the geoms' creation, whatever the hashing did.
        found.sort_unstable();
        pairs.clear();
        pairs.extend(found.iter().map(|&(i, j)| (entries[i].raw, entries[j].raw)));
        pairs
    }
}

/// The enabled geoms of `space`, with their boxes and collision bits.
fn gather_entries(entries: &mut Vec<Entry>, world: &World, space: SpaceHandle) {
    entries.clear();
    for (_, g) in world.geoms.iter().filter(|(_, g)| g.space == space) {
        // SAFETY: the geom is live (owned by the world's arena).
        let (enabled, category, collide) = unsafe {
            (ffi::dGeomIsEnabled(g.raw) != 0, ffi::dGeomGetCategoryBits(g.raw), ffi::dGeomGetCollideBits(g.raw))
        };
        // A geom without bits touches nothing (`may_touch`): its box is not worth
        // bringing up to date (a visual mesh's every vertex).
        if !enabled || (category == 0 && collide == 0) {
            continue;
        }
        let mut aabb = [0.0; 6];
        // SAFETY: as above; `aabb` holds 6 reals. dGeomGetAABB brings a moved geom's
        // box up to date.
        unsafe { ffi::dGeomGetAABB(g.raw, aabb.as_mut_ptr()) };
        entries.push(Entry { raw: g.raw, body: g.body_raw, category, collide, aabb });
    }
}

/// The grid's cell size: twice the median extent of the finite boxes (1 m without any).
fn cell_size(entries: &[Entry], extents: &mut Vec<f64>) -> f64 {
    extents.clear();
    extents.extend(entries.iter().map(Entry::extent).filter(|e| e.is_finite()));
    if extents.is_empty() {
        1.0
    } else {
        let middle = extents.len() / 2;
        let (_, median, _) = extents.select_nth_unstable_by(middle, f64::total_cmp);
        (2.0 * *median).max(1e-6)
    }
}

/// Every (cell, geom) a small geom's box covers.
fn cover_cells(entries: &[Entry], small: &[usize], size: f64, covered: &mut Vec<(u64, u32)>) {
    covered.clear();
    for &i in small.iter() {
        let b = &entries[i].aabb;
        let (lo, hi) = ([0, 2, 4].map(|k| cell(b[k], size)), [1, 3, 5].map(|k| cell(b[k], size)));
        for x in lo[0]..=hi[0] {
            for y in lo[1]..=hi[1] {
                for z in lo[2]..=hi[2] {
                    covered.push((key([x, y, z]), i as u32));
                }
            }
        }
    }
}

/// The bucket of a cell's key among `buckets` (a power of two).
#[inline]
fn bucket(key: u64, buckets: usize) -> usize {
    (key.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> 32) as usize & (buckets - 1)
}

/// `covered` grouped by a hash of the cell with a counting sort (linear): the geoms of
/// a cell are then in one bucket, `grouped[starts[b]..starts[b + 1]]`.
fn group_by_cell(covered: &[(u64, u32)], starts: &mut Vec<u32>, next: &mut Vec<u32>, grouped: &mut Vec<(u64, u32)>) {
    let buckets = (2 * covered.len()).next_power_of_two().max(1);
    starts.clear();
    starts.resize(buckets + 1, 0);
    for &(k, _) in covered.iter() {
        starts[bucket(k, buckets) + 1] += 1;
    }
    for b in 0..buckets {
        starts[b + 1] += starts[b];
    }
    grouped.clear();
    grouped.resize(covered.len(), (0, 0));
    next.clear();
    next.extend_from_slice(starts);
    for &(k, i) in covered.iter() {
        let slot = &mut next[bucket(k, buckets)];
        grouped[*slot as usize] = (k, i);
        *slot += 1;
    }
}

/// The pairs of small geoms that share a cell and may touch, each found once.
fn pairs_in_cells(
    entries: &[Entry],
    starts: &[u32],
    grouped: &[(u64, u32)],
    size: f64,
    found: &mut Vec<(usize, usize)>,
) {
    for b in 0..starts.len() - 1 {
        let run = &grouped[starts[b] as usize..starts[b + 1] as usize];
        for (n, &(cell_key, i)) in run.iter().enumerate() {
            for &(other_key, j) in &run[n + 1..] {
                if other_key != cell_key {
                    continue;
                }
                let (a, b) = (&entries[i as usize], &entries[j as usize]);
                // Once each: in the cell that holds the corner where their boxes
                // start to overlap (cells that share a key by wrapping only add
                // candidates).
                let first = key([0, 2, 4].map(|k| cell(a.aabb[k].max(b.aabb[k]), size)));
                if first == cell_key && a.may_touch(b) {
                    let (i, j) = (i as usize, j as usize);
                    found.push((i.min(j), i.max(j)));
                }
            }
        }
    }
}
