//! What `stickslip check` says of a pipeline, one description per section of the scene and of
//! the analysis: each a [`Section`] of labelled lines that the command prints in its order.
//! Built here, below the command line, from the validated [`crate::Pipeline`], the built
//! [`stickslip_solver::Model`] and what [`stickslip_solver::inspect`] found; the command only
//! prints (and times its probe, and refuses what does not fit).

mod analysis;
mod cycles;
mod scene;

pub use analysis::{
    accelerograms, broadband, cost_before_building, events, report, scale, seeds, set, skip_ahead, spectra,
};
pub use cycles::cycles;
pub use scene::{
    Probe, block, critical_step, describe_boundaries, describe_friction, fault, medium, record, run_cost,
    spring_slider, stages, stiffness,
};

use stickslip_solver::{Model, NodeId};

/// One section of the description: lines, each with a label that says which part of the section
/// it is (a command prints a section whole, or its parts where they belong), as printed below the
/// pipeline's heading (a sub-line carries its own indent).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Section {
    /// The lines in order.
    pub lines: Vec<Line>,
}

/// A labelled line of a [`Section`].
#[derive(Clone, Debug, PartialEq)]
pub struct Line {
    /// Which part of its section the line is (e.g. `"law"` or `"map"` of the friction).
    pub label: &'static str,
    /// The text.
    pub text: String,
}

impl Section {
    /// Adds a line labelled `label`.
    pub fn push(&mut self, label: &'static str, text: impl Into<String>) {
        self.lines.push(Line { label, text: text.into() });
    }

    /// The texts of the lines labelled `label`, in order.
    pub fn part<'a>(&'a self, label: &'a str) -> impl Iterator<Item = &'a str> + 'a {
        self.lines.iter().filter(move |l| l.label == label).map(|l| l.text.as_str())
    }

    /// The texts of every line, in order.
    pub fn texts(&self) -> impl Iterator<Item = &str> {
        self.lines.iter().map(|l| l.text.as_str())
    }
}

/// A number as a reader wants it: `{}` writes it short (`1e300`, not 300 digits; see
/// [`crate::check::num`]), and `{:.3}` keeps three decimals while it is below 10⁶ in size, then
/// switches to an exponent.
#[derive(Clone, Copy, Debug)]
pub struct N(pub f64);

impl std::fmt::Display for N {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let v = self.0;
        match f.precision() {
            None => f.write_str(&crate::check::num(v)),
            Some(p) if v.is_finite() && (v == 0.0 || (1e-3..1e6).contains(&v.abs())) => write!(f, "{v:.p$}"),
            Some(p) if v.is_finite() => write!(f, "{v:.p$e}"),
            Some(_) => write!(f, "{v}"),
        }
    }
}

/// Positions written without the round-off of `i·Lc` (and short when huge or tiny): to 12
/// significant digits, whatever their size (`2.8000000000000003` is 2.8, `12000000.000000002`
/// is 12000000).
pub fn round(v: f64) -> N {
    let r: f64 = format!("{v:.11e}").parse().unwrap_or(v);
    N(if r.is_finite() { r } else { v })
}

/// A node as "LDEM 36 at (0.2, 0.1, 0.1) m".
pub fn position(model: &Model, id: NodeId) -> String {
    let p = model.lattice().position(id);
    format!("LDEM {} at ({}, {}, {}) m", id.ldem(), round(p[0]), round(p[1]), round(p[2]))
}

/// Seconds as `1.2 s`, `3.4 min`, `5.6 h` or `7.8 days`.
pub fn duration(s: f64) -> String {
    if s < 120.0 {
        format!("{s:.1} s")
    } else if s < 7200.0 {
        format!("{:.1} min", s / 60.0)
    } else if s < 172_800.0 {
        format!("{:.1} h", s / 3600.0)
    } else {
        format!("{:.1} days", s / 86_400.0)
    }
}

#[cfg(test)]
mod tests {
    use super::{N, round};

    #[test]
    fn positions_are_written_without_round_off_at_any_size() {
        assert_eq!(round(0.1 * 28.0).to_string(), "2.8");
        assert_eq!(round(3.0 * 0.1).to_string(), "0.3");
        assert_eq!(round(1.2e7 + 2.0 * f64::EPSILON * 1.2e7).to_string(), "12000000");
        assert_eq!(round(0.1 * 3.0 * 1e-6).to_string(), N(3e-7).to_string());
        assert_eq!(round(0.0).to_string(), "0");
        assert_eq!(round(1e300).to_string(), "1e300");
    }

    #[test]
    fn numbers_stay_short() {
        assert_eq!(format!("{}", N(1e300)), "1e300");
        assert_eq!(format!("{}", N(0.1)), "0.1");
        assert_eq!(format!("{:.3}", N(1.2494e305)), "1.249e305");
        assert_eq!(format!("{:.3}", N(0.7)), "0.700");
        assert_eq!(format!("{:.1}", N(1e-9)), "1.0e-9");
        assert_eq!(format!("{:.3}", N(f64::INFINITY)), "inf");
    }
}
