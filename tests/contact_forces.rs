//! Contact forces (ODE's joint feedback on contact joints): a resting box's contacts
//! carry its weight, a stacked box's weight passes through the one below, and asking
//! for the forces changes nothing of the motion.

use ars::nalgebra::Vector3;
use ars::sensors::ContactForces;
use ars::{Mass, Simulation};

const G: f64 = 9.81;

/// A 2 kg box resting on the floor plane, and a 1 kg box on it.
fn stack() -> Simulation {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    sim.scene_mut().add_box([0.4, 0.2, 0.4], [0.0, 0.1, 0.0], Mass::Total(2.0)).unwrap();
    sim.scene_mut().add_box([0.2, 0.2, 0.2], [0.0, 0.3, 0.0], Mass::Total(1.0)).unwrap();
    sim
}

#[test]
fn a_resting_box_s_contacts_carry_its_weight() {
    let mut sim = Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap();
    let box_ = sim.scene_mut().add_box([0.4, 0.2, 0.4], [0.0, 0.1, 0.0], Mass::Total(2.0)).unwrap();
    let forces = sim.add_sensor(ContactForces::new(box_)).unwrap();
    sim.run_for(1.0).unwrap();
    let last = sim.records(forces).unwrap().last().unwrap().record;
    eprintln!("resting 2 kg box: {} contacts, force {:?} N (weight {} N)", last.contacts, last.force, 2.0 * G);
    assert_eq!(last.contacts, 4, "a box on a plane touches at its four corners");
    let weight = 2.0 * G;
    assert!((last.force.y - weight).abs() < 0.01 * weight, "{} N against {weight} N", last.force.y);
    assert!(last.force.x.abs() < 1e-6 && last.force.z.abs() < 1e-6, "{:?}", last.force);
}

#[test]
fn a_stacked_box_s_weight_passes_through_the_box_below() {
    let mut sim = stack();
    let (lower, upper) = (sim.scene().object("box").unwrap().id(), sim.scene().object("box/1").unwrap().id());
    let on_lower = sim.add_sensor(ContactForces::new(lower)).unwrap();
    let on_upper = sim.add_sensor(ContactForces::new(upper)).unwrap();
    sim.run_for(1.0).unwrap();
    let lower = sim.records(on_lower).unwrap().last().unwrap().record;
    let upper = sim.records(on_upper).unwrap().last().unwrap().record;
    // The floor pushes the lower box up with both weights, the upper box down with its
    // own: the lower box's contacts sum to its own weight.
    assert!((lower.force.y - 2.0 * G).abs() < 0.02 * G, "{:?}", lower.force);
    assert!((upper.force.y - G).abs() < 0.01 * G, "{:?}", upper.force);
    assert_eq!(lower.contacts, 8, "four corners on the floor, four under the upper box");
    let floor = sim.scene().world().contacts().iter().filter(|c| c.pair.body1.is_none() || c.pair.body2.is_none());
    let from_floor: f64 = floor.map(|c| if c.pair.body1.is_none() { -c.force.y } else { c.force.y }).sum();
    assert!((from_floor - 3.0 * G).abs() < 0.03 * G, "the floor carries both: {from_floor} N");
}

#[test]
fn asking_for_contact_forces_changes_nothing_of_the_motion() {
    let states = |sim: &Simulation| -> Vec<u64> {
        sim.scene()
            .bodies()
            .flat_map(|(_, h)| {
                let b = sim.scene().world().body(h).unwrap();
                let (p, v) = (b.position(), b.linear_velocity());
                [p.x, p.y, p.z, v.x, v.y, v.z].map(f64::to_bits)
            })
            .collect()
    };
    let (mut plain, mut measured) = (stack(), stack());
    let upper = measured.scene().object("box/1").unwrap().id();
    measured.add_sensor(ContactForces::new(upper)).unwrap();
    plain.run_for(0.5).unwrap();
    measured.run_for(0.5).unwrap();
    assert_eq!(states(&plain), states(&measured));
    assert!(plain.scene().world().contacts().iter().all(|c| c.force == Vector3::zeros()), "off unless asked");
    assert!(measured.scene().world().contacts().iter().any(|c| c.force != Vector3::zeros()));
}
