//! The window's session: what one window holds while it runs a simulation (the
//! camera's view, the mouse's hand, the panel, the pacing), its frame loop, and the
//! one place where a [`Command`], asked by a key or by the panel, is applied.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use ars_core::nalgebra::Matrix4;
use ars_core::{Program, ProgramRunner, Simulation, WindowSettings};
use kiss3d::camera::Camera3d;
use kiss3d::event::{Action, Key as WindowKey, Modifiers, MouseButton, WindowEvent};
use kiss3d::glamx::Vec2;
use kiss3d::post_processing::Fxaa;
use kiss3d::text::Font;
use kiss3d::window::Window;

use crate::ViewerOptions;
use crate::command::{Command, key_command};
use crate::convert;
use crate::driver::{Driver, Shown};
use crate::edit::{Edit, apply_edit};
use crate::error::Result;
use crate::focus::Focus;
use crate::gui;
use crate::hand::{Hand, drag_mode, held_modifiers};
use crate::layout;
use crate::scene::DrawnScene;
use crate::state::{DragLine, Selected, ViewerState};
use crate::video::WindowVideo;
use crate::viewports;
use crate::window::{VIEWER_KEYS, WindowReport, open_window, resident_mb};
use crate::window_views::Viewports;

/// Opens the program's window and runs it until the window is closed; returns the
/// simulation as it was then.
pub(crate) fn run_window<P: Program>(program: &mut P, options: &ViewerOptions) -> Result<ars_core::Simulation> {
    run_window_until(program, options, None).map(|(sim, _)| sim)
}

/// The window loop of a program, until the window closes or `limit` of wall time has
/// passed.
pub(crate) fn run_window_until<P: Program>(
    program: &mut P,
    options: &ViewerOptions,
    limit: Option<Duration>,
) -> Result<(ars_core::Simulation, WindowReport)> {
    let view = program.window_settings();
    let mut runner = ProgramRunner::new(program)?;
    let report = drive_window(&mut runner, &view, options, limit, None)?;
    Ok((runner.into_simulation(), report))
}

/// The window loop: shows what `runner` drives until the window closes or `limit` of
/// wall time has passed.
pub(crate) fn drive_window<D: Driver>(
    runner: &mut D,
    view: &WindowSettings,
    options: &ViewerOptions,
    limit: Option<Duration>,
    video: Option<&mut WindowVideo>,
) -> Result<WindowReport> {
    kiss3d::pollster::block_on(async move {
        let mut session = Session::open(runner, view, options).await?;
        let outcome = session.run(limit, video).await;
        let report = session.close();
        outcome.map(|()| report)
    })
}

/// Frames run per drawn frame at most when the simulation is behind wall time.
const MAX_CATCH_UP_FRAMES: u32 = 4;

/// One window running what a [`Driver`] drives (or a file opened from the panel).
pub(crate) struct Session<'a, D: Driver> {
    /// The program's simulation, or a file opened from the panel (then titled so).
    runner: Shown<'a, D>,
    view: &'a WindowSettings,
    title: String,
    window: Window,
    shown: DrawnScene,
    hand: Hand,
    /// The keyboard focus, taken where no window manager gives it.
    focus: Focus,
    feedback: Feedback,
    views: Viewports,
    /// Where the extra views were drawn last (their clicks are not the scene's).
    view_covers: Vec<layout::Rect>,
    font: Arc<Font>,
    paused: bool,
    pacer: Pacer,
    panel: gui::Panel,
    started: Instant,
    report: WindowReport,
    /// Without multisampling (drawing fast), FXAA smooths the edges for a few
    /// milliseconds a frame.
    fxaa: Fxaa,
    smooth: bool,
}

