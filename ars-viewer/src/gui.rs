//! The window's panel (egui): run controls and speed, live plots of the
//! program's sensors, a table of the named objects and joints, sliders for the joints'
//! position set-points, and a screenshot button. Never drawn off screen.

use std::collections::HashMap;

use ars_core::nalgebra::UnitQuaternion;
use ars_core::sensors::DepthCamera;
use ars_core::{Actuator, DcMotor, JointId, JointParam, ObjectId, PositionServo, Profile, Simulation, VelocityServo};
use egui_plot::{Line, Plot, PlotPoints};
use kiss3d::egui;

use crate::command::Command;
use crate::edit::{Edit, joint_param, parse_number};
use crate::state::Selected;

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
    /// Where the editor was drawn last, `[left, top, right, bottom]` (`None` while
    /// hidden).
    pub(crate) editor_covers: Option<[f32; 4]>,
    /// The editor's number fields being typed in, by label (a field not in it shows
    /// the simulation's value).
    typing: HashMap<String, String>,
    /// The editor's fields drawn last frame, by label, with their rectangles (window
    /// pixels).
    pub(crate) fields: Vec<(String, [f32; 4])>,
    /// What each of those fields showed, by label: the characters drawn whole.
    pub(crate) field_texts: Vec<(String, String)>,
    /// The joint the editor shows.
    joint: Option<JointId>,
    /// The error shown in red: the last edit refused, or a save that failed.
    pub(crate) error: Option<String>,
    /// Where the scene is saved.
    pub(crate) save_path: String,
    /// Where it was saved last.
    pub(crate) saved: Option<String>,
    /// The file to open.
    pub(crate) open_path: String,
    /// The file shown, if one was opened.
    pub(crate) opened: Option<String>,
    /// The contact-force arrows' length per newton, m/N.
    pub(crate) force_scale: f64,
}

