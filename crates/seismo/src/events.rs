//! Stick-slip events and sub-events from the interface series (docs/model.md §7).
//!
//! The detector works on two signals smoothed by a centred moving average of `smoothing_s`
//! (vibrations of lifted nodes and of the stress field are much faster than a slip burst):
//! - the slip rate `V̄` (mean x-velocity of the contact nodes), which is the time derivative of
//!   the mean slip δ, so its moving average is `[δ(t + w/2) − δ(t − w/2)]/w`;
//! - the shear stress `τ̄`.
//!
//! A **sub-event** starts when `V̄` rises above `v_on_m_s` and ends when it has stayed below
//! `v_off_m_s` for `quiet_s` (hysteresis: `v_off < v_on`); its end is the first instant of that
//! quiet spell. Sub-events whose gap is shorter than `merge_gap_s` form one **event**. An event's
//! stress drop is `τ̄` at its start minus the minimum of `τ̄` inside it; events with a drop below
//! `min_drop_pa` are dropped from the catalogue (slip bursts without a stress drop). Events whose
//! drop is at least `main_fraction` of the largest drop of the run are **main shocks**, labelled
//! S1, S2, … in time order; every other event is a foreshock of the next main shock or an
//! aftershock of the previous one, whichever is nearer in time.

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
    /// `τ̄(start) − min τ̄` inside (Pa).
    pub stress_drop_pa: f64,
    /// Time of that minimum (s): `drop_end_s − start_s` is the time the stress takes to fall.
    pub drop_end_s: f64,
    /// `δ̄(end) − δ̄(start)` (m).
    pub slip_m: f64,
    /// Peak smoothed slip rate (m/s).
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
}

