//! The eligible records over the range and a set of them with its running sums: the objective `J`
//! of a set, and of a set with one record swapped, from the sums.

use crate::selection::options::Candidate;

/// The eligible records' data over the range, row-major (record × range period).
pub(super) struct Pool<'a> {
    pub(super) m: usize,
    /// Candidate index of each eligible record.
    pub(super) index: Vec<usize>,
    pub(super) group: Vec<usize>,
    /// Log residual at its own scale.
    pub(super) resid: Vec<f64>,
    /// Its own misfit.
    pub(super) misfit: Vec<f64>,
    /// Its own (clamped) scale.
    pub(super) scale: Vec<f64>,
    /// Unscaled PSA / target over the range.
    pub(super) ratio: Vec<f64>,
    pub(super) candidates: &'a [Candidate],
}

impl Pool<'_> {
    pub(super) fn resid(&self, e: usize) -> &[f64] {
        &self.resid[e * self.m..(e + 1) * self.m]
    }
    pub(super) fn ratio(&self, e: usize) -> &[f64] {
        &self.ratio[e * self.m..(e + 1) * self.m]
    }
}

/// The search state: chosen eligible indices, running sums.
pub(super) struct SetState {
    pub(super) chosen: Vec<usize>,
    pub(super) in_set: Vec<bool>,
    pub(super) per_group: Vec<usize>,
    pub(super) sum_resid: Vec<f64>,
    pub(super) sum_ratio: Vec<f64>,
    pub(super) sum_misfit: f64,
}

impl SetState {
    pub(super) fn new(pool: &Pool, groups: usize) -> Self {
        SetState {
            chosen: Vec::new(),
            in_set: vec![false; pool.index.len()],
            per_group: vec![0; groups],
            sum_resid: vec![0.0; pool.m],
            sum_ratio: vec![0.0; pool.m],
            sum_misfit: 0.0,
        }
    }
    pub(super) fn add(&mut self, pool: &Pool, e: usize) {
        self.chosen.push(e);
        self.in_set[e] = true;
        self.per_group[pool.group[e]] += 1;
        for (s, r) in self.sum_resid.iter_mut().zip(pool.resid(e)) {
            *s += r;
        }
        for (s, r) in self.sum_ratio.iter_mut().zip(pool.ratio(e)) {
            *s += r;
        }
        self.sum_misfit += pool.misfit[e];
    }
    pub(super) fn swap(&mut self, pool: &Pool, position: usize, e: usize) {
        let out = self.chosen[position];
        self.in_set[out] = false;
        self.per_group[pool.group[out]] -= 1;
        for (s, r) in self.sum_resid.iter_mut().zip(pool.resid(out)) {
            *s -= r;
        }
        for (s, r) in self.sum_ratio.iter_mut().zip(pool.ratio(out)) {
            *s -= r;
        }
        self.sum_misfit -= pool.misfit[out];
        self.chosen[position] = e;
        self.in_set[e] = true;
        self.per_group[pool.group[e]] += 1;
        for (s, r) in self.sum_resid.iter_mut().zip(pool.resid(e)) {
            *s += r;
        }
        for (s, r) in self.sum_ratio.iter_mut().zip(pool.ratio(e)) {
            *s += r;
        }
        self.sum_misfit += pool.misfit[e];
    }
}

/// Objective pieces of a set of `n` records given the sums, with `out` removed and `inn` added
/// (either may be absent). Returns `(J, min_T sum_ratio/n)`.
pub(super) fn evaluate(
    pool: &Pool,
    st: &SetState,
    n: usize,
    out: Option<usize>,
    inn: Option<usize>,
    w: f64,
) -> (f64, f64) {
    let m = pool.m;
    let inv = 1.0 / n as f64;
    let (ro, qo) = match out {
        Some(o) => (Some(pool.resid(o)), Some(pool.ratio(o))),
        None => (None, None),
    };
    let (ri, qi) = match inn {
        Some(i) => (Some(pool.resid(i)), Some(pool.ratio(i))),
        None => (None, None),
    };
    let mut sq = 0.0;
    let mut min_ratio = f64::INFINITY;
    for t in 0..m {
        let mut r = st.sum_resid[t];
        let mut q = st.sum_ratio[t];
        if let (Some(ro), Some(qo)) = (ro, qo) {
            r -= ro[t];
            q -= qo[t];
        }
        if let (Some(ri), Some(qi)) = (ri, qi) {
            r += ri[t];
            q += qi[t];
        }
        let mean = r * inv;
        sq += mean * mean;
        min_ratio = min_ratio.min(q * inv);
    }
    let mut spread = st.sum_misfit;
    if let Some(o) = out {
        spread -= pool.misfit[o];
    }
    if let Some(i) = inn {
        spread += pool.misfit[i];
    }
    (sq / m as f64 + w * spread * inv, min_ratio)
}