impl<'a, D: Driver> Session<'a, D> {
    /// Opens the window for what `runner` drives, as `view` and `options` say.
    pub(crate) async fn open(runner: &'a mut D, view: &'a WindowSettings, options: &ViewerOptions) -> Result<Self> {
        let mut runner = Shown::new(runner);
        let mut window = open_window(view).await?;
        window.rebind_close_key(Some(WindowKey::Escape));
        window.set_background_color(convert::color(view.background));
        let mut shown = DrawnScene::new(view, &mut window);
        shown.mirror.show_axes = options.axes;
        // A plain left drag orbits; with a modifier it drags the selected body.
        shown.camera.orbit.set_rotate_modifiers(Some(Modifiers::empty()));
        let mut feedback = Feedback::default();
        let mut views = Viewports::new();
        views.count = options.views.clamp(1, 4);
        if options.forces {
            shown.mirror.show_forces = true;
            feedback.show(&mut runner.simulation(), true);
        }
        let pacer = Pacer::new(runner.simulation().scene().time());
        let smooth = shown.mirror.draws_fast();
        Ok(Session {
            runner,
            view,
            title: view.title.clone(),
            window,
            shown,
            hand: Hand::default(),
            focus: Focus::new(),
            feedback,
            views,
            view_covers: Vec::new(),
            font: Font::default(),
            paused: false,
            pacer,
            panel: gui::Panel::default(),
            started: Instant::now(),
            report: WindowReport::default(),
            fxaa: Fxaa::new(),
            smooth,
        })
    }

    /// The frame loop, until the window closes, the program asks to close, or `limit`
    /// of wall time has passed; each drawn frame goes to `video` too.
    pub(crate) async fn run(&mut self, limit: Option<Duration>, mut video: Option<&mut WindowVideo>) -> Result<()> {
        loop {
            if !self.render().await {
                return Ok(());
            }
            self.focus.shown();
            let wall = self.started.elapsed();
            self.report.frames += 1;
            // The first frame is drawn before the scene is (see `shown.update`).
            if let Some(video) = video.as_deref_mut().filter(|_| self.report.frames > 1) {
                let time = self.time();
                video.shown(time, || self.window.snap_image())?;
            }
            if wall.as_secs_f64() >= self.report.resident_mb.len() as f64 {
                self.report.resident_mb.push((wall.as_secs_f64(), resident_mb()));
            }
            if limit.is_some_and(|l| wall >= l) {
                return Ok(());
            }
            self.events()?;
            // Ctrl-C in the terminal closes the window too, once the program asked for
            // it (`ars_core::interrupt::stop_on_ctrl_c`: the examples do).
            if self.runner.wants_to_close() || ars_core::interrupt::requested() {
                return Ok(());
            }
            self.drag();
            self.advance()?;
            self.draw_panel().await?;
            self.tell_driver();
            self.draw()?;
        }
    }

    /// Ends the session: a drag in progress ends with the window (closed, or stopped by
    /// an error), so that its hooks do not go on pushing the body in the simulation
    /// handed back. Returns what the run measured.
    pub(crate) fn close(mut self) -> WindowReport {
        self.hand.deselect(&mut self.runner.simulation());
        self.report.wall_seconds = self.started.elapsed().as_secs_f64();
        self.report.simulated_seconds = self.time();
        self.report
    }

    /// Draws the frame prepared; `false` once the window is closed.
    async fn render(&mut self) -> bool {
        let (window, shown) = (&mut self.window, &mut self.shown);
        if self.smooth {
            window.render_3d_with_chain(&mut shown.scene, &mut shown.camera, &mut [&mut self.fxaa]).await
        } else {
            window.render_3d(&mut shown.scene, &mut shown.camera).await
        }
    }

    fn time(&mut self) -> f64 {
        self.runner.simulation().scene().time()
    }

    fn size(&self) -> Vec2 {
        Vec2::new(self.window.width() as f32, self.window.height() as f32)
    }

    /// Pacing starts again from now, at the panel's speed.
    fn restart_pacer(&mut self) {
        self.pacer = Pacer::with_speed(self.time(), self.panel.speed);
    }

