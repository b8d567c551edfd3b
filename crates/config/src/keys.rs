//! The pipeline keys behind the solver's advice: the solver names physical quantities (the time
//! step, the settling damping), this names the keys of a pipeline file that set them, for the
//! command line to print next to the solver's message.

use stickslip_solver::SolverError;
use stickslip_solver::inspect::{Regime, Slider};
use stickslip_solver::laws::FrictionLaw;

/// The keys that set what `e` asks to change; `None` when it asks nothing of the file.
pub fn for_error(e: &SolverError) -> Option<&'static str> {
    match e {
        SolverError::TimeStepAboveCritical { .. } => Some("time.dt_fraction, time.dt_s"),
        SolverError::NotSettled { .. } => Some("self_weight.damping_per_s, self_weight.max_duration_s"),
        SolverError::Unsupported(_) => Some("skip_ahead.enabled"),
        SolverError::TooManySteps { .. } => {
            Some("shear.duration_s, self_weight.max_duration_s, time.dt_fraction, time.dt_s")
        }
        SolverError::RecordIntervalTooFine { .. } => Some("record.interval_s, time.dt_fraction, time.dt_s"),
        SolverError::Unstable { .. } | SolverError::Numerical(_) | SolverError::Cancelled => None,
    }
}

/// The keys that set what the spring-slider verdict of `regime` asks to change; `None` when it
/// asks nothing (or nothing one key sets).
pub fn for_regime(regime: Regime) -> Option<&'static str> {
    match regime {
        Regime::Tips => Some("loading_plate.face, friction.mu_static"),
        Regime::NoWeakening => Some("friction.mu_dynamic, friction.mu_static"),
        Regime::Overdamped => Some("shear.damping_per_s, shear.velocity_m_s"),
        Regime::LetsGoEarly | Regime::Marginal => Some("loading_plate, friction.mu_dynamic, shear.damping_per_s"),
        Regime::StiffLoading | Regime::StickSlip | Regime::Undetermined => None,
    }
}

/// `e`'s message followed by the keys to change, as the command line prints it.
pub fn describe(e: &SolverError) -> String {
    with_keys(e.to_string(), for_error(e))
}

/// The spring-slider verdict followed by the keys to change, as the command line prints it.
/// The strength keys are those of the scene's `law` (under rate and state, μs and μd are
/// f(V₀, θ₀) and the steady state at 1 m/s: f₀, a and b set them).
pub fn verdict(slider: &Slider, law: &FrictionLaw) -> String {
    let [strength, drop] = crate::laws::of(law).strength_keys;
    let keys = for_regime(slider.regime())
        .map(|k| k.replace("friction.mu_static", strength).replace("friction.mu_dynamic", drop));
    with_keys(slider.verdict(), keys.as_deref())
}

fn with_keys(message: String, keys: Option<&str>) -> String {
    match keys {
        Some(keys) => format!("{message} (pipeline keys: {keys})"),
        None => message,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Whether `text` names a section or key of a pipeline file.
    fn names_a_key(text: &str) -> bool {
        let sections = ["block", "material", "friction", "time", "self_weight", "shear", "skip_ahead", "rupture"];
        sections
            .iter()
            .chain(&["record", "loading_plate", "boundary"])
            .any(|s| text.contains(&format!("[{s}]")) || text.contains(&format!("{s}.")))
    }

    fn slider(tipping_n: f64, critical_n_m: f64, damping_ratio: f64) -> Slider {
        Slider {
            normal_n: 100.0,
            strength_n: 50.0,
            tipping_n,
            block_n_m: 1e6,
            block_note: None,
            plate_n_m: f64::INFINITY,
            k_n_m: 1e6,
            critical_n_m,
            critical_formula: "(μs − μd)·N/Dc",
            steady_reason: "μ does not weaken with slip",
            damping_ratio,
            slip_speed_m_s: 1.0,
            loading_speed_m_s: 1e-4,
            sliding_n: 40.0,
            let_go: None,
        }
    }

    #[test]
    fn solver_errors_name_quantities_and_the_keys_come_from_here() {
        let errors = [
            SolverError::TimeStepAboveCritical { dt_s: 2e-6, critical_s: 1e-6, seed: 1 },
            SolverError::NotSettled { max_s: 0.1, residual: 1e-3, tolerance: 1e-6 },
        ];
        for e in &errors {
            let message = e.to_string();
            assert!(!names_a_key(&message), "{message}");
            let described = describe(e);
            assert!(described.starts_with(&message), "{described}");
            assert!(described.ends_with(&format!("(pipeline keys: {})", for_error(e).unwrap())), "{described}");
        }
        assert!(describe(&errors[0]).contains("time.dt_s"));
        assert!(describe(&errors[1]).contains("self_weight.max_duration_s"));
        assert_eq!(describe(&SolverError::Cancelled), "run cancelled");
    }

    #[test]
    fn every_verdict_names_quantities_and_its_advice_gets_keys() {
        let cases = [
            (slider(10.0, f64::INFINITY, 0.1), Regime::Tips, true),
            (slider(1e3, 0.0, 0.1), Regime::NoWeakening, true),
            (slider(1e3, 1e5, 0.1), Regime::StiffLoading, false),
            (slider(1e3, 1e7, 2.0), Regime::Overdamped, true),
            (slider(1e3, 1e7, 0.1), Regime::StickSlip, false),
        ];
        // The same slider under rigid drivers: it must hold its base to 0.80·μs·N (a drop of
        // 10 N to μd·N swings it at 1 m/s; 1.4 mN suffices against 0.1 mm/s).
        let driven = |let_go| Slider { let_go: Some(let_go), ..slider(1e3, f64::INFINITY, 0.1) };
        assert!((driven((0.73, 0.81)).holds_until().unwrap() - 0.80).abs() < 1e-3);
        let cases = cases.into_iter().chain([
            (driven((0.73, 0.81)), Regime::Marginal, true),
            (driven((0.5, 0.7)), Regime::LetsGoEarly, true),
            (driven((0.85, 0.95)), Regime::StickSlip, false),
        ]);
        for (s, regime, keyed) in cases {
            assert_eq!(s.regime(), regime);
            let text = s.verdict();
            assert!(!names_a_key(&text), "{text}");
            let law = stickslip_solver::laws::Coulomb { mu: 1.0 }.into();
            assert_eq!(verdict(&s, &law).contains("(pipeline keys: "), keyed, "{}", verdict(&s, &law));
            assert!(verdict(&s, &law).starts_with(&text));
        }
    }
}
