//! `ars.Simulation`'s methods for a geom's own contact parameters, MuJoCo's (the Rust
//! `GeomContact`: how they combine per pair and map onto ODE's contact).

use ars_core::GeomContact;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use super::{Int, PySimulation};
use crate::errors::{Checked, count, raise};

/// A geom's parameters as the dict `geom_contact` returns.
fn as_dict<'py>(py: Python<'py>, c: &GeomContact) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("friction", c.friction.to_vec())?;
    dict.set_item("condim", c.condim)?;
    dict.set_item("solref", c.solref.to_vec())?;
    dict.set_item("solimp", c.solimp.to_vec())?;
    dict.set_item("priority", c.priority)?;
    dict.set_item("solmix", c.solmix)?;
    Ok(dict)
}

/// `values` as `N` numbers, or an `InputError` naming `what`.
fn numbers<const N: usize>(py: Python<'_>, what: &str, values: Vec<f64>) -> PyResult<[f64; N]> {
    let n = values.len();
    values.try_into().map_err(|_| raise(py, "InputError", format!("{what} takes {N} numbers, got {n}")))
}

#[pymethods]
impl PySimulation {
    /// Gives geom `geom` of object `name` (0: its first) contact parameters of its own,
    /// MuJoCo's (what `load_mjcf` reads from a file's geoms): `friction` (sliding
    /// coefficient, torsional and rolling, m), `condim` (1, 3, 4 or 6), `solref`,
    /// `solimp`, `priority`, `solmix`. Those not given keep the geom's current ones
    /// (MuJoCo's defaults for a geom without any). Two touching geoms' parameters are
    /// combined as MuJoCo combines them and mapped onto ODE's contact (see the Rust
    /// `GeomContact`); a pair with a `set_contact_surface` of its own keeps it.
    #[pyo3(signature = (name, geom=Checked(0), *, friction=None, condim=None, solref=None, solimp=None, priority=None,
                        solmix=None))]
    fn set_geom_contact(
        &self,
        py: Python<'_>,
        name: &str,
        geom: Int,
        friction: Option<Vec<f64>>,
        condim: Option<Int>,
        solref: Option<Vec<f64>>,
        solimp: Option<Vec<f64>>,
        priority: Option<Int>,
        solmix: Option<f64>,
    ) -> PyResult<()> {
        let geom: usize = count(py, "geom", geom)?;
        let friction = friction.map(|f| numbers::<3>(py, "friction", f)).transpose()?;
        let solref = solref.map(|r| numbers::<2>(py, "solref", r)).transpose()?;
        let solimp = solimp.map(|s| numbers::<5>(py, "solimp", s)).transpose()?;
        let condim = condim
            .map(|Checked(c)| {
                u8::try_from(c).map_err(|_| raise(py, "InputError", format!("condim {c} must be 1, 3, 4 or 6")))
            })
            .transpose()?;
        let priority = priority
            .map(|Checked(p)| {
                i32::try_from(p).map_err(|_| raise(py, "InputError", format!("priority {p} is beyond ±2³¹")))
            })
            .transpose()?;
        self.with(py, move |sim| {
            let object = Self::object_id(sim, name)?;
            let mut c = sim.scene().geom_contact(object, geom)?.unwrap_or_default();
            c.friction = friction.unwrap_or(c.friction);
            c.condim = condim.unwrap_or(c.condim);
            c.solref = solref.unwrap_or(c.solref);
            c.solimp = solimp.unwrap_or(c.solimp);
            c.priority = priority.unwrap_or(c.priority);
            c.solmix = solmix.unwrap_or(c.solmix);
            sim.scene_mut().set_geom_contact(object, geom, c)
        })
    }

    /// The contact parameters of geom `geom` of object `name` (0: its first), as a dict
    /// of `set_geom_contact`'s keywords, or `None` when it has none of its own.
    #[pyo3(signature = (name, geom=Checked(0)))]
    fn geom_contact<'py>(&self, py: Python<'py>, name: &str, geom: Int) -> PyResult<Option<Bound<'py, PyDict>>> {
        let geom: usize = count(py, "geom", geom)?;
        let contact = self.with(py, move |sim| sim.scene().geom_contact(Self::object_id(sim, name)?, geom))?;
        contact.map(|c| as_dict(py, &c)).transpose()
    }

    /// Every geom with contact parameters of its own: `(object name, geom index,
    /// parameters)`, in the objects' creation order.
    fn geom_contacts<'py>(&self, py: Python<'py>) -> PyResult<Vec<(String, usize, Bound<'py, PyDict>)>> {
        let all = self.with(py, |sim| {
            sim.scene()
                .geom_contacts()
                .into_iter()
                .map(|(id, k, c)| Ok((sim.scene().object(id)?.name().to_string(), k, c)))
                .collect::<ars_core::Result<Vec<_>>>()
        })?;
        all.into_iter().map(|(name, k, c)| Ok((name, k, as_dict(py, &c)?))).collect()
    }
}