    /// This frame's events: clicks and drags on the scene, and keys (the viewer's
    /// commands, or the program's). An event handled here is inhibited: the camera and
    /// the panel do not see it.
    fn events(&mut self) -> Result<()> {
        // Keys pressed in this frame's events: under X11 a press sometimes arrives
        // twice in one frame (seen with xdotool); a press of a key already down in
        // the same frame is that copy, not a new press.
        let mut pressed: Vec<WindowKey> = Vec::new();
        // While a text field of the panel has the keyboard, keys are its own (any other
        // widget egui gave the focus to does not keep the window's keys); while the
        // pointer is over the panel, clicks are.
        let typing = self.window.egui_context().text_edit_focused();
        let egui_pointer = self.window.is_egui_capturing_mouse();
        let mut panels: Vec<layout::Rect> = self.panel.covers.map(|(r, _)| r).into_iter().collect();
        panels.extend(self.panel.editor_covers);
        panels.extend(self.view_covers.iter().copied());
        let mut events = self.window.events();
        for mut event in events.iter() {
            match event.value {
                WindowEvent::CursorPos(x, y, _) => {
                    self.hand.cursor = (x, y);
                    // A drag moves the body, not the camera; so does a drag that will
                    // be one (the left button down with a drag's modifier held).
                    event.inhibited = self.hand.grab.is_some() || self.dragging_with_modifier();
                }
                WindowEvent::MouseButton(MouseButton::Button1, action, modifiers) => {
                    if action == Action::Press {
                        self.focus.clicked();
                    }
                    let (cursor, seen) = (self.hand.cursor, self.hand.ui_cursor);
                    let over_panel = layout::pointer_on_panel(cursor, seen, egui_pointer, &panels);
                    if !over_panel || self.hand.grab.is_some() {
                        event.inhibited = self.button(action, modifiers);
                    }
                }
                WindowEvent::Key(WindowKey::Escape, action, _) => event.inhibited = self.escape(action, typing),
                WindowEvent::Key(key, action, modifiers) if !typing => {
                    // Every other key is the viewer's or the program's, not the camera's.
                    event.inhibited = true;
                    match action {
                        Action::Press if pressed.contains(&key) => continue,
                        Action::Press => pressed.push(key),
                        Action::Release => pressed.retain(|k| *k != key),
                    }
                    let ctrl = (modifiers | held_modifiers(&self.window)).contains(Modifiers::Control);
                    if let Some(command) = key_command(key, action, ctrl, self.paused) {
                        self.apply(command)?;
                    }
                }
                _ => {}
            }
        }
        Ok(())
    }

    /// Whether the left button is down with Ctrl, Shift or Alt held: a drag of the
    /// body, never the camera's orbit (X11 stamps the pointer's events with no
    /// modifiers while the window does not have the focus, and the camera would orbit).
    fn dragging_with_modifier(&self) -> bool {
        self.window.get_mouse_button(MouseButton::Button1) == Action::Press
            && drag_mode(held_modifiers(&self.window)).is_some()
    }

    /// The left button went down or up on the scene (`modifiers` held): a drag of the
    /// selected body starts or ends, or a click selects. Returns whether the button
    /// was the drag's (the camera must not see it).
    fn button(&mut self, action: Action, modifiers: Modifiers) -> bool {
        let ray = self.hand.ray(&self.shown.camera, self.size());
        match action {
            Action::Press => {
                let forward = convert::vector_back(self.shown.camera.orbit.at() - self.shown.camera.eye());
                let modifiers = modifiers | held_modifiers(&self.window);
                self.hand.press(&self.runner.simulation(), ray, forward, modifiers)
            }
            Action::Release => {
                let dragging = self.hand.grab.is_some();
                self.hand.release(&mut self.runner.simulation(), ray);
                dragging
            }
        }
    }

