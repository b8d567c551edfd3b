//! Stick-slip events and sub-events from the interface signals (docs/model.md §7).
//!
//! The detector finds bursts of slip on the slip rate averaged over a centred window of
//! `smoothing_s` in time (vibrations of lifted nodes and of the stress field are much faster than
//! a slip burst), `V̄ = [δ(t + w/2) − δ(t − w/2)]/w` from the mean slip δ of the contact nodes.
//! The signals may be sampled unevenly: the solver's event trace holds every step around each
//! burst and few samples between, so events do not depend on the recording interval.
//!
//! A **sub-event** is found when `V̄` rises above `v_on_m_s` and lasts until `V̄` has stayed below
//! `v_off_m_s` for `quiet_s` (hysteresis: `v_off < v_on`). Its **start** and **end** come from the
//! unsmoothed slip rate `V`: the first sample from half a window before the detection on whose
//! `V` reaches `v_on`, and the sample after the last one before the quiet spell whose `V` does.
//! Sub-events whose gap is shorter than `merge_gap_s` form one **event**. The **stress drop** is
//! read on `τ̄`, τ averaged over the same window (raw τ rings by several kPa in a block whose nodes
//! lift): the highest `τ̄` in the half window up to the start minus the lowest `τ̄` from the start
//! to half a window past the end. Events with a drop below `min_drop_pa` are dropped from the
//! catalogue (slip bursts without a stress drop). Events whose drop is at least `main_fraction` of
//! the largest drop of the run are **main shocks**, labelled S1, S2, … in time order; every other
//! event is a foreshock of the next main shock or an aftershock of the previous one, whichever is
//! nearer in time.

/// Detector thresholds (the pipeline's `[events]` section).
#[derive(Clone, Debug, PartialEq)]
pub struct EventParams {
    /// Smoothing window of `V` and `τ` in seconds. Default 1e-3.
    pub smoothing_s: f64,
    /// A sub-event starts when the smoothed slip rate exceeds this (m/s). Default 2e-4.
    pub v_on_m_s: f64,
    /// … and ends when it stays below this (m/s) for `quiet_s`. Default 5e-5.
    pub v_off_m_s: f64,
    /// Quiet time that ends a sub-event (s). Default 0.5e-3.
    pub quiet_s: f64,
    /// Sub-events closer than this form one event (s). Default 3e-3.
    pub merge_gap_s: f64,
    /// Events with a smaller stress drop are not catalogued (Pa). Default 500.
    pub min_drop_pa: f64,
    /// Main shocks have a drop of at least this fraction of the largest. Default 0.5.
    pub main_fraction: f64,
    /// A fault node has ruptured when its slip rate first reaches this (m/s): its rupture time
    /// ([`crate::front`]). Default 1e-3, the convention of the SCEC dynamic-rupture benchmarks.
    pub rupture_rate_m_s: f64,
}

impl Default for EventParams {
    fn default() -> Self {
        EventParams {
            smoothing_s: 1e-3,
            v_on_m_s: 2e-4,
            v_off_m_s: 5e-5,
            quiet_s: 0.5e-3,
            merge_gap_s: 3e-3,
            min_drop_pa: 500.0,
            main_fraction: 0.5,
            rupture_rate_m_s: 1e-3,
        }
    }
}

/// What an event is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EventKind {
    /// Main shock `S<k>` (k from 1).
    Main(u32),
    /// Foreshock of `S<k>`.
    Foreshock(u32),
    /// Aftershock of `S<k>`.
    Aftershock(u32),
    /// No main shock in the run.
    Minor,
}

impl EventKind {
    /// `"main"`, `"foreshock"`, `"aftershock"`, `"minor"`.
    pub fn name(self) -> &'static str {
        match self {
            EventKind::Main(_) => "main",
            EventKind::Foreshock(_) => "foreshock",
            EventKind::Aftershock(_) => "aftershock",
            EventKind::Minor => "minor",
        }
    }

    /// Label of the main shock it belongs to (`S2` for the main shock S2 and its fore- and
    /// aftershocks), empty for a minor event.
    pub fn label(self) -> String {
        match self {
            EventKind::Main(k) | EventKind::Foreshock(k) | EventKind::Aftershock(k) => format!("S{k}"),
            EventKind::Minor => String::new(),
        }
    }

    /// The main shock it belongs to (1 for S1), if any.
    pub fn rank(self) -> Option<u32> {
        match self {
            EventKind::Main(k) | EventKind::Foreshock(k) | EventKind::Aftershock(k) => Some(k),
            EventKind::Minor => None,
        }
    }

    /// Whether it is a main shock.
    pub fn is_main(self) -> bool {
        matches!(self, EventKind::Main(_))
    }

    /// The kind written as [`EventKind::name`] `name` with [`EventKind::label`] `label`.
    pub fn parse(name: &str, label: &str) -> Option<EventKind> {
        let rank = || label.strip_prefix('S')?.parse().ok();
        match name {
            "main" => Some(EventKind::Main(rank()?)),
            "foreshock" => Some(EventKind::Foreshock(rank()?)),
            "aftershock" => Some(EventKind::Aftershock(rank()?)),
            "minor" if label.is_empty() => Some(EventKind::Minor),
            _ => None,
        }
    }
}

