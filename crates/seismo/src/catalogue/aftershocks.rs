//! Aftershock decay: stacked sequences, binned rates and the Omori–Utsu law by maximum likelihood.
//!
//! - **Stacking**: each main shock at `T_i` owns the events at `T_i < t < T_i + w_i`, with the
//!   window `w_i` = `max_time`, cut at the next main shock (if asked) and at the end of the
//!   catalogue. Their times since the main shock, `τ = t − T_i`, are pooled.
//! - **Rate** in logarithmic bins `[τ_a, τ_b)`: `count / exposure`, the exposure being
//!   `Σ_i |[τ_a, τ_b) ∩ (0, w_i)|` (main shock × time), so the rate is *per main shock*; its error
//!   is `√count / exposure` (Poisson).
//! - **Modified Omori law** (Utsu 1961, Geophys. Mag. 30, 521–605): per main shock
//!   `n(τ) = K/(τ + c)^p` (events per unit time). Fitted by maximum likelihood as a
//!   non-stationary Poisson process (Ogata 1983, J. Phys. Earth 31, 115–124) on
//!   `[t_start, t_end]`: with `N` events `τ_k` and window ends `e_i = min(t_end, w_i)`,
//!   `ℓ(K, c, p) = N ln K − p·Σ_k ln(τ_k + c) − K·Σ_i A_i(c, p)`,
//!   `A_i = ∫_{t_start}^{e_i} (τ + c)^(−p) dτ`. `K` is profiled out (`K̂ = N/Σ A_i`) and
//!   `(ln c, p)` are found by Levenberg–Marquardt on the profile likelihood with its exact
//!   gradient and Hessian. The integrals and their derivatives in `p` are computed in
//!   `x = ln(τ + c)` as `∫ x^m e^((1−p)x) dx`, by series near `p = 1` and in closed form away
//!   from it, so `p = 1` is not a special case. Uncertainties: the inverse of the observed
//!   information matrix (the negative Hessian of `ℓ` in `(K, c, p)`) at the optimum.
//!
//! A fit needs at least [`MIN_AFTERSHOCKS`] events in `[t_start, t_end]`. A fit whose `c` runs to
//! 0 or to infinity, or whose information matrix is singular, is refused as degenerate.

use nalgebra::{Matrix2, Matrix3, Vector2};

use crate::catalogue::FitError;

/// Fewest stacked aftershocks for an Omori–Utsu fit: 100.
///
/// Three parameters are fitted; with fewer than about 100 events `c` is seldom resolved (its
/// error exceeds its value) and `p` is known to no better than ±0.1–0.2, too loose to tell
/// sequences apart (Utsu, Ogata & Matsu'ura 1995, J. Phys. Earth 43, 1–33).
pub const MIN_AFTERSHOCKS: usize = 100;

/// How far each main shock's aftershock window reaches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Window {
    /// Longest window after a main shock (time unit of the input, e.g. s).
    pub max_time: f64,
    /// Cut the window at the next main shock.
    pub stop_at_next_main_shock: bool,
    /// End of the catalogue (same time axis as the events); windows are cut there.
    /// `f64::INFINITY` if `max_time` is always covered.
    pub catalogue_end: f64,
}

/// Aftershocks of several main shocks, in time since their main shock.
#[derive(Clone, Debug, PartialEq)]
pub struct StackedAftershocks {
    /// Times since their main shock of all following events in the windows, ascending.
    pub times: Vec<f64>,
    /// Window length of each main shock, in main-shock time order.
    pub windows: Vec<f64>,
    /// Events in each main shock's window, same order.
    pub counts: Vec<usize>,
}

