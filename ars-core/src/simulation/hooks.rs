//! Hooks: code a [`Simulation`] runs at fixed points of its step loop.
//!
//! There is one mechanism: the [`Hooks`] trait. A [`Program`](crate::Program) is
//! hooks plus a scene; anything else (a controller, a logger, a closure) is added to a
//! simulation with [`Simulation::add_hooks`] and runs after the program's hooks, in
//! the order added. Closures become hooks through [`PreStep`], [`PostStep`],
//! [`PreFrame`] and [`PostFrame`]:
//!
//! ```
//! use ars_core::{Mass, PostStep, Simulation};
//!
//! let mut sim = Simulation::new()?;
//! let ball = sim.scene_mut().add_sphere(0.1, [0.0, 10.0, 0.0], Mass::Total(1.0))?;
//! let lowest = sim.add_hooks(PostStep(move |sim: &mut Simulation| {
//!     let y = sim.scene().body(ball)?.position().y;
//!     Ok(())
//! }))?;
//! sim.step_n(10)?;
//! sim.remove_hooks(lowest)?;
//! # Ok::<(), ars_core::Error>(())
//! ```

use std::any::Any;
use std::fmt;
use std::marker::PhantomData;

use super::Simulation;
use crate::error::{Error, Result};
use crate::handle::{Arena, RawHandle, WorldId};
use crate::panic::contain;

/// Code run by a simulation at fixed points of its step loop (see the order in the
/// [simulation docs](crate::simulation)). Every method does nothing by default.
pub trait Hooks {
    /// Before each step, with the time at the start of the step.
    fn pre_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// After each step (after the sensors sampled), with the time at the end of the step.
    fn post_step(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// Before the steps of a frame.
    fn pre_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// After the steps of a frame.
    fn post_frame(&mut self, sim: &mut Simulation) -> Result<()> {
        let _ = sim;
        Ok(())
    }
    /// Whether these hooks do something at `point` (by default: at every point).
    ///
    /// Asked once, when the hooks are added with [`Simulation::add_hooks`]: they are
    /// not called at the points where they say `false`, which spares the call (and its
    /// panic containment) at every step for a method left at its default. Say `false`
    /// only for a method that does nothing. A program run by its runner is called at
    /// every point whatever it says.
    ///
    /// ```
    /// use ars_core::{HookPoint, Hooks, Result, Simulation};
    ///
    /// struct Counter(u64);
    /// impl Hooks for Counter {
    ///     fn pre_step(&mut self, _: &mut Simulation) -> Result<()> {
    ///         self.0 += 1;
    ///         Ok(())
    ///     }
    ///     fn runs_at(&self, point: HookPoint) -> bool {
    ///         point == HookPoint::PreStep
    ///     }
    /// }
    /// let mut sim = Simulation::new()?;
    /// let counter = sim.add_hooks(Counter(0))?;
    /// sim.step_n(3)?;
    /// assert_eq!(sim.hooks(counter)?.0, 3);
    /// # Ok::<(), ars_core::Error>(())
    /// ```
    fn runs_at(&self, point: HookPoint) -> bool {
        let _ = point;
        true
    }

    /// What the hooks carry from one step to the next (a rate read in the previous
    /// step), for [snapshots](crate::Snapshot): nothing by default. Hooks with such
    /// state override this and [`restore_state`](Hooks::restore_state), or a restored
    /// simulation runs them from the state they are in. A closure's captured variables
    /// and a Python hook's are not seen by ARS.
    fn save_state(&self) -> Vec<u64> {
        Vec::new()
    }

    /// Puts back what [`save_state`](Hooks::save_state) returned.
    fn restore_state(&mut self, state: &[u64]) -> Result<()> {
        let _ = state;
        Ok(())
    }
}

/// No hooks.
impl Hooks for () {}

macro_rules! closure_hook {
    ($(#[$doc:meta])* $name:ident, $method:ident) => {
        $(#[$doc])*
        pub struct $name<F: FnMut(&mut Simulation) -> Result<()>>(pub F);

        impl<F: FnMut(&mut Simulation) -> Result<()>> Hooks for $name<F> {
            fn $method(&mut self, sim: &mut Simulation) -> Result<()> {
                (self.0)(sim)
            }
            fn runs_at(&self, point: HookPoint) -> bool {
                point == HookPoint::$name
            }
        }

        impl<F: FnMut(&mut Simulation) -> Result<()>> fmt::Debug for $name<F> {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str(stringify!($name))
            }
        }
    };
}

closure_hook!(
    /// A closure run before every step.
    PreStep,
    pre_step
);
closure_hook!(
    /// A closure run after every step.
    PostStep,
    post_step
);
closure_hook!(
    /// A closure run before every frame.
    PreFrame,
    pre_frame
);
closure_hook!(
    /// A closure run after every frame.
    PostFrame,
    post_frame
);

/// The points of the step loop where hooks run (see [`Hooks::runs_at`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum HookPoint {
    /// [`Hooks::pre_step`].
    PreStep,
    /// [`Hooks::post_step`].
    PostStep,
    /// [`Hooks::pre_frame`].
    PreFrame,
    /// [`Hooks::post_frame`].
    PostFrame,
}

impl HookPoint {
    /// Every point, in the order of `HookSet::at`.
    const ALL: [HookPoint; 4] = [HookPoint::PreStep, HookPoint::PostStep, HookPoint::PreFrame, HookPoint::PostFrame];

