//! A joint group's motion each step: its joints' positions and rates read from the
//! two bodies' relative pose (kept while a step's drives are applied), its members'
//! efforts, and the rows its ODE motors get before the step.

use nalgebra::{Point3, Rotation3, Vector3};

use super::{GroupMember, JointGroup};
use crate::control::JointState;
use crate::error::Result;
use crate::handle::{BodyHandle, JointId};
use crate::joint::JointParam;
use crate::limits;
use crate::scene::Scene;
use crate::scene::joints::JointType;
use crate::world::limit_rows::LimitRow;

/// The group's joints as they are: each one's position and rate, the direction its
/// efforts act along (unit, world) and its dual axis' length; the locked rotations'
/// and translations' directions, their dual length and their error.
#[derive(Clone, Default)]
pub(crate) struct GroupKinematics {
    position: [f64; 6],
    rate: [f64; 6],
    direction: [Vector3<f64>; 6],
    scale: [f64; 6],
    /// Euler angles of the relative rotation in the group's frame, their rates' dual
    /// directions and lengths.
    angles: [f64; 3],
    euler_direction: [Vector3<f64>; 3],
    euler_scale: [f64; 3],
    /// The anchor's displacement (world) from where the joints read 0.
    displacement: Vector3<f64>,
    /// The anchor's world position.
    anchor: Point3<f64>,
}

/// A group's dual axes are at most this long (the hinges near gimbal lock).
const MAX_DUAL: f64 = 1e6;

impl Scene {
    /// The group's kinematics now.
    fn group_kinematics(&self, g: &JointGroup) -> Result<GroupKinematics> {
        let mut k = GroupKinematics::default();
        self.fill_group_kinematics(g, &mut k)?;
        Ok(k)
    }

    /// Writes the group's kinematics now into `k` (every field).
    fn fill_group_kinematics(&self, g: &JointGroup, k: &mut GroupKinematics) -> Result<()> {
        let child = self.world.body(g.child)?;
        let (xc, rc, vc, wc) = (child.position(), child.rotation(), child.linear_velocity(), child.angular_velocity());
        // The group's frame in the world: its hinges' axes where they are now.
        let (xp, rp, world_frame, wp, vp_at) = match g.parent {
            Some(p) => {
                let body = self.world.body(p)?;
                let rp = body.rotation();
                let anchor = child.point_to_world(Point3::from(g.anchor_child));
                (body.position(), Some(rp), rp.matrix() * g.frame, body.angular_velocity(), body.point_velocity(anchor))
            }
            None => (Point3::origin(), None, g.frame, Vector3::zeros(), Vector3::zeros()),
        };
        // The child's rotation is parent · G · rest; G in the group's frame F is
        // Rx(a)·Ry(b)·Rz(c), its first angles the hinges': Fᵀ·G·F = (parent·F)ᵀ·child·(restᵀ·F).
        let m = world_frame.transpose() * (rc.matrix() * g.rest_frame);
        let a = (-m[(1, 2)]).atan2(m[(2, 2)]);
        let b = m[(0, 2)].atan2(m[(0, 0)].hypot(m[(0, 1)]));
        let c = (-m[(0, 1)]).atan2(m[(0, 0)]);
        k.angles = [a, b, c];
        let arm = rc * g.anchor_child;
        let anchor = xc + arm;
        let anchor_velocity = vc + wc.cross(&arm) - vp_at;
        k.anchor = anchor;
        k.displacement = match rp {
            Some(rp) => rp * ((rp.inverse() * (anchor - xp)) - g.anchor_parent),
            None => anchor.coords - g.anchor_parent,
        };
        let slides = g.slides.len();
        for (i, axis) in g.slides.iter().enumerate() {
            k.position[i] = axis.dot(&k.displacement);
            k.rate[i] = axis.dot(&anchor_velocity);
            k.direction[i] = *axis;
            k.scale[i] = 1.0;
        }
        if g.hinges == 0 {
            // No turn is free: the frame's own axes (the world's, fixed) hold the
            // rotation, each correcting its angle.
            for i in 0..3 {
                (k.euler_direction[i], k.euler_scale[i]) = (world_frame.column(i).into_owned(), 1.0);
            }
            return Ok(());
        }
        let (sin_a, cos_a) = a.sin_cos();
        let (sin_b, cos_b) = b.sin_cos();
        // The Euler axes in the world: x, Rx(a)·y, Rx(a)·Ry(b)·z of the group's frame.
        let w1 = world_frame.column(0).into_owned();
        let w2 = world_frame * Vector3::new(0.0, cos_a, sin_a);
        let w3 = world_frame * Vector3::new(sin_b, -sin_a * cos_b, cos_a * cos_b);
        let det = w1.dot(&w2.cross(&w3));
        let det = if det.abs() < 1.0 / MAX_DUAL { (1.0 / MAX_DUAL).copysign(det) } else { det };
        let duals = [w2.cross(&w3) / det, w3.cross(&w1) / det, w1.cross(&w2) / det];
        let relative = wc - wp;
        for (i, (d, w)) in duals.iter().zip([w1, w2, w3]).enumerate() {
            let length = d.norm();
            // At gimbal lock the middle dual axis vanishes: its own axis stands in.
            (k.euler_direction[i], k.euler_scale[i]) =
                if length > 1e-12 { (d / length, length.min(MAX_DUAL)) } else { (w, 1.0) };
        }
        let axes = [w1, w2, w3];
        for (h, dual) in duals.iter().enumerate().take(g.hinges) {
            let sign = if h == 2 { g.third_sign } else { 1.0 };
            let i = slides + h;
            k.position[i] = sign * k.angles[h];
            k.rate[i] = sign * dual.dot(&relative);
            if g.hinges == 3 {
                k.direction[i] = sign * k.euler_direction[h];
                k.scale[i] = k.euler_scale[h];
            } else {
                // With a rotation locked, the turn is in the span of the hinges' axes,
                // which are perpendicular: each axis is its own dual there (scale 1).
                k.direction[i] = axes[h];
                k.scale[i] = 1.0;
            }
        }
        Ok(())
    }

