//! The names Python gives ARS's choices (spaces, steppers), in one place: parsed from
//! keyword arguments and given back by the properties. A refusal is the name of the
//! `ars` exception class to raise and its message.

use ars_core::world::{SpaceKind, Stepper};

/// Why a name was refused: the `ars` exception class and the message.
pub(crate) type Refusal = (&'static str, String);

/// The space called `name`.
pub(crate) fn space(name: &str) -> Result<SpaceKind, Refusal> {
    match name {
        "simple" => Ok(SpaceKind::Simple),
        "hash" => Ok(SpaceKind::HASH),
        "sweep_and_prune" => Ok(SpaceKind::SWEEP_AND_PRUNE),
        "grid" => Ok(SpaceKind::Grid),
        other => Err((
            "UnknownKindError",
            format!(
                "there is no space {other:?}; the spaces are \"grid\" (the default), \"sweep_and_prune\", \"hash\" and \"simple\""
            ),
        )),
    }
}

/// The name of a space kind.
pub(crate) fn space_name(kind: SpaceKind) -> String {
    match kind {
        SpaceKind::Simple => "simple".into(),
        SpaceKind::Hash { .. } => "hash".into(),
        SpaceKind::SweepAndPrune { .. } => "sweep_and_prune".into(),
        SpaceKind::Grid => "grid".into(),
        other => format!("{other:?}"),
    }
}

/// The stepper called `name` (`None`: the exact one), with `iterations` for the quick one.
pub(crate) fn stepper(name: Option<&str>, iterations: Option<u32>) -> Result<Stepper, Refusal> {
    match (name.unwrap_or("exact"), iterations) {
        ("exact", None) => Ok(Stepper::Exact),
        ("exact", Some(_)) => Err(("InputError", "quick_iterations is for the \"quick\" stepper only".into())),
        ("quick", n) => Ok(Stepper::Quick { iterations: n.unwrap_or(20) }),
        (other, _) => Err((
            "UnknownKindError",
            format!("there is no stepper {other:?}; the steppers are \"exact\" and \"quick\""),
        )),
    }
}

/// The name of a stepper.
pub(crate) fn stepper_name(stepper: Stepper) -> String {
    match stepper {
        Stepper::Exact => "exact".into(),
        Stepper::Quick { .. } => "quick".into(),
        other => format!("{other:?}"),
    }
}
