//! The window's panel (egui): run controls and speed, live plots of the
//! program's sensors, a table of the named objects and joints, sliders for the joints'
//! position set-points, and a screenshot button. Never drawn off screen.

use ars_core::{JointId, PositionServo, Profile, Simulation};
use egui_plot::{Line, Plot, PlotPoints};
use kiss3d::egui;

/// What the panel asks the window to do this frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Command {
    /// Pause or resume.
    TogglePause,
    /// One frame while paused.
    StepFrame,
    /// One physics step while paused.
    StepPhysics,
    /// Rebuild the simulation.
    Reset,
    /// Write a PNG of the window.
    Screenshot,
    /// Follow an object with the camera, or stop.
    ToggleFollow,
    /// Draw the contact points, or stop.
    ToggleContacts,
    /// Draw the joints' anchors and axes, or stop.
    ToggleJoints,
    /// Draw the world axes, or stop.
    ToggleAxes,
    /// Set a joint's position set-point (rad or m).
    Setpoint(JointId, f64),
}

/// The panel's own state.
pub(crate) struct Panel {
    /// Whether it is shown (`g`).
    pub(crate) shown: bool,
    /// Simulated seconds per wall-clock second.
    pub(crate) speed: f64,
    /// Run as fast as the machine can (no real-time pacing).
    pub(crate) fastest: bool,
    sensor: usize,
    column: usize,
    /// Seconds of simulated time the plot shows.
    span: f64,
    /// Where the panel was drawn last, `[left, top, right, bottom]`, with the size of
    /// the window, in egui's points (`None` while hidden).
    pub(crate) covers: Option<([f32; 4], (f32, f32))>,
}

impl Default for Panel {
    fn default() -> Self {
        Panel { shown: true, speed: 1.0, fastest: false, sensor: 0, column: 0, span: 10.0, covers: None }
    }
}

/// What the window tells the panel about itself.
pub(crate) struct Status<'a> {
    /// The window's title (the program's), the panel's heading.
    pub(crate) title: &'a str,
    pub(crate) paused: bool,
    pub(crate) real_time_factor: f64,
    pub(crate) following: bool,
    pub(crate) contacts: bool,
    pub(crate) joints: bool,
    pub(crate) axes: bool,
}

impl Panel {
    /// Draws the panel for `sim` and returns what was asked.
    pub(crate) fn draw(&mut self, ctx: &egui::Context, sim: &Simulation, status: &Status<'_>) -> Vec<Command> {
        let mut commands = Vec::new();
        self.covers = None;
        if !self.shown {
            return commands;
        }
        let window = egui::Window::new("ARS").default_pos([8.0, 8.0]).default_width(340.0).resizable(true);
        let shown = window.show(ctx, |ui| {
            ui.heading(status.title);
            ui.label(format!(
                "t = {:.3} s, step {}   ×{:.2} real time",
                sim.time(),
                sim.step_count(),
                status.real_time_factor
            ));
            ui.horizontal(|ui| {
                if ui.button(if status.paused { "▶ Run" } else { "⏸ Pause" }).clicked() {
                    commands.push(Command::TogglePause);
                }
                if ui.add_enabled(status.paused, egui::Button::new("Frame")).clicked() {
                    commands.push(Command::StepFrame);
                }
                if ui.add_enabled(status.paused, egui::Button::new("Step")).clicked() {
                    commands.push(Command::StepPhysics);
                }
                if ui.button("Reset").clicked() {
                    commands.push(Command::Reset);
                }
            });
            ui.horizontal(|ui| {
                ui.label("Speed");
                ui.add_enabled(
                    !self.fastest,
                    egui::Slider::new(&mut self.speed, 0.1..=10.0).logarithmic(true).suffix("×"),
                );
                ui.checkbox(&mut self.fastest, "fastest");
            });
            ui.horizontal(|ui| {
                if ui.selectable_label(status.following, "Follow").clicked() {
                    commands.push(Command::ToggleFollow);
                }
                if ui.selectable_label(status.contacts, "Contacts").clicked() {
                    commands.push(Command::ToggleContacts);
                }
                if ui.selectable_label(status.joints, "Joints").clicked() {
                    commands.push(Command::ToggleJoints);
                }
                if ui.selectable_label(status.axes, "Axes").clicked() {
                    commands.push(Command::ToggleAxes);
                }
                if ui.button("Screenshot (p)").clicked() {
                    commands.push(Command::Screenshot);
                }
            });
            ui.separator();
            self.plots(ui, sim);
            ui.separator();
            setpoints(ui, sim, &mut commands);
            ui.separator();
            egui::ScrollArea::vertical().min_scrolled_height(260.0).show(ui, |ui| state_table(ui, sim));
        });
        if let Some(shown) = shown {
            let (r, screen) = (shown.response.rect, ctx.viewport_rect());
            let o = screen.min;
            let rect = [r.min.x - o.x, r.min.y - o.y, r.max.x - o.x, r.max.y - o.y];
            self.covers = Some((rect, (screen.width(), screen.height())));
        }
        commands
    }