    /// A group member's position and rate now.
    pub(crate) fn member_state(&self, member: GroupMember) -> Result<JointState> {
        let state = |k: &GroupKinematics| JointState { position: k.position[member.index], rate: k.rate[member.index] };
        match self.kept_kinematics(member.group) {
            Some(k) => Ok(state(k)),
            None => Ok(state(&self.group_kinematics(self.group(member.group)?)?)),
        }
    }

    /// Group `group`'s kinematics as worked out for the step about to be taken, while
    /// its drives are applied (nothing moves then).
    fn kept_kinematics(&self, group: usize) -> Option<&GroupKinematics> {
        if self.group_kinematics_kept { self.group_kinematics_now.get(group) } else { None }
    }

    /// Works out every group's kinematics for the drives of the step about to be taken
    /// (`forget_group_kinematics` after them).
    pub(crate) fn keep_group_kinematics(&mut self) -> Result<()> {
        // Into the room of the last step's.
        let mut kinematics = std::mem::take(&mut self.group_kinematics_now);
        if kinematics.len() != self.groups.len() {
            kinematics.resize_with(self.groups.len(), GroupKinematics::default);
        }
        let worked =
            self.groups.iter().zip(kinematics.iter_mut()).try_for_each(|(g, k)| self.fill_group_kinematics(g, k));
        // None kept after a failure: a group's would be read as another's.
        self.group_kinematics_kept = worked.is_ok();
        self.group_kinematics_now = kinematics;
        worked
    }

    /// The bodies may move again: group kinematics are worked out when asked (the
    /// list's room is kept for the next step).
    pub(crate) fn forget_group_kinematics(&mut self) {
        self.group_kinematics_kept = false;
    }

    /// Puts `effort` (N·m or N) on a group member for the next step: a torque along its
    /// dual axis (a force through the anchor along a slide's axis), opposite on the
    /// parent.
    pub(crate) fn put_member_effort(&mut self, member: GroupMember, effort: f64) -> Result<()> {
        let i = member.index;
        let read = |k: &GroupKinematics| (k.direction[i], k.scale[i], k.anchor);
        let (direction, scale, anchor) = match self.kept_kinematics(member.group) {
            Some(k) => read(k),
            None => read(&self.group_kinematics(self.group(member.group)?)?),
        };
        let g = self.group(member.group)?;
        let (child, parent, slide) = (g.child, g.parent, i < g.slides.len());
        let along = direction * (effort * scale);
        if slide {
            limits::vector_within("joint force", &along, limits::MAX_FORCE, "N")?;
            self.world.body_mut(child)?.add_force_at_point(along, anchor)?;
            if let Some(p) = parent {
                self.world.body_mut(p)?.add_force_at_point(-along, anchor)?;
            }
        } else {
            limits::vector_within("joint torque", &along, limits::MAX_TORQUE, "N·m")?;
            self.world.body_mut(child)?.add_torque(along)?;
            if let Some(p) = parent {
                self.world.body_mut(p)?.add_torque(-along)?;
            }
        }
        Ok(())
    }