/// Collects the events of `event_times` following each of `main_shock_times` within its
/// [`Window`] (all times on one axis, e.g. s; unsorted is fine; non-finite times are left out;
/// events at the very time of a main shock, such as the main shock itself, are not its
/// aftershocks).
pub fn stack_aftershocks(
    main_shock_times: &[f64],
    event_times: &[f64],
    window: Window,
) -> Result<StackedAftershocks, FitError> {
    if !(window.max_time > 0.0) {
        return Err(FitError::InvalidParameter { what: "max_time", must: "positive", value: window.max_time });
    }
    if window.catalogue_end.is_nan() {
        return Err(FitError::InvalidParameter { what: "catalogue_end", must: "a time", value: f64::NAN });
    }
    let mut mains: Vec<f64> = main_shock_times.iter().copied().filter(|t| t.is_finite()).collect();
    mains.sort_by(f64::total_cmp);
    if mains.is_empty() {
        return Err(FitError::TooFew { what: "main shocks", have: 0, need: 1 });
    }
    let mut events: Vec<f64> = event_times.iter().copied().filter(|t| t.is_finite()).collect();
    events.sort_by(f64::total_cmp);
    let mut times = Vec::new();
    let mut windows = Vec::with_capacity(mains.len());
    let mut counts = Vec::with_capacity(mains.len());
    for (i, &t0) in mains.iter().enumerate() {
        let mut w = window.max_time.min(window.catalogue_end - t0);
        if window.stop_at_next_main_shock
            && let Some(&next) = mains.get(i + 1)
        {
            w = w.min(next - t0);
        }
        if !w.is_finite() {
            return Err(FitError::InvalidParameter {
                what: "max_time",
                must: "finite, or the window cut by the next main shock or the catalogue end",
                value: window.max_time,
            });
        }
        let w = w.max(0.0);
        let from = events.partition_point(|&t| t <= t0);
        let to = events.partition_point(|&t| t < t0 + w);
        let before = times.len();
        times.extend(events[from..to.max(from)].iter().map(|&t| t - t0).filter(|&tau| tau > 0.0 && tau < w));
        windows.push(w);
        counts.push(times.len() - before);
    }
    times.sort_by(f64::total_cmp);
    Ok(StackedAftershocks { times, windows, counts })
}

/// Rate of stacked aftershocks in one time bin.
#[derive(Clone, Debug, PartialEq)]
pub struct RateBin {
    /// Start of the bin (time since main shock).
    pub start: f64,
    /// End of the bin.
    pub end: f64,
    /// Geometric centre `√(start·end)`.
    pub centre: f64,
    /// Events in the bin.
    pub count: usize,
    /// Observed time in the bin summed over main shocks (main shock × time unit).
    pub exposure: f64,
    /// Events per unit time per main shock.
    pub rate: f64,
    /// Poisson standard error of the rate, `√count / exposure`.
    pub rate_error: f64,
}

/// Per-main-shock rate of `stack` in `bins_per_decade` logarithmic bins from `t_min` to `t_max`
/// (time since main shock, `0 < t_min < t_max`). Bins no window reaches are left out.
pub fn aftershock_rate(
    stack: &StackedAftershocks,
    t_min: f64,
    t_max: f64,
    bins_per_decade: usize,
) -> Result<Vec<RateBin>, FitError> {
    if !(t_min > 0.0) || !t_min.is_finite() {
        return Err(FitError::InvalidParameter { what: "t_min", must: "finite and positive", value: t_min });
    }
    if !(t_max > t_min) || !t_max.is_finite() {
        return Err(FitError::InvalidParameter { what: "t_max", must: "finite and above t_min", value: t_max });
    }
    if bins_per_decade == 0 || bins_per_decade > 1000 {
        let value = bins_per_decade as f64;
        return Err(FitError::InvalidParameter { what: "bins per decade", must: "between 1 and 1000", value });
    }
    let mut edges = vec![t_min];
    let mut j = 1;
    loop {
        let e = t_min * 10f64.powf(j as f64 / bins_per_decade as f64);
        if e >= t_max * (1.0 - 1e-12) {
            edges.push(t_max);
            break;
        }
        edges.push(e);
        j += 1;
    }
    let mut out = Vec::with_capacity(edges.len() - 1);
    for e in edges.windows(2) {
        let (a, b) = (e[0], e[1]);
        let exposure: f64 = stack.windows.iter().map(|&w| (w.min(b) - a).max(0.0)).sum();
        if !(exposure > 0.0) {
            continue;
        }
        let count = stack.times.partition_point(|&t| t < b) - stack.times.partition_point(|&t| t < a);
        out.push(RateBin {
            start: a,
            end: b,
            centre: (a * b).sqrt(),
            count,
            exposure,
            rate: count as f64 / exposure,
            rate_error: (count as f64).sqrt() / exposure,
        });
    }
    Ok(out)
}

