//! Errors a caller can act on: each cause has its own variant, and each message is a
//! sentence naming objects by their names, never by an internal handle.

use ars_core::limits::MAX_FORCE;
use ars_core::nalgebra::{Point3, Vector3};
use ars_core::*;

/// A message a person can read: no range talk for what is not a range, no handle
/// (`body#0v0@w1`, `hooks#0v0@WorldId(1)`), no "is out of range" tail.
fn readable(error: &Error) -> String {
    let message = error.to_string();
    assert!(!message.contains('#'), "a handle in {message:?}");
    assert!(!message.contains("WorldId") && !message.contains("v0@"), "a handle in {message:?}");
    assert!(!message.contains("out of range"), "{message:?}");
    message
}

fn sim_with_floor() -> Simulation {
    Simulation::builder().floor_plane(Vector3::y(), 0.0).build().unwrap()
}

#[test]
fn an_unknown_sensor_kind_lists_the_known_ones() {
    let err = "Gpss".parse::<ars_core::SensorKind>().unwrap_err();
    let Error::UnknownKind { what, name, known } = &err else { panic!("{err:?}") };
    assert_eq!((*what, name.as_str()), ("sensor kind", "Gpss"));
    assert!(known.iter().any(|k| k == "Gps"), "{known:?}");
    assert!(readable(&err).starts_with(r#"unknown sensor kind "Gpss"; the known ones are "#), "{err}");
}

#[test]
fn a_missing_scene_file_is_an_io_error_with_its_path() {
    let path = std::env::temp_dir().join("ars-no-such-folder/scene.json");
    let err = Simulation::load_scene_from(&path).unwrap_err();
    let Error::Io { operation, path: shown, kind, errno, .. } = &err else { panic!("{err:?}") };
    assert_eq!(*operation, "read the scene file");
    assert_eq!(shown, &path.display().to_string());
    assert_eq!(*kind, std::io::ErrorKind::NotFound);
    assert!(errno.is_some(), "the OS error number is kept");
    assert!(readable(&err).starts_with(&format!("cannot read the scene file {:?}: ", path.display().to_string())));

    let sim = Simulation::new().unwrap();
    let err = sim.save_scene_to(&path).unwrap_err();
    assert!(matches!(&err, Error::Io { operation: "write the scene file", .. }), "{err:?}");
}

#[test]
fn a_malformed_scene_is_a_format_error_with_its_position() {
    let err = Simulation::load_scene("{\n  \"format\": 3,\n").unwrap_err();
    let Error::Format { format, file, element, line, column, .. } = &err else { panic!("{err:?}") };
    assert_eq!((*format, file.as_str(), element.as_str(), *line), ("scene file", "<string>", "", Some(2)));
    assert!(column.is_some(), "{err}");
    assert!(readable(&err).starts_with("<string>, line 2, column "), "{err}");

    let dir = std::env::temp_dir().join(format!("ars-error-messages-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("bad.json");
    std::fs::write(&path, "not json").unwrap();
    let err = Simulation::load_scene_from(&path).unwrap_err();
    assert!(matches!(&err, Error::Format { file, .. } if *file == path.display().to_string()), "{err:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_static_object_has_no_body_and_the_message_names_it() {
    let mut sim = sim_with_floor();
    let err = sim.scene().body(sim.scene().object("floor").unwrap().id()).map(drop).unwrap_err();
    assert!(matches!(&err, Error::NoBody { object, .. } if object == "floor"), "{err:?}");
    assert!(readable(&err).starts_with(r#"object "floor" is static (it has no body)"#), "{err}");

    let ball = sim.scene_mut().add_sphere(0.1, [0.0, 1.0, 0.0], Mass::Total(1.0)).unwrap();
    let floor = sim.scene().object("floor").unwrap().id();
    let err = sim.scene_mut().add_fixed_joint("j", floor, JointEnd::Object(ball)).unwrap_err();
    assert_eq!(readable(&err), r#"object "floor" is static (it has no body); the first object of a joint needs one"#);
}

#[test]
fn messages_read_as_sentences() {
    let mut sim = Simulation::new().unwrap();
    let err = sim.scene_mut().add_box([1e12, 1.0, 1.0], [0.0; 3], Mass::Total(1.0)).unwrap_err();
    assert!(matches!(err, Error::OutOfRange { what: "box edges", .. }), "{err:?}");
    assert!(readable(&err).starts_with("box edges must be within ["), "{err}");

    let ball = sim.scene_mut().add_sphere(0.1, [0.0; 3], Mass::Total(1.0)).unwrap();
    let err = sim.scene_mut().add_fixed_joint("self", ball, JointEnd::Object(ball)).unwrap_err();
    assert_eq!(readable(&err), r#"a fixed joint cannot connect object "sphere" to itself"#);

    let err = Profile::new(vec![(1.0, 0.0), (0.0, 0.0)]).unwrap_err();
    assert_eq!(readable(&err), "a profile's times must not decrease");
}

#[test]
fn removed_things_are_named_as_removed_not_by_handle() {
    let mut sim = Simulation::new().unwrap();
    let ball = sim.scene_mut().add_sphere(0.1, [0.0; 3], Mass::Total(1.0)).unwrap();
    sim.remove_object(ball).unwrap();
    let err = sim.scene().object(ball).map(drop).unwrap_err();
    assert_eq!(err, Error::StaleHandle { kind: "object" });
    assert_eq!(readable(&err), "the object was removed: its handle no longer refers to anything");

    let hooks = sim.add_hooks(PreStep(|_: &mut Simulation| Ok(()))).unwrap();
    sim.remove_hooks(hooks).unwrap();
    let err = sim.remove_hooks(hooks).map(drop).unwrap_err();
    assert_eq!(readable(&err), "the hook was removed: its handle no longer refers to anything");

    let other = Simulation::new().unwrap();
    let err = other.scene().object(ball).map(drop).unwrap_err();
    assert_eq!(readable(&err), "the object belongs to another world or simulation");
}

/// A pre-step hook whose type can be named (to hold its own id).
type Hook = Box<dyn FnMut(&mut Simulation) -> Result<()> + Send>;

#[test]
fn a_hook_reaching_itself_is_busy() {
    let mut sim = Simulation::new().unwrap();
    let seen = std::sync::Arc::new(std::sync::Mutex::new(None));
    let id = std::sync::Arc::new(std::sync::Mutex::new(None::<HookId<PreStep<Hook>>>));
    let (seen2, id2) = (seen.clone(), id.clone());
    let hook: Hook = Box::new(move |sim: &mut Simulation| {
        if let Some(me) = *id2.lock().unwrap() {
            *seen2.lock().unwrap() = Some(sim.hooks(me).map(drop).unwrap_err());
        }
        Ok(())
    });
    *id.lock().unwrap() = Some(sim.add_hooks(PreStep(hook)).unwrap());
    sim.step().unwrap();
    let err = seen.lock().unwrap().take().expect("the hook ran");
    assert!(matches!(err, Error::Busy(_)), "{err:?}");
    assert!(readable(&err).starts_with("the hooks are running"), "{err}");
}

#[test]
fn a_diverged_body_is_named_by_its_object() {
    let mut sim = Simulation::builder().gravity(Vector3::zeros()).build().unwrap();
    let ball = sim.scene_mut().add_sphere(0.1, Point3::origin(), Mass::Total(1.0)).unwrap();
    sim.scene_mut().set_name(ball, "ball").unwrap();
    let mut result = Ok(());
    for _ in 0..1000 {
        sim.scene_mut().body_mut(ball).unwrap().add_force(Vector3::new(MAX_FORCE, 0.0, 0.0)).unwrap();
        result = sim.step();
        if result.is_err() {
            break;
        }
    }
    let err = result.unwrap_err();
    assert!(matches!(&err, Error::Diverged { body, .. } if body == r#"object "ball""#), "{err:?}");
    assert!(readable(&err).starts_with(r#"object "ball" diverged at t = "#), "{err}");
}
