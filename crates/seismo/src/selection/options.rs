//! What a selection reads (the candidates, the period range, the options) and what it returns.

use crate::catalogue::compact;
use crate::error::SeismoError;

/// One candidate record.
#[derive(Clone, Debug, PartialEq)]
pub struct Candidate {
    /// Identifier reported back.
    pub id: String,
    /// Group key (e.g. `"seed 3 / event 17"`); at most `per_group` records of one group are chosen.
    pub group: String,
    /// PSA on the common period grid (any unit, the target's).
    pub psa: Vec<f64>,
    /// Lowest usable period (s).
    pub usable_min: f64,
    /// Highest usable period (s); `f64::INFINITY` for no limit.
    pub usable_max: f64,
}

/// Period range over which the set is fitted and checked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PeriodRange {
    /// `[t_a, t_b]` (s).
    Explicit {
        /// Lower bound (s).
        t_a: f64,
        /// Upper bound (s).
        t_b: f64,
    },
    /// `[0.2·t1, 2·t1]` from the fundamental period `t1` (s).
    Fundamental {
        /// Fundamental period (s).
        t1: f64,
    },
}

impl PeriodRange {
    /// `(T_a, T_b)` (s), checked: `0 < T_a < T_b`, finite.
    pub fn bounds(&self) -> Result<(f64, f64), SeismoError> {
        match *self {
            PeriodRange::Fundamental { t1 } => {
                if !(t1 > 0.0 && t1.is_finite()) {
                    return Err(SeismoError::parameter("range.t1", format!("{t1} s"), "a finite T_1 > 0 s"));
                }
                // T₁/5 rather than 0.2·T₁: 0.05/5 is 0.01, 0.2·0.05 is 0.010000000000000002.
                Ok((t1 / 5.0, 2.0 * t1))
            }
            PeriodRange::Explicit { t_a, t_b } => {
                if !(t_a > 0.0 && t_a < t_b && t_b.is_finite()) {
                    return Err(SeismoError::parameter(
                        "range",
                        format!("[{}, {}] s", compact(t_a), compact(t_b)),
                        "0 < T_a < T_b, finite",
                    ));
                }
                Ok((t_a, t_b))
            }
        }
    }
}

/// Options of [`select`](crate::selection::select); [`SelectionOptions::new`] gives the documented defaults.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SelectionOptions {
    /// Period range.
    pub range: PeriodRange,
    /// Number of records N (default 11), ≥ 1.
    pub count: usize,
    /// At most this many records of one group (default 2), ≥ 1.
    pub per_group: usize,
    /// Smallest scale factor (default 0.25), > 0.
    pub scale_min: f64,
    /// Largest scale factor (default 4.0), ≥ `scale_min`. (0.25–4 is a common engineering limit, not a code rule.)
    pub scale_max: f64,
    /// The code rule: the set's mean must not fall below this fraction of the target (default 0.9), in (0, 1].
    pub rule_fraction: f64,
    /// Weight `w` of the records' own misfits in the objective (default 0.1), ≥ 0.
    pub spread_weight: f64,
    /// Bound on swap passes (default 100).
    pub max_swap_passes: usize,
    /// Number of starts of greedy-with-swaps (default 8), ≥ 1: start `k` forces the record with the
    /// `k`-th smallest own misfit into the set first (start 0 is the plain greedy).
    pub starts: usize,
}

impl SelectionOptions {
    /// Defaults for `range`.
    pub fn new(range: PeriodRange) -> Self {
        SelectionOptions {
            range,
            count: 11,
            per_group: 2,
            scale_min: 0.25,
            scale_max: 4.0,
            rule_fraction: 0.9,
            spread_weight: 0.1,
            max_swap_passes: 100,
            starts: 8,
        }
    }
}

/// One chosen record.
#[derive(Clone, Debug, PartialEq)]
pub struct Chosen {
    /// Index into the candidates.
    pub index: usize,
    /// The candidate's id.
    pub id: String,
    /// The candidate's group.
    pub group: String,
    /// Final amplitude scale factor, in `[scale_min, scale_max]`.
    pub scale: f64,
    /// Mean squared log residual of the scaled record over the range, `mean_T r_i(T)²`.
    pub misfit: f64,
}

/// A selected set.
#[derive(Clone, Debug, PartialEq)]
pub struct Selection {
    /// The chosen records, in the order they were chosen or swapped in.
    pub records: Vec<Chosen>,
    /// `(T_a, T_b)` (s).
    pub range: (f64, f64),
    /// Indices of the grid periods inside the range.
    pub range_indices: std::ops::Range<usize>,
    /// Arithmetic mean of the scaled spectra on the whole grid (the target's unit).
    pub mean: Vec<f64>,
    /// `min_T mean(T)/target(T)` over the range.
    pub min_ratio: f64,
    /// Period where it is reached (s).
    pub min_ratio_period: f64,
    /// Mean squared log residual of the set's mean log-spectrum over the range, `mean_T (mean_i r_i)²`.
    pub mean_log_misfit: f64,
    /// Objective `J` of the final set.
    pub objective: f64,
    /// Common factor applied in step (5) (1 if none was needed).
    pub common_scale: f64,
    /// Number of eligible candidates.
    pub eligible: usize,
}
