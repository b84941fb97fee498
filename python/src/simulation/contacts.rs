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

/// A pair of geoms with parameters of their own, as `geom_pair_contacts` lists it.
type PairRow<'py> = (String, usize, String, usize, Bound<'py, PyDict>);

/// The parameters a call gives, each checked; those not given are `None`.
struct Given {
    friction: Option<[f64; 3]>,
    condim: Option<u8>,
    solref: Option<[f64; 2]>,
    solimp: Option<[f64; 5]>,
    priority: Option<i32>,
    solmix: Option<f64>,
}

impl Given {
    fn read(
        py: Python<'_>,
        friction: Option<Vec<f64>>,
        condim: Option<Int>,
        solref: Option<Vec<f64>>,
        solimp: Option<Vec<f64>>,
        priority: Option<Int>,
        solmix: Option<f64>,
    ) -> PyResult<Given> {
        Ok(Given {
            friction: friction.map(|f| numbers::<3>(py, "friction", f)).transpose()?,
            solref: solref.map(|r| numbers::<2>(py, "solref", r)).transpose()?,
            solimp: solimp.map(|s| numbers::<5>(py, "solimp", s)).transpose()?,
            condim: condim
                .map(|Checked(c)| {
                    u8::try_from(c).map_err(|_| raise(py, "InputError", format!("condim {c} must be 1, 3, 4 or 6")))
                })
                .transpose()?,
            priority: priority
                .map(|Checked(p)| {
                    i32::try_from(p).map_err(|_| raise(py, "InputError", format!("priority {p} is beyond ±2³¹")))
                })
                .transpose()?,
            solmix,
        })
    }

    /// `c` with the parameters given in place of its own.
    fn over(&self, mut c: GeomContact) -> GeomContact {
        c.friction = self.friction.unwrap_or(c.friction);
        c.condim = self.condim.unwrap_or(c.condim);
        c.solref = self.solref.unwrap_or(c.solref);
        c.solimp = self.solimp.unwrap_or(c.solimp);
        c.priority = self.priority.unwrap_or(c.priority);
        c.solmix = self.solmix.unwrap_or(c.solmix);
        c
    }
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
        let given = Given::read(py, friction, condim, solref, solimp, priority, solmix)?;
        self.with(py, move |sim| {
            let object = Self::object_id(sim, name)?;
            let c = given.over(sim.scene().geom_contact(object, geom)?.unwrap_or_default());
            sim.scene_mut().set_geom_contact(object, geom, c)
        })
    }

    /// Gives the pair of geoms `a_geom` of object `a` and `b_geom` of object `b` contact
    /// parameters of their own, used in place of the two geoms' combined (an MJCF
    /// `<contact><pair>`'s): `friction`, `condim`, `solref`, `solimp` as
    /// `set_geom_contact` takes them, MuJoCo's defaults for those not given. Setting
    /// it again replaces it.
    #[pyo3(signature = (a, b, a_geom=Checked(0), b_geom=Checked(0), *, friction=None, condim=None, solref=None,
                        solimp=None))]
    fn set_geom_pair_contact(
        &self,
        py: Python<'_>,
        a: &str,
        b: &str,
        a_geom: Int,
        b_geom: Int,
        friction: Option<Vec<f64>>,
        condim: Option<Int>,
        solref: Option<Vec<f64>>,
        solimp: Option<Vec<f64>>,
    ) -> PyResult<()> {
        let (a_geom, b_geom): (usize, usize) = (count(py, "a_geom", a_geom)?, count(py, "b_geom", b_geom)?);
        let c = Given::read(py, friction, condim, solref, solimp, None, None)?.over(GeomContact::default());
        self.with(py, move |sim| {
            let (a, b) = (Self::object_id(sim, a)?, Self::object_id(sim, b)?);
            sim.scene_mut().set_geom_pair_contact((a, a_geom), (b, b_geom), c)
        })
    }

    /// Every pair of geoms with contact parameters of its own: `(object, geom index,
    /// object, geom index, parameters)`, in the order set.
    fn geom_pair_contacts<'py>(&self, py: Python<'py>) -> PyResult<Vec<PairRow<'py>>> {
        let all = self.with(py, |sim| {
            let name = |id| -> ars_core::Result<String> { Ok(sim.scene().object(id)?.name().to_string()) };
            sim.scene()
                .geom_pair_contacts()
                .into_iter()
                .map(|((a, ka), (b, kb), c)| Ok((name(a)?, ka, name(b)?, kb, c)))
                .collect::<ars_core::Result<Vec<_>>>()
        })?;
        all.into_iter().map(|(a, ka, b, kb, c)| Ok((a, ka, b, kb, as_dict(py, &c)?))).collect()
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
