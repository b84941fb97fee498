//! Generational handles and the arena that issues them.
//!
//! A handle is small and `Copy`: the id of the world that issued it, a slot index and
//! the slot's generation. Removing an object bumps the slot's generation, so an old
//! handle is recognised as stale instead of reaching a freed ODE object, and a handle
//! from another world is recognised by its world id.

use std::fmt;
use std::sync::atomic::{AtomicU32, Ordering};

use crate::error::{Error, Result};

/// Identifies one world (and its handles) within the process.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub struct WorldId(u32);

impl WorldId {
    /// The id of no world (worlds are numbered from 1).
    const NONE: WorldId = WorldId(0);

    pub(crate) fn next() -> Self {
        static NEXT: AtomicU32 = AtomicU32::new(1);
        WorldId(NEXT.fetch_add(1, Ordering::Relaxed))
    }
}

/// The common part of every handle.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Debug)]
pub(crate) struct RawHandle {
    pub(crate) world: WorldId,
    pub(crate) index: u32,
    pub(crate) generation: u32,
}

impl RawHandle {
    /// A handle no arena issues (of no world): what a cache of a looked-up handle
    /// holds before the first look-up.
    pub(crate) const NONE: RawHandle = RawHandle { world: WorldId::NONE, index: u32::MAX, generation: u32::MAX };

    /// `self == other`, compared as two words rather than field by field (for a
    /// handle checked at every step).
    #[inline(always)]
    pub(crate) fn same_as(self, other: RawHandle) -> bool {
        let slot = |h: RawHandle| u64::from(h.index) | u64::from(h.generation) << 32;
        (slot(self) == slot(other)) & (self.world == other.world)
    }
}

macro_rules! handle_type {
    ($(#[$doc:meta])* $name:ident, $kind:literal) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash)]
        pub struct $name(pub(crate) RawHandle);

        impl $name {
            /// Name of the kind of object this handle refers to.
            pub const KIND: &'static str = $kind;
        }

        impl fmt::Debug for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}", self)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "{}#{}v{}@w{}", $kind, self.0.index, self.0.generation, self.0.world.0)
            }
        }
    };
}

handle_type!(
    /// A rigid body of a [`World`](crate::World).
    BodyHandle,
    "body"
);
handle_type!(
    /// A collision geometry of a [`World`](crate::World).
    GeomHandle,
    "geom"
);
handle_type!(
    /// A joint of a [`World`](crate::World).
    JointHandle,
    "joint"
);
handle_type!(
    /// A collision space of a [`World`](crate::World).
    SpaceHandle,
    "space"
);
handle_type!(
    /// A named object (body, static shape or floor) of a [`Simulation`](crate::Simulation).
    ObjectId,
    "object"
);
handle_type!(
    /// A named joint of a [`Simulation`](crate::Simulation).
    JointId,
    "joint"
);

enum Slot<T> {
    Occupied { generation: u32, value: T },
    Vacant { generation: u32 },
}

/// Why `h` does not reach a value of the arena of `world` (out of the hot path: it
/// formats).
#[cold]
#[inline(never)]
fn refusal(world: WorldId, h: RawHandle, kind: &'static str) -> Error {
    if h.world != world { Error::ForeignHandle { kind } } else { Error::StaleHandle { kind } }
}

/// Slots of `T`, reused after removal with a new generation.
pub(crate) struct Arena<T> {
    world: WorldId,
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
}

impl<T> Arena<T> {
    pub(crate) fn new(world: WorldId) -> Self {
        Arena { world, slots: Vec::new(), free: Vec::new() }
    }

    pub(crate) fn insert(&mut self, value: T) -> RawHandle {
        if let Some(index) = self.free.pop() {
            let slot = &mut self.slots[index as usize];
            let generation = match slot {
                Slot::Vacant { generation } => *generation,
                Slot::Occupied { .. } => unreachable!("free list points at an occupied slot"),
            };
            *slot = Slot::Occupied { generation, value };
            RawHandle { world: self.world, index, generation }
        } else {
            let index = u32::try_from(self.slots.len()).expect("fewer than 2^32 objects");
            self.slots.push(Slot::Occupied { generation: 0, value });
            RawHandle { world: self.world, index, generation: 0 }
        }
    }

    #[inline]
    fn check(&self, h: RawHandle, kind: &'static str) -> Result<usize> {
        match self.slots.get(h.index as usize) {
            Some(Slot::Occupied { generation, .. }) if *generation == h.generation && h.world == self.world => {
                Ok(h.index as usize)
            }
            _ => Err(refusal(self.world, h, kind)),
        }
    }