    fn name(self) -> &'static str {
        match self {
            HookPoint::PreStep => "pre-step",
            HookPoint::PostStep => "post-step",
            HookPoint::PreFrame => "pre-frame",
            HookPoint::PostFrame => "post-frame",
        }
    }

    /// Runs `hooks` at this point, turning a panic into [`Error::Panicked`].
    pub(crate) fn run<H: Hooks + ?Sized>(
        self,
        hooks: &mut H,
        sim: &mut Simulation,
        who: &dyn fmt::Display,
    ) -> Result<()> {
        contain(
            || format!("the {} hook of {who}", self.name()),
            || match self {
                HookPoint::PreStep => hooks.pre_step(sim),
                HookPoint::PostStep => hooks.post_step(sim),
                HookPoint::PreFrame => hooks.pre_frame(sim),
                HookPoint::PostFrame => hooks.post_frame(sim),
            },
        )
    }
}

/// A typed handle to hooks added to a simulation (stale once they are removed).
pub struct HookId<H> {
    handle: RawHandle,
    _hooks: PhantomData<fn() -> H>,
}

impl<H> Clone for HookId<H> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<H> Copy for HookId<H> {}
impl<H> fmt::Debug for HookId<H> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "hooks#{}v{}@{:?}", self.handle.index, self.handle.generation, self.handle.world)
    }
}
impl<H> fmt::Display for HookId<H> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        fmt::Debug::fmt(self, f)
    }
}

trait AnyHooks: Hooks + Send {
    fn as_any(&self) -> &dyn Any;
    fn as_any_mut(&mut self) -> &mut dyn Any;
    fn into_any(self: Box<Self>) -> Box<dyn Any>;
}

impl<H: Hooks + Send + 'static> AnyHooks for H {
    fn as_any(&self) -> &dyn Any {
        self
    }
    fn as_any_mut(&mut self) -> &mut dyn Any {
        self
    }
    fn into_any(self: Box<Self>) -> Box<dyn Any> {
        self
    }
}

/// The hooks added to a simulation. A slot is empty while its hooks run (they get the
/// simulation mutably, so they cannot stay inside it).
pub(crate) struct HookSet {
    slots: Arena<Option<Box<dyn AnyHooks>>>,
    /// For each point (in the order of [`HookPoint::ALL`]), the handles of the hooks
    /// that run there, in the order they were added (slots are reused, so slot order
    /// is not that order).
    at: [Vec<RawHandle>; 4],
    /// Changes to `at` so far (a running hook may add or remove others).
    edits: u64,
}

impl HookSet {
    pub(crate) fn new(world: WorldId) -> Self {
        HookSet { slots: Arena::new(world), at: Default::default(), edits: 0 }
    }

    pub(crate) fn len(&self) -> usize {
        self.slots.len()
    }

    /// What every hook set saves of its state (see [`Hooks::save_state`]), in slot
    /// order.
    pub(crate) fn save(&self) -> Result<Vec<Vec<u64>>> {
        self.slots
            .values()
            .map(|h| {
                h.as_ref()
                    .map(|h| h.save_state())
                    .ok_or_else(|| Error::Busy("a snapshot cannot be taken by a hook while its own hooks run".into()))
            })
            .collect()
    }

    /// Checks that `states` fit these hooks: one per hook set, unless every state is
    /// empty (hooks without state may differ).
    pub(crate) fn check_fits(&self, states: &[Vec<u64>]) -> Result<()> {
        if states.len() != self.slots.len() && states.iter().any(|s| !s.is_empty()) {
            return Err(Error::SnapshotMismatch {
                detail: format!(
                    "the snapshot holds the state of {} hook sets, this simulation has {}",
                    states.len(),
                    self.slots.len()
                ),
            });
        }
        Ok(())
    }