    /// The inertia (mass) a group member's motion moves at least: the child's about its
    /// dual axis through the anchor (its mass along a slide).
    pub(crate) fn member_inertia(&self, member: GroupMember) -> Result<f64> {
        let g = self.group(member.group)?;
        let body = self.world.body(g.child)?;
        if member.index < g.slides.len() {
            return Ok(body.mass());
        }
        let k = self.group_kinematics(g)?;
        let axis = k.direction[member.index];
        let arm = body.position() - k.anchor;
        let across = arm - axis * arm.dot(&axis);
        Ok(axis.dot(&(body.inertia_world() * axis)) + body.mass() * across.norm_squared())
    }

    /// Sets every group's rows for the coming step: the locked freedoms' directions and
    /// drift corrections, and each member's motor turned and scaled to its dual axis.
    pub(crate) fn hold_groups(&mut self) -> Result<()> {
        // The stops' rows of the last step, emptied: its room is kept.
        let mut stops = std::mem::take(&mut self.group_stops);
        stops.clear();
        // The kinematics kept for this step, read in place (worked out here without).
        let is_kept = self.group_kinematics_kept;
        let kept = std::mem::take(&mut self.group_kinematics_now);
        let held = (0..self.groups.len()).try_for_each(|group| match kept.get(group).filter(|_| is_kept) {
            Some(k) => self.hold_group(group, k, &mut stops),
            None => {
                let k = self.group_kinematics(self.group(group)?)?;
                self.hold_group(group, &k, &mut stops)
            }
        });
        self.group_kinematics_now = kept;
        let set = held.and_then(|()| self.world.set_limit_rows(&stops));
        self.group_stops = stops;
        set
    }

    /// Sets group `group`'s rows for the coming step, its kinematics `k`; its slides at
    /// their stops add a one-sided row to `stops`.
    fn hold_group(&mut self, group: usize, k: &GroupKinematics, stops: &mut Vec<LimitRow>) -> Result<()> {
        let (erp, h) = (self.world.erp(), self.time_step.get());
        let speed = |v: f64| v.clamp(-limits::MAX_SPEED, limits::MAX_SPEED);
        let g = self.group(group)?;
        let (hinges, lock_turns, lock_slides, child) = (g.hinges, g.lock_turns, g.lock_slides, g.child);
        // At most two normals (one slide).
        let mut corrections = [0.0; 2];
        for (c, n) in corrections.iter_mut().zip(&g.normals) {
            *c = -erp * n.dot(&k.displacement) / h;
        }
        let normals = g.normals.len();
        if let Some(lock) = lock_turns {
            let mut motor = self.world.joint_mut(lock)?;
            for (row, euler) in (hinges..3).enumerate() {
                if hinges > 0 {
                    // Without hinges the rows keep the frame's axes they were made with.
                    motor.set_motor_axis(row, k.euler_direction[euler])?;
                }
                let correction = -erp * k.angles[euler] / (h * k.euler_scale[euler]);
                motor.set_param(JointParam::Velocity, row, speed(correction))?;
            }
        }
        if let Some(lock) = lock_slides {
            let mut motor = self.world.joint_mut(lock)?;
            for (row, correction) in corrections.into_iter().take(normals).enumerate() {
                motor.set_param(JointParam::Velocity, row, speed(correction))?;
            }
        }
        for m in 0..self.group(group)?.members.len() {
            let id = self.group(group)?.members[m];
            self.hold_member(id, k, (hinges, child), stops)?;
        }
        Ok(())
    }

