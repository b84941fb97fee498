//! One-sided rows for the next step, made as ODE frictionless contact joints with the
//! world: what holds a slide of a joint group at its stops (ODE's linear motor has
//! none). A contact row pushes its body only away from where it is held, at `point`
//! along `normal`, correcting `depth` as a stop corrects its overshoot (its ERP and
//! CFM), and never pulls.

use nalgebra::{Point3, Vector3};
use ode_sys as ffi;

use super::World;
use crate::error::{Error, Result};
use crate::handle::BodyHandle;
use crate::limits;

/// A one-sided row: `body`, at the world `point`, may move along `normal` (a unit
/// vector) and not against it; it is `depth` (m, ≥ 0) past where it is held.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct LimitRow {
    pub(crate) body: BodyHandle,
    pub(crate) point: Point3<f64>,
    pub(crate) normal: Vector3<f64>,
    pub(crate) depth: f64,
    /// The stop's ERP and CFM.
    pub(crate) erp: f64,
    pub(crate) cfm: f64,
}

impl World {
    /// Replaces the one-sided rows of the next step with `rows` (none: `&[]`).
    pub(crate) fn set_limit_rows(&mut self, rows: &[LimitRow]) -> Result<()> {
        self.check_usable()?;
        let mut raw = Vec::with_capacity(rows.len());
        for r in rows {
            raw.push(self.body_raw(r.body)?);
            limits::point("limit row point", &r.point)?;
            limits::in_range("limit row depth", r.depth, 0.0, limits::MAX_COORDINATE)?;
            let unit = (r.normal.norm() - 1.0).abs() < 1e-6;
            if !(unit && (0.0..=1.0).contains(&r.erp) && r.cfm.is_finite() && r.cfm >= 0.0) {
                return Err(Error::Invalid {
                    what: "a limit row",
                    problem: format!("needs a unit normal, an ERP in [0, 1] and a CFM ≥ 0: {r:?}"),
                });
            }
        }
        if self.limit_rows == 0 && rows.is_empty() {
            return Ok(());
        }
        // SAFETY: the group is live and holds only the contact joints made here.
        unsafe { ffi::dJointGroupEmpty(self.limit_group) };
        for (r, body) in rows.iter().zip(raw) {
            let mut contact = ffi::dContact::default();
            contact.surface.mode = (ffi::dContactSoftERP | ffi::dContactSoftCFM) as i32;
            contact.surface.soft_erp = r.erp;
            contact.surface.soft_cfm = r.cfm;
            contact.geom.pos = [r.point.x, r.point.y, r.point.z, 0.0];
            contact.geom.normal = [r.normal.x, r.normal.y, r.normal.z, 0.0];
            contact.geom.depth = r.depth;
            // SAFETY: the world, the group and the body are live (looked up above); the
            // contact is fully initialised and finite, its friction 0 (one row).
            unsafe {
                let j = ffi::dJointCreateContact(self.raw, self.limit_group, &contact);
                ffi::dJointAttach(j, body, std::ptr::null_mut());
            }
        }
        self.limit_rows = rows.len();
        Ok(())
    }
}