    /// A plot of one column of one sensor, over the last `span` seconds.
    fn plots(&mut self, ui: &mut egui::Ui, sim: &Simulation) {
        let tables = sim.sensor_tables();
        if tables.is_empty() {
            ui.label("No sensors to plot.");
            return;
        }
        self.sensor = self.sensor.min(tables.len() - 1);
        let (name, log) = (&tables[self.sensor].0, tables[self.sensor].1);
        let headers = log.headers();
        self.column = self.column.min(headers.len().saturating_sub(1));
        ui.horizontal(|ui| {
            egui::ComboBox::from_id_salt("ars-plot-sensor")
                .selected_text(format!("{}: {}", self.sensor + 1, elided(name)))
                .show_ui(ui, |ui| {
                    for (i, (n, _)) in tables.iter().enumerate() {
                        ui.selectable_value(&mut self.sensor, i, format!("{}: {}", i + 1, elided(n)));
                    }
                });
            egui::ComboBox::from_id_salt("ars-plot-column")
                .selected_text(headers.get(self.column).cloned().unwrap_or_default())
                .show_ui(ui, |ui| {
                    for (i, h) in headers.iter().enumerate() {
                        ui.selectable_value(&mut self.column, i, h);
                    }
                });
        });
        ui.add(egui::Slider::new(&mut self.span, 1.0..=60.0).text("s shown"));
        // The samples of the last `span` seconds (found by bisection: the log is
        // not copied), at most about 2,000 of them.
        let from = sim.time() - self.span;
        let (mut first, mut end) = (0, log.len());
        while first < end {
            let mid = (first + end) / 2;
            if log.stamp(mid).0 < from { first = mid + 1 } else { end = mid }
        }
        let every = ((log.len() - first) / 2000).max(1);
        let points: Vec<[f64; 2]> = (first..log.len())
            .step_by(every)
            .filter_map(|i| Some([log.stamp(i).0, log.cells(i).get(self.column).copied().flatten()?]))
            .collect();
        let label = headers.get(self.column).cloned().unwrap_or_default();
        Plot::new("ars-plot").height(180.0).allow_scroll(false).show(ui, |plot| {
            plot.line(Line::new(label, PlotPoints::from(points)));
        });
    }
}

/// A slider for every joint held by a position servo: its set-point.
fn setpoints(ui: &mut egui::Ui, sim: &Simulation, commands: &mut Vec<Command>) {
    let mut any = false;
    for (name, id) in sim.joints() {
        let Ok(Some(servo)) = sim.joint_controller::<PositionServo>(id) else { continue };
        any = true;
        let mut value = servo.setpoint.value(sim.time());
        let slider = egui::Slider::new(&mut value, -std::f64::consts::PI..=std::f64::consts::PI).text(elided(name));
        if ui.add(slider).on_hover_text(name).changed() {
            commands.push(Command::Setpoint(id, value));
        }
    }
    if !any {
        ui.label("No position set-points (joints with a PositionServo get a slider).");
    }
}