    /// Escape went down or up: returns whether the window must not see it. kiss3d
    /// closes the window on the close key's release. While a field is typed in, the
    /// press is egui's (it leaves the field); with a selection, it deselects; either
    /// way its release must not close the window. Otherwise it goes to kiss3d, and
    /// closes.
    fn escape(&mut self, action: Action, typing: bool) -> bool {
        match action {
            Action::Press if typing => {
                self.hand.escape_held = true;
                false
            }
            Action::Press if self.hand.selected.is_some() => {
                self.hand.escape_held = true;
                self.hand.deselect(&mut self.runner.simulation());
                true
            }
            Action::Release if self.hand.escape_held => {
                self.hand.escape_held = false;
                true
            }
            _ => false,
        }
    }

    /// Moves the drag's target under the cursor (an error ends the drag).
    fn drag(&mut self) {
        let ray = self.hand.ray(&self.shown.camera, self.size());
        let dragged = self.hand.drag(&mut self.runner.simulation(), ray, self.paused);
        if let Err(e) = dragged {
            self.panel.error = Some(format!("drag: {e}"));
            self.hand.deselect(&mut self.runner.simulation());
        }
    }

    /// Runs the simulation up to wall time (at the panel's speed), or for about 30 ms
    /// as fast as the machine can; nothing while paused.
    fn advance(&mut self) -> Result<()> {
        if self.panel.speed != self.pacer.speed {
            self.restart_pacer();
        }
        if self.paused {
            return Ok(());
        }
        if self.panel.fastest {
            let budget = Instant::now();
            while budget.elapsed() < Duration::from_millis(30) {
                self.runner.step_frame()?;
            }
        } else {
            let mut frames = 0;
            while self.time() < self.pacer.target() && frames < MAX_CATCH_UP_FRAMES {
                self.runner.step_frame()?;
                frames += 1;
            }
            let time = self.time();
            self.pacer.behind = time < self.pacer.target() - 0.1 * self.pacer.speed.max(1.0);
            if self.pacer.behind {
                // Give up on the lost time rather than spiral: keep pacing from now.
                self.pacer.wall_origin = Instant::now();
                self.pacer.sim_origin = time;
            }
        }
        let time = self.time();
        self.pacer.measure(time);
        Ok(())
    }

    /// The extra views and the panel, then what the panel asked.
    async fn draw_panel(&mut self) -> Result<()> {
        let selected = self.hand.selected.and_then(|id| Selected::of(&self.runner.simulation(), id));
        if selected.is_none() && self.hand.selected.is_some() {
            // The body is gone (removed by the program).
            self.hand.deselect(&mut self.runner.simulation());
        }
        if self.views.count > 1 {
            self.render_views().await?;
        }
        let drawn = selected.as_ref().and_then(|s| self.shown.mirror.drawn_color(s.id)).unwrap_or([0.5; 3]);
        let status = gui::Status {
            title: &self.title,
            paused: self.paused,
            real_time_factor: self.pacer.factor,
            following: self.shown.following,
            contacts: self.shown.mirror.show_contacts,
            forces: self.shown.mirror.show_forces,
            views: self.views.count,
            camera: self.views.camera,
            joints: self.shown.mirror.show_joints,
            axes: self.shown.mirror.show_axes,
            selected: selected.as_ref().map(|s| (s, drawn)),
        };
        let (views, panel, runner) = (&mut self.views, &mut self.panel, &mut self.runner);
        let (mut commands, mut covers) = (Vec::new(), Vec::new());
        self.window.draw_ui(|ctx| {
            covers = views.show(ctx);
            commands = panel.draw(ctx, &runner.simulation(), &status);
        });
        self.view_covers = covers;
        self.hand.ui_cursor = self.hand.cursor;
        self.shown.camera.shift = self.camera_shift();
        for command in commands {
            self.apply(command)?;
        }
        Ok(())
    }

    /// The extra views (follow, top, camera), drawn off screen.
    async fn render_views(&mut self) -> Result<()> {
        let sim = self.runner.simulation();
        let camera = &self.shown.camera;
        let free = (convert::point_back(camera.eye()), convert::point_back(camera.orbit.at()));
        let target = viewports::followed(&sim, self.hand.selected, self.shown.follow.as_deref());
        let size = (self.window.width() as f32, self.window.height() as f32);
        self.views.render(&sim, self.view, size, free, target).await?;
        Ok(())
    }