/// A modified-Omori (Omori–Utsu) fit `n(τ) = K/(τ + c)^p` per main shock.
#[derive(Clone, Debug, PartialEq)]
pub struct OmoriFit {
    /// Productivity K (events per main shock × time unit^(p − 1)).
    pub k: f64,
    /// c (time unit of the input).
    pub c: f64,
    /// p (dimensionless).
    pub p: f64,
    /// Standard error of K.
    pub k_se: f64,
    /// Standard error of c.
    pub c_se: f64,
    /// Standard error of p.
    pub p_se: f64,
    /// Covariance of (K, c, p), inverse observed information.
    pub covariance: [[f64; 3]; 3],
    /// Events fitted.
    pub n: usize,
    /// Main shocks whose window reaches into `[t_start, t_end]`.
    pub main_shocks: usize,
    /// Start of the fitted interval (time since main shock).
    pub t_start: f64,
    /// End of the fitted interval.
    pub t_end: f64,
    /// Maximised log-likelihood.
    pub log_likelihood: f64,
    /// Akaike information criterion, `6 − 2ℓ`.
    pub aic: f64,
}

impl OmoriFit {
    /// Rate `K/(τ + c)^p` per main shock at time `tau` since it (events per time unit).
    pub fn rate(&self, tau: f64) -> f64 {
        self.k / (tau + self.c).powf(self.p)
    }

    /// Expected events of one main shock in `[t0, t1]`, `K·∫(τ + c)^(−p) dτ`.
    pub fn expected_count(&self, t0: f64, t1: f64) -> f64 {
        self.k * integrals(self.c, self.p, t0, t1).a
    }
}

/// `∫_0^d y^m e^(u y) dy` for m = 0, 1, 2.
fn j_moments(u: f64, d: f64) -> [f64; 3] {
    let ud = u * d;
    if ud.abs() < 1.0 {
        let mut out = [0.0; 3];
        for (m, o) in out.iter_mut().enumerate() {
            // Σ_j (ud)^j/j! · d^(m+1)/(j + m + 1).
            let (mut term, mut sum) = (1.0, 0.0);
            for j in 0..80 {
                let add = term / (j + m + 1) as f64;
                sum += add;
                if add.abs() <= 1e-17 * sum.abs() {
                    break;
                }
                term *= ud / (j + 1) as f64;
            }
            *o = sum * d.powi(m as i32 + 1);
        }
        out
    } else {
        let e = ud.exp();
        let j0 = (e - 1.0) / u;
        let j1 = (d * e - j0) / u;
        let j2 = (d * d * e - 2.0 * j1) / u;
        [j0, j1, j2]
    }
}

/// `A = ∫_s^e (τ + c)^(−p) dτ` and its first and second derivatives in c and p.
#[derive(Clone, Copy, Debug, Default)]
struct Integrals {
    a: f64,
    a_c: f64,
    a_p: f64,
    a_cc: f64,
    a_cp: f64,
    a_pp: f64,
}

fn integrals(c: f64, p: f64, s: f64, e: f64) -> Integrals {
    if !(e > s) {
        return Integrals::default();
    }
    let (xa, xb) = ((s + c).ln(), (e + c).ln());
    let d = xb - xa;
    let u = 1.0 - p;
    let [j0, j1, j2] = j_moments(u, d);
    let ea = (u * xa).exp();
    let (fa, fb) = ((-p * xa).exp(), (-p * xb).exp());
    Integrals {
        a: ea * j0,
        a_p: -ea * (xa * j0 + j1),
        a_pp: ea * (xa * xa * j0 + 2.0 * xa * j1 + j2),
        a_c: fb - fa,
        a_cc: -p * (fb / (e + c) - fa / (s + c)),
        a_cp: -xb * fb + xa * fa,
    }
}

/// The data of one fit: event times and distinct window ends with multiplicity.
struct OmoriData<'a> {
    times: &'a [f64],
    t_start: f64,
    ends: Vec<(f64, f64)>,
}

/// Sums needed by ℓ and its derivatives at (c, p).
struct Sums {
    n: f64,
    log_sum: f64,
    inv_sum: f64,
    inv2_sum: f64,
    a: Integrals,
}

