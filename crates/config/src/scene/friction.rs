//! `[friction]` checked into the friction law of the base and its map of patches and grid.

use stickslip_solver::geometry::Lattice;
use stickslip_solver::laws::{FrictionLaw, Law, RateState};
use stickslip_solver::scene::Friction;

use super::FrictionSection;
use crate::check::Checker;
use crate::laws::{self, FrictionKeys};

/// The background friction law of `[friction]`, its `mu_cv` checked too.
pub(super) fn law(ck: &mut Checker, f: &FrictionSection) -> FrictionLaw {
    let law = friction_law(ck, f);
    ck.range("friction.mu_cv", f.mu_cv, 0.0, false, 1.0, false);
    law
}

/// The friction of the base: the background `law` and the map of `[friction]`'s patches and grid
/// on `lattice` (every refused value recorded in `ck`).
pub(super) fn friction(ck: &mut Checker, f: &FrictionSection, law: FrictionLaw, lattice: &Lattice) -> Friction {
    let mut grid = f.grid.as_ref();
    if let (Some(_), Some(why)) = (grid, laws::of(&law).grid_refused) {
        ck.push("friction.grid", "a grid", format!("left out with law = {:?}: {why}", law.name()));
        grid = None;
    }
    let mut rate_state_grid = f.rate_state_grid.as_ref();
    if rate_state_grid.is_some() && !matches!(law.node(1.0), stickslip_solver::laws::NodeFriction::RateState(_)) {
        ck.push(
            "friction.rate_state_grid",
            "a grid",
            format!(
                "left out with law = {:?} (its rows give a, b, L and f₀ of \"rate_state_aging\" and \"rate_state_slip\"; \
                 [friction.grid] gives μs, μd and Dc)",
                law.name()
            ),
        );
        rate_state_grid = None;
    }
    let rows = match (grid.filter(|g| !g.refused), rate_state_grid.filter(|g| !g.refused)) {
        (Some(g), _) => Some(g.rows()),
        (None, Some(g)) => Some(g.rows()),
        (None, None) => None,
    };
    let map = crate::friction_map::build(ck, lattice, &law, &f.patches, rows);
    Friction { law, mu_cv: f.mu_cv, map, heals: f.heals }
}

/// The friction law the section describes: the law `[friction] law` names, from its keys.
fn friction_law(ck: &mut Checker, f: &FrictionSection) -> FrictionLaw {
    let keys = FrictionKeys {
        mu_static: f.mu_static,
        mu_dynamic: f.mu_dynamic,
        slip_weakening_m: f.slip_weakening_m,
        heals: f.heals,
        rate_state: f.rate_state,
    };
    let chosen = laws::chosen(ck, f.law.as_deref());
    if f.rate_state.is_some() && chosen.solver_law != <RateState as Law>::NAME {
        ck.push(
            "friction.rate_state",
            "a section",
            format!(
                "left out with law = {:?} (it is read by \"rate_state_aging\" and \"rate_state_slip\")",
                chosen.name
            ),
        );
    }
    (chosen.law)(ck, &keys)
}