impl Default for Panel {
    fn default() -> Self {
        let stamp = std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_secs());
        Panel {
            shown: true,
            speed: 1.0,
            fastest: false,
            sensor: 0,
            column: 0,
            span: 10.0,
            covers: None,
            editor_covers: None,
            typing: HashMap::new(),
            fields: Vec::new(),
            field_texts: Vec::new(),
            joint: None,
            error: None,
            save_path: format!("./scene-{stamp}.json"),
            saved: None,
            open_path: String::new(),
            opened: None,
            force_scale: crate::scene::DEFAULT_FORCE_SCALE,
        }
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
    /// Whether contact forces are drawn.
    pub(crate) forces: bool,
    /// How many views are shown.
    pub(crate) views: usize,
    /// The depth camera the camera view shows (from 0).
    pub(crate) camera: usize,
    pub(crate) joints: bool,
    pub(crate) axes: bool,
    /// The selected body, with the colour it is drawn with.
    pub(crate) selected: Option<(&'a Selected, [f32; 3])>,
}

impl Panel {
    /// Draws the panel for `sim` and returns what was asked.
    pub(crate) fn draw(&mut self, ctx: &egui::Context, sim: &Simulation, status: &Status<'_>) -> Vec<Command> {
        let mut commands = Vec::new();
        self.covers = None;
        self.editor_covers = None;
        if !self.shown {
            return commands;
        }
        let window = egui::Window::new("ARS").default_pos([8.0, 8.0]).default_width(340.0).resizable(true);
        let shown = window.show(ctx, |ui| {
            ui.heading(status.title);
            ui.label(format!(
                "t = {:.3} s, step {}   ×{:.2} real time",
                sim.scene().time(),
                sim.scene().step_count(),
                status.real_time_factor
            ));
            ui.horizontal(|ui| run_buttons(ui, status, &mut commands));
            ui.horizontal(|ui| {
                ui.label("Speed");
                ui.add_enabled(
                    !self.fastest,
                    egui::Slider::new(&mut self.speed, 0.1..=10.0).logarithmic(true).suffix("×"),
                );
                ui.checkbox(&mut self.fastest, "fastest");
            });
            ui.horizontal(|ui| display_toggles(ui, status, &mut commands));
            ui.horizontal(|ui| view_choice(ui, sim, status, &mut commands));
            if status.forces {
                let slider = egui::Slider::new(&mut self.force_scale, 0.001..=1.0).logarithmic(true).suffix(" m/N");
                ui.add(slider.text("force arrows"));
            }
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
        self.fields.clear();
        self.field_texts.clear();
        let editor = egui::Window::new("Edit").anchor(egui::Align2::RIGHT_TOP, [-8.0, 8.0]).default_width(280.0);
        let edited = editor.show(ctx, |ui| self.editor(ui, sim, status, &mut commands));
        self.editor_covers = edited.map(|shown| {
            let (r, o) = (shown.response.rect, ctx.viewport_rect().min);
            [r.min.x - o.x, r.min.y - o.y, r.max.x - o.x, r.max.y - o.y]
        });
        commands
    }

    /// The editor: the selected body, a joint, the simulation's settings, saving.
    fn editor(&mut self, ui: &mut egui::Ui, sim: &Simulation, status: &Status<'_>, commands: &mut Vec<Command>) {
        if let Some(error) = &self.error {
            ui.colored_label(egui::Color32::from_rgb(220, 40, 40), error);
        }
        egui::CollapsingHeader::new("Selected body").default_open(true).show(ui, |ui| match status.selected {
            None => {
                ui.label("Click a body to select it; Ctrl+drag pulls it, Shift+drag turns it.");
            }
            Some((s, rgb)) => self.selected_body(ui, s, rgb, status.paused, commands),
        });
        egui::CollapsingHeader::new("Joint").default_open(status.selected.is_some()).show(ui, |ui| {
            self.joint_editor(ui, sim, status.selected.map(|(s, _)| s.id), commands);
        });
        egui::CollapsingHeader::new("Simulation").default_open(false).show(ui, |ui| {
            let g = sim.scene().gravity();
            egui::Grid::new("ars-edit-sim").show(ui, |ui| {
                for (axis, label) in ["gravity x", "gravity y", "gravity z"].into_iter().enumerate() {
                    ui.label(label);
                    if let Some(v) = self.number(ui, label, g[axis]) {
                        let mut g = g;
                        g[axis] = v;
                        commands.push(Command::Edit(Edit::Gravity(g)));
                    }
                    ui.end_row();
                }
                let world = sim.scene().world();
                type Make = fn(f64) -> Edit;
                let settings: [(&str, f64, Make); 3] = [
                    ("time step", sim.scene().time_step(), Edit::TimeStep),
                    ("ERP", world.erp(), Edit::Erp),
                    ("CFM", world.cfm(), Edit::Cfm),
                ];
                for (label, value, make) in settings {
                    ui.label(label);
                    if let Some(v) = self.number(ui, label, value) {
                        commands.push(Command::Edit(make(v)));
                    }
                    ui.end_row();
                }
            });
        });
        ui.separator();
        ui.horizontal(|ui| {
            if ui.button("Save (Ctrl+S)").clicked() {
                commands.push(Command::Save);
            }
            ui.add(egui::TextEdit::singleline(&mut self.save_path).desired_width(170.0));
        });
        if let Some(saved) = &self.saved {
            ui.label(format!("saved to {saved}"));
        }
        ui.horizontal(|ui| {
            if ui.button("Open").on_hover_text("a scene file (.json), a URDF robot or an MJCF model (.xml)").clicked() {
                commands.push(Command::Open);
            }
            ui.add(egui::TextEdit::singleline(&mut self.open_path).hint_text("file").desired_width(170.0));
        });
        if let Some(opened) = &self.opened {
            ui.label(format!("showing {opened}"));
        }
    }

    /// The selected body: what it is and where, and its colour, mass and pose to edit.
    fn selected_body(
        &mut self,
        ui: &mut egui::Ui,
        s: &Selected,
        mut rgb: [f32; 3],
        paused: bool,
        commands: &mut Vec<Command>,
    ) {
        ui.horizontal(|ui| {
            ui.strong(elided(&s.name)).on_hover_text(&s.name);
            if ui.small_button("✖ (Esc)").clicked() {
                commands.push(Command::Deselect);
            }
        });
        let (roll, pitch, yaw) = s.rotation.euler_angles();
        let v3 = |v: [f64; 3]| format!("{:7.3} {:7.3} {:7.3}", v[0], v[1], v[2]);
        egui::Grid::new("ars-selected").show(ui, |ui| {
            ui.label("position [m]");
            ui.monospace(v3(s.position.coords.into()));
            ui.end_row();
            ui.label("roll pitch yaw [°]");
            ui.monospace(v3([roll.to_degrees(), pitch.to_degrees(), yaw.to_degrees()]));
            ui.end_row();
            ui.label("velocity [m/s]");
            ui.monospace(v3(s.linear_velocity.into()));
            ui.end_row();
            ui.label("angular [rad/s]");
            ui.monospace(v3(s.angular_velocity.into()));
            ui.end_row();
        });
        egui::Grid::new("ars-edit-body").show(ui, |ui| {
            ui.label("colour");
            if ui.color_edit_button_rgb(&mut rgb).changed() {
                commands.push(Command::Edit(Edit::Color(s.id, rgb)));
            }
            ui.end_row();
            ui.label("mass [kg]");
            if let Some(m) = self.number(ui, "mass", s.mass) {
                commands.push(Command::Edit(Edit::Mass(s.id, m)));
            }
            ui.end_row();
            if let Some(volume) = s.volume {
                ui.label("density [kg/m³]");
                if let Some(rho) = self.number(ui, "density", s.mass / volume) {
                    commands.push(Command::Edit(Edit::Density(s.id, rho)));
                }
                ui.end_row();
            }
            for (axis, label) in ["x", "y", "z"].into_iter().enumerate() {
                ui.label(format!("{label} [m]"));
                let shown = format_pose(s.position[axis]);
                let field = ui.add_enabled_ui(paused, |ui| self.field(ui, label, shown)).inner;
                if let Some(v) = field {
                    let mut p = s.position;
                    p[axis] = v;
                    commands.push(Command::Edit(Edit::Position(s.id, p)));
                }
                ui.end_row();
            }
            let angles = [roll, pitch, yaw].map(f64::to_degrees);
            for (axis, label) in ["roll", "pitch", "yaw"].into_iter().enumerate() {
                ui.label(format!("{label} [°]"));
                let shown = format_pose(angles[axis]);
                let field = ui.add_enabled_ui(paused, |ui| self.field(ui, label, shown)).inner;
                if let Some(v) = field {
                    let mut a = angles;
                    a[axis] = v;
                    let [r, p, y] = a.map(f64::to_radians);
                    commands.push(Command::Edit(Edit::Rotation(s.id, UnitQuaternion::from_euler_angles(r, p, y))));
                }
                ui.end_row();
            }
        });
        if !paused {
            ui.label("Pause (space) to edit the pose.");
        }
    }

    /// A joint (of the selected body first): limits, motor, viscous friction, and its
    /// controller's set-point and gains.
    fn joint_editor(
        &mut self,
        ui: &mut egui::Ui,
        sim: &Simulation,
        selected: Option<ObjectId>,
        commands: &mut Vec<Command>,
    ) {
        let joints: Vec<(String, JointId)> = sim.scene().joints().map(|(n, id)| (n.to_string(), id)).collect();
        if joints.is_empty() {
            ui.label("No joints.");
            return;
        }
        let of_selected = |id: JointId| {
            sim.scene().joint(id).is_ok_and(|j| {
                let (a, b) = j.objects();
                Some(a) == selected || b == selected
            })
        };
        if self.joint.is_none_or(|j| sim.scene().joint(j).is_err()) {
            self.joint = joints.iter().map(|(_, id)| *id).find(|id| of_selected(*id)).or(Some(joints[0].1));
        }
        let Some(id) = self.joint else { return };
        let name = joints.iter().find(|(_, j)| *j == id).map(|(n, _)| n.clone()).unwrap_or_default();
        egui::ComboBox::from_id_salt("ars-edit-joint").selected_text(elided(&name)).show_ui(ui, |ui| {
            for (n, j) in &joints {
                let mark = if of_selected(*j) { " •" } else { "" };
                ui.selectable_value(&mut self.joint, Some(*j), format!("{}{mark}", elided(n)));
            }
        });
        let param = |p| joint_param(sim, id, p).unwrap_or(f64::NAN);
        egui::Grid::new("ars-edit-joint-grid").show(ui, |ui| {
            let (low, high) = (param(JointParam::LoStop), param(JointParam::HiStop));
            ui.label("limits low, high");
            ui.horizontal(|ui| {
                if let Some(v) = self.number(ui, "low", low) {
                    commands.push(Command::Edit(Edit::JointLimits(id, v, high)));
                }
                if let Some(v) = self.number(ui, "high", high) {
                    commands.push(Command::Edit(Edit::JointLimits(id, low, v)));
                }
            });
            ui.end_row();
            let (speed, force) = (param(JointParam::Velocity), param(JointParam::MaxForce));
            ui.label("motor speed, max");
            ui.horizontal(|ui| {
                if let Some(v) = self.number(ui, "motor speed", speed) {
                    commands.push(Command::Edit(Edit::Motor(id, v, force)));
                }
                if let Some(v) = self.number(ui, "motor max", force) {
                    commands.push(Command::Edit(Edit::Motor(id, speed, v)));
                }
            });
            ui.end_row();
            ui.label("viscous friction");
            let friction = sim.scene().joint(id).map_or(0.0, |j| j.viscous_friction());
            if let Some(v) = self.number(ui, "viscous friction", friction) {
                commands.push(Command::Edit(Edit::ViscousFriction(id, v)));
            }
            ui.end_row();
            self.controller_rows(ui, sim, id, commands);
        });
    }

    /// The rows of a joint's controller: its set-point and its gains.
    fn controller_rows(&mut self, ui: &mut egui::Ui, sim: &Simulation, id: JointId, commands: &mut Vec<Command>) {
        let now = sim.scene().time();
        let controller = if let Ok(Some(s)) = sim.scene().joint_controller::<PositionServo>(id) {
            Some(("position", s.setpoint.value(now), vec![("kp", s.pid.kp), ("ki", s.pid.ki), ("kd", s.pid.kd)]))
        } else if let Ok(Some(s)) = sim.scene().joint_controller::<VelocityServo>(id) {
            Some(("speed", s.setpoint.value(now), vec![("gain", s.gain)]))
        } else if let Ok(Some(m)) = sim.scene().joint_controller::<DcMotor>(id) {
            Some(("voltage", m.voltage.value(now), vec![]))
        } else {
            None
        };
        if let Some((what, setpoint, gains)) = controller {
            ui.label(format!("set-point ({what})"));
            if let Some(v) = self.number(ui, "set-point", setpoint) {
                commands.push(Command::Edit(Edit::Setpoint(id, v)));
            }
            ui.end_row();
            if !gains.is_empty() {
                ui.label(gains.iter().map(|(n, _)| *n).collect::<Vec<_>>().join(", "));
                ui.horizontal(|ui| {
                    let mut all = [0.0; 3];
                    for (i, (_, g)) in gains.iter().enumerate() {
                        all[i] = *g;
                    }
                    for (i, (label, g)) in gains.iter().enumerate() {
                        if let Some(v) = self.number(ui, label, *g) {
                            all[i] = v;
                            commands.push(Command::Edit(Edit::Gains(id, all)));
                        }
                    }
                });
                ui.end_row();
            }
        }
    }

    /// A number field showing `value`: what was typed once it is entered (Enter, or
    /// focus moved away) and differs from what was shown; a typo is the panel's error.
    fn number(&mut self, ui: &mut egui::Ui, label: &str, value: f64) -> Option<f64> {
        self.field(ui, label, format_number(value))
    }

    /// A number field showing `shown`: what was typed once it is entered and differs
    /// from it, as [`number`](Self::number) says.
    fn field(&mut self, ui: &mut egui::Ui, label: &str, shown: String) -> Option<f64> {
        let text = self.typing.entry(label.to_string()).or_insert_with(|| shown.clone());
        // At least 72 px wide, and as wide as its text: a number cut to the field's
        // width read as another number ("-0.20" of -0.207, "-93.8" of -93.878).
        let output = egui::TextEdit::singleline(text).desired_width(72.0).clip_text(false).show(ui);
        self.field_texts.push((label.to_string(), shown_text(&output)));
        let response = output.response.response.on_hover_text(label);
        let r = response.rect;
        self.fields.push((label.to_string(), [r.min.x, r.min.y, r.max.x, r.max.y]));
        if response.lost_focus() {
            let typed = self.typing.remove(label).unwrap_or_default();
            if typed.trim() == shown {
                return None;
            }
            match parse_number(label, &typed) {
                Ok(v) => return Some(v),
                Err(e) => self.error = Some(e),
            }
        } else if !response.has_focus() {
            // Not being typed in: show the simulation's value next frame.
            self.typing.remove(label);
        }
        None
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
        let from = sim.scene().time() - self.span;
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
    let pi = std::f64::consts::PI;
    for (name, id) in sim.scene().joints() {
        // A position servo's set-point, or an actuator's control over its range.
        let (mut value, range, label) = if let Ok(Some(servo)) = sim.scene().joint_controller::<PositionServo>(id) {
            (servo.setpoint.value(sim.scene().time()), -pi..=pi, name)
        } else if let Ok(Some(actuator)) = sim.scene().joint_controller::<Actuator>(id) {
            let (lo, hi) = actuator.ctrl_range().unwrap_or((-1.0, 1.0));
            (actuator.ctrl(), lo..=hi, actuator.name())
        } else {
            continue;
        };
        any = true;
        let slider = egui::Slider::new(&mut value, range).text(elided(label));
        if ui.add(slider).on_hover_text(label).changed() {
            commands.push(Command::Setpoint(id, value));
        }
    }
    if !any {
        ui.label("No set-points (joints with a PositionServo or an actuator get a slider).");
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
            for (name, id) in sim.scene().objects() {
                let Ok(object) = sim.scene().object(id) else { continue };
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
            for (name, id) in sim.scene().joints() {
                let Ok(joint) = sim.scene().joint(id) else { continue };
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

/// A number as the editor shows it: short, and read back as the same number when it
/// was typed so (`inf` for no limit).
fn format_number(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-3..1e6).contains(&v.abs()) {
        let s = format!("{v:.6}");
        if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
    } else {
        format!("{v:e}")
    }
}

/// A coordinate of the selected body's pose as its fields show it: millimetres or
/// thousandths of a degree, as the readout above them, and never in powers of ten (a
/// body at rest near zero is at -9.86e-5 m one step and 1.2e-6 m the next: the
/// field, a few characters wide, showed "-9.86" of it).
fn format_pose(v: f64) -> String {
    let s = format!("{v:.3}");
    if s == "-0.000" { "0.000".to_string() } else { s }
}

/// The characters a text field drew whole: those of its first line inside the
/// rectangle its text is clipped to (a text wider than the field is cut there).
fn shown_text(output: &egui::text_edit::TextEditOutput) -> String {
    let (left, right) = (output.text_clip_rect.min.x, output.text_clip_rect.max.x);
    let Some(row) = output.galley.rows.first() else { return String::new() };
    let x0 = output.galley_pos.x + row.pos.x;
    let inside = |g: &&egui::epaint::text::Glyph| x0 + g.pos.x >= left - 0.5 && x0 + g.max_x() <= right + 0.5;
    row.row.glyphs.iter().filter(inside).map(|g| g.chr).collect()
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
    if let Some(servo) = sim.scene_mut().joint_mut(joint)?.controller_mut::<PositionServo>() {
        servo.setpoint = profile;
    }
    Ok(())
}

/// Run, pause, one frame, one step, reset.
fn run_buttons(ui: &mut egui::Ui, status: &Status<'_>, commands: &mut Vec<Command>) {
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
}

/// What the scene is drawn with: following, contacts, forces, joints, axes; and a
/// screenshot.
fn display_toggles(ui: &mut egui::Ui, status: &Status<'_>, commands: &mut Vec<Command>) {
    if ui.selectable_label(status.following, "Follow").clicked() {
        commands.push(Command::ToggleFollow);
    }
    if ui.selectable_label(status.contacts, "Contacts").clicked() {
        commands.push(Command::ToggleContacts);
    }
    if ui
        .selectable_label(status.forces, "Forces")
        .on_hover_text("contact forces (cyan) and joint reactions (amber) as arrows")
        .clicked()
    {
        commands.push(Command::ToggleForces);
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
}

/// How many views, and which camera sensor the fourth shows.
fn view_choice(ui: &mut egui::Ui, sim: &Simulation, status: &Status<'_>, commands: &mut Vec<Command>) {
    ui.label("Views (1–4)");
    for (n, name) in [(1, "free"), (2, "+ follow"), (3, "+ top"), (4, "+ camera")] {
        if ui.selectable_label(status.views == n, name).clicked() {
            commands.push(Command::Views(n));
        }
    }
    // Which camera sensor the fourth view shows, when there are several.
    let cameras = sim.sensors_of::<DepthCamera>().count();
    if status.views == 4 && cameras > 1 {
        let mut chosen = status.camera.min(cameras - 1);
        egui::ComboBox::from_id_salt("ars-view-camera").selected_text(format!("camera {}", chosen + 1)).show_ui(
            ui,
            |ui| {
                for i in 0..cameras {
                    ui.selectable_value(&mut chosen, i, format!("camera {}", i + 1));
                }
            },
        );
        if chosen != status.camera {
            commands.push(Command::ViewportCamera(chosen));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_shown_short_and_read_back_the_same() {
        assert_eq!(format_number(2.0), "2");
        assert_eq!(format_number(0.0004), "4e-4");
        assert_eq!(format_number(-9.81), "-9.81");
        assert_eq!(format_number(1e-10), "1e-10");
        assert_eq!(format_number(f64::INFINITY), "inf");
        assert_eq!(format_number(f64::NEG_INFINITY), "-inf");
        for v in [2.0, 0.0004, -9.81, 1e-10, 0.2, f64::INFINITY, -f64::INFINITY, 1234.5] {
            assert_eq!(parse_number("v", &format_number(v)), Ok(v));
        }
    }

    #[test]
    fn a_pose_is_shown_to_the_millimetre_and_never_in_powers_of_ten() {
        assert_eq!(format_pose(-9.860_412e-5), "0.000");
        assert_eq!(format_pose(0.507_6), "0.508");
        assert_eq!(format_pose(-1.745_329), "-1.745");
        assert_eq!(format_pose(-12_345.0), "-12345.000");
    }

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
