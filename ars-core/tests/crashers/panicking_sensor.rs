//! Cause: a panic in one sensor unwound out of `step` while the simulation held its
//! sensor set outside itself: every sensor and all their records were lost. Now the
//! panic is contained (`Error::Panicked`), the other sensors still sample that step,
//! and every record stays.

use ars_core::sensors::{Gps, Position};
use ars_core::*;

struct Flaky {
    inner: Gps,
}

impl Sensor for Flaky {
    type Record = Position;
    fn measure(&mut self, sim: &Scene) -> Result<Position> {
        if sim.step_count() == 3 {
            panic!("flaky sensor");
        }
        self.inner.measure(sim)
    }
    fn objects(&self) -> Vec<ObjectId> {
        self.inner.objects()
    }
}

#[test]
fn a_panicking_sensor_is_reported_and_nothing_is_lost() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let flaky = sim.add_sensor(Flaky { inner: Gps::new(ball) }).unwrap();
    let gps = sim.add_sensor(Gps::new(ball)).unwrap();
    sim.step_n(2).unwrap();
    let err = sim.step().unwrap_err();
    assert!(matches!(&err, Error::Panicked { message, .. } if message == "flaky sensor"), "{err}");
    assert_eq!(sim.records(gps).unwrap().len(), 3, "the other sensor sampled step 3");
    assert_eq!(sim.records(flaky).unwrap().len(), 2, "its own records stay");
    sim.step().unwrap();
    assert_eq!(sim.records(flaky).unwrap().len(), 3);
    assert_eq!(sim.records(gps).unwrap().len(), 4);
}