/// Measures of one burst of slip (an event or a sub-event).
#[derive(Clone, Debug, PartialEq)]
pub struct Burst {
    /// Start (s, shear-stage time).
    pub start_s: f64,
    /// End (s).
    pub end_s: f64,
    /// The highest `τ̄` in the half window up to the start minus the lowest from the start to
    /// half a window past the end (Pa).
    pub stress_drop_pa: f64,
    /// Time of that minimum (s): `drop_end_s − start_s` is the time the stress takes to fall.
    pub drop_end_s: f64,
    /// `δ̄(end) − δ̄(start)` (m).
    pub slip_m: f64,
    /// Peak of the smoothed slip rate `V̄` (m/s).
    pub peak_slip_rate_m_s: f64,
    /// Peak number of sliding contact nodes (raw samples).
    pub peak_slipping_nodes: u32,
    /// That count's share of the contact area (m²).
    pub rupture_area_m2: f64,
    /// Peak |acceleration| (m/s², raw samples) of each of [`Signals::accelerations`], in order.
    pub peak_acceleration: Vec<f64>,
    /// First and one-past-last sample index.
    pub samples: (usize, usize),
}

impl Burst {
    /// `end − start` (s).
    pub fn duration_s(&self) -> f64 {
        self.end_s - self.start_s
    }

    /// Time the stress takes to fall, `drop_end − start` (s).
    pub fn drop_time_s(&self) -> f64 {
        self.drop_end_s - self.start_s
    }
}

/// One stick-slip event.
#[derive(Clone, Debug, PartialEq)]
pub struct Event {
    /// Main shock, fore- or aftershock.
    pub kind: EventKind,
    /// Its measures.
    pub burst: Burst,
    /// Sub-events (their indices in [`Catalogue::sub_events`]).
    pub sub_events: std::ops::Range<usize>,
    /// For a main shock, time since the start of the previous main shock (s).
    pub recurrence_s: Option<f64>,
}

/// All events of one run.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Catalogue {
    /// Events in time order.
    pub events: Vec<Event>,
    /// Sub-events in time order.
    pub sub_events: Vec<Burst>,
    /// A slip episode that never stopped and is not an earthquake (see [`Sliding`]), if the run
    /// ended in one: it is not among the events.
    pub sliding: Option<Sliding>,
    /// Slip episodes left out because their stress drop was no larger than the ringing of τ̄
    /// before them (twice its RMS about a straight line over the stuck stretch).
    pub within_ringing: usize,
}

/// Stable sliding: a slip episode still going when the run ends that has lasted longer than the
/// loading takes to restore its stress drop and longer than every episode that ended — the
/// interface slides along with its loading instead of slipping in a burst and locking again — or
/// more than half the run. It is not
/// catalogued (no earthquake, no magnitude): the run is read as sliding from `start_s` on.
#[derive(Clone, Debug, PartialEq)]
pub struct Sliding {
    /// Its measures (start, end = the end of the run, the drop of τ̄ at its onset, slip, …).
    pub burst: Burst,
    /// The rate τ̄ rose at while the base was stuck before it, its fastest stretch (Pa/s);
    /// `None` when no stuck stretch was long enough to tell.
    pub loading_rate_pa_s: Option<f64>,
}

impl Sliding {
    /// The time the loading takes to restore the episode's stress drop (s), if the loading rate
    /// is known.
    pub fn restore_s(&self) -> Option<f64> {
        self.loading_rate_pa_s.map(|r| self.burst.stress_drop_pa.max(0.0) / r)
    }
}

impl Catalogue {
    /// Main shocks in order (S1, S2, …).
    pub fn main_shocks(&self) -> impl Iterator<Item = &Event> {
        self.events.iter().filter(|e| matches!(e.kind, EventKind::Main(_)))
    }
}

/// How the scene loads the interface: what tells steady sliding from a rupture when a slip
/// episode is still going at the end of the run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loading {
    /// A driver or a loading plate moves: the interface can slide along with it for good.
    Driven,
    /// Fixed tractions (a fault loaded by its initial stress, nothing moving): a slip that has
    /// not stopped is a rupture the end of the run cut short, never sliding.
    Fixed,
}

/// The interface signals the detector reads, all sampled at the same instants.
#[derive(Clone, Copy, Debug)]
pub struct Signals<'a> {
    /// Sample times (s).
    pub time_s: &'a [f64],
    /// Shear stress τ (Pa).
    pub shear_stress_pa: &'a [f64],
    /// Mean slip δ of the contact nodes (m).
    pub mean_slip_m: &'a [f64],
    /// Mean slip rate of the contact nodes (m/s).
    pub mean_slip_rate_m_s: &'a [f64],
    /// Number of sliding contact nodes, if recorded.
    pub slipping_nodes: Option<&'a [f64]>,
    /// Accelerations (m/s²) whose peak |a| every burst reports, e.g. at control nodes.
    pub accelerations: &'a [&'a [f64]],
}