    /// The camera's shift: what it looks at appears in the middle of what the panel
    /// leaves free (from the next frame on).
    fn camera_shift(&self) -> Vec2 {
        match self.panel.covers {
            // Several views: the free one in the top-left quarter.
            _ if self.views.count > 1 => {
                let (w, h) = (self.window.width() as f32, self.window.height() as f32);
                let [l, t, r, b] = viewports::viewports(w, h, self.views.count)[0];
                layout::ndc_shift(w, h, ((l + r) / 2.0, (t + b) / 2.0))
            }
            Some((panel_rect, (w, h))) => {
                let panels: Vec<layout::Rect> = std::iter::once(panel_rect).chain(self.panel.editor_covers).collect();
                layout::ndc_shift(w, h, layout::free_centre_of(w, h, &panels))
            }
            None => Vec2::ZERO,
        }
    }

    /// Does what a key or the panel asked.
    fn apply(&mut self, command: Command) -> Result<()> {
        match command {
            Command::TogglePause => {
                self.paused = !self.paused;
                self.restart_pacer();
            }
            Command::StepFrame => self.runner.step_frame()?,
            Command::StepPhysics => self.runner.step()?,
            Command::Reset => self.reset()?,
            Command::Screenshot => screenshot(&self.window, &self.title),
            Command::ToggleFollow => self.shown.toggle_follow(&self.runner.simulation()),
            Command::ToggleContacts => self.shown.mirror.show_contacts ^= true,
            Command::ToggleForces => {
                self.shown.mirror.show_forces ^= true;
                self.feedback.show(&mut self.runner.simulation(), self.shown.mirror.show_forces);
            }
            Command::ToggleJoints => self.shown.mirror.show_joints ^= true,
            Command::ToggleAxes => self.shown.mirror.show_axes ^= true,
            Command::TogglePanel => self.panel.shown ^= true,
            Command::Setpoint(joint, value) => gui::set_setpoint(&mut self.runner.simulation(), joint, value)?,
            Command::Edit(edit) => self.edit(&edit),
            Command::Save => save(&self.runner.simulation(), &mut self.panel),
            Command::Open => self.open_file(),
            Command::Views(n) => self.views.count = n,
            Command::ViewportCamera(i) => self.views.camera = i,
            Command::Deselect => self.hand.deselect(&mut self.runner.simulation()),
            Command::KeyDown(key) => self.runner.key_down(key)?,
            Command::KeyUp(key) => self.runner.key_up(key)?,
        }
        Ok(())
    }

    /// Rebuilds the simulation (`r`, the panel's Reset).
    fn reset(&mut self) -> Result<()> {
        self.hand.deselect(&mut self.runner.simulation());
        self.runner.reset()?;
        self.rebuilt();
        Ok(())
    }

    /// The simulation shown is a new one (reset, or a file opened): nothing of the old
    /// one is drawn, and pacing starts again from its clock.
    fn rebuilt(&mut self) {
        self.shown.mirror.clear();
        self.views.clear();
        self.feedback.rebuilt(&mut self.runner.simulation(), self.shown.mirror.show_forces);
        self.restart_pacer();
    }

    /// Applies an edit from the panel; a refusal is the panel's error.
    fn edit(&mut self, edit: &Edit) {
        match apply_edit(&mut self.runner.simulation(), edit) {
            Ok(()) => {
                self.panel.error = None;
                if let Edit::Color(id, _) = *edit {
                    self.shown.mirror.redraw(id);
                    self.views.redraw(id);
                }
            }
            Err(e) => self.panel.error = Some(e.to_string()),
        }
    }