/// The named objects (position, speed) and joints (position, rate), live.
fn state_table(ui: &mut egui::Ui, sim: &Simulation) {
    egui::CollapsingHeader::new("Objects").default_open(true).show(ui, |ui| {
        egui::Grid::new("ars-objects").striped(true).show(ui, |ui| {
            ui.strong("name");
            ui.strong("x, y, z [m]");
            ui.strong("speed [m/s]");
            ui.end_row();
            for (name, id) in sim.objects() {
                let Ok(object) = sim.object(id) else { continue };
                let Ok(body) = object.body() else { continue };
                let p = body.position();
                name_label(ui, name);
                ui.monospace(format!("{:7.3} {:7.3} {:7.3}", p.x, p.y, p.z));
                ui.monospace(format!("{:7.3}", body.linear_velocity().norm()));
                ui.end_row();
            }
        });
    });
    egui::CollapsingHeader::new("Joints").default_open(true).show(ui, |ui| {
        egui::Grid::new("ars-joints").striped(true).show(ui, |ui| {
            ui.strong("name");
            ui.strong("type");
            ui.strong("position");
            ui.strong("rate");
            ui.end_row();
            for (name, id) in sim.joints() {
                let Ok(joint) = sim.joint(id) else { continue };
                name_label(ui, name);
                ui.label(joint.joint_type().default_name());
                match joint.state() {
                    Ok(s) => {
                        ui.monospace(format!("{:8.4}", s.position));
                        ui.monospace(format!("{:8.4}", s.rate));
                    }
                    Err(_) => {
                        ui.label("");
                        ui.label("");
                    }
                }
                ui.end_row();
            }
        });
    });
}

/// The longest name the panel shows whole, in characters.
const SHOWN_NAME_CHARS: usize = 24;

/// `name`, or its start and end around an ellipsis when it is longer than
/// [`SHOWN_NAME_CHARS`] (the original's default names, such as
/// `sphere/<ars.model.simulator.SimulatedBody object at 0x7f…>`, would widen the
/// panel over the scene).
fn elided(name: &str) -> String {
    let count = name.chars().count();
    if count <= SHOWN_NAME_CHARS {
        return name.to_owned();
    }
    let tail = SHOWN_NAME_CHARS / 2;
    let head = SHOWN_NAME_CHARS - tail - 1;
    let start: String = name.chars().take(head).collect();
    let end: String = name.chars().skip(count - tail).collect();
    format!("{start}…{end}")
}

/// A name in the state table: elided when long, whole on hover.
fn name_label(ui: &mut egui::Ui, name: &str) {
    ui.label(elided(name)).on_hover_text(name);
}

/// Applies a set-point from the panel to the joint's position servo.
pub(crate) fn set_setpoint(sim: &mut Simulation, joint: JointId, value: f64) -> ars_core::Result<()> {
    let profile = Profile::constant(value)?;
    if let Some(servo) = sim.joint_mut(joint)?.controller_mut::<PositionServo>() {
        servo.setpoint = profile;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_names_keep_their_start_and_end_around_an_ellipsis() {
        assert_eq!(elided("arm"), "arm");
        let exact = "a".repeat(SHOWN_NAME_CHARS);
        assert_eq!(elided(&exact), exact);
        let long = "sphere/<ars.model.simulator.SimulatedBody object at 0x7f3a2c1d>";
        let short = elided(long);
        assert_eq!(short.chars().count(), SHOWN_NAME_CHARS);
        assert_eq!(short, "sphere/<ars… 0x7f3a2c1d>");
        // Characters, not bytes: a name in Greek is cut between letters.
        assert_eq!(elided(&"αβγδ".repeat(10)).chars().count(), SHOWN_NAME_CHARS);
    }
}