/// Centred moving average over `w` samples (shrinking at the ends): for uniformly sampled
/// series such as figures draw.
pub fn moving_average(x: &[f64], w: usize) -> Vec<f64> {
    let n = x.len();
    if w <= 1 || n == 0 {
        return x.to_vec();
    }
    let mut prefix = Vec::with_capacity(n + 1);
    prefix.push(0.0);
    for v in x {
        prefix.push(prefix.last().unwrap() + v);
    }
    let half = w / 2;
    (0..n)
        .map(|i| {
            let lo = i.saturating_sub(half);
            let hi = (i + w - half).min(n);
            (prefix[hi] - prefix[lo]) / (hi - lo) as f64
        })
        .collect()
}

/// A piecewise-linear signal through samples `(t, x)` (times increasing, not necessarily
/// evenly spaced), with its running integral.
struct Piecewise<'a> {
    t: &'a [f64],
    x: &'a [f64],
    integral: Vec<f64>,
}

impl<'a> Piecewise<'a> {
    fn new(t: &'a [f64], x: &'a [f64]) -> Self {
        let mut integral = Vec::with_capacity(t.len());
        integral.push(0.0);
        for k in 1..t.len() {
            integral.push(integral[k - 1] + 0.5 * (x[k] + x[k - 1]) * (t[k] - t[k - 1]));
        }
        Piecewise { t, x, integral }
    }

    /// The segment `k` with `t[k] ≤ at ≤ t[k + 1]`, starting the search from `hint`.
    fn segment(&self, at: f64, hint: &mut usize) -> usize {
        let last = self.t.len() - 2;
        let mut k = (*hint).min(last);
        while k > 0 && self.t[k] > at {
            k -= 1;
        }
        while k < last && self.t[k + 1] < at {
            k += 1;
        }
        *hint = k;
        k
    }

    /// The value at `at` in segment `k` (linear between its samples).
    fn value_in(&self, k: usize, at: f64) -> f64 {
        let (t0, t1) = (self.t[k], self.t[k + 1]);
        let f = if t1 > t0 { ((at - t0) / (t1 - t0)).clamp(0.0, 1.0) } else { 0.0 };
        self.x[k] + f * (self.x[k + 1] - self.x[k])
    }

    /// The value at `at` (linear between samples).
    fn value(&self, at: f64, hint: &mut usize) -> f64 {
        let k = self.segment(at, hint);
        self.value_in(k, at)
    }

    /// `∫ x` from the first sample to `at`.
    fn integral_to(&self, at: f64, hint: &mut usize) -> f64 {
        let k = self.segment(at, hint);
        self.integral[k] + 0.5 * (self.x[k] + self.value_in(k, at)) * (at - self.t[k]).max(0.0)
    }

    /// The window `[t − w/2, t + w/2]` of every sample, clipped to the record.
    fn windows(&self, w: f64) -> impl Iterator<Item = (f64, f64)> + '_ {
        let (first, last) = (self.t[0], self.t[self.t.len() - 1]);
        self.t.iter().map(move |&c| ((c - 0.5 * w).max(first), (c + 0.5 * w).min(last)))
    }

    /// The centred time average of the signal over `w` at every sample.
    fn mean(&self, w: f64) -> Vec<f64> {
        let (mut h0, mut h1) = (0, 0);
        self.windows(w)
            .zip(self.x)
            .map(
                |((lo, hi), &x)| {
                    if hi > lo {
                        (self.integral_to(hi, &mut h1) - self.integral_to(lo, &mut h0)) / (hi - lo)
                    } else {
                        x
                    }
                },
            )
            .collect()
    }

    /// The centred time derivative over `w` at every sample, `[x(t + w/2) − x(t − w/2)]/w`.
    fn rate(&self, w: f64) -> Vec<f64> {
        let (mut h0, mut h1) = (0, 0);
        self.windows(w)
            .map(|(lo, hi)| if hi > lo { (self.value(hi, &mut h1) - self.value(lo, &mut h0)) / (hi - lo) } else { 0.0 })
            .collect()
    }
}

