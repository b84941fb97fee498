//! What the window is asked to do, by a key or by the panel: one [`Command`] each,
//! whichever asked, applied in one place (the window's session).

use ars_core::{JointId, Key};
use kiss3d::event::{Action, Key as WindowKey};

use crate::edit::Edit;

/// What a key or the panel asks the window to do.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum Command {
    /// Pause or resume (space, the panel's Run/Pause button).
    TogglePause,
    /// One frame while paused (the panel's Frame button).
    StepFrame,
    /// One physics step while paused (`n`, the panel's Step button).
    StepPhysics,
    /// Rebuild the simulation (`r`, the panel's Reset button).
    Reset,
    /// Write a PNG of the window (`p`).
    Screenshot,
    /// Follow an object with the camera, or stop (`f`).
    ToggleFollow,
    /// Draw the contact points, or stop (`k`).
    ToggleContacts,
    /// Draw the contact forces as arrows, or stop.
    ToggleForces,
    /// Draw the joints' anchors and axes, or stop (`j`).
    ToggleJoints,
    /// Draw the world axes, or stop (`x`).
    ToggleAxes,
    /// Show the panel, or hide it (`g`).
    TogglePanel,
    /// Set a joint's position set-point (rad or m).
    Setpoint(JointId, f64),
    /// Change the simulation (the editor).
    Edit(Edit),
    /// Save the scene to the panel's save path (`Ctrl+S`).
    Save,
    /// Open the file at the panel's open path (a scene file, a URDF or an MJCF model)
    /// instead of the program.
    Open,
    /// Show this many views (1 to 4: keys `1`–`4`).
    Views(usize),
    /// Show this depth camera (counted from 0, in the order the sensors were added) in
    /// the camera view.
    ViewportCamera(usize),
    /// Forget the selection (Escape, the editor's ✖).
    Deselect,
    /// A key the viewer does not use went down: the program's.
    KeyDown(Key),
    /// A key went up: the program's (every key's release is).
    KeyUp(Key),
}

/// The command of `key` going down or up (`action`) with Control held (`ctrl`), the
/// simulation `paused` or not; `None` for a key nobody uses. Escape is not here: it
/// deselects, or closes the window (see the window's events).
pub(crate) fn key_command(key: WindowKey, action: Action, ctrl: bool, paused: bool) -> Option<Command> {
    use WindowKey as K;
    if key == K::S && ctrl {
        return (action == Action::Press).then_some(Command::Save);
    }
    if action == Action::Release {
        return program_key(key).map(Command::KeyUp);
    }
    Some(match key {
        K::Space => Command::TogglePause,
        K::N if paused => Command::StepPhysics,
        K::R => Command::Reset,
        K::J => Command::ToggleJoints,
        K::Key1 => Command::Views(1),
        K::Key2 => Command::Views(2),
        K::Key3 => Command::Views(3),
        K::Key4 => Command::Views(4),
        K::F => Command::ToggleFollow,
        K::G => Command::TogglePanel,
        K::K => Command::ToggleContacts,
        K::X => Command::ToggleAxes,
        K::P => Command::Screenshot,
        _ => return program_key(key).map(Command::KeyDown),
    })
}

/// The program's name of a window key: the arrows, space and the letters.
fn program_key(key: WindowKey) -> Option<Key> {
    use WindowKey as K;
    Some(match key {
        K::Up => Key::Up,
        K::Down => Key::Down,
        K::Left => Key::Left,
        K::Right => Key::Right,
        K::Space => Key::Space,
        K::A => Key::Char('a'),
        K::B => Key::Char('b'),
        K::C => Key::Char('c'),
        K::D => Key::Char('d'),
        K::E => Key::Char('e'),
        K::F => Key::Char('f'),
        K::G => Key::Char('g'),
        K::H => Key::Char('h'),
        K::I => Key::Char('i'),
        K::J => Key::Char('j'),
        K::K => Key::Char('k'),
        K::L => Key::Char('l'),
        K::M => Key::Char('m'),
        K::N => Key::Char('n'),
        K::O => Key::Char('o'),
        K::P => Key::Char('p'),
        K::Q => Key::Char('q'),
        K::R => Key::Char('r'),
        K::S => Key::Char('s'),
        K::T => Key::Char('t'),
        K::U => Key::Char('u'),
        K::V => Key::Char('v'),
        K::W => Key::Char('w'),
        K::X => Key::Char('x'),
        K::Y => Key::Char('y'),
        K::Z => Key::Char('z'),
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keys_ask_what_the_panel_asks_and_the_rest_is_the_programs() {
        let press = |key, paused| key_command(key, Action::Press, false, paused);
        assert_eq!(press(WindowKey::R, false), Some(Command::Reset));
        assert_eq!(press(WindowKey::Space, false), Some(Command::TogglePause));
        assert_eq!(press(WindowKey::Key3, false), Some(Command::Views(3)));
        assert_eq!(press(WindowKey::G, false), Some(Command::TogglePanel));
        // `n` steps while paused; running, it is the program's.
        assert_eq!(press(WindowKey::N, true), Some(Command::StepPhysics));
        assert_eq!(press(WindowKey::N, false), Some(Command::KeyDown(Key::Char('n'))));
        assert_eq!(press(WindowKey::Up, false), Some(Command::KeyDown(Key::Up)));
        assert_eq!(press(WindowKey::Z, false), Some(Command::KeyDown(Key::Char('z'))));
        assert_eq!(press(WindowKey::F1, false), None);
        // Every release is the program's, the viewer's keys' too.
        assert_eq!(key_command(WindowKey::R, Action::Release, false, false), Some(Command::KeyUp(Key::Char('r'))));
        // Ctrl+S saves on the press, and its release is nobody's.
        assert_eq!(key_command(WindowKey::S, Action::Press, true, false), Some(Command::Save));
        assert_eq!(key_command(WindowKey::S, Action::Release, true, false), None);
    }
}