impl Catalogue {
    /// Main shocks in order (S1, S2, …).
    pub fn main_shocks(&self) -> impl Iterator<Item = &Event> {
        self.events.iter().filter(|e| matches!(e.kind, EventKind::Main(_)))
    }
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

/// Centred moving average over `w` samples (shrinking at the ends).
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

/// Detects the events of one run. `contact_nodes` and `contact_area_m2` convert the slipping
/// count into a rupture area.
pub fn detect(signals: &Signals<'_>, contact_nodes: usize, contact_area_m2: f64, params: &EventParams) -> Catalogue {
    let t = signals.time_s;
    let n = t.len();
    let (tau, slip, rate) = (signals.shear_stress_pa, signals.mean_slip_m, signals.mean_slip_rate_m_s);
    let slipping = signals.slipping_nodes;
    if n < 3 {
        return Catalogue::default();
    }
    // The sampling interval: the median spacing (a run with skip-ahead may sample quiet phases
    // more sparsely).
    let dt = {
        let mut gaps: Vec<f64> = t.windows(2).map(|w| w[1] - w[0]).collect();
        let mid = gaps.len() / 2;
        *gaps.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let w = ((params.smoothing_s / dt).round() as usize).max(1);
    let v = moving_average(rate, w);
    let tau_s = moving_average(tau, w);
    let quiet = ((params.quiet_s / dt).round() as usize).max(1);
    let accel = signals.accelerations;
    let measure = |a: usize, b: usize| -> Burst {
        let (imin, min_tau) = tau_s[a..b]
            .iter()
            .copied()
            .enumerate()
            .fold((0, f64::INFINITY), |m, (i, v)| if v < m.1 { (i, v) } else { m });
        let peak_nodes = slipping.map_or(0.0, |s| s[a..b].iter().copied().fold(0.0, f64::max));
        // `b` is one past the last slipping sample: the first sample of the quiet spell, which is
        // the documented end (the record's last sample if it ends while slipping).
        let end = b.min(n - 1);
        Burst {
            start_s: t[a],
            end_s: t[end],
            stress_drop_pa: tau_s[a] - min_tau,
            drop_end_s: t[a + imin],
            slip_m: slip[end] - slip[a],
            peak_slip_rate_m_s: v[a..b].iter().copied().fold(f64::NEG_INFINITY, f64::max),
            peak_slipping_nodes: peak_nodes as u32,
            rupture_area_m2: peak_nodes / contact_nodes as f64 * contact_area_m2,
            peak_acceleration: accel.iter().map(|x| x[a..b].iter().fold(0.0f64, |m, v| m.max(v.abs()))).collect(),
            samples: (a, b),
        }
    };
    // Sub-events: hysteresis on the smoothed slip rate.
    let mut spans: Vec<(usize, usize)> = Vec::new();
    let mut i = 0;
    while i < n {
        if v[i] > params.v_on_m_s {
            let start = i;
            let mut below = 0;
            let mut j = i + 1;
            while j < n {
                if v[j] < params.v_off_m_s {
                    below += 1;
                    if below >= quiet {
                        break;
                    }
                } else {
                    below = 0;
                }
                j += 1;
            }
            // End at the first sample of the quiet spell (or the end of the record).
            let end = if j < n { j + 1 - below } else { n };
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
    for (k0, k1) in groups {
        let (a, b) = (spans[k0].0, spans[k1 - 1].1);
        let burst = measure(a, b);
        if burst.stress_drop_pa < params.min_drop_pa {
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
        let params = EventParams { smoothing_s: DT, ..EventParams::default() };
        let cat = detect(&signals(&rec), 22, 0.1, &params);
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
            assert!((e.burst.start_s - a as f64 * DT).abs() <= DT * 1.0001, "start {} vs {a}", e.burst.start_s / DT);
            assert!((e.burst.end_s - b as f64 * DT).abs() <= DT * 1e-6, "end {} vs {b}", e.burst.end_s / DT);
        }
        let sub_starts: Vec<usize> = cat.sub_events.iter().map(|s| (s.start_s / DT).round() as usize).collect();
        assert_eq!(sub_starts, vec![2000, 2150, 6000, 7000, 7600, 12000, 12100, 12200]);
        let drops: Vec<f64> = cat.events.iter().map(|e| e.burst.stress_drop_pa).collect();
        for (d, want) in drops.iter().zip([8000.0, 1000.0, 7000.0, 1000.0, 6000.0]) {
            assert!((d - want).abs() < 1e-6 * want, "drop {d} vs {want}");
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
        detect(&signals(&rec), 22, 0.1, &EventParams::default())
    }

    /// What the default smoothing does to a clean burst, in closed form: with a centred moving
    /// average of w samples, V̄ = rate × (share of the window inside the burst), so V̄ crosses
    /// v_on = 0.2 × rate 0.3w before the burst starts, and falls below v_off = 0.05 × rate 0.45w
    /// after it ends; a burst of L samples is measured L + 0.75w long (0.75 ms at 1 ms smoothing).
    #[test]
    fn a_clean_ramp_and_drop_is_measured_as_the_smoothing_predicts() {
        let w = 100.0;
        let (a, b) = (5000usize, 5200usize);
        let cat = one_burst(&[(a, b, 1e-3, 6000.0)]);
        assert_eq!(cat.events.len(), 1);
        let e = &cat.events[0].burst;
        let start = (a as f64 - 0.3 * w) * DT;
        let end = (b as f64 + 0.45 * w) * DT;
        assert!((e.start_s - start).abs() <= 1.0001 * DT, "start {} vs {}", e.start_s / DT, start / DT);
        assert!((e.end_s - end).abs() <= 1.0001 * DT, "end {} vs {}", e.end_s / DT, end / DT);
        assert!((e.duration_s() - (b - a) as f64 * DT - 0.75 * w * DT).abs() <= 2.0001 * DT);
        // Slip: all of the burst's (200 samples at 1 mm/s), whatever the smoothing.
        assert!((e.slip_m - 200.0 * 1e-3 * DT).abs() < 1e-12, "slip {}", e.slip_m);
        // Drop: τ̄ at the (early) start minus the minimum of τ̄. The start falls 30 samples
        // before the burst, where τ̄ averages the rising ramp (3 Pa per sample) with the first
        // 20 samples of the fall; the minimum of τ̄ is shaved by averaging the bottom of the
        // fall with the flat stretch after it. Both lower the drop: 6 kPa is read as 5.6–6 kPa.
        assert!(e.stress_drop_pa < 6000.0 && e.stress_drop_pa > 0.93 * 6000.0, "drop {}", e.stress_drop_pa);
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
        let rung = detect(&signals(&rec), 22, 0.1, &EventParams::default());
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
        assert!(e.stress_drop_pa < 6000.0 && e.stress_drop_pa > 0.93 * 6000.0, "drop {}", e.stress_drop_pa);
        assert!((e.end_s - (5450.0 + 45.0) * DT).abs() <= 1.0001 * DT, "end {}", e.end_s / DT);
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
        let cat = detect(&signals(&rec), 22, 0.1, &EventParams::default());
        assert!(cat.events.is_empty() && cat.sub_events.is_empty());
    }
}