    /// Puts back every hook set's state (checked with `check_fits`).
    pub(crate) fn restore(&mut self, states: &[Vec<u64>]) -> Result<()> {
        if states.len() != self.slots.len() {
            return Ok(());
        }
        for (h, state) in self.slots.values_mut().zip(states) {
            let h = h.as_mut().ok_or_else(|| Error::Busy("a hook cannot restore a snapshot while it runs".into()))?;
            h.restore_state(state)?;
        }
        Ok(())
    }
}

impl Simulation {
    /// Adds hooks that run at every step and frame after the program's, in the order
    /// added. Hooks added by a hook run from the next point of the step loop on.
    /// They are called only at the points where [`Hooks::runs_at`] says they run.
    pub fn add_hooks<H: Hooks + Send + 'static>(&mut self, hooks: H) -> Result<HookId<H>> {
        let points = HookPoint::ALL.map(|p| hooks.runs_at(p));
        let handle = self.hooks.slots.insert(Some(Box::new(hooks)));
        for (list, runs) in self.hooks.at.iter_mut().zip(points) {
            if runs {
                list.push(handle);
            }
        }
        self.hooks.edits += 1;
        Ok(HookId { handle, _hooks: PhantomData })
    }

    /// Removes hooks and hands them back. Hooks cannot remove themselves while they run.
    pub fn remove_hooks<H: Hooks + Send + 'static>(&mut self, id: HookId<H>) -> Result<H> {
        self.hook_slot(id)?;
        let slot = self.hooks.slots.remove(id.handle, "hook")?;
        for list in &mut self.hooks.at {
            list.retain(|h| *h != id.handle);
        }
        self.hooks.edits += 1;
        let boxed = slot.expect("checked above: not running");
        match boxed.into_any().downcast::<H>() {
            Ok(hooks) => Ok(*hooks),
            Err(_) => unreachable!("the slot's type was checked above"),
        }
    }

    /// Hooks added with [`add_hooks`](Self::add_hooks) (their state).
    pub fn hooks<H: Hooks + Send + 'static>(&self, id: HookId<H>) -> Result<&H> {
        self.hook_slot(id)?.as_any().downcast_ref::<H>().ok_or(STALE)
    }

    /// Hooks added with [`add_hooks`](Self::add_hooks), mutably.
    pub fn hooks_mut<H: Hooks + Send + 'static>(&mut self, id: HookId<H>) -> Result<&mut H> {
        self.hook_slot(id)?;
        let slot = self.hooks.slots.get_mut(id.handle, "hook")?;
        slot.as_mut().and_then(|h| h.as_any_mut().downcast_mut::<H>()).ok_or(STALE)
    }

    fn hook_slot<H: Hooks + Send + 'static>(&self, id: HookId<H>) -> Result<&dyn AnyHooks> {
        match self.hooks.slots.get(id.handle, "hook")? {
            Some(hooks) if hooks.as_any().is::<H>() => Ok(&**hooks),
            Some(_) => Err(STALE),
            None => Err(Error::Busy(
                "the hooks are running: hooks cannot reach (or remove) themselves through the simulation".into(),
            )),
        }
    }

    /// Runs the added hooks of one point in the order added, up to the first error.
    #[inline]
    pub(crate) fn run_added_hooks(&mut self, at: HookPoint) -> Result<()> {
        if self.hooks.at[at as usize].is_empty() { Ok(()) } else { self.run_each_added_hook(at) }
    }

    #[inline(never)]
    fn run_each_added_hook(&mut self, at: HookPoint) -> Result<()> {
        let mut i = 0;
        while let Some(&handle) = self.hooks.at[at as usize].get(i) {
            // Take the hooks out of their slot while they run (they get the simulation
            // mutably), then put them back: a running slot cannot be removed.
            let Ok(Some(mut hooks)) = self.hooks.slots.get_mut(handle, "hook").map(Option::take) else {
                i += 1;
                continue;
            };
            let edits = self.hooks.edits;
            let who = HookSetNumber(i + 1);
            let result = at.run(&mut *hooks, self, &who);
            *self.hooks.slots.get_mut(handle, "hook").expect("a running slot is not removed") = Some(hooks);
            result?;
            // Hooks removed by this one may have shifted the order.
            i = if self.hooks.edits == edits {
                i + 1
            } else {
                self.hooks.at[at as usize].iter().position(|h| *h == handle).map_or(i, |p| p + 1)
            };
        }
        Ok(())
    }
}

/// Added hooks in messages: their rank among the hooks that run at a point, in the
/// order added, from 1 (formatted only if a message is made).
struct HookSetNumber(usize);

impl fmt::Display for HookSetNumber {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "hook set {}", self.0)
    }
}

/// The error for an id whose hooks were removed (or are of another type).
const STALE: Error = Error::StaleHandle { kind: "hook" };
