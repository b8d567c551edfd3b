//! Rupture fronts: how each event starts and spreads over the fault (docs/model.md §13).
//!
//! The input is, for every fault node, the times it started to slide: the times its slip rate
//! first reached a threshold ([`rate_onsets`], when the fault's slip rates are recorded) or its
//! sustained slip onsets; and, per event, a time window. Within an event's window:
//! - a node **ruptured** when it has an onset in the window; its onset is the first one;
//! - the **hypocentre** is the node with the earliest onset (ties: the lower node index);
//! - the **rupture area** is the sum of the ruptured nodes' tributary areas, its extent along x
//!   their smallest and largest x;
//! - the **rupture speed** is the inverse of the median slowness of the front's one-way
//!   stretches: the rupture time of each column of nodes along x (its earliest node's) is taken,
//!   and every run of [`FRONT_WINDOW`] neighbouring ruptured columns whose rupture times rise (or
//!   fall) strictly along x is a stretch the front ran through; its slowness is the least-squares
//!   slope of time against x, and the median over the stretches is the front's. Local, because
//!   a rupture here often runs as more than one front (the asperity's, and others set off by its
//!   waves at the block's edge): a single line through rupture time against distance from the
//!   hypocentre averages them into a speed no front has. Over stretches, not neighbouring pairs,
//!   because single pairs are noisy where the base chatters: the median of `|Δt|/Δx` over pairs
//!   counts every jump between two fronts and every late node as a slow front, and read the
//!   fronts of a thin block running at 1.4 c_s as 0.3 c_s. A window that mixes two fronts, or a
//!   late node, is not one-way and is left out. Without any one-way stretch, a front where most
//!   neighbouring columns started in the same instant is faster than any wave
//!   ([`Regime::Simultaneous`]); otherwise its speed is not measured ([`Regime::Undetermined`]);
//! - the speed is classed against the medium's P, S and Rayleigh speeds;
//! - at each end along x the front **arrested** at the block's edge (its last node is on the
//!   edge), at a barrier (the nodes just beyond it belong to a stronger region) or because it ran
//!   out of stress (neither).

/// Neighbouring ruptured columns a stretch of front is fitted over (0.4 m of fault at the paper's
/// Lc = 0.1 m: a step's jitter in the rupture times moves a 1.5·c_s front's speed by about 3%).
pub const FRONT_WINDOW: usize = 5;

/// Wave speeds the rupture speed is compared with (m/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaveSpeeds {
    /// P (longitudinal) speed.
    pub p_m_s: f64,
    /// S (transverse) speed.
    pub s_m_s: f64,
    /// Rayleigh speed.
    pub rayleigh_m_s: f64,
}

impl WaveSpeeds {
    /// P and S speeds, with the Rayleigh speed of an isotropic solid of the same two
    /// ([`rayleigh_speed`]).
    pub fn new(p_m_s: f64, s_m_s: f64) -> WaveSpeeds {
        WaveSpeeds { p_m_s, s_m_s, rayleigh_m_s: rayleigh_speed(p_m_s, s_m_s) }
    }

    /// The regime of a front of speed `v` (m/s, may be infinite).
    pub fn regime(&self, v: f64) -> Regime {
        if !(v > 0.0) {
            Regime::Undetermined
        } else if v.is_infinite() || v > self.p_m_s {
            Regime::Simultaneous
        } else if v > self.s_m_s {
            Regime::Supershear
        } else if v > self.rayleigh_m_s {
            Regime::RayleighToShear
        } else {
            Regime::SubRayleigh
        }
    }
}