    #[inline]
    pub(crate) fn get(&self, h: RawHandle, kind: &'static str) -> Result<&T> {
        match self.slots.get(h.index as usize) {
            Some(Slot::Occupied { generation, value }) if *generation == h.generation && h.world == self.world => {
                Ok(value)
            }
            _ => Err(refusal(self.world, h, kind)),
        }
    }

    #[inline]
    pub(crate) fn get_mut(&mut self, h: RawHandle, kind: &'static str) -> Result<&mut T> {
        // One bounds and occupancy check (the refusal needs only the world id, so the
        // slot's borrow ends in the other arm).
        let world = self.world;
        match self.slots.get_mut(h.index as usize) {
            Some(Slot::Occupied { generation, value }) if *generation == h.generation && h.world == world => Ok(value),
            _ => Err(refusal(world, h, kind)),
        }
    }

    pub(crate) fn remove(&mut self, h: RawHandle, kind: &'static str) -> Result<T> {
        let i = self.check(h, kind)?;
        let next = h.generation.wrapping_add(1);
        let old = std::mem::replace(&mut self.slots[i], Slot::Vacant { generation: next });
        self.free.push(h.index);
        match old {
            Slot::Occupied { value, .. } => Ok(value),
            Slot::Vacant { .. } => unreachable!("checked above"),
        }
    }

    /// Value in slot `index`, whatever its generation (used for ids that ODE hands back
    /// during collision, which are live by construction).
    #[inline]
    pub(crate) fn get_by_index(&self, index: u32) -> Option<(RawHandle, &T)> {
        match self.slots.get(index as usize) {
            Some(Slot::Occupied { generation, value }) => {
                Some((RawHandle { world: self.world, index, generation: *generation }, value))
            }
            _ => None,
        }
    }

    pub(crate) fn iter(&self) -> impl Iterator<Item = (RawHandle, &T)> + '_ {
        self.slots.iter().enumerate().filter_map(move |(i, s)| match s {
            Slot::Occupied { generation, value } => {
                Some((RawHandle { world: self.world, index: i as u32, generation: *generation }, value))
            }
            Slot::Vacant { .. } => None,
        })
    }

    pub(crate) fn iter_mut(&mut self) -> impl Iterator<Item = (RawHandle, &mut T)> + '_ {
        let world = self.world;
        self.slots.iter_mut().enumerate().filter_map(move |(i, s)| match s {
            Slot::Occupied { generation, value } => {
                Some((RawHandle { world, index: i as u32, generation: *generation }, value))
            }
            Slot::Vacant { .. } => None,
        })
    }

    /// Every value, in slot order.
    #[inline]
    pub(crate) fn values(&self) -> impl Iterator<Item = &T> + '_ {
        self.slots.iter().filter_map(|s| match s {
            Slot::Occupied { value, .. } => Some(value),
            Slot::Vacant { .. } => None,
        })
    }

    pub(crate) fn values_mut(&mut self) -> impl Iterator<Item = &mut T> + '_ {
        self.slots.iter_mut().filter_map(|s| match s {
            Slot::Occupied { value, .. } => Some(value),
            Slot::Vacant { .. } => None,
        })
    }

    pub(crate) fn len(&self) -> usize {
        self.slots.len() - self.free.len()
    }

    /// Removes every value, in slot order.
    pub(crate) fn drain(&mut self) -> Vec<T> {
        self.free.clear();
        let slots = std::mem::take(&mut self.slots);
        slots
            .into_iter()
            .filter_map(|s| match s {
                Slot::Occupied { value, .. } => Some(value),
                Slot::Vacant { .. } => None,
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn removed_slot_is_reused_with_a_new_generation() {
        let mut arena = Arena::new(WorldId::next());
        let a = arena.insert(1);
        arena.remove(a, "body").unwrap();
        let b = arena.insert(2);
        assert_eq!(a.index, b.index);
        assert_ne!(a.generation, b.generation);
        assert!(matches!(arena.get(a, "body"), Err(Error::StaleHandle { .. })));
        assert_eq!(*arena.get(b, "body").unwrap(), 2);
    }

    #[test]
    fn handle_of_another_arena_is_foreign() {
        let mut one = Arena::new(WorldId::next());
        let two: Arena<i32> = Arena::new(WorldId::next());
        let h = one.insert(5);
        assert!(matches!(two.get(h, "body"), Err(Error::ForeignHandle { .. })));
    }
}