impl OmoriData<'_> {
    fn sums(&self, c: f64, p: f64, derivatives: bool) -> Sums {
        let (mut log_sum, mut inv_sum, mut inv2_sum) = (0.0, 0.0, 0.0);
        for &t in self.times {
            log_sum += (t + c).ln();
            if derivatives {
                let r = 1.0 / (t + c);
                inv_sum += r;
                inv2_sum += r * r;
            }
        }
        let mut a = Integrals::default();
        for &(e, mult) in &self.ends {
            let i = if derivatives {
                integrals(c, p, self.t_start, e)
            } else {
                Integrals { a: integrals(c, p, self.t_start, e).a, ..Default::default() }
            };
            a.a += mult * i.a;
            a.a_c += mult * i.a_c;
            a.a_p += mult * i.a_p;
            a.a_cc += mult * i.a_cc;
            a.a_cp += mult * i.a_cp;
            a.a_pp += mult * i.a_pp;
        }
        Sums { n: self.times.len() as f64, log_sum, inv_sum, inv2_sum, a }
    }

    /// Profile log-likelihood at (c, p), K profiled out.
    fn profile(&self, c: f64, p: f64) -> f64 {
        let s = self.sums(c, p, false);
        s.n * (s.n / s.a.a).ln() - s.n - p * s.log_sum
    }

    /// Full Hessian of ℓ in (K, c, p) and gradient in (c, p), at K = K̂(c, p).
    fn derivatives(&self, c: f64, p: f64) -> (f64, Matrix3<f64>, Vector2<f64>) {
        let s = self.sums(c, p, true);
        let k = s.n / s.a.a;
        let g = Vector2::new(-p * s.inv_sum - k * s.a.a_c, -s.log_sum - k * s.a.a_p);
        let h = Matrix3::new(
            -s.n / (k * k),
            -s.a.a_c,
            -s.a.a_p,
            -s.a.a_c,
            p * s.inv2_sum - k * s.a.a_cc,
            -s.inv_sum - k * s.a.a_cp,
            -s.a.a_p,
            -s.inv_sum - k * s.a.a_cp,
            -k * s.a.a_pp,
        );
        (k, h, g)
    }

    /// Profile gradient and Hessian in (σ = ln c, p).
    fn profile_newton(&self, c: f64, p: f64) -> (Vector2<f64>, Matrix2<f64>) {
        let (_, h, g) = self.derivatives(c, p);
        // Schur complement removes K: H_θθ − H_θK H_KK⁻¹ H_Kθ.
        let hk = Vector2::new(h[(0, 1)], h[(0, 2)]);
        let hp = Matrix2::new(h[(1, 1)], h[(1, 2)], h[(2, 1)], h[(2, 2)]) - hk * hk.transpose() / h[(0, 0)];
        let gs = Vector2::new(c * g[0], g[1]);
        let hs = Matrix2::new(c * c * hp[(0, 0)] + c * g[0], c * hp[(0, 1)], c * hp[(1, 0)], hp[(1, 1)]);
        (gs, hs)
    }
}

/// Bounds outside which the fit is called degenerate: p in [P_MIN, P_MAX], c in
/// [C_MIN_REL, C_MAX_REL] × t_end.
const P_MIN: f64 = -2.0;
const P_MAX: f64 = 10.0;
const C_MIN_REL: f64 = 1e-9;
const C_MAX_REL: f64 = 1e3;