    /// Sets group member `id`'s rows for the coming step (its group of `hinges` hinges
    /// moving `child`, its kinematics `k`): its motor turned and scaled to its dual axis,
    /// its armature, and a slide's stop row in `stops` when it is at one.
    fn hold_member(
        &mut self,
        id: JointId,
        k: &GroupKinematics,
        (hinges, child): (usize, BodyHandle),
        stops: &mut Vec<LimitRow>,
    ) -> Result<()> {
        let speed = |v: f64| v.clamp(-limits::MAX_SPEED, limits::MAX_SPEED);
        let d = self.joint_data(id)?;
        let Some(member) = d.member else { return Ok(()) };
        let (i, handle, stops_of_member, armature, kind) = (member.index, d.handle, d.limits, d.armature, d.kind);
        let (direction, scale) = (k.direction[i], k.scale[i]);
        if let (JointType::Slider, Some((low, high))) = (kind, stops_of_member) {
            // ODE's linear motor has no stops: a one-sided row at the anchor.
            let position = k.position[i];
            let (normal, depth) = if position <= low {
                (direction, low - position)
            } else if position >= high {
                (-direction, position - high)
            } else {
                (Vector3::zeros(), -1.0)
            };
            if depth >= 0.0 {
                let ode = self.world.joint(handle)?;
                let (erp, cfm) = (ode.param(JointParam::StopErp, 0)?, ode.param(JointParam::StopCfm, 0)?);
                stops.push(LimitRow { body: child, point: k.anchor, normal, depth, erp, cfm });
            }
        }
        // A hinge's motor has rows with stops, a speed motor or dry friction (a
        // force limit): only then is it turned to the hinge's axis.
        let rows = stops_of_member.is_some() || member.motor.1 > 0.0;
        if kind == JointType::Hinge && rows {
            // A slide's direction is fixed (the world's, where it was made).
            let mut motor = self.world.joint_mut(handle)?;
            motor.set_motor_axis(0, direction)?;
            if stops_of_member.is_some() {
                motor.set_motor_angle(0, k.position[i] / scale)?;
            }
        }
        // Its stops and speed motor, scaled to its dual axis when that changed
        // (three hinges; NaN: set unscaled since).
        if scale != member.scale {
            let mut motor = self.world.joint_mut(handle)?;
            if let (JointType::Hinge, Some((low, high))) = (kind, stops_of_member) {
                motor.set_limits(0, low / scale, high / scale)?;
            }
            let (velocity, force) = member.motor;
            let force = if force == f64::INFINITY { force } else { (force * scale).min(limits::MAX_FORCE) };
            motor.set_motor(0, speed(velocity / scale), force)?;
            if let Some(m) = self.joints.get_mut(id.0, JointId::KIND)?.member.as_mut() {
                m.scale = scale;
            }
        }
        if let Some(armature) = armature {
            if kind == JointType::Hinge {
                self.world.joint_mut(armature.motor)?.set_motor_axis(0, direction)?;
            }
            // Damping alone on a unit axis (a slide, or a hinge of fewer than three)
            // keeps the target and CFM it was given.
            if armature.inertia > 0.0 || hinges == 3 && kind == JointType::Hinge {
                self.hold_scaled_armature(armature, k.rate[i], scale)?;
            }
        }
        Ok(())
    }

    /// A member's current anchor and axis (world), as a scene file saves a joint.
    pub(crate) fn member_geometry(&self, member: GroupMember) -> Result<(Point3<f64>, Vector3<f64>)> {
        let g = self.group(member.group)?;
        let k = self.group_kinematics(g)?;
        let i = member.index;
        let axis = if i < g.slides.len() {
            g.slides[i]
        } else {
            // The hinge's own axis: the first fixed in the parent, the last in the child.
            let (rp, _) = self.group_poses(g.child, g.parent).map(|(c, p)| (p.rotation, c))?;
            let h = i - g.slides.len();
            let rx = Rotation3::from_axis_angle(&Vector3::x_axis(), k.angles[0]);
            let ry = Rotation3::from_axis_angle(&Vector3::y_axis(), k.angles[1]);
            let local = [Vector3::x(), rx * Vector3::y(), rx * ry * Vector3::z()][h];
            let sign = if h == 2 { g.third_sign } else { 1.0 };
            rp.to_rotation_matrix() * (g.frame * local) * sign
        };
        Ok((k.anchor, axis))
    }
}