/// Detects the events of one run (docs/model.md §7). The signals may be sampled unevenly (the
/// solver's event trace is: every step around each burst of slip, sparsely between); the
/// smoothing is over time, not samples. `contact_nodes` and `contact_area_m2` convert the
/// slipping count into a rupture area; `loading` says whether a slip that never stops can be
/// sliding ([`Sliding`]).
pub fn detect(
    signals: &Signals<'_>,
    contact_nodes: usize,
    contact_area_m2: f64,
    loading: Loading,
    params: &EventParams,
) -> Catalogue {
    let t = signals.time_s;
    let n = t.len();
    let (tau, slip, rate) = (signals.shear_stress_pa, signals.mean_slip_m, signals.mean_slip_rate_m_s);
    let slipping = signals.slipping_nodes;
    if n < 3 {
        return Catalogue::default();
    }
    let w = params.smoothing_s;
    let half = 0.5 * w;
    // Detection: the slip rate averaged over w, from the slip itself.
    let v = Piecewise::new(t, slip).rate(w);
    let tau_s = Piecewise::new(t, tau).mean(w);
    let accel = signals.accelerations;
    let at = |time: f64| t.partition_point(|&x| x < time).min(n - 1);
    // Measures of the burst the detector found between samples `on` and `quiet` (the first of
    // its quiet spell), from the unsmoothed slip rate: it starts at the first sample from
    // `on − w/2` on whose raw rate reaches V_on, and ends at the sample after the last one
    // before `quiet` whose raw rate does.
    let measure = |on: usize, quiet: usize| -> Burst {
        let above = |k: &usize| rate[*k] >= params.v_on_m_s;
        // A burst that starts on the record's last sample is measured over its last two.
        let a = (at(t[on] - half)..quiet.max(on + 1)).find(above).unwrap_or(on).min(n - 2);
        let b = (a..quiet.max(a + 1)).rev().find(above).map_or(quiet, |k| k + 1).min(n - 1).max(a + 1);
        // Stress before: the highest τ̄ in the half window up to the start; after: the lowest τ̄
        // from the start to half a window past the end (where τ̄ has taken in the whole fall).
        let before = tau_s[at(t[a] - half)..=a].iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let after_end = (at(t[b] + half) + 1).min(n);
        let (imin, min_tau) = tau_s[a..after_end]
            .iter()
            .copied()
            .enumerate()
            .fold((0, f64::INFINITY), |m, (i, v)| if v < m.1 { (i, v) } else { m });
        let peak_nodes = slipping.map_or(0.0, |s| s[a..=b].iter().copied().fold(0.0, f64::max));
        Burst {
            start_s: t[a],
            end_s: t[b],
            stress_drop_pa: before - min_tau,
            drop_end_s: t[a + imin],
            slip_m: slip[b] - slip[a],
            peak_slip_rate_m_s: v[a..b].iter().copied().fold(f64::NEG_INFINITY, f64::max),
            peak_slipping_nodes: peak_nodes as u32,
            rupture_area_m2: peak_nodes / contact_nodes as f64 * contact_area_m2,
            peak_acceleration: accel.iter().map(|x| x[a..b].iter().fold(0.0f64, |m, v| m.max(v.abs()))).collect(),
            samples: (a, b),
        }
    };
    // Sub-events: hysteresis on the smoothed slip rate; each ends at the first sample of a
    // spell of at least `quiet_s` below V_off (or at the end of the record).
    let mut spans: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < n {
        if v[i] > params.v_on_m_s {
            let start = i;
            let mut spell: Option<usize> = None;
            let mut end = n;
            for j in i + 1..n {
                if v[j] < params.v_off_m_s {
                    // The spell lasts to the next sample: its length is that of its samples.
                    let s0 = *spell.get_or_insert(j);
                    if t[j] - t[s0] + (t[j] - t[j - 1]) >= params.quiet_s * (1.0 - 1e-9) {
                        end = s0;
                        break;
                    }
                } else {
                    spell = None;
                }
            }
            spans.push((start, end.max(start + 1)));
            i = end.max(start + 1);
        } else {
            i += 1;
        }
    }
    // Events: merge sub-events separated by less than the merge gap.
    let gap = params.merge_gap_s;
    let mut groups: Vec<(usize, usize)> = Vec::new(); // ranges of sub-event indices
    for (k, &(a, _)) in spans.iter().enumerate() {
        match groups.last_mut() {
            Some(g) if t[a] - t[spans[g.1 - 1].1 - 1] < gap => g.1 = k + 1,
            _ => groups.push((k, k + 1)),
        }
    }
    let mut catalogue = Catalogue::default();
    // The loading rate of τ̄ while the base is stuck: over the stretch before the first episode
    // and each gap between episodes at least three windows long (a window past the end of the
    // one before, half a window before the next), the fastest.
    let loading_rate_pa_s = {
        let mut stuck: Vec<(f64, f64)> = Vec::new();
        let mut from = t[0];
        for &(a, b) in &spans {
            stuck.push((from, t[a] - half));
            from = t[b.min(n - 1)] + w;
        }
        let mut hint = 0;
        let tau_bar = Piecewise::new(t, &tau_s);
        stuck
            .into_iter()
            .filter(|&(lo, hi)| hi - lo >= 2.0 * w)
            .map(|(lo, hi)| (tau_bar.value(hi, &mut hint) - tau_bar.value(lo, &mut hint)) / (hi - lo))
            .filter(|r| *r > 0.0 && r.is_finite())
            .fold(None, |m: Option<f64>, r| Some(m.map_or(r, |m| m.max(r))))
    };
    let record_s = t[n - 1] - t[0];
    // The ringing of τ̄ while the base is stuck before an episode: twice the RMS of τ̄ about its
    // least-squares line over the stretch from a window past the previous episode's end to half
    // a window before this one's start (at least three windows long; else not judged).
    let ringing = |lo: f64, hi: f64| -> Option<f64> {
        if hi - lo < 3.0 * w {
            return None;
        }
        let idx: Vec<usize> = (at(lo)..n).take_while(|&i| t[i] <= hi).collect();
        if idx.len() < 8 {
            return None;
        }
        let m = idx.len() as f64;
        let (tm, ym) = idx.iter().fold((0.0, 0.0), |(a, b), &i| (a + t[i] / m, b + tau_s[i] / m));
        let (sxx, sxy) =
            idx.iter().fold((0.0, 0.0), |(a, b), &i| (a + (t[i] - tm).powi(2), b + (t[i] - tm) * (tau_s[i] - ym)));
        let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
        let ss: f64 = idx.iter().map(|&i| (tau_s[i] - ym - slope * (t[i] - tm)).powi(2)).sum();
        Some(2.0 * (ss / m).sqrt())
    };
    // The longest episode that ended before the run did: an unfinished one shorter than that
    // may be a burst the end of the run cut short.
    let longest_finished = groups
        .iter()
        .map(|&(k0, k1)| (spans[k0].0, spans[k1 - 1].1))
        .filter(|&(_, b)| b < n)
        .map(|(a, b)| t[b] - t[a])
        .fold(0.0, f64::max);
    let mut previous_end = t[0] - w;
    for (k0, k1) in groups {
        let (a, b) = (spans[k0].0, spans[k1 - 1].1);
        let burst = measure(a, b);
        let ring = ringing(previous_end + w, burst.start_s - half);
        previous_end = burst.end_s;
        // An episode still slipping when the run ends under a moving driver, for longer than
        // the loading needs to restore its drop and than any episode that ended (or for more
        // than half the run, as when the base slides from the start and no stuck stretch gives
        // a loading rate): stable sliding, not an earthquake. Under fixed tractions (a fault's
        // one rupture, which may last most of a short run) it is an event.
        let burst = if b >= n && loading == Loading::Driven {
            let sliding = Sliding { burst, loading_rate_pa_s };
            let lasted = sliding.burst.end_s - sliding.burst.start_s;
            let outlasted = sliding.restore_s().is_some_and(|r| lasted > r) && lasted > longest_finished;
            if outlasted || lasted > 0.5 * record_s {
                catalogue.sliding = Some(sliding);
                continue;
            }
            sliding.burst
        } else {
            burst
        };
        if burst.stress_drop_pa < params.min_drop_pa {
            continue;
        }
        // A drop no larger than the ringing of the stuck interface before it is not an event.
        if ring.is_some_and(|r| burst.stress_drop_pa <= r) {
            catalogue.within_ringing += 1;
            continue;
        }
        let first = catalogue.sub_events.len();
        catalogue.sub_events.extend(spans[k0..k1].iter().map(|&(a, b)| measure(a, b)));
        catalogue.events.push(Event {
            kind: EventKind::Minor,
            burst,
            sub_events: first..catalogue.sub_events.len(),
            recurrence_s: None,
        });
    }
    classify(&mut catalogue.events, params.main_fraction);
    catalogue
}