/// Levenberg–Marquardt ascent of the profile likelihood from (c0, p0); returns (c, p, ℓ_P).
fn maximise(data: &OmoriData, c0: f64, p0: f64, t_end: f64) -> Result<(f64, f64, f64), FitError> {
    let (mut sigma, mut p) = (c0.ln(), p0);
    let mut value = data.profile(c0, p0);
    let mut mu = 1e-3;
    let degenerate = |why: String| Err(FitError::Degenerate { what: "Omori–Utsu fit", why });
    if !value.is_finite() {
        return degenerate(format!("log-likelihood not finite at the start c = {c0}, p = {p0} (times not sorted?)"));
    }
    for _ in 0..300 {
        let c = sigma.exp();
        let (g, h) = data.profile_newton(c, p);
        let neg = -h;
        let mut stepped = false;
        for _ in 0..30 {
            let damped =
                neg + Matrix2::new(mu * neg[(0, 0)].abs().max(1e-12), 0.0, 0.0, mu * neg[(1, 1)].abs().max(1e-12));
            let Some(step) = damped.lu().solve(&g) else {
                mu *= 10.0;
                continue;
            };
            let step = step * (1.0f64).min(2.0 / step[0].abs().max(1e-300)).min(0.5 / step[1].abs().max(1e-300));
            let (ts, tp) = (sigma + step[0], p + step[1]);
            let trial = data.profile(ts.exp(), tp);
            if trial.is_finite() && trial >= value {
                let gain = trial - value;
                sigma = ts;
                p = tp;
                value = trial;
                mu = (mu / 3.0).max(1e-12);
                stepped = true;
                if gain <= 1e-12 * (1.0 + value.abs()) && g.dot(&step).abs() <= 1e-10 * (1.0 + value.abs()) {
                    return Ok((sigma.exp(), p, value));
                }
                break;
            }
            mu *= 4.0;
        }
        let c = sigma.exp();
        if c < C_MIN_REL * t_end {
            return degenerate(format!(
                "c runs to 0 (below {:e} of t_end): the rate is a pure power law on [t_start, t_end], \
                 c is not resolved; start the fit earlier",
                C_MIN_REL
            ));
        }
        if c > C_MAX_REL * t_end || !(P_MIN..=P_MAX).contains(&p) {
            return degenerate(format!("no decay resolved: the fit runs to c = {c:e}, p = {p} (flat rate?)"));
        }
        if !stepped {
            // No ascent possible: at the optimum to machine precision.
            return Ok((c, p, value));
        }
    }
    degenerate("no convergence in 300 iterations".into())
}