/// The Rayleigh wave speed of an isotropic elastic solid with P speed `c_p` and S speed `c_s`
/// (m/s): the root `ξ = c/c_s` in (0, 1) of `(2 − ξ²)² = 4·√(1 − ξ²·c_s²/c_p²)·√(1 − ξ²)`, by
/// bisection (0.9194·c_s at ν = 0.25).
pub fn rayleigh_speed(c_p: f64, c_s: f64) -> f64 {
    let eta2 = (c_s / c_p).powi(2);
    let f = |xi: f64| {
        let x2 = xi * xi;
        (2.0 - x2).powi(2) - 4.0 * (1.0 - x2 * eta2).sqrt() * (1.0 - x2).sqrt()
    };
    // f < 0 just above 0 (f ≈ 2ξ²(η² − 1)) and f(1) = 1 > 0: one root between.
    let (mut lo, mut hi) = (1e-3, 1.0);
    for _ in 0..80 {
        let mid = 0.5 * (lo + hi);
        if f(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi) * c_s
}

/// How fast a front ran against the medium's waves.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regime {
    /// Slower than Rayleigh waves: the usual earthquake.
    SubRayleigh,
    /// Between the Rayleigh and S speeds (unstable for a mode II crack in a continuum).
    RayleighToShear,
    /// Between the S and P speeds.
    Supershear,
    /// Faster than P waves, or every node at once: not a propagating front but a slab of fault
    /// brought to its strength together.
    Simultaneous,
    /// Too few ruptured columns of nodes to measure a speed.
    Undetermined,
}

impl Regime {
    /// Name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Regime::SubRayleigh => "sub_rayleigh",
            Regime::RayleighToShear => "rayleigh_to_shear",
            Regime::Supershear => "supershear",
            Regime::Simultaneous => "simultaneous",
            Regime::Undetermined => "undetermined",
        }
    }
}

/// Why the front stopped at one end along x.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Arrest {
    /// Its last node lies on the block's edge.
    Edge,
    /// The nodes just beyond its last one lie in a barrier (a stronger region).
    Barrier,
    /// Neither: it ran out of stress.
    Stress,
}

impl Arrest {
    /// Name in tables.
    pub fn name(self) -> &'static str {
        match self {
            Arrest::Edge => "edge",
            Arrest::Barrier => "barrier",
            Arrest::Stress => "stress",
        }
    }
}

/// The fault: where its nodes are, what area each stands for and which lie in barriers.
#[derive(Clone, Copy, Debug)]
pub struct Fault<'a> {
    /// In-plane position `(x, y)` of each node (m).
    pub position_m: &'a [[f64; 2]],
    /// Tributary area of each node (m²).
    pub area_m2: &'a [f64],
    /// Whether each node lies in a barrier.
    pub barrier: &'a [bool],
}

/// The front of one event.
#[derive(Clone, Debug, PartialEq)]
pub struct Front {
    /// The hypocentre (node index) and its onset time (s).
    pub hypocentre: (usize, f64),
    /// Every ruptured node and its first onset in the window (s), in onset order.
    pub onsets: Vec<(usize, f64)>,
    /// Sum of the ruptured nodes' areas (m²).
    pub area_m2: f64,
    /// Smallest and largest x of the ruptured nodes (m).
    pub x_range_m: (f64, f64),
    /// Median slowness along x of the front's one-way stretches (s/m); zero for a simultaneous
    /// rupture; `None` when it cannot be told.
    pub slowness_s_m: Option<f64>,
    /// One-way stretches of [`FRONT_WINDOW`] columns the median was taken over.
    pub windows: usize,
    /// Arrest at the −x and +x ends.
    pub arrest: [Arrest; 2],
}

impl Front {
    /// Rupture speed (m/s): `1/slowness`, infinite when the slowness is zero, NaN when there was
    /// too little to measure it on.
    pub fn speed_m_s(&self) -> f64 {
        match self.slowness_s_m {
            Some(s) if s > 0.0 => 1.0 / s,
            Some(_) => f64::INFINITY,
            None => f64::NAN,
        }
    }

    /// Time from the first to the last onset (s).
    pub fn spread_s(&self) -> f64 {
        self.onsets.last().map_or(0.0, |&(_, t)| t - self.hypocentre.1)
    }