    /// Shows the file the panel names instead of what was shown.
    fn open_file(&mut self) {
        let path = PathBuf::from(self.panel.open_path.trim());
        let opened = match Simulation::open(&path) {
            Ok(opened) => opened,
            Err(e) => {
                self.panel.error = Some(format!("not opened: {e}"));
                return;
            }
        };
        self.hand.deselect(&mut self.runner.simulation());
        eprintln!("opened {}", path.display());
        let skipped = opened.skipped_summary();
        if let Some(line) = &skipped {
            eprintln!("{line}");
        }
        self.runner.open(path.clone(), opened.simulation);
        self.rebuilt();
        self.title = format!("ARS: {}", path.display());
        self.panel.opened = Some(path.display().to_string());
        self.panel.error = skipped;
    }

    /// Hands the driver what the window shows this frame.
    fn tell_driver(&mut self) {
        self.shown.mirror.force_scale = self.panel.force_scale;
        let size = self.size();
        let sim = self.runner.simulation();
        let state = ViewerState {
            paused: self.paused,
            selected: self.hand.selected.and_then(|id| Selected::of(&sim, id)),
            drag: self.hand.grab.and_then(|g| {
                let from = g.point(&sim).ok()?;
                Some(DragLine { mode: g.mode, from, to: g.target })
            }),
            error: self.panel.error.clone(),
            save_path: self.panel.save_path.clone().into(),
            saved: self.panel.saved.clone().map(Into::into),
            fields: self.panel.fields.clone(),
            field_texts: self.panel.field_texts.clone(),
            window_size: (size.x, size.y),
            views: self.views.count,
            view_projection: view_projection(&self.shown.camera),
        };
        drop(sim);
        self.runner.viewer_state(&state);
    }

    /// The scene as it is now, the selection and the drag; and the status and the keys
    /// in text while the panel (which says the same) is hidden.
    fn draw(&mut self) -> Result<()> {
        let sim = self.runner.simulation();
        self.shown.update(&sim, &mut self.window)?;
        self.hand.draw(&sim, &mut self.window);
        let time = sim.scene().time();
        drop(sim);
        if !self.panel.shown {
            self.overlay(time);
        }
        Ok(())
    }

    /// The status line and the keys, wrapped to the window's width (10 px margins).
    fn overlay(&mut self, time: f64) {
        let status = if self.paused {
            "paused".to_string()
        } else if self.pacer.behind {
            format!("x{:.2} real time: slower than real time", self.pacer.factor)
        } else {
            format!("x{:.2} real time", self.pacer.factor)
        };
        let (font, width) = (&self.font, self.window.width() as f32 - 20.0);
        let text = format!("t = {time:.3} s   {status}");
        let (text, lines) = wrapped(font, STATUS_SIZE, &text, "   ", width);
        let dark = kiss3d::color::Color::new(0.1, 0.1, 0.1, 1.0);
        self.window.draw_text(&text, Vec2::new(10.0, 10.0), STATUS_SIZE, font, dark);
        let (keys, _) = wrapped(font, KEYS_SIZE, VIEWER_KEYS, ", ", width);
        let at = Vec2::new(10.0, 16.0 + lines as f32 * line_height(font, STATUS_SIZE));
        self.window.draw_text(&keys, at, KEYS_SIZE, font, kiss3d::color::Color::new(0.3, 0.3, 0.3, 1.0));
    }
}

/// The text overlay's sizes, pixels: the status line, the key line.
const STATUS_SIZE: f32 = 28.0;
const KEYS_SIZE: f32 = 16.0;

/// How wide `text` is drawn in `font` at `size` pixels.
fn text_width(font: &Font, size: f32, text: &str) -> f32 {
    let scale = rusttype::Scale::uniform(size);
    font.font()
        .layout(text, scale, rusttype::point(0.0, 0.0))
        .last()
        .map_or(0.0, |g| g.position().x + g.unpositioned().h_metrics().advance_width)
}

/// The height of a line of `font` at `size` pixels, as kiss3d draws lines.
fn line_height(font: &Font, size: f32) -> f32 {
    let v = font.font().v_metrics(rusttype::Scale::uniform(size));
    v.ascent - v.descent
}