/// Fits `n(τ) = K/(τ + c)^p` per main shock to the stacked aftershocks in `[t_start, t_end]`
/// (time since main shock, `0 ≤ t_start < t_end`, time unit of the input) by maximum likelihood.
pub fn fit_omori(stack: &StackedAftershocks, t_start: f64, t_end: f64) -> Result<OmoriFit, FitError> {
    if !(t_start >= 0.0) || !t_start.is_finite() {
        return Err(FitError::InvalidParameter { what: "t_start", must: "finite and ≥ 0", value: t_start });
    }
    if !(t_end > t_start) || !t_end.is_finite() {
        return Err(FitError::InvalidParameter { what: "t_end", must: "finite and above t_start", value: t_end });
    }
    let from = stack.times.partition_point(|&t| t < t_start);
    let to = stack.times.partition_point(|&t| t <= t_end);
    let times = &stack.times[from..to.max(from)];
    if times.len() < MIN_AFTERSHOCKS {
        return Err(FitError::TooFew {
            what: "aftershocks in [t_start, t_end]",
            have: times.len(),
            need: MIN_AFTERSHOCKS,
        });
    }
    let mut ends: Vec<f64> = stack.windows.iter().map(|&w| w.min(t_end)).filter(|&e| e > t_start).collect();
    let main_shocks = ends.len();
    ends.sort_by(f64::total_cmp);
    let mut grouped: Vec<(f64, f64)> = Vec::new();
    for e in ends {
        match grouped.last_mut() {
            Some((last, m)) if *last == e => *m += 1.0,
            _ => grouped.push((e, 1.0)),
        }
    }
    let data = OmoriData { times, t_start, ends: grouped };
    // Several starts for c (quantiles of the event times), p = 1; keep the best optimum.
    let q = |f: f64| times[((times.len() - 1) as f64 * f) as usize];
    let floor = (C_MIN_REL * 10.0 * t_end).max(f64::MIN_POSITIVE);
    let mut best: Option<(f64, f64, f64)> = None;
    let mut last_err = None;
    for c0 in [q(0.01).max(floor), q(0.1).max(floor), (q(0.5) - t_start).max(q(0.1)).max(floor)] {
        match maximise(&data, c0, 1.0, t_end) {
            Ok(r) if best.is_none_or(|b| r.2 > b.2) => best = Some(r),
            Ok(_) => {}
            Err(e) => last_err = Some(e),
        }
    }
    let Some((c, p, profile)) = best else {
        return Err(last_err.expect("a start either succeeds or fails"));
    };
    let (k, h, _) = data.derivatives(c, p);
    let info = -h;
    let cov = info.try_inverse().filter(|m| (0..3).all(|i| m[(i, i)] > 0.0 && m[(i, i)].is_finite()));
    let Some(cov) = cov else {
        return Err(FitError::Degenerate {
            what: "Omori–Utsu fit",
            why: format!("observed information singular at K = {k}, c = {c}, p = {p}"),
        });
    };
    if ![k, c, p, profile].iter().all(|v| v.is_finite()) {
        return Err(FitError::Degenerate {
            what: "Omori–Utsu fit",
            why: format!("non-finite estimate K = {k}, c = {c}, p = {p}, ℓ = {profile}"),
        });
    }
    let mut covariance = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            covariance[i][j] = cov[(i, j)];
        }
    }
    Ok(OmoriFit {
        k,
        c,
        p,
        k_se: cov[(0, 0)].sqrt(),
        c_se: cov[(1, 1)].sqrt(),
        p_se: cov[(2, 2)].sqrt(),
        covariance,
        n: times.len(),
        main_shocks,
        t_start,
        t_end,
        log_likelihood: profile,
        aic: 6.0 - 2.0 * profile,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::rngs::ChaCha8Rng;
    use rand::{RngExt, SeedableRng};
    use rand_distr::{Distribution, Poisson};

    /// Main shocks every `spacing`, each followed by an Omori–Utsu sequence (K, c, p) on
    /// (0, spacing); the main shocks are in the event list too.
    fn omori_catalogue(seed: u64, mains: usize, spacing: f64, k: f64, c: f64, p: f64) -> (Vec<f64>, Vec<f64>) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let u = 1.0 - p;
        let (lo, hi) = (c.powf(u), (spacing + c).powf(u));
        let expected = k * (hi - lo) / u;
        let pois = Poisson::new(expected).unwrap();
        let mut main_times = Vec::new();
        let mut events = Vec::new();
        for i in 0..mains {
            let t0 = 100.0 + i as f64 * spacing;
            main_times.push(t0);
            events.push(t0);
            let n = pois.sample(&mut rng) as usize;
            for _ in 0..n {
                let r: f64 = rng.random();
                events.push(t0 + (lo + r * (hi - lo)).powf(1.0 / u) - c);
            }
        }
        (main_times, events)
    }

    #[test]
    fn stacking_by_hand() {
        // Main shocks at 10 and 20; window 15, cut at the next main shock; catalogue ends at 28.
        let events = [5.0, 10.0, 11.0, 12.5, 19.0, 20.0, 20.5, 27.0, 29.0, f64::NAN];
        let w = Window { max_time: 15.0, stop_at_next_main_shock: true, catalogue_end: 28.0 };
        let s = stack_aftershocks(&[20.0, 10.0], &events, w).unwrap();
        assert_eq!(s.windows, vec![10.0, 8.0]);
        assert_eq!(s.counts, vec![3, 2]);
        assert_eq!(s.times, vec![0.5, 1.0, 2.5, 7.0, 9.0]);
        // Without the cut the first window reaches 25 and takes in 20.0 and 20.5.
        let w = Window { stop_at_next_main_shock: false, ..w };
        let s = stack_aftershocks(&[10.0, 20.0], &events, w).unwrap();
        assert_eq!((s.windows.clone(), s.counts.clone()), (vec![15.0, 8.0], vec![5, 2]));
        let bad = Window { max_time: f64::INFINITY, stop_at_next_main_shock: false, catalogue_end: f64::INFINITY };
        assert!(matches!(stack_aftershocks(&[1.0], &events, bad), Err(FitError::InvalidParameter { .. })));
        assert!(matches!(stack_aftershocks(&[], &events, w), Err(FitError::TooFew { .. })));
    }

    #[test]
    fn rate_bins_by_hand() {
        // Two windows, 10 and 1: bin [0.1, 1) has exposure 2·0.9, bin [1, 10) has 9.
        let s =
            StackedAftershocks { times: vec![0.2, 0.5, 0.9, 2.0, 5.0], windows: vec![10.0, 1.0], counts: vec![4, 1] };
        let r = aftershock_rate(&s, 0.1, 10.0, 1).unwrap();
        assert_eq!(r.len(), 2);
        assert_eq!(r[0].count, 3);
        assert!((r[0].exposure - 1.8).abs() < 1e-12 && (r[0].rate - 3.0 / 1.8).abs() < 1e-12);
        assert!((r[1].exposure - 9.0).abs() < 1e-12 && (r[1].rate_error - 2f64.sqrt() / 9.0).abs() < 1e-12);
        assert!((r[0].centre - 0.1f64.sqrt()).abs() < 1e-12);
        // Bins beyond every window are left out.
        assert_eq!(aftershock_rate(&s, 0.1, 100.0, 1).unwrap().len(), 2);
        assert!(matches!(aftershock_rate(&s, 0.0, 1.0, 1), Err(FitError::InvalidParameter { .. })));
    }

    #[test]
    fn integrals_match_closed_forms_and_finite_differences() {
        for &(c, p, s, e) in
            &[(0.01, 1.1, 0.0, 1000.0), (0.5, 1.0, 0.1, 10.0), (0.01, 0.999_999, 0.0, 1e4), (2.0, 2.5, 1.0, 3.0)]
        {
            let i = integrals(c, p, s, e);
            let exact = if p == 1.0 {
                ((e + c) / (s + c)).ln()
            } else {
                ((e + c).powf(1.0 - p) - (s + c).powf(1.0 - p)) / (1.0 - p)
            };
            assert!((i.a / exact - 1.0).abs() < 1e-10, "A at c {c} p {p}: {} vs {exact}", i.a);
            let (hc, hp) = (1e-6 * c, 1e-6);
            let dc = (integrals(c + hc, p, s, e).a - integrals(c - hc, p, s, e).a) / (2.0 * hc);
            let dp = (integrals(c, p + hp, s, e).a - integrals(c, p - hp, s, e).a) / (2.0 * hp);
            let dpp = (integrals(c, p + hp, s, e).a_p - integrals(c, p - hp, s, e).a_p) / (2.0 * hp);
            let dcp = (integrals(c + hc, p, s, e).a_p - integrals(c - hc, p, s, e).a_p) / (2.0 * hc);
            let dcc = (integrals(c + hc, p, s, e).a_c - integrals(c - hc, p, s, e).a_c) / (2.0 * hc);
            for (name, got, want) in [
                ("A_c", i.a_c, dc),
                ("A_p", i.a_p, dp),
                ("A_pp", i.a_pp, dpp),
                ("A_cp", i.a_cp, dcp),
                ("A_cc", i.a_cc, dcc),
            ] {
                assert!((got - want).abs() < 1e-6 * (1.0 + want.abs()), "{name} at c {c} p {p}: {got} vs {want}");
            }
        }
    }

    /// The acceptance test: 8 main shocks, K = 40, c = 0.01, p = 1.1 on windows of 1000 (time
    /// units): about 3500 stacked events. Every parameter within 3 of its standard errors.
    #[test]
    fn recovers_omori_utsu_parameters() {
        let (k, c, p) = (40.0, 0.01, 1.1);
        for seed in [61, 62, 63] {
            let (mains, events) = omori_catalogue(seed, 8, 1000.0, k, c, p);
            let w = Window { max_time: 1000.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
            let s = stack_aftershocks(&mains, &events, w).unwrap();
            assert!(s.times.len() > 3000, "{}", s.times.len());
            let f = fit_omori(&s, 0.0, 1000.0).unwrap();
            assert_eq!(f.main_shocks, 8);
            assert!((f.p - p).abs() < 3.0 * f.p_se, "seed {seed}: p = {} ± {}", f.p, f.p_se);
            assert!((f.c - c).abs() < 3.0 * f.c_se, "seed {seed}: c = {} ± {}", f.c, f.c_se);
            assert!((f.k - k).abs() < 3.0 * f.k_se, "seed {seed}: K = {} ± {}", f.k, f.k_se);
            assert!(f.p_se < 0.03 && f.c_se < 0.005, "errors p {} c {}", f.p_se, f.c_se);
            // The fit accounts for every event: expected count over the windows is N.
            let expected = 8.0 * f.expected_count(0.0, 1000.0);
            assert!((expected / f.n as f64 - 1.0).abs() < 1e-9);
            // Binned rates agree with the fitted law within Poisson error (4σ, ~18 bins).
            for b in aftershock_rate(&s, 1e-3, 1000.0, 3).unwrap() {
                let model = f.expected_count(b.start, b.end) * 8.0 / b.exposure;
                assert!((b.rate - model).abs() < 4.0 * model.sqrt() / b.exposure.sqrt() + 1e-12, "{b:?} vs {model}");
            }
        }
    }

    #[test]
    fn late_start_and_units() {
        // Fitting from t_start = 0.05 (beyond c) still recovers p. In a unit 3600 times longer,
        // p is unchanged, c is divided by 3600 and K multiplied by 3600^(1 − p).
        let (mains, events) = omori_catalogue(64, 10, 1000.0, 40.0, 0.01, 1.1);
        let w = Window { max_time: 1000.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
        let s = stack_aftershocks(&mains, &events, w).unwrap();
        let f = fit_omori(&s, 0.05, 1000.0).unwrap();
        assert!((f.p - 1.1).abs() < 3.0 * f.p_se, "p = {} ± {}", f.p, f.p_se);
        let whole = fit_omori(&s, 0.0, 1000.0).unwrap();
        let scaled = StackedAftershocks {
            times: s.times.iter().map(|t| t / 3600.0).collect(),
            windows: s.windows.iter().map(|t| t / 3600.0).collect(),
            counts: s.counts.clone(),
        };
        let g = fit_omori(&scaled, 0.0, 1000.0 / 3600.0).unwrap();
        assert!((g.p - whole.p).abs() < 1e-6, "{} vs {}", g.p, whole.p);
        assert!((g.c * 3600.0 / whole.c - 1.0).abs() < 1e-5);
        assert!((g.k / (whole.k * 3600f64.powf(1.0 - whole.p)) - 1.0).abs() < 1e-5);
    }

    #[test]
    fn too_few_or_no_decay_is_refused() {
        let empty =
            stack_aftershocks(&[1.0], &[], Window { max_time: 1.0, stop_at_next_main_shock: true, catalogue_end: 2.0 })
                .unwrap();
        assert!(matches!(fit_omori(&empty, 0.0, 1.0), Err(FitError::TooFew { have: 0, .. })));
        let (mains, events) = omori_catalogue(65, 1, 1000.0, 3.0, 0.01, 1.1);
        let w = Window { max_time: 1000.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
        let s = stack_aftershocks(&mains, &events, w).unwrap();
        assert!(s.times.len() < MIN_AFTERSHOCKS);
        assert_eq!(
            fit_omori(&s, 0.0, 1000.0),
            Err(FitError::TooFew {
                what: "aftershocks in [t_start, t_end]",
                have: s.times.len(),
                need: MIN_AFTERSHOCKS
            })
        );
        assert!(matches!(fit_omori(&s, 1.0, 0.5), Err(FitError::InvalidParameter { .. })));
        // A flat (Poisson) rate has no Omori decay: refused as degenerate, with the reason.
        let mut rng = ChaCha8Rng::seed_from_u64(66);
        let flat: Vec<f64> = (0..2000).map(|_| 1000.0 * rng.random::<f64>()).collect();
        let s = stack_aftershocks(&[0.0], &flat, Window { max_time: 1000.0, ..w }).unwrap();
        match fit_omori(&s, 0.0, 1000.0) {
            Err(FitError::Degenerate { why, .. }) => assert!(why.contains("no decay"), "{why}"),
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn standard_errors_cover_the_truth_over_seeds() {
        // 200 catalogues of 2 main shocks (≈ 870 events): |θ̂ − θ| < 1.96·se in about 95% of
        // them; binomial sd ≈ 1.5%, and the errors are asymptotic: accept 87%–99.5%.
        let (k, c, p) = (40.0, 0.01, 1.1);
        let w = Window { max_time: 1000.0, stop_at_next_main_shock: true, catalogue_end: f64::INFINITY };
        let mut hits = [0usize; 3];
        for seed in 0..200 {
            let (mains, events) = omori_catalogue(5000 + seed, 2, 1000.0, k, c, p);
            let f = fit_omori(&stack_aftershocks(&mains, &events, w).unwrap(), 0.0, 1000.0).unwrap();
            hits[0] += usize::from((f.k - k).abs() < 1.96 * f.k_se);
            hits[1] += usize::from((f.c - c).abs() < 1.96 * f.c_se);
            hits[2] += usize::from((f.p - p).abs() < 1.96 * f.p_se);
        }
        for (name, h) in ["K", "c", "p"].iter().zip(hits) {
            assert!((174..=199).contains(&h), "{name} coverage {h}/200");
        }
    }
}
