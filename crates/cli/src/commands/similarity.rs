//! `stickslip similarity`: one model event scaled to a prototype fault, by hand.

use anyhow::Result;
use stickslip_seismo::similarity::{
    ModelEvent, SECONDS_PER_YEAR, SimilarityParams, moment_magnitude, riera_magnitude, scale,
};

use crate::text::pad;

/// Arguments of `stickslip similarity`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Mean stress drop Δσ of the event (Pa).
    #[arg(long, allow_negative_numbers = true)]
    pub stress_drop_pa: f64,
    /// Model fault length L_m (m).
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub model_length_m: f64,
    /// Model rupture area A_m (m²).
    #[arg(long, default_value_t = 0.1, allow_negative_numbers = true)]
    pub model_area_m2: f64,
    /// Prototype fault length L_p (m).
    #[arg(long, default_value_t = 1.0e4, allow_negative_numbers = true)]
    pub prototype_length_m: f64,
    /// Event duration at model scale (s).
    #[arg(long, allow_negative_numbers = true)]
    pub duration_s: Option<f64>,
    /// Recurrence at model scale (s).
    #[arg(long, allow_negative_numbers = true)]
    pub recurrence_s: Option<f64>,
    /// Model loading rate u̇_m (m/s).
    #[arg(long, default_value_t = 1.1e-4, allow_negative_numbers = true)]
    pub model_rate_m_s: f64,
    /// Prototype loading rate u̇_p (m/s); 3.17e-10 is 1 cm/yr.
    #[arg(long, default_value = "3.17e-10", allow_negative_numbers = true)]
    pub prototype_rate_m_s: f64,
}

/// `stickslip similarity`.
pub fn run(a: Args) -> Result<()> {
    let mut given = vec![
        ("--stress-drop-pa", a.stress_drop_pa),
        ("--model-length-m", a.model_length_m),
        ("--model-area-m2", a.model_area_m2),
        ("--prototype-length-m", a.prototype_length_m),
        ("--model-rate-m-s", a.model_rate_m_s),
        ("--prototype-rate-m-s", a.prototype_rate_m_s),
    ];
    given.extend(a.duration_s.map(|v| ("--duration-s", v)));
    given.extend(a.recurrence_s.map(|v| ("--recurrence-s", v)));
    for (name, v) in given {
        anyhow::ensure!(v > 0.0 && v.is_finite(), "{name} = {v} is not allowed: a positive, finite number");
    }
    let params = SimilarityParams {
        prototype_length_m: a.prototype_length_m,
        prototype_rate_m_s: a.prototype_rate_m_s,
        ..SimilarityParams::default()
    };
    let e = ModelEvent {
        stress_drop_pa: a.stress_drop_pa,
        model_length_m: a.model_length_m,
        model_area_m2: a.model_area_m2,
        duration_s: a.duration_s,
        recurrence_s: a.recurrence_s,
        model_rate_m_s: a.model_rate_m_s,
    };
    let s = scale(&e, &params);
    let row = |k: &str, v: String| outln!("  {} {v}", pad(k, 44));
    outln!("similarity (docs/model.md §9): λ = L_p/L_m");
    row("λ", format!("{:.6e}", s.lambda));
    row("prototype rupture area A_p = λ²·A_m", format!("{:.4e} m²", s.prototype_area_m2));
    if let Some(d) = s.prototype_duration_s {
        row("prototype duration λ·t_m", format!("{d:.4} s"));
    }
    if let Some(r) = s.prototype_recurrence_s {
        row("prototype recurrence Δt_m·λ·u̇_m/u̇_p", format!("{r:.4e} s = {:.3} years", r / SECONDS_PER_YEAR));
    }
    row("M0, paper's Eq. 15 (Δσ·L_p·A_p·λ)", format!("{:.4e} dyne·cm", s.m0_paper_dyne_cm));
    row("  Riera M, interplate (X = 0)", format!("{:.3}", riera_magnitude(s.m0_paper_dyne_cm, false)));
    row("  Riera M, intraplate (X = 1)", format!("{:.3}", riera_magnitude(s.m0_paper_dyne_cm, true)));
    row("  Mw (Hanks & Kanamori)", format!("{:.3}", moment_magnitude(s.m0_paper_dyne_cm)));
    row("M0, consistent (Δσ·L_p·A_p)", format!("{:.4e} dyne·cm", s.m0_consistent_dyne_cm));
    row("  Riera M, interplate (X = 0)", format!("{:.3}", riera_magnitude(s.m0_consistent_dyne_cm, false)));
    row("  Riera M, intraplate (X = 1)", format!("{:.3}", riera_magnitude(s.m0_consistent_dyne_cm, true)));
    row("  Mw (Hanks & Kanamori)", format!("{:.3}", moment_magnitude(s.m0_consistent_dyne_cm)));
    Ok(())
}
