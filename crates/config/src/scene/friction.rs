//! `[friction]` checked into the friction law of the base and its map of patches and grid.

use stickslip_solver::geometry::Lattice;
use stickslip_solver::laws::{Coulomb, FrictionLaw, SlipWeakening, StaticDynamic};
use stickslip_solver::scene::Friction;

use super::FrictionSection;
use crate::check::{Checker, num};

/// The background friction law of `[friction]`, its `mu_cv` checked too.
pub(super) fn law(ck: &mut Checker, f: &FrictionSection) -> FrictionLaw {
    let law = friction_law(ck, f);
    ck.range("friction.mu_cv", f.mu_cv, 0.0, false, 1.0, false);
    law
}

/// The friction of the base: the background `law` and the map of `[friction]`'s patches and grid
/// on `lattice` (every refused value recorded in `ck`).
pub(super) fn friction(ck: &mut Checker, f: &FrictionSection, law: FrictionLaw, lattice: &Lattice) -> Friction {
    let map = crate::friction_map::build(ck, lattice, &law, &f.patches, f.grid.as_ref());
    Friction { law, mu_cv: f.mu_cv, map, heals: f.heals }
}

/// The friction law the section describes.
fn friction_law(ck: &mut Checker, f: &FrictionSection) -> FrictionLaw {
    ck.non_negative("friction.mu_static", f.mu_static);
    if f.mu_dynamic.is_some() && f.mu_static.is_finite() {
        ck.range("friction.mu_dynamic", f.mu_dynamic.unwrap_or(0.0), 0.0, false, f.mu_static.max(0.0), false);
    }
    ck.non_negative("friction.slip_weakening_m", f.slip_weakening_m);
    match f.mu_dynamic {
        None => {
            if f.slip_weakening_m > 0.0 {
                ck.push(
                    "friction.slip_weakening_m",
                    f.slip_weakening_m,
                    "0 without friction.mu_dynamic (slip weakening from μs to μd needs μd < μs)",
                );
            }
            FrictionLaw::Coulomb(Coulomb { mu: f.mu_static })
        }
        Some(mu_dynamic) if f.slip_weakening_m > 0.0 => {
            if !(mu_dynamic < f.mu_static) {
                ck.push(
                    "friction.mu_dynamic",
                    mu_dynamic,
                    format!(
                        "below mu_static ({}) when slip_weakening_m > 0 (otherwise nothing weakens)",
                        num(f.mu_static)
                    ),
                );
            }
            FrictionLaw::SlipWeakening(SlipWeakening { mu_static: f.mu_static, mu_dynamic, dc_m: f.slip_weakening_m })
        }
        Some(mu_dynamic) => FrictionLaw::StaticDynamic(StaticDynamic { mu_static: f.mu_static, mu_dynamic }),
    }
}