/// `text`, a list of items joined by `separator`, in lines no wider than `width`
/// pixels in `font` at `size`; with the number of lines.
fn wrapped(font: &Font, size: f32, text: &str, separator: &str, width: f32) -> (String, usize) {
    let items: Vec<&str> = text.split(separator).collect();
    let lines = layout::wrap_items(&items, separator, width, |s| text_width(font, size, s));
    (lines.join("\n"), lines.len())
}

/// The world's contact feedback (ODE's forces of the contact points), on while the
/// forces are drawn, and as it was before (a `ContactForces` sensor keeps it on) once
/// they are not.
#[derive(Default)]
struct Feedback {
    /// Whether the world reported the forces before the window asked.
    before: bool,
}

impl Feedback {
    /// Forces drawn (`on`) or not from now on.
    fn show(&mut self, sim: &mut Simulation, on: bool) {
        let world = sim.scene_mut().world_mut();
        if on {
            self.before = world.contact_feedback();
            crate::scene::report_forces(world);
        } else {
            world.set_contact_feedback(self.before);
        }
    }

    /// The simulation was rebuilt: ask the new one for the forces if they are drawn.
    fn rebuilt(&mut self, sim: &mut Simulation, on: bool) {
        if on {
            self.show(sim, true);
        }
    }
}

/// Saves the scene where the panel says, and says how it went.
fn save(sim: &Simulation, panel: &mut gui::Panel) {
    match sim.save_scene_to(&panel.save_path) {
        Ok(()) => {
            eprintln!("scene saved to {}", panel.save_path);
            panel.saved = Some(panel.save_path.clone());
            panel.error = None;
        }
        Err(e) => panel.error = Some(format!("not saved: {e}")),
    }
}

/// The camera's world-to-device matrix, in the simulation's numbers.
fn view_projection(camera: &layout::FramedCamera) -> Matrix4<f64> {
    let m = camera.transformation().to_cols_array().map(f64::from);
    Matrix4::from_column_slice(&m)
}

/// Real-time pacing: simulated time follows wall time while the machine keeps up.
struct Pacer {
    wall_origin: Instant,
    sim_origin: f64,
    /// Simulated seconds per wall-clock second.
    speed: f64,
    /// (wall, sim) a second ago, for the real-time factor.
    window: (Instant, f64),
    factor: f64,
    behind: bool,
}

impl Pacer {
    fn new(sim_time: f64) -> Self {
        Pacer::with_speed(sim_time, 1.0)
    }

    fn with_speed(sim_time: f64, speed: f64) -> Self {
        let now = Instant::now();
        Pacer { wall_origin: now, sim_origin: sim_time, speed, window: (now, sim_time), factor: 0.0, behind: false }
    }

    /// Simulated time to reach now.
    fn target(&self) -> f64 {
        self.sim_origin + self.speed * self.wall_origin.elapsed().as_secs_f64()
    }

    fn measure(&mut self, sim_time: f64) {
        let elapsed = self.window.0.elapsed();
        if elapsed >= Duration::from_millis(500) {
            self.factor = (sim_time - self.window.1) / elapsed.as_secs_f64();
            self.window = (Instant::now(), sim_time);
        }
    }
}

/// Writes what the window shows to `ars-<title>-<n>.png` in the current folder.
fn screenshot(window: &Window, title: &str) {
    let stem = title.to_lowercase().replace(|c: char| !c.is_ascii_alphanumeric(), "_");
    let path = (1..)
        .map(|n| std::path::PathBuf::from(format!("ars-{stem}-{n:03}.png")))
        .find(|p| !p.exists())
        .expect("a free name");
    match window.snap_image().save(&path) {
        Ok(()) => eprintln!("screenshot: {}", path.display()),
        Err(e) => eprintln!("screenshot not written ({}): {e}", path.display()),
    }
}