    /// The regime of its speed.
    pub fn regime(&self, speeds: &WaveSpeeds) -> Regime {
        speeds.regime(self.speed_m_s())
    }

    /// The arrest in one word: `edges` when both ends reached an edge, else `barrier` when one
    /// end met a barrier, else `stress`.
    pub fn arrest_summary(&self) -> &'static str {
        match self.arrest {
            [Arrest::Edge, Arrest::Edge] => "edges",
            a if a.contains(&Arrest::Barrier) => "barrier",
            _ => "stress",
        }
    }
}

/// The times each node's slip rate reaches `threshold` (m/s) from below, in time order: the
/// onsets [`front`] reads. `rates[i]` is node `i`'s slip rate at the instants `time_s`; a node
/// already at or above the threshold at the first instant has no onset then.
pub fn rate_onsets(time_s: &[f64], rates: &[&[f64]], threshold: f64) -> Vec<(f64, usize)> {
    let mut out: Vec<(f64, usize)> = Vec::new();
    for (i, r) in rates.iter().enumerate() {
        assert_eq!(r.len(), time_s.len(), "one rate per instant");
        out.extend(
            (1..r.len()).filter(|&k| r[k].abs() >= threshold && r[k - 1].abs() < threshold).map(|k| (time_s[k], i)),
        );
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    out
}

/// The front of the event in the window `[from_s, to_s]`, from the onsets `(time_s, node)` in
/// time order; `None` when no node started to slide in the window.
pub fn front(onsets: &[(f64, usize)], fault: &Fault<'_>, from_s: f64, to_s: f64) -> Option<Front> {
    let n = fault.position_m.len();
    let mut first = vec![f64::NAN; n];
    let a = onsets.partition_point(|&(t, _)| t < from_s);
    for &(t, node) in onsets[a..].iter().take_while(|&&(t, _)| t <= to_s) {
        if first[node].is_nan() {
            first[node] = t;
        }
    }
    let mut hit: Vec<(usize, f64)> = (0..n).filter(|&i| first[i].is_finite()).map(|i| (i, first[i])).collect();
    if hit.is_empty() {
        return None;
    }
    hit.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)));
    let hypocentre = hit[0];
    // Each ruptured column of nodes along x and its rupture time (its earliest node's).
    let mut columns: Vec<(f64, f64)> = Vec::new();
    for &(i, t) in &hit {
        let x = fault.position_m[i][0];
        match columns.iter_mut().find(|c| (c.0 - x).abs() < 1e-9) {
            Some(c) => c.1 = c.1.min(t),
            None => columns.push((x, t)),
        }
    }
    columns.sort_by(|a, b| a.0.total_cmp(&b.0));
    let (slowness, windows) = front_slowness(&columns);
    let xs: Vec<f64> = hit.iter().map(|&(i, _)| fault.position_m[i][0]).collect();
    let (x_lo, x_hi) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &x| (lo.min(x), hi.max(x)));
    let arrest = [end_arrest(fault, &first, x_lo, -1.0), end_arrest(fault, &first, x_hi, 1.0)];
    Some(Front {
        hypocentre,
        area_m2: hit.iter().map(|&(i, _)| fault.area_m2[i]).sum(),
        x_range_m: (x_lo, x_hi),
        slowness_s_m: slowness,
        windows,
        onsets: hit,
        arrest,
    })
}

/// The median slowness of the one-way stretches among `columns` (x, rupture time; sorted by x)
/// and their count (see the module doc).
fn front_slowness(columns: &[(f64, f64)]) -> (Option<f64>, usize) {
    let slopes: Vec<f64> = columns
        .windows(FRONT_WINDOW)
        .filter(|w| w.windows(2).all(|p| p[1].1 > p[0].1) || w.windows(2).all(|p| p[1].1 < p[0].1))
        .filter_map(|w| crate::fit::line_fit(w).map(|l| l.slope.abs()))
        .collect();
    if !slopes.is_empty() {
        return (Some(crate::stats::median(&slopes)), slopes.len());
    }
    let pairs = columns.len().saturating_sub(1);
    let same = columns.windows(2).filter(|p| p[1].1 == p[0].1).count();
    if pairs + 1 >= FRONT_WINDOW && 2 * same > pairs { (Some(0.0), 0) } else { (None, 0) }
}

