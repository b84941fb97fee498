//! Cause: a sensor added on a removed object, or on an object of another simulation,
//! was accepted; every later step then returned `Err` while time still advanced, and
//! a sensor could not be removed. Now such a sensor is refused at `add_sensor`, and
//! `remove_sensor` hands back a sensor's records.

use ars_core::sensors::{Gps, Velometer};
use ars_core::*;

#[test]
fn sensors_on_removed_or_foreign_objects_are_refused() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    sim.remove_object(ball).unwrap();
    assert!(matches!(sim.add_sensor(Gps::new(ball)), Err(Error::StaleHandle { .. })));

    let mut other = Simulation::new().unwrap();
    let foreign = other.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    assert!(matches!(sim.add_sensor(Gps::new(foreign)), Err(Error::ForeignHandle { .. })));
    sim.step_n(3).unwrap();
    assert_eq!(sim.scene().time(), 3.0 * sim.scene().time_step());
}

#[test]
fn a_sensor_can_be_removed_with_its_records() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.5, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let gps = sim.add_sensor(Gps::new(ball)).unwrap();
    let speed = sim.add_sensor(Velometer::new(ball)).unwrap();
    sim.step_n(5).unwrap();
    let log = sim.remove_sensor(gps).unwrap();
    assert_eq!(log.len(), 5);
    assert!(matches!(sim.records(gps), Err(Error::StaleHandle { .. })));
    assert!(matches!(sim.remove_sensor(gps), Err(Error::StaleHandle { .. })));
    sim.step_n(2).unwrap();
    assert_eq!(sim.records(speed).unwrap().len(), 7, "the other sensor is untouched");
    let gps2 = sim.add_sensor(Gps::new(ball)).unwrap();
    assert!(sim.records(gps).is_err(), "the old id stays stale when its slot is reused");
    sim.step().unwrap();
    assert_eq!(sim.records(gps2).unwrap().len(), 1);
}