/// Labels main shocks, fore- and aftershocks, and recurrences.
fn classify(events: &mut [Event], main_fraction: f64) {
    let largest = events.iter().map(|e| e.burst.stress_drop_pa).fold(0.0, f64::max);
    if largest <= 0.0 {
        return;
    }
    let mains: Vec<usize> =
        (0..events.len()).filter(|&i| events[i].burst.stress_drop_pa >= main_fraction * largest).collect();
    let mut previous_start: Option<f64> = None;
    for (k, &i) in mains.iter().enumerate() {
        events[i].kind = EventKind::Main(k as u32 + 1);
        events[i].recurrence_s = previous_start.map(|s| events[i].burst.start_s - s);
        previous_start = Some(events[i].burst.start_s);
    }
    for i in 0..events.len() {
        if matches!(events[i].kind, EventKind::Main(_)) {
            continue;
        }
        let before = mains.iter().rposition(|&m| m < i);
        let after = mains.iter().position(|&m| m > i);
        let e = &events[i].burst;
        events[i].kind = match (before, after) {
            (Some(b), Some(a)) => {
                let gap_before = e.start_s - events[mains[b]].burst.end_s;
                let gap_after = events[mains[a]].burst.start_s - e.end_s;
                if gap_before <= gap_after {
                    EventKind::Aftershock(b as u32 + 1)
                } else {
                    EventKind::Foreshock(a as u32 + 1)
                }
            }
            (Some(b), None) => EventKind::Aftershock(b as u32 + 1),
            (None, Some(a)) => EventKind::Foreshock(a as u32 + 1),
            (None, None) => EventKind::Minor,
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 1e-5;

    /// A synthetic run: τ rises at 300 Pa/ms and falls linearly through each burst of slip
    /// rate; `bursts` are (first sample, one past last, slip rate, stress drop), at least two
    /// samples long.
    fn synthetic(n: usize, bursts: &[(usize, usize, f64, f64)]) -> [Vec<f64>; 5] {
        let mut v = vec![0.0; n];
        let mut tau = vec![0.0; n];
        let mut delta = vec![0.0; n];
        let mut level = 0.0;
        for i in 0..n {
            match bursts.iter().find(|b| i >= b.0 && i < b.1) {
                // Inside a burst τ falls linearly from its level at the first sample to the
                // level minus the drop at the last one.
                Some(&(a, b, rate, drop)) => {
                    v[i] = rate;
                    if i > a {
                        level -= drop / (b - a - 1) as f64;
                    }
                }
                // Flat for 100 samples after a burst (so sub-events of one event are not
                // separated by reloading), rising otherwise.
                None if !bursts.iter().any(|b| i >= b.1 && i < b.1 + 100) => level += 300.0e3 * DT,
                None => {}
            }
            tau[i] = level;
            delta[i] = if i == 0 { 0.0 } else { delta[i - 1] + v[i] * DT };
        }
        [(0..n).map(|i| i as f64 * DT).collect(), tau, delta, v, vec![1.0; n]]
    }

    fn signals(s: &[Vec<f64>; 5]) -> Signals<'_> {
        Signals {
            time_s: &s[0],
            shear_stress_pa: &s[1],
            mean_slip_m: &s[2],
            mean_slip_rate_m_s: &s[3],
            slipping_nodes: Some(&s[4]),
            accelerations: &[],
        }
    }

    #[test]
    fn synthetic_events_and_sub_events_are_found_exactly() {
        let bursts = [
            // S1: two sub-events 0.5 ms apart, 8 kPa in all.
            (2000, 2100, 1e-3, 4000.0),
            (2150, 2250, 1e-3, 4000.0),
            // Foreshock of S2 (1 kPa).
            (6000, 6050, 5e-4, 1000.0),
            // S2: one sub-event with a dip of the slip rate shorter than the quiet time.
            (7000, 7080, 1e-3, 3500.0),
            (7080, 7100, 1e-6, 0.0),
            (7100, 7200, 1e-3, 3500.0),
            // Aftershock of S2, 4 ms after it.
            (7600, 7650, 5e-4, 1000.0),
            // S3: three sub-events.
            (12000, 12050, 1e-3, 2000.0),
            (12100, 12150, 1e-3, 2000.0),
            (12200, 12300, 1e-3, 2000.0),
            // Slip without a stress drop: not an event.
            (15000, 15050, 1e-3, 0.0),
        ];
        let rec = synthetic(20000, &bursts);
        // One-sample smoothing averages each sample with half of its neighbours': the 50-sample
        // gaps between sub-events read as 49 quiet samples, so the quiet time is 0.4 ms here.
        let params = EventParams { smoothing_s: DT, quiet_s: 0.4e-3, ..EventParams::default() };
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &params);
        let kinds: Vec<EventKind> = cat.events.iter().map(|e| e.kind).collect();
        assert_eq!(
            kinds,
            vec![
                EventKind::Main(1),
                EventKind::Foreshock(2),
                EventKind::Main(2),
                EventKind::Aftershock(2),
                EventKind::Main(3)
            ]
        );
        let subs: Vec<usize> = cat.events.iter().map(|e| e.sub_events.len()).collect();
        assert_eq!(subs, vec![2, 1, 1, 1, 3]);
        assert_eq!(cat.sub_events.len(), 8);
        // Starts at the first sample of each burst, ends at the first sample after it.
        let expected = [(2000, 2250), (6000, 6050), (7000, 7200), (7600, 7650), (12000, 12300)];
        for (e, (a, b)) in cat.events.iter().zip(expected) {
            assert!((e.burst.start_s - a as f64 * DT).abs() <= DT * 1e-6, "start {} vs {a}", e.burst.start_s / DT);
            assert!((e.burst.end_s - b as f64 * DT).abs() <= DT * 1e-6, "end {} vs {b}", e.burst.end_s / DT);
        }
        let sub_starts: Vec<usize> = cat.sub_events.iter().map(|s| (s.start_s / DT).round() as usize).collect();
        assert_eq!(sub_starts, vec![2000, 2150, 6000, 7000, 7600, 12000, 12100, 12200]);
        let drops: Vec<f64> = cat.events.iter().map(|e| e.burst.stress_drop_pa).collect();
        for (d, want) in drops.iter().zip([8000.0, 1000.0, 7000.0, 1000.0, 6000.0]) {
            // One-sample smoothing shaves up to a quarter of a sample's fall off the top (S1 falls
            // 40 Pa a sample).
            assert!((d - want).abs() < 10.0, "drop {d} vs {want}");
        }
        let s2 = &cat.events[2];
        assert!((s2.recurrence_s.unwrap() - 0.05).abs() < 1e-12);
        // 180 samples at 1 mm/s and 20 at 1 µm/s, within one sample.
        let slip = (180.0 * 1e-3 + 20.0 * 1e-6) * DT;
        assert!((s2.burst.slip_m - slip).abs() <= 1e-3 * DT * 1.0001, "slip {} vs {slip}", s2.burst.slip_m);
        assert!(cat.events[0].recurrence_s.is_none() && cat.events[1].recurrence_s.is_none());
    }

    /// One burst of `len` samples at 1 mm/s from sample 5000 with a drop of `drop` Pa, under the
    /// default 1-ms smoothing (w = 100 samples at DT = 10 µs).
    fn one_burst(bursts: &[(usize, usize, f64, f64)]) -> Catalogue {
        let rec = synthetic(12000, bursts);
        detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default())
    }

    /// A clean burst under the default 1-ms smoothing: start and end come from the raw slip
    /// rate, so they are the burst's own (the detector's smoothed rate crosses V_on 0.3w early
    /// and falls below V_off 0.45w late, which is where they were read before); the slip is all
    /// of the burst's; the drop is read on τ̄, in closed form below.
    #[test]
    fn a_clean_ramp_and_drop_is_measured_exactly_where_it_starts_and_ends() {
        let (a, b) = (5000usize, 5200usize);
        let cat = one_burst(&[(a, b, 1e-3, 6000.0)]);
        assert_eq!(cat.events.len(), 1);
        let e = &cat.events[0].burst;
        assert!((e.start_s - a as f64 * DT).abs() < 1e-9 * DT, "start {}", e.start_s / DT);
        assert!((e.end_s - b as f64 * DT).abs() < 1e-9 * DT, "end {}", e.end_s / DT);
        assert!((e.duration_s() - (b - a) as f64 * DT).abs() < 1e-9 * DT);
        // Slip: the burst's 200 samples at 1 mm/s, within one sample (the synthetic slip takes a
        // sample's rate over the interval before it).
        assert!((e.slip_m - 200.0 * 1e-3 * DT).abs() <= 1.0001e-3 * DT, "slip {}", e.slip_m);
        // Drop: the lowest τ̄ after the end lies in the flat stretch, the bottom exactly; the
        // highest τ̄ up to the start averages the rising ramp (3 Pa a sample) with the first u of
        // the 100 samples of its window past the onset (30.15 Pa a sample): its shortfall
        // [1.5·(100 − u)² + 15.08·u²]/100 is least, 136 Pa, at u = 9. So 6 kPa reads 5864 Pa.
        assert!((e.stress_drop_pa - 5864.0).abs() < 15.0, "drop {}", e.stress_drop_pa);
    }

    /// Ringing faster than the smoothing window (2 kHz: two periods per millisecond) averages
    /// out of τ̄: the drop is that of the clean burst, up to what the ringing's decay (10 ms)
    /// leaves in a 1-ms window (about w/τ × amplitude ≈ 100 Pa, 2% of the drop).
    #[test]
    fn ringing_superposed_on_the_drop_is_averaged_out() {
        let (a, b) = (5000usize, 5200usize);
        let clean = one_burst(&[(a, b, 1e-3, 6000.0)]);
        let mut rec = synthetic(12000, &[(a, b, 1e-3, 6000.0)]);
        for (i, tau) in rec[1].iter_mut().enumerate() {
            if i >= a {
                let t = (i - a) as f64 * DT;
                *tau += 1000.0 * (2.0 * std::f64::consts::PI * 2000.0 * t).sin() * (-t / 0.01).exp();
            }
        }
        let rung = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert_eq!(rung.events.len(), 1);
        let (d0, d1) = (clean.events[0].burst.stress_drop_pa, rung.events[0].burst.stress_drop_pa);
        // A 1-kPa ringing, unsmoothed, would change the drop by up to 1 kPa (17%).
        assert!((d1 - d0).abs() < 0.03 * d0, "drop {d1} with ringing vs {d0} clean");
        assert_eq!(rung.events[0].burst.start_s, clean.events[0].burst.start_s);
    }

    /// Two drops 0.5 ms apart (closer than the 1-ms window) are one event whose drop is both.
    #[test]
    fn two_drops_closer_than_the_smoothing_window_are_one_event() {
        let cat = one_burst(&[(5000, 5200, 1e-3, 3000.0), (5250, 5450, 1e-3, 3000.0)]);
        assert_eq!(cat.events.len(), 1, "{:?}", cat.events.iter().map(|e| e.burst.start_s).collect::<Vec<_>>());
        let e = &cat.events[0].burst;
        // As for one burst: the first fall is 15.08 Pa a sample, so τ̄ peaks 125 Pa under the
        // stress at the onset (u = 17 in the closed form above); the end is the second burst's.
        assert!((e.stress_drop_pa - 5875.0).abs() < 15.0, "drop {}", e.stress_drop_pa);
        assert!((e.start_s - 5000.0 * DT).abs() < 1e-9 * DT, "start {}", e.start_s / DT);
        assert!((e.end_s - 5450.0 * DT).abs() < 1e-9 * DT, "end {}", e.end_s / DT);
    }

    /// The base slides at 1 mm/s from sample 5000 to the end of the record, τ̄ having dropped by
    /// 1 kPa at the onset: the loading (300 Pa/ms) restores that in 3.3 ms, and the episode lasts
    /// 150 ms without stopping. Stable sliding, not an event (the plate scene at 400 1/s read it
    /// as a main shock S1 lasting 233 ms).
    #[test]
    fn sliding_that_never_stops_is_not_an_earthquake() {
        let n = 20_000;
        let rec = synthetic(n, &[(5000, n, 1e-3, 1000.0)]);
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert!(cat.events.is_empty(), "{:?}", cat.events);
        let s = cat.sliding.expect("stable sliding");
        assert!((s.burst.start_s - 5000.0 * DT).abs() < 1e-9, "{}", s.burst.start_s);
        let rate = s.loading_rate_pa_s.expect("a loading rate");
        assert!((rate / 300e3 - 1.0).abs() < 0.01, "loading rate {rate} Pa/s");
        assert!((s.restore_s().unwrap() - s.burst.stress_drop_pa / 300e3).abs() < 1e-4);
        // Stick-slip first, then sliding: the event stays, the sliding is not one.
        let rec = synthetic(n, &[(5000, 5200, 1e-3, 6000.0), (12_000, n, 1e-3, 1000.0)]);
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert_eq!(cat.events.iter().map(|e| e.kind).collect::<Vec<_>>(), [EventKind::Main(1)]);
        assert!((cat.sliding.unwrap().burst.start_s - 12_000.0 * DT).abs() < 1e-9);
        // A 30-ms event, then the onset of the next (a small drop so far) 5 ms before the end:
        // not sliding, it has not outlasted the event before it.
        let rec = synthetic(n, &[(5000, 8000, 1e-3, 6000.0), (19_500, n, 1e-3, 50.0)]);
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert!(cat.sliding.is_none(), "{:?}", cat.sliding);
        assert_eq!(cat.events.len(), 1);
    }

    /// A slip from 1 ms into the run to its end, 2 kPa of drop at its onset: no stuck stretch is
    /// long enough to give a loading rate. Under a moving driver it is sliding from the start (a
    /// plate on 10¹⁵ N/m springs); under fixed tractions it is one rupture the run cut short (a
    /// fault's), an event.
    #[test]
    fn a_slip_from_the_start_is_sliding_under_a_driver_and_a_rupture_under_fixed_tractions() {
        let n = 20_000;
        let rec = synthetic(n, &[(100, n, 1e-3, 2000.0)]);
        let driven = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert!(driven.events.is_empty(), "{:?}", driven.events);
        let s = driven.sliding.expect("stable sliding");
        assert!(s.loading_rate_pa_s.is_none() && (s.burst.start_s - 100.0 * DT).abs() < 1e-9);
        let fixed = detect(&signals(&rec), 22, 0.1, Loading::Fixed, &EventParams::default());
        assert!(fixed.sliding.is_none());
        assert_eq!(fixed.events.iter().map(|e| e.kind).collect::<Vec<_>>(), [EventKind::Main(1)]);
        // Sliding after stick-slip is sliding only under a driver too.
        let rec = synthetic(n, &[(5000, n, 1e-3, 1000.0)]);
        let fixed = detect(&signals(&rec), 22, 0.1, Loading::Fixed, &EventParams::default());
        assert!(fixed.sliding.is_none() && fixed.events.len() == 1);
    }

    /// A burst the end of the run cuts short (2 ms before it, 6 kPa: the loading needs 20 ms to
    /// restore that) is an earthquake seen in part, not sliding.
    #[test]
    fn an_event_cut_by_the_end_of_the_run_is_still_an_event() {
        let n = 20_000;
        let rec = synthetic(n, &[(19_800, n, 1e-3, 6000.0)]);
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert!(cat.sliding.is_none());
        assert_eq!(cat.events.len(), 1);
        assert_eq!(cat.events[0].kind, EventKind::Main(1));
    }

    /// Slip that starts on the record's last samples (a fault scene whose barrier creeps at the
    /// very end) is measured over what the record holds, not past its end (it panicked).
    #[test]
    fn slip_starting_on_the_last_sample_does_not_read_past_the_record() {
        let n = 2_000;
        for start in 1..=40 {
            for rate in [1e-4, 1e-3, 1e-2, 1.0] {
                let rec = synthetic(n, &[(n - start, n, rate, 10.0)]);
                // Under fixed tractions (a fault scene) the unfinished slip is always measured.
                let cat = detect(&signals(&rec), 22, 0.1, Loading::Fixed, &EventParams::default());
                assert!(cat.sub_events.iter().all(|b| b.samples.1 < n), "starting {start} from the end");
            }
        }
    }

    /// τ̄ ringing by ±2 kPa (50 Hz, slower than the 1-ms window) while the base is stuck: a 1-kPa
    /// drop inside that ringing is not an event, a 6-kPa one is.
    #[test]
    fn a_drop_below_the_ringing_is_not_an_event() {
        let n = 20_000;
        for (drop, events) in [(1000.0, 0usize), (6000.0, 1)] {
            let mut rec = synthetic(n, &[(15_000, 15_200, 1e-3, drop)]);
            for (i, tau) in rec[1].iter_mut().enumerate().take(15_000) {
                *tau += 2000.0 * (2.0 * std::f64::consts::PI * 50.0 * i as f64 * DT).sin();
            }
            let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
            assert_eq!(cat.events.len(), events, "drop {drop}");
            assert_eq!(cat.within_ringing, 1 - events, "drop {drop}");
        }
    }

    #[test]
    fn kinds_read_back_from_their_names() {
        for k in [EventKind::Main(3), EventKind::Foreshock(1), EventKind::Aftershock(12), EventKind::Minor] {
            assert_eq!(EventKind::parse(k.name(), &k.label()), Some(k));
        }
        assert_eq!(EventKind::parse("main", ""), None);
        assert_eq!(EventKind::parse("quake", "S1"), None);
    }

    #[test]
    fn no_main_shocks_without_events() {
        let rec = synthetic(3000, &[]);
        let cat = detect(&signals(&rec), 22, 0.1, Loading::Driven, &EventParams::default());
        assert!(cat.events.is_empty() && cat.sub_events.is_empty());
    }
}
