//! Friction laws as the configuration knows them: each law's keys in `[friction]`, its patches
//! and grid rows, and its refusals, one file per law ([`slip_weakening`], [`exponential`],
//! [`rate_state`]); the
//! table [`LAWS`] maps `[friction] law` to the file. `scene::friction` and the friction map ask
//! the law chosen here for the background and for each region's coefficients, and never name a
//! law. A new law is its file here and its line in [`LAWS`] (beside its file in the solver's
//! `laws`; ARCHITECTURE.md lists the files).

mod exponential;
mod rate_state;
mod slip_weakening;

pub use rate_state::{RateStatePatch, RateStateSection};

use stickslip_solver::laws::{FrictionLaw, NodeFriction};

use crate::check::Checker;

/// The keys of `[friction]` a law reads for the background.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FrictionKeys {
    /// `mu_static`.
    pub mu_static: f64,
    /// `mu_dynamic`.
    pub mu_dynamic: Option<f64>,
    /// `slip_weakening_m`.
    pub slip_weakening_m: f64,
    /// `heals`.
    pub heals: bool,
    /// `[friction.rate_state]`.
    pub rate_state: Option<RateStateSection>,
}

/// The coefficients a region of the base gives (a patch, a grid row): the keys shared by every
/// region, `None` where the region leaves one to the background's.
#[derive(Clone, Copy, Debug)]
pub(crate) struct RegionKeys {
    /// `mu_static` (required by the slip-weakening laws).
    pub mu_static: Option<f64>,
    /// `mu_dynamic`; `None` = the region's μs.
    pub mu_dynamic: Option<f64>,
    /// `slip_weakening_m`; `None` = the background's.
    pub slip_weakening_m: Option<f64>,
    /// `[…rate_state]`: a rate-and-state region's coefficients.
    pub rate_state: Option<RateStatePatch>,
}

/// A friction law of `[friction]`: its name, what it is, and how its keys become coefficients.
pub(crate) struct LawKeys {
    /// Its value of `[friction] law`.
    pub name: &'static str,
    /// What it is, for the refusal of an unknown name.
    pub about: &'static str,
    /// The solver's law it builds (its `Law::NAME`).
    pub solver_law: &'static str,
    /// The background law of `[friction]`, its values checked into `ck`.
    pub law: fn(&mut Checker, &FrictionKeys) -> FrictionLaw,
    /// A region's coefficients under this law over the background `law`, checked into `ck`
    /// under the region's `field`.
    pub region: fn(&mut Checker, &str, &RegionKeys, &FrictionLaw) -> NodeFriction,
    /// The keys that set the static strength and the drop from it, as `check`'s verdicts name
    /// them in place of `friction.mu_static` and `friction.mu_dynamic`.
    pub strength_keys: [&'static str; 2],
    /// Why `[friction.grid]` is refused under this law; `None` when its rows are read.
    pub grid_refused: Option<&'static str>,
    /// Why the skip-ahead is refused under this law; `None` when it runs.
    pub skip_ahead_refused: Option<&'static str>,
    /// Whether a fault whose modules do not resolve the law's process zone is refused (rather
    /// than warned of by `check`).
    pub zone_refused: bool,
}

/// The slip-weakening laws' [`LawKeys::strength_keys`]: μs and μd.
const MU_KEYS: [&str; 2] = ["friction.mu_static", "friction.mu_dynamic"];

/// Every law, the first the default of `[friction] law`.
pub(crate) const LAWS: [LawKeys; 4] = [slip_weakening::KEYS, exponential::KEYS, rate_state::AGING, rate_state::SLIP];

/// The law `[friction] law` names (refused with every allowed name when it names none).
pub(crate) fn chosen(ck: &mut Checker, law: Option<&str>) -> &'static LawKeys {
    let Some(name) = law else { return &LAWS[0] };
    LAWS.iter().find(|l| l.name == name).unwrap_or_else(|| {
        let allowed: Vec<String> = LAWS.iter().map(|l| format!("\"{}\" ({})", l.name, l.about)).collect();
        ck.push("friction.law", format!("{name:?}"), format!("one of {}", allowed.join(", ")));
        &LAWS[0]
    })
}

/// The entry of [`LAWS`] whose law built the background `law`.
pub(crate) fn of(law: &FrictionLaw) -> &'static LawKeys {
    LAWS.iter().find(|l| l.name == law.name()).unwrap_or_else(|| {
        let name = law.background.law_name();
        LAWS.iter().find(|l| l.solver_law == name).expect("every law's background comes from LAWS")
    })
}

/// A region's μs (checked non-negative) and μd (its μs when omitted; checked within 0…μs).
fn region_coefficients(ck: &mut Checker, field: &str, keys: &RegionKeys) -> (f64, f64) {
    if keys.rate_state.is_some() {
        ck.push(format!("{field}.rate_state"), "a section", "left out under a slip-weakening law (give mu_static)");
    }
    let Some(mu_static) = keys.mu_static else {
        ck.push(format!("{field}.mu_static"), "none", "the region's μs ≥ 0 (required under a slip-weakening law)");
        return (0.0, 0.0);
    };
    ck.non_negative(&format!("{field}.mu_static"), mu_static);
    let mu_dynamic = keys.mu_dynamic.unwrap_or(mu_static);
    if mu_static.is_finite() {
        ck.range(&format!("{field}.mu_dynamic"), mu_dynamic, 0.0, false, mu_static.max(0.0), false);
    }
    (mu_static, mu_dynamic)
}