/// Why the front stopped at its end `x_end` on the side `dir` (−1: toward −x, +1: toward +x):
/// edge when no node lies beyond it, barrier when a node of the next column beyond it that did
/// not rupture lies in a barrier, stress otherwise.
fn end_arrest(fault: &Fault<'_>, first: &[f64], x_end: f64, dir: f64) -> Arrest {
    let beyond = |x: f64| (x - x_end) * dir > 1e-9;
    let Some(next) = fault
        .position_m
        .iter()
        .map(|p| p[0])
        .filter(|&x| beyond(x))
        .min_by(|a, b| ((a - x_end) * dir).total_cmp(&((b - x_end) * dir)))
    else {
        return Arrest::Edge;
    };
    let column = (0..fault.position_m.len()).filter(|&i| (fault.position_m[i][0] - next).abs() < 1e-9);
    if column.into_iter().any(|i| fault.barrier[i] && first[i].is_nan()) { Arrest::Barrier } else { Arrest::Stress }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// At ν = 0.25 (c_p = √3·c_s) the Rayleigh speed is √(2 − 2/√3)·c_s = 0.919402·c_s, the
    /// closed form of the cubic in ξ² that the equation reduces to.
    #[test]
    fn rayleigh_speed_at_quarter_poisson() {
        let c_s = 1000.0;
        let c_r = rayleigh_speed(3f64.sqrt() * c_s, c_s);
        let exact = (2.0 - 2.0 / 3f64.sqrt()).sqrt() * c_s;
        assert!((c_r - exact).abs() < 1e-9 * c_s, "{c_r} against {exact}");
        // ν → 0.5 (c_p → ∞): the incompressible value 0.955313·c_s.
        let c_r = rayleigh_speed(1e9 * c_s, c_s);
        assert!((c_r / c_s - 0.955313).abs() < 1e-5, "{}", c_r / c_s);
    }

    /// A line of 11 nodes every 0.1 m; a front from node 2 at 500 m/s both ways; nodes 8..=10
    /// are a barrier that it does not enter.
    #[test]
    fn bilateral_front_speed_and_arrest() {
        let pos: Vec<[f64; 2]> = (0..11).map(|i| [0.1 * f64::from(i), 0.0]).collect();
        let area = vec![0.01; 11];
        let barrier: Vec<bool> = (0..11).map(|i| i >= 8).collect();
        let fault = Fault { position_m: &pos, area_m2: &area, barrier: &barrier };
        let mut onsets: Vec<(f64, usize)> = (0..8).map(|i| (1.0 + (pos[i][0] - 0.2).abs() / 500.0, i)).collect();
        onsets.push((0.5, 5)); // an earlier onset outside the window is ignored
        onsets.push((1.0005, 3)); // a second onset of node 3 does not replace its first
        onsets.sort_by(|a, b| a.0.total_cmp(&b.0));
        let f = front(&onsets, &fault, 0.9, 1.1).unwrap();
        assert_eq!(f.hypocentre, (2, 1.0));
        assert_eq!(f.onsets.len(), 8);
        assert!((f.speed_m_s() - 500.0).abs() < 1e-6, "{}", f.speed_m_s());
        assert!((f.area_m2 - 0.08).abs() < 1e-12);
        assert_eq!(f.x_range_m, (0.0, 0.7000000000000001));
        assert_eq!(f.arrest, [Arrest::Edge, Arrest::Barrier]);
        assert_eq!(f.arrest_summary(), "barrier");
        let speeds = WaveSpeeds::new(3000.0, 1700.0);
        assert_eq!(f.regime(&speeds), Regime::SubRayleigh);
        // Without the barrier the same front ran out of stress.
        let none = vec![false; 11];
        let plain = Fault { barrier: &none, ..fault };
        assert_eq!(front(&onsets, &plain, 0.9, 1.1).unwrap().arrest, [Arrest::Edge, Arrest::Stress]);
        // No onset in the window: no front.
        assert!(front(&onsets, &fault, 2.0, 3.0).is_none());
    }

    /// Crossings of the threshold from below, each node's in time order, merged.
    #[test]
    fn rate_onsets_are_upward_crossings() {
        let t = [0.0, 1.0, 2.0, 3.0, 4.0];
        let rates: [&[f64]; 2] = [&[0.0, 0.5, 2.0, 0.1, 3.0], &[5.0, 5.0, 0.0, -2.0, 0.0]];
        assert_eq!(rate_onsets(&t, &rates, 1.0), vec![(2.0, 0), (3.0, 1), (4.0, 0)]);
    }

    /// Every node at once is not a front: infinite speed, simultaneous; two columns give no
    /// speed; a front through one-way stretches is measured on them, not on a late node or the
    /// jump to a second front.
    #[test]
    fn simultaneous_and_undetermined() {
        let pos: Vec<[f64; 2]> = (0..5).map(|i| [0.1 * f64::from(i), 0.0]).collect();
        let area = vec![0.01; 5];
        let barrier = vec![false; 5];
        let fault = Fault { position_m: &pos, area_m2: &area, barrier: &barrier };
        let onsets: Vec<(f64, usize)> = (0..5).map(|i| (1.0, i)).collect();
        let f = front(&onsets, &fault, 0.0, 2.0).unwrap();
        assert_eq!(f.speed_m_s(), f64::INFINITY);
        assert_eq!(f.regime(&WaveSpeeds::new(3000.0, 1700.0)), Regime::Simultaneous);
        assert_eq!(f.arrest_summary(), "edges");
        let f = front(&onsets[..2], &fault, 0.0, 2.0).unwrap();
        assert!(f.speed_m_s().is_nan());
        assert_eq!(f.regime(&WaveSpeeds::new(3000.0, 1700.0)), Regime::Undetermined);
        // 21 columns, a front from column 0 at 2500 m/s; column 7 is late, and from column 14 on a
        // second front, started at the far end, runs back at the same speed and meets it.
        let pos: Vec<[f64; 2]> = (0..21).map(|i| [0.1 * f64::from(i), 0.0]).collect();
        let area = vec![0.01; 21];
        let barrier = vec![false; 21];
        let fault = Fault { position_m: &pos, area_m2: &area, barrier: &barrier };
        let mut onsets: Vec<(f64, usize)> = (0..21)
            .map(|i| {
                let x = pos[i][0];
                let t = if i < 14 { x / 2500.0 } else { 4e-4 + (2.0 - x) / 2500.0 };
                (if i == 7 { t + 3e-4 } else { t }, i)
            })
            .collect();
        onsets.sort_by(|a, b| a.0.total_cmp(&b.0));
        let f = front(&onsets, &fault, 0.0, 1.0).unwrap();
        assert!((f.speed_m_s() / 2500.0 - 1.0).abs() < 1e-9, "{}", f.speed_m_s());
        // Ten windows run one way: 0–4 … 3–7, 8–12 … 10–14 and 14–18 … 16–20; two of them end on
        // the late column or the other front and are outvoted by the median.
        assert_eq!(f.windows, 10);
        // Supershear and Rayleigh-to-shear bands.
        let w = WaveSpeeds::new(3000.0, 1700.0);
        assert_eq!(w.regime(2000.0), Regime::Supershear);
        assert_eq!(w.regime(0.5 * (w.rayleigh_m_s + 1700.0)), Regime::RayleighToShear);
    }
}
