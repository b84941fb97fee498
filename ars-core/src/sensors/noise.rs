//! Gaussian measurement noise for any sensor whose record can be perturbed.

use nalgebra::{Point3, Vector3};

use super::body::{
    Acceleration, Attitude, ContactForceReading, ContactReading, ImuReading, Inclination, Position, Velocity,
};
use super::energy::{Energy, Kinetic, Potential};
use super::joint::{Effort, Power, Reaction};
use super::laser::LaserReading;
use super::magnetometer::MagneticField;
use super::momentum::MomentumReading;
use super::touch::TouchReading;
use super::{Record, Sensor};
use crate::control::JointState;
use crate::error::Result;
use crate::handle::{JointId, ObjectId};
use crate::random::SplitMix64;
use crate::scene::Scene;

/// A record whose values can be perturbed by noise.
pub trait Perturb: Record {
    /// Adds `noise()` to every measured value.
    fn perturb(&mut self, noise: &mut dyn FnMut() -> f64);
}

fn v3(v: &mut Vector3<f64>, noise: &mut dyn FnMut() -> f64) {
    v.iter_mut().for_each(|x| *x += noise());
}

fn p3(p: &mut Point3<f64>, noise: &mut dyn FnMut() -> f64) {
    v3(&mut p.coords, noise);
}

macro_rules! perturb_fields {
    ($ty:ty, |$r:ident, $n:ident| $body:block) => {
        impl Perturb for $ty {
            fn perturb(&mut self, $n: &mut dyn FnMut() -> f64) {
                let $r = self;
                $body
            }
        }
    };
}

perturb_fields!(Position, |r, n| { p3(&mut r.position, n) });
perturb_fields!(Velocity, |r, n| {
    v3(&mut r.linear, n);
    v3(&mut r.angular, n)
});
perturb_fields!(MagneticField, |r, n| { v3(&mut r.field, n) });
perturb_fields!(MomentumReading, |r, n| {
    p3(&mut r.centre, n);
    v3(&mut r.velocity, n);
    v3(&mut r.angular_momentum, n)
});
perturb_fields!(Acceleration, |r, n| {
    v3(&mut r.linear, n);
    v3(&mut r.angular, n)
});
perturb_fields!(ImuReading, |r, n| {
    v3(&mut r.specific_force, n);
    v3(&mut r.angular_velocity, n)
});
perturb_fields!(Inclination, |r, n| {
    r.pitch += n();
    r.roll += n()
});
perturb_fields!(Attitude, |r, n| {
    let q = r.rotation.into_inner();
    let noisy = nalgebra::Quaternion::new(q.w + n(), q.i + n(), q.j + n(), q.k + n());
    // Renormalised (a zero quaternion, improbable, keeps the reading).
    if noisy.norm() > 0.0 {
        r.rotation = nalgebra::UnitQuaternion::from_quaternion(noisy);
    }
});
perturb_fields!(TouchReading, |r, n| { r.normal_force = (r.normal_force + n()).max(0.0) });
perturb_fields!(ContactReading, |r, n| { r.max_depth += n() });
perturb_fields!(ContactForceReading, |r, n| { v3(&mut r.force, n) });
perturb_fields!(LaserReading, |r, n| {
    if let Some(d) = r.distance.as_mut() {
        *d += n();
    }
});
perturb_fields!(JointState, |r, n| {
    r.position += n();
    r.rate += n()
});
perturb_fields!(Effort, |r, n| { r.value += n() });
perturb_fields!(Power, |r, n| { r.power += n() });
perturb_fields!(Reaction, |r, n| {
    v3(&mut r.force, n);
    v3(&mut r.torque, n)
});
perturb_fields!(Kinetic, |r, n| {
    r.translational += n();
    r.rotational += n()
});
perturb_fields!(Potential, |r, n| { r.potential += n() });
perturb_fields!(Energy, |r, n| {
    r.kinetic += n();
    r.potential += n()
});

/// Wraps a sensor and adds zero-mean Gaussian noise of standard deviation `std_dev`
/// to every value it records, from a generator seeded with `seed` (the same seed gives
/// the same noise).
///
/// ```
/// use ars_core::{Mass, Simulation, sensors::{Gps, Noisy}};
/// let mut sim = Simulation::new()?;
/// let ball = sim.scene_mut().add_sphere(0.5, [0.0, 10.0, 0.0], Mass::Total(1.0))?;
/// let gps = sim.add_sensor(Noisy::new(Gps::new(ball), 0.01, 42)?)?;
/// sim.step()?;
/// let y = sim.records(gps)?.last().unwrap().record.position.y;
/// assert!((y - 10.0).abs() < 0.1 && y != sim.scene().body(ball)?.position().y);
/// # Ok::<(), ars_core::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct Noisy<S> {
    inner: S,
    std_dev: f64,
    rng: SplitMix64,
}

impl<S: Sensor> Noisy<S> {
    /// `inner` with noise of standard deviation `std_dev` (finite, ≥ 0).
    pub fn new(inner: S, std_dev: f64, seed: u64) -> Result<Self> {
        crate::validate::non_negative("noise standard deviation", std_dev)?;
        Ok(Noisy { inner, std_dev, rng: SplitMix64::new(seed) })
    }

    /// The wrapped sensor.
    pub fn inner(&self) -> &S {
        &self.inner
    }
}

impl<S: Sensor> Sensor for Noisy<S>
where
    S::Record: Perturb,
{
    type Record = S::Record;

    fn attach(&mut self, sim: &mut Scene) -> Result<()> {
        self.inner.attach(sim)
    }
    fn before_step(&mut self, sim: &Scene) -> Result<()> {
        self.inner.before_step(sim)
    }
    fn measure(&mut self, sim: &Scene) -> Result<S::Record> {
        let mut record = self.inner.measure(sim)?;
        let (rng, std_dev) = (&mut self.rng, self.std_dev);
        record.perturb(&mut || std_dev * rng.normal());
        Ok(record)
    }
    fn objects(&self) -> Vec<ObjectId> {
        self.inner.objects()
    }
    fn joints(&self) -> Vec<JointId> {
        self.inner.joints()
    }
    fn sample_at(&self) -> super::SampleAt {
        self.inner.sample_at()
    }
    fn measures_every_step(&self) -> bool {
        self.inner.measures_every_step()
    }
    fn settings(&self) -> Option<super::SensorSettings> {
        self.inner.settings()
    }
    fn noise(&self) -> Option<(f64, u64)> {
        Some((self.std_dev, self.rng.state()))
    }
    /// The generator's state, then the wrapped sensor's.
    fn save_state(&self) -> Vec<u64> {
        std::iter::once(self.rng.state()).chain(self.inner.save_state()).collect()
    }
    fn restore_state(&mut self, state: &[u64]) -> Result<()> {
        let Some((rng, inner)) = state.split_first() else {
            return Err(crate::Error::SnapshotCorrupt { detail: "a noisy sensor's state has no generator".into() });
        };
        self.inner.restore_state(inner)?;
        self.rng = crate::random::SplitMix64::new(*rng);
        Ok(())
    }
}
