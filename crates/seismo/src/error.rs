//! Errors of the seismology numerics: unreadable accelerogram files, bad parameters, spectra that
//! cannot be computed, record sets that cannot be selected. Every error type of the crate lives
//! here (re-exported where it is raised), so this module imports none of the others.

use std::path::PathBuf;

/// Everything that can go wrong in this crate; each variant carries what is needed to act on it.
#[derive(Debug, thiserror::Error)]
pub enum SeismoError {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A parameter is outside its allowed range; nothing was computed.
    #[error("{name} = {value} is not allowed: {allowed}")]
    Parameter {
        /// The parameter, as named in the API (e.g. `f_low`, `candidates[3].psa`).
        name: String,
        /// The value given, as text.
        value: String,
        /// What is allowed, e.g. `0 < f_low < f_high (25 Hz)`.
        allowed: String,
    },
    /// No record set meets the selection rules; the reason says which rule could not be met.
    #[error("no record set can be selected: {0}")]
    Selection(Refusal),
    /// A spectrum could not be computed (a bad interval, period, damping or sample).
    #[error(transparent)]
    Spectrum(#[from] SpectrumError),
    /// A file is not in the format it claims.
    #[error("{}: {what}", path.display())]
    Format {
        /// The file.
        path: PathBuf,
        /// What is wrong.
        what: String,
    },
}

impl SeismoError {
    /// A [`SeismoError::Parameter`] from anything printable.
    pub fn parameter(name: impl Into<String>, value: impl std::fmt::Display, allowed: impl Into<String>) -> Self {
        SeismoError::Parameter { name: name.into(), value: value.to_string(), allowed: allowed.into() }
    }
}

/// A numerical input the spectra cannot answer for.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum SpectrumError {
    /// The sampling interval is not a positive finite number.
    #[error("sampling interval {dt} s: need 0 < Δt (finite)")]
    Interval {
        /// The interval (s).
        dt: f64,
    },
    /// A period is not a positive finite number.
    #[error("period {index} is {value} s: need 0 < T (finite)")]
    Period {
        /// Its position in the list.
        index: usize,
        /// The period (s).
        value: f64,
    },
    /// A damping ratio is outside [0, 1).
    #[error("damping {index} is {value}: need 0 ≤ ξ < 1")]
    Damping {
        /// Its position in the list.
        index: usize,
        /// The damping ratio.
        value: f64,
    },
    /// A sample of the record is NaN or infinite.
    #[error("sample {index} of {component} is {value}: records must be finite")]
    NonFinite {
        /// Which record ("record", "x" or "y").
        component: &'static str,
        /// Sample index.
        index: usize,
        /// The value.
        value: f64,
    },
    /// The two horizontal components do not have the same number of samples.
    #[error("the components have {x} and {y} samples: they must be sampled alike")]
    Components {
        /// Samples of x.
        x: usize,
        /// Samples of y.
        y: usize,
    },
}

/// Why no set could be selected.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum Refusal {
    /// Too few records have a usable band covering the range.
    #[error(
        "only {eligible} of {candidates} candidates have a usable band covering the period range [{t_a}, {t_b}] s; \
         {needed} are needed"
    )]
    TooFewEligible {
        /// Records needed (N).
        needed: usize,
        /// Eligible records.
        eligible: usize,
        /// Candidates given.
        candidates: usize,
        /// Range (s).
        t_a: f64,
        /// Range (s).
        t_b: f64,
    },
    /// The group cap leaves too few records.
    #[error(
        "the {eligible} eligible records come from {groups} groups; at most {per_group} per group allows only \
         {capacity} records, {needed} are needed"
    )]
    TooFewGroups {
        /// Records needed (N).
        needed: usize,
        /// Eligible records.
        eligible: usize,
        /// Groups among the eligible records.
        groups: usize,
        /// The cap.
        per_group: usize,
        /// Records the cap allows.
        capacity: usize,
    },
    /// Even at the largest scale factor the mean cannot reach the rule somewhere in the range.
    #[error(
        "at T = {period} s even the {needed} strongest eligible records allowed by the group cap, all scaled by \
         s_max = {scale_max}, reach only {:.1}% of the target (the rule asks {:.0}%): raise s_max or add stronger records",
        100.0 * best_ratio, 100.0 * rule_fraction
    )]
    ScaleBounds {
        /// Records needed (N).
        needed: usize,
        /// Period where the bound fails (s).
        period: f64,
        /// Best reachable ratio of the mean to the target there.
        best_ratio: f64,
        /// The scale bound.
        scale_max: f64,
        /// The rule.
        rule_fraction: f64,
    },
    /// The necessary check passed but the search found no set meeting the rule.
    #[error(
        "the search found no set meeting the rule: the best set, all scaled by s_max = {scale_max}, reaches \
         {:.1}% of the target at T = {period} s (the rule asks {:.0}%)",
        100.0 * best_ratio, 100.0 * rule_fraction
    )]
    NotFound {
        /// Best reachable ratio of the best set found.
        best_ratio: f64,
        /// Period where it is reached (s).
        period: f64,
        /// The scale bound.
        scale_max: f64,
        /// The rule.
        rule_fraction: f64,
    },
}
