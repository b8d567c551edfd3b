//! Statistics seismologists judge an earthquake catalogue by (a list of events with times,
//! magnitudes, moments, areas, durations, stress drops), as pure numerics.
//!
//! - [`magnitude_frequency`]: Gutenberg–Richter distributions, completeness magnitude, b-value;
//! - [`recurrence`]: inter-event times, coefficient of variation, BPT and Weibull renewal fits;
//! - [`aftershocks`]: stacked aftershock sequences and the Omori–Utsu law by maximum likelihood;
//! - [`scaling`]: power-law scaling relations (moment–area, moment–duration, stress drop–magnitude).
//!
//! Inputs are plain slices. Every fit returns its result or a [`FitError`] saying why it cannot be
//! made; no function panics on data and none returns NaN.

pub mod aftershocks;
pub mod magnitude_frequency;
pub mod recurrence;
pub mod scaling;

/// Why a statistic or fit cannot be made from the data given.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FitError {
    /// Fewer usable values than the estimator needs.
    #[error("{what}: {have} usable, at least {need} needed")]
    TooFew {
        /// What was counted (e.g. "events at or above Mc").
        what: &'static str,
        /// How many there are.
        have: usize,
        /// The stated minimum.
        need: usize,
    },
    /// All values are the same, so the quantity is not defined.
    #[error("{what}: no spread (every value is {})", compact(*value))]
    NoSpread {
        /// What has no spread (e.g. "magnitudes at or above Mc").
        what: &'static str,
        /// The single value.
        value: f64,
    },
    /// A parameter of the call is out of its range.
    #[error("{what} must be {must}, got {value}")]
    InvalidParameter {
        /// The parameter.
        what: &'static str,
        /// Its valid range, in words.
        must: &'static str,
        /// The value given.
        value: f64,
    },
    /// A data value is outside the range the estimator accepts.
    #[error("{what} {index} is {value}; it must be {must}")]
    InvalidValue {
        /// What the value is (e.g. "interval").
        what: &'static str,
        /// Its position in the input.
        index: usize,
        /// The value.
        value: f64,
        /// Its valid range, in words.
        must: &'static str,
    },
    /// The fit has no proper maximum (runs to a boundary, flat or singular likelihood).
    #[error("{what}: {why}")]
    Degenerate {
        /// The fit.
        what: &'static str,
        /// What happened.
        why: String,
    },
    /// No completeness magnitude reaches the goodness-of-fit level asked for.
    #[error(
        "goodness of fit: no Mc explains {level_percent}% of the distribution \
         (best {best_percent:.1}% at Mc = {best_mc})"
    )]
    LevelNotReached {
        /// The level asked for (percent, e.g. 90).
        level_percent: f64,
        /// The best R found (percent).
        best_percent: f64,
        /// The Mc where it was found.
        best_mc: f64,
    },
}

/// A value as a message shows it: six significant digits at most, in scientific notation when
/// very large or small (1e7, not 10000000; 0.01, not 0.010000000000000002).
pub fn compact(v: f64) -> String {
    let a = v.abs();
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    if !(1e-3..1e5).contains(&a) {
        let s = format!("{v:.5e}");
        let (m, e) = s.split_once('e').unwrap_or((&s, "0"));
        let m = if m.contains('.') { m.trim_end_matches('0').trim_end_matches('.') } else { m };
        return format!("{m}e{e}");
    }
    let digits = (5 - a.log10().floor() as i32).max(0) as usize;
    let s = format!("{v:.digits$}");
    if s.contains('.') { s.trim_end_matches('0').trim_end_matches('.').to_string() } else { s }
}
