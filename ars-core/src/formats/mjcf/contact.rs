//! A geom's contact parameters as MJCF gives them: `contype` and `conaffinity` (ODE's
//! category and collide bits), and `friction`, `condim`, `solref`, `solimp`,
//! `priority` and `solmix` (a [`GeomContact`], combined per pair and mapped onto ODE's
//! contact as its docs say). A `<pair>`'s own `friction`, `condim`, `solref` and
//! `solimp` replace its two geoms' combined (MuJoCo's defaults where it gives none, not
//! the geoms'). `margin` and `gap`, a pair's `solreffriction`, and a pair's second
//! sliding and rolling frictions where they differ from the first (ODE's friction is
//! the same in every direction), are read and said unused.

use super::CONTACT_PARAMETERS_UNUSED;
use super::defaults::Attrs;
use super::problem::{Parsed, problem};
use crate::scene::GeomContact;

/// A geom's `contype` or `conaffinity` bits (1 when not given).
pub(super) fn collision_bits(a: &Attrs<'_, '_>, name: &str) -> Parsed<u64> {
    match a.get(name) {
        None => Ok(1),
        // MuJoCo's are 32 bits; ODE's upper 32 are left for `<contact><pair>`.
        Some(v) => v
            .parse::<u32>()
            .map(u64::from)
            .map_err(|_| problem(&a.node, format!("{name}=\"{v}\" is not a whole number of at most 32 bits"))),
    }
}

/// A geom's `friction`, `condim`, `solref`, `solimp`, `priority` and `solmix`, MuJoCo's
/// defaults where not given (its class's first). Impedances are kept within MuJoCo's
/// [0.0001, 0.9999], as MuJoCo keeps them.
pub(super) fn geom_contact(a: &Attrs<'_, '_>) -> Parsed<GeomContact> {
    let mut c = GeomContact::default();
    if let Some(f) = a.numbers("friction")? {
        at_most(a, "friction", &f, 3)?;
        c.friction[..f.len()].copy_from_slice(&f);
    }
    read_condim_and_softness(a, &mut c)?;
    if let Some(p) = a.number("priority")? {
        if p.fract() != 0.0 || p.abs() > f64::from(i32::MAX) {
            return Err(problem(&a.node, format!("priority {p} must be a whole number")));
        }
        c.priority = p as i32;
    }
    if let Some(m) = a.number("solmix")? {
        c.solmix = m;
    }
    c.validate().map_err(|e| problem(&a.node, e.to_string()))?;
    Ok(c)
}

/// Refuses `values` of `name` unless there are 1 to `most` of them.
fn at_most(a: &Attrs<'_, '_>, name: &str, values: &[f64], most: usize) -> Parsed<()> {
    if values.is_empty() || values.len() > most {
        return Err(problem(&a.node, format!("{name} takes 1 to {most} numbers, got {}", values.len())));
    }
    Ok(())
}

/// A geom's or a pair's `condim`, `solref` and `solimp` into `c` (those given),
/// impedances kept within MuJoCo's [0.0001, 0.9999], as MuJoCo keeps them.
fn read_condim_and_softness(a: &Attrs<'_, '_>, c: &mut GeomContact) -> Parsed<()> {
    if let Some(d) = a.number("condim")? {
        c.condim = match d {
            1.0 => 1,
            3.0 => 3,
            4.0 => 4,
            6.0 => 6,
            _ => return Err(problem(&a.node, format!("condim {d} must be 1, 3, 4 or 6"))),
        };
    }
    if let Some(r) = a.numbers("solref")? {
        at_most(a, "solref", &r, 2)?;
        c.solref[..r.len()].copy_from_slice(&r);
    }
    if let Some(s) = a.numbers("solimp")? {
        at_most(a, "solimp", &s, 5)?;
        c.solimp[..s.len()].copy_from_slice(&s);
    }
    for d in &mut c.solimp[..2] {
        if d.is_finite() {
            *d = d.clamp(0.0001, 0.9999);
        }
    }
    Ok(())
}

/// A `<pair>`'s own contact parameters: `friction` (up to 5: two sliding, torsional,
/// two rolling), `condim`, `solref`, `solimp`; MuJoCo's defaults for those it does not
/// give (its class's first). Returns them with what ODE has no place for.
pub(super) fn pair_contact(a: &Attrs<'_, '_>) -> Parsed<(GeomContact, Vec<&'static str>)> {
    let mut c = GeomContact::default();
    let mut unused = Vec::new();
    if let Some(f) = a.numbers("friction")? {
        at_most(a, "friction", &f, 5)?;
        // MuJoCo's pair friction: tangent 1, tangent 2, torsional, rolling 1, rolling 2.
        let at = |i: usize, default: f64| f.get(i).copied().unwrap_or(default);
        c.friction = [f[0], at(2, c.friction[1]), at(3, c.friction[2])];
        // The second sliding and rolling frictions take MuJoCo's defaults (1 and 1e-4)
        // when not given: `friction="0.2"` is 0.2 one way and 1 the other.
        if at(1, 1.0) != f[0] || at(4, 1e-4) != at(3, 1e-4) {
            unused.push("anisotropic friction");
        }
    }
    read_condim_and_softness(a, &mut c)?;
    c.validate().map_err(|e| problem(&a.node, e.to_string()))?;
    for name in ["margin", "gap", "solreffriction"] {
        if a.get(name).is_some() {
            unused.push(name);
        }
    }
    Ok((c, unused))
}

/// Says `names` (the contact parameters of `node` ODE has no place for) unused.
pub(super) fn contact_parameters_unused(node: &roxmltree::Node<'_, '_>, names: &[&str], skipped: &mut Vec<String>) {
    if !names.is_empty() {
        skipped.push(format!(
            "<{}> at line {}: {} {CONTACT_PARAMETERS_UNUSED}",
            node.tag_name().name(),
            problem(node, "").line,
            names.join(", ")
        ));
    }
}
