//! The keyboard focus on an X server with no window manager (Xvfb, a bare X session
//! driven by xdotool): nobody gives the window the focus there, so no key reached it,
//! not Ctrl (a Ctrl-drag was a plain drag, and turned the camera), not `r`, not Escape.
//! There, the window takes the focus itself, as a window manager would give it: when it
//! first shows, if no window holds the focus, and when it is clicked. With a window
//! manager, or with no X display (Wayland, Windows, macOS), this does nothing.

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
use x11::Display;

#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
use no_x11::Display;

/// The window's hold on the keyboard focus under X11 (nothing elsewhere).
pub(crate) struct Focus {
    x: Option<Display>,
    /// Frames left in which to look for the window when it first shows.
    looks_left: u32,
}

/// How many frames the window is looked for after it opens (it is mapped by then; on
/// Wayland it is never found, and the looking stops).
const LOOKS: u32 = 60;

impl Focus {
    /// The X display the window is on, if any (a failure to reach it leaves the focus
    /// alone: the window works as before).
    pub(crate) fn new() -> Self {
        Focus { x: Display::open(), looks_left: LOOKS }
    }

    /// A frame was drawn: while the window has not yet been found, look for it, and
    /// take the focus if no window holds it and no window manager would give it.
    pub(crate) fn shown(&mut self) {
        if self.looks_left == 0 {
            return;
        }
        self.looks_left -= 1;
        if let Some(x) = &mut self.x
            && x.find_window()
        {
            self.looks_left = 0;
            if x.unowned() {
                x.take();
            }
        }
    }

    /// The window was clicked: with no window manager, it takes the focus (a window
    /// manager gives it on a click, or as it sees fit).
    pub(crate) fn clicked(&mut self) {
        if let Some(x) = &mut self.x
            && (x.window.is_some() || x.find_window())
        {
            x.take();
        }
    }
}

#[cfg(not(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android")))))]
mod no_x11 {
    /// No X display: nothing to find or take.
    pub(super) struct Display {
        pub(super) window: Option<()>,
    }

    impl Display {
        pub(super) fn open() -> Option<Self> {
            None
        }
        pub(super) fn find_window(&mut self) -> bool {
            false
        }
        pub(super) fn unowned(&self) -> bool {
            false
        }
        pub(super) fn take(&self) {}
    }
}

#[cfg(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))))]
mod x11 {
    use x11rb::connection::Connection;
    use x11rb::protocol::xproto::{AtomEnum, ConnectionExt, EventMask, InputFocus, MapState, Window};
    use x11rb::rust_connection::RustConnection;

    /// The X focus's "nobody" values: `None` and `PointerRoot`.
    const NO_WINDOW: [Window; 2] = [0, 1];

    /// A connection to the window's X display, with the window once found.
    pub(super) struct Display {
        connection: RustConnection,
        root: Window,
        /// This process's top-level window, once found.
        pub(super) window: Option<Window>,
    }

    impl Display {
        /// Connects to `$DISPLAY` unless the window is on Wayland (then X has no
        /// say on its focus).
        pub(super) fn open() -> Option<Self> {
            if std::env::var_os("WAYLAND_DISPLAY").is_some_and(|v| !v.is_empty()) {
                return None;
            }
            let (connection, screen) = x11rb::connect(None).ok()?;
            let root = connection.setup().roots.get(screen)?.root;
            Some(Display { connection, root, window: None })
        }

        /// Looks for this process's window among the root's children (winit marks it
        /// with `_NET_WM_PID`), the topmost viewable one; returns whether it was found.
        pub(super) fn find_window(&mut self) -> bool {
            self.window = self.viewable_window_of_this_process();
            self.window.is_some()
        }

        fn viewable_window_of_this_process(&self) -> Option<Window> {
            let c = &self.connection;
            let pid_atom = c.intern_atom(true, b"_NET_WM_PID").ok()?.reply().ok()?.atom;
            let children = c.query_tree(self.root).ok()?.reply().ok()?.children;
            // Bottom to top: the last match is the topmost.
            children.into_iter().rev().find(|&w| {
                let pid = c
                    .get_property(false, w, pid_atom, AtomEnum::CARDINAL, 0, 1)
                    .ok()
                    .and_then(|cookie| cookie.reply().ok())
                    .and_then(|p| p.value32().and_then(|mut v| v.next()));
                let viewable = || {
                    c.get_window_attributes(w)
                        .ok()
                        .and_then(|cookie| cookie.reply().ok())
                        .is_some_and(|a| a.map_state == MapState::VIEWABLE)
                };
                pid == Some(std::process::id()) && viewable()
            })
        }

        /// The window holding the focus (`None` and `PointerRoot` are 0 and 1).
        fn focus(&self) -> Option<Window> {
            self.connection.get_input_focus().ok().and_then(|c| c.reply().ok()).map(|f| f.focus)
        }

        /// Whether no window holds the focus (`None` or `PointerRoot`): keys then go
        /// nowhere, or to whatever the pointer is over with nobody to say so.
        pub(super) fn unowned(&self) -> bool {
            self.focus().is_some_and(|f| NO_WINDOW.contains(&f))
        }

        /// Whether a window manager runs: it redirects the root's substructure (and
        /// gives the focus itself).
        fn window_manager(&self) -> bool {
            let attributes = self.connection.get_window_attributes(self.root).ok().and_then(|c| c.reply().ok());
            // Unknown: leave the focus to whoever may manage it.
            attributes.is_none_or(|a| u32::from(a.all_event_masks) & u32::from(EventMask::SUBSTRUCTURE_REDIRECT) != 0)
        }

        /// Gives the window the focus, when no window manager would and it does not
        /// have it (setting it again would tell the window it lost it, and egui would
        /// leave the field being typed in); it reverts to the root's if the window goes.
        pub(super) fn take(&self) {
            let Some(window) = self.window else { return };
            if self.focus() == Some(window) || self.window_manager() {
                return;
            }
            let set = self.connection.set_input_focus(InputFocus::PARENT, window, x11rb::CURRENT_TIME);
            // An error (the window unmapped meanwhile) leaves the focus where it was.
            if let Ok(cookie) = set {
                let _ = cookie.check();
            }
        }
    }
}
