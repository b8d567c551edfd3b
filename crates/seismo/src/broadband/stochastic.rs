//! The stochastic finite-fault synthesis of the Graves–Pitarka method (the Platform's
//! `hb_high_v6.0.5`), on the subfaults of a deterministic rupture ([`FiniteFault`]).
//!
//! For a station at distance `R_i` from subfault `i` (straight ray in the homogeneous crust of
//! S-wave speed β and density ρ), each component's Fourier acceleration amplitude (m/s) is
//! ```text
//! A_i(f) = F·R_c/(4πρβ³) · w_i·m_e·(2πf)²/(1 + (f/f_c,i)²) · C(f_c,i² + f²)/(f_c,i² + C·f²)
//!          · exp(−πκ₀f) · exp(−πfR_i/(Q(f)·β))/R_i · A_crust(f)
//! m_e = Δσ_p·dl³,   C = M0/(m_e·√N),   f_c,i = C_zero·(v_r,i/β)·β/(π·dl),   Q(f) = Q0·f^η
//! ```
//! with F = 2 the free surface, R_c the component's radiation coefficient (conically averaged,
//! [`Stochastic::radiation_horizontal`], [`Stochastic::radiation_vertical`]), `w_i` the
//! subfault's moment over the mean moment of the N subfaults of the rupture's rectangle, Δσ_p the
//! stress parameter scaled with the rupture's area ([`Stochastic::stress_parameter`]), dl the
//! subfault size and `v_r,i` its rupture speed ([`CornerSpeed`]: the Platform's kinematic one, with
//! which its stress parameter was calibrated, or the deterministic rupture's local one). The
//! Brune spectrum times Frankel's factor is a single-corner ω² spectrum of moment `C·m_e` and
//! corner `f_c/√C`; N such subfaults with independent random phases add up to M0 below the corner
//! and to a high-frequency level that does not depend on dl (Graves & Pitarka 2015; the method's
//! 2022 release notes).
//!
//! Each subfault and component is one [`realization`] under a Saragoni–Hart window reaching η at
//! `T_w = √C/f_c,i + D_p(R_i)` (source duration plus the Boore & Thompson 2014 path duration),
//! started at `t_r,i + max(R_i/β − ε·T_w, R_i/(2β))` so that the envelope peaks at the S arrival,
//! with the last tenth of each subfault's series tapered by a cos² (the Platform's). Subfaults
//! whose weight is below 0.001 are skipped (they still count in N). The Platform adds a ray
//! reflected off its crust's deepest interface; the lattice's crust is a half-space, so the
//! direct ray alone is used.
//!
//! **Random phases.** Every (station, component, subfault) draws from its own ChaCha8 stream of
//! the seed, named by the station's key, the component and the subfault's cell: a station's record
//! does not depend on which other stations are simulated, in which order or on how many threads.

use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;

use rand_distr::{Distribution, Open01, StandardNormal};

use super::fault::FiniteFault;
use super::params::{
    CornerSpeed, PLATFORM_SPEED_CAP, PLATFORM_SPEED_RATIO, PLATFORM_SPEED_SIGMA, PLATFORM_SPEED_SPREAD, Stochastic,
    path_duration_s, platform_speed_ratio,
};
use super::synth::{bin_frequencies, fft_length, realization};

/// The medium the stochastic part travels through.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Medium {
    /// S-wave speed β (m/s).
    pub s_speed_m_s: f64,
    /// Density ρ (kg/m³).
    pub density_kg_m3: f64,
}

/// The components of a record: along strike (x), vertical (y), fault-normal (z).
pub const COMPONENTS: [&str; 3] = ["x", "y", "z"];

/// Free-surface amplification.
const FREE_SURFACE: f64 = 2.0;

/// Subfaults lighter than this fraction of the mean moment are left out (the Platform's).
const MIN_WEIGHT: f64 = 1e-3;

/// The synthesis of one rupture's stochastic part.
#[derive(Clone, Debug)]
pub struct Synthesis<'a> {
    fault: &'a FiniteFault,
    params: &'a Stochastic,
    medium: Medium,
    /// Δσ_p after its area scaling (Pa).
    stress_pa: f64,
    /// Subevent moment m_e (N·m).
    subevent_n_m: f64,
    /// Frankel's C.
    frankel: f64,
    /// Q at 1 Hz.
    q0: f64,
    /// Each subfault's rupture speed over β (in the order of the fault's subfaults).
    speeds: Vec<f64>,
}

/// The Fourier amplitude of one subfault at one station, without its radiation coefficient.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SubfaultSpectrum {
    /// `F/(4πρβ³)·w·m_e` (m/s per (rad/s)² … the low-frequency level before C).
    level: f64,
    corner_hz: f64,
    frankel: f64,
    kappa_s: f64,
    q0: f64,
    q_exponent: f64,
    /// `R/β` (s).
    travel_s: f64,
    distance_m: f64,
}

impl SubfaultSpectrum {
    /// Its amplitude at `f` (Hz) for radiation coefficient 1, through `crust(f)`.
    pub fn at(&self, f: f64, crust: f64) -> f64 {
        if f <= 0.0 {
            return 0.0;
        }
        let w = 2.0 * std::f64::consts::PI * f;
        let (fc2, c) = (self.corner_hz * self.corner_hz, self.frankel);
        let source = self.level * w * w / (1.0 + f * f / fc2) * c * (fc2 + f * f) / (fc2 + c * f * f);
        let q = self.q0 * f.powf(self.q_exponent);
        source * (-std::f64::consts::PI * f * (self.kappa_s + self.travel_s / q)).exp() / self.distance_m * crust
    }

    /// The subfault's corner frequency f_c (Hz).
    pub fn corner_hz(&self) -> f64 {
        self.corner_hz
    }
}

/// A stream key for a station: FNV-1a of its name.
pub fn station_key(name: &str) -> u64 {
    name.bytes().fold(0xcbf2_9ce4_8422_2325u64, |h, b| (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3))
}

fn splitmix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The random stream of one station, component and subfault cell of `seed`.
pub fn stream(seed: u64, station: u64, component: usize, cell: usize) -> ChaCha8Rng {
    const TAG: u64 = 0xb20a_dba4_d5ee_d000;
    let mut rng = ChaCha8Rng::seed_from_u64(splitmix(seed ^ TAG));
    rng.set_stream(splitmix(station ^ splitmix(((cell as u64) << 2) | component as u64)));
    rng
}

impl<'a> Synthesis<'a> {
    /// The synthesis of `fault` (of moment magnitude `mw`) in `medium` with `params`, its random
    /// rupture speeds (if the Platform's) drawn from `seed`.
    pub fn new(fault: &'a FiniteFault, mw: f64, medium: Medium, params: &'a Stochastic, seed: u64) -> Synthesis<'a> {
        let stress_pa = params.stress_parameter(mw, fault.area_m2);
        let subevent_n_m = stress_pa * fault.size_m.powi(3);
        let frankel = fault.moment_n_m / (subevent_n_m * (fault.cells as f64).sqrt());
        let speeds = match params.corner_speed {
            CornerSpeed::Lattice => fault.subfaults.iter().map(|s| s.speed_ratio).collect(),
            CornerSpeed::Platform => {
                // The seed's factor, then each subfault's perturbation: streams of the seed no
                // station uses (station key 0).
                let u: f64 = Open01.sample(&mut stream(seed, 0, 3, usize::MAX));
                let factor = 1.0 + PLATFORM_SPEED_SPREAD / PLATFORM_SPEED_RATIO * (2.0 * u - 1.0);
                fault
                    .subfaults
                    .iter()
                    .map(|s| {
                        let g: f64 = StandardNormal.sample(&mut stream(seed, 0, 3, s.cell));
                        let r = factor * platform_speed_ratio(s.depth_m, fault.hypocentre_depth_m);
                        (r * (PLATFORM_SPEED_SIGMA * g).exp()).min(PLATFORM_SPEED_CAP)
                    })
                    .collect()
            }
        };
        Synthesis {
            fault,
            params,
            medium,
            stress_pa,
            subevent_n_m,
            frankel,
            q0: params.q0_for(medium.s_speed_m_s),
            speeds,
        }
    }

    /// The stress parameter after its area scaling (Pa).
    pub fn stress_parameter_pa(&self) -> f64 {
        self.stress_pa
    }

    /// Frankel's C.
    pub fn frankel(&self) -> f64 {
        self.frankel
    }

    /// The rupture speed over β of each subfault (in the fault's order).
    pub fn speeds(&self) -> &[f64] {
        &self.speeds
    }

    /// The spectrum of the fault's `k`-th subfault at `distance_m`.
    pub fn spectrum(&self, k: usize, distance_m: f64) -> SubfaultSpectrum {
        let s = &self.fault.subfaults[k];
        let (beta, rho) = (self.medium.s_speed_m_s, self.medium.density_kg_m3);
        let mean = self.fault.moment_n_m / self.fault.cells as f64;
        let weight = s.moment_n_m / mean;
        let constant = FREE_SURFACE / (4.0 * std::f64::consts::PI * rho * beta.powi(3));
        let speed = self.speeds[k];
        SubfaultSpectrum {
            level: constant * weight * self.subevent_n_m,
            corner_hz: self.params.corner_constant * speed * beta / (std::f64::consts::PI * self.fault.size_m),
            frankel: self.frankel,
            kappa_s: self.params.kappa_s,
            q0: self.q0,
            q_exponent: self.params.q_exponent,
            travel_s: distance_m / beta,
            distance_m,
        }
    }

    /// The window's ground-motion duration `T_w = √C/f_c + D_p(R)` of a subfault of corner
    /// `corner_hz` at `distance_m` (s).
    pub fn duration_s(&self, corner_hz: f64, distance_m: f64) -> f64 {
        self.frankel.sqrt() / corner_hz + path_duration_s(distance_m / 1000.0)
    }

    /// The three components ([`COMPONENTS`]) of the stochastic record at `station_m` = (x, depth,
    /// distance from the fault plane), `len` samples from the rupture's start, at the parameters'
    /// interval, before any site term: the crust's amplification is in it.
    pub fn record(&self, station_m: [f64; 3], len: usize, seed: u64, station: u64) -> [Vec<f64>; 3] {
        let dt = self.params.interval_s;
        let beta = self.medium.s_speed_m_s;
        let mut out: [Vec<f64>; 3] = std::array::from_fn(|_| vec![0.0; len]);
        let mean = self.fault.moment_n_m / self.fault.cells as f64;
        let radiation =
            [self.params.radiation_horizontal, self.params.radiation_vertical, self.params.radiation_horizontal];
        let eps = self.params.window.epsilon;
        for (k, s) in self.fault.subfaults.iter().enumerate() {
            if s.moment_n_m < MIN_WEIGHT * mean {
                continue;
            }
            let [x, y, z] = station_m;
            let r = ((x - s.x_m).powi(2) + (y - s.depth_m).powi(2) + z * z).sqrt().max(1.0);
            let spectrum = self.spectrum(k, r);
            let t_w = self.duration_s(spectrum.corner_hz, r);
            let travel = r / beta;
            let start = s.rupture_time_s + (travel - eps * t_w).max(0.5 * travel);
            let t_eta = self.params.window.duration_factor * t_w;
            // Half a window of zeros ahead of it holds the spread of the zero-phase shaping.
            let lead = (0.5 * t_eta / dt).ceil() as usize;
            let n = fft_length(lead + (2.0 * t_eta / dt).ceil() as usize);
            let window = self.params.window.envelope(t_w, dt, n - lead);
            let base: Vec<f64> =
                bin_frequencies(n, dt).map(|f| spectrum.at(f, self.params.crust.amplification(f))).collect();
            let first = ((start / dt).round() as i64) - lead as i64;
            let taper = n / 10;
            for (c, rec) in out.iter_mut().enumerate() {
                let amplitude: Vec<f64> = base.iter().map(|a| a * radiation[c]).collect();
                let mut rng = stream(seed, station, c, s.cell);
                let mut series = realization(&window, lead, n, dt, &amplitude, &mut rng);
                for i in 1..=taper {
                    series[n - taper - 1 + i] *= 0.5 * (1.0 + (i as f64 * std::f64::consts::PI / taper as f64).cos());
                }
                for (k, v) in series.iter().enumerate() {
                    let at = first + k as i64;
                    if at >= 0 && (at as usize) < len {
                        rec[at as usize] += v;
                    }
                }
            }
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::broadband::fault::FaultNode;

    fn fault() -> FiniteFault {
        let mut nodes = Vec::new();
        for i in 0..24 {
            for j in 0..16 {
                let (x, y) = (250.0 + 500.0 * i as f64, 250.0 + 500.0 * j as f64);
                let t = (x - 3000.0).hypot(y - 5000.0) / 2700.0;
                nodes.push(FaultNode { x_m: x, depth_m: y, area_m2: 0.25e6, slip_m: 0.8, rupture_time_s: t });
            }
        }
        FiniteFault::from_nodes(&nodes, 500.0, 1000.0, 3.2e10, 3464.0).unwrap().unwrap()
    }

    const MEDIUM: Medium = Medium { s_speed_m_s: 3464.0, density_kg_m3: 2670.0 };

    #[test]
    fn the_subfaults_add_up_to_the_moment_below_the_corner_and_to_dl_free_levels_above() {
        let f = fault();
        let p = Stochastic::default();
        let syn = Synthesis::new(&f, 6.0, MEDIUM, &p, 1);
        // Incoherent sum of N subfaults at f → 0: √(Σ (w_i·C·m_e)²) = M0 for equal weights.
        let n = f.cells as f64;
        assert!((syn.frankel * syn.subevent_n_m * n.sqrt() / f.moment_n_m - 1.0).abs() < 1e-12);
        // Far above the corners the subfault level is level·(2π f_c)²·…: with equal weights the
        // incoherent sum ∝ √N·dl³·f_c² ∝ √A·dl⁰ — the same with 2 km subfaults.
        let hf = |target: f64| {
            let nodes = {
                let mut v = Vec::new();
                for i in 0..24 {
                    for j in 0..16 {
                        let (x, y) = (250.0 + 500.0 * i as f64, 250.0 + 500.0 * j as f64);
                        v.push(FaultNode { x_m: x, depth_m: y, area_m2: 0.25e6, slip_m: 0.8, rupture_time_s: 1.0 });
                    }
                }
                v
            };
            let f = FiniteFault::from_nodes(&nodes, 500.0, target, 3.2e10, 3464.0).unwrap().unwrap();
            let syn = Synthesis::new(&f, 6.0, MEDIUM, &p, 1);
            let s = syn.spectrum(0, 20e3);
            // At 30 Hz without κ and Q: the high-frequency plateau of one subfault times √N.
            let plateau = s.at(30.0, 1.0)
                / (-std::f64::consts::PI * 30.0 * (s.kappa_s + s.travel_s / (s.q0 * 30f64.powf(s.q_exponent)))).exp();
            plateau * (f.cells as f64).sqrt()
        };
        let (one, two) = (hf(1000.0), hf(2000.0));
        assert!((one / two - 1.0).abs() < 0.02, "{one} vs {two}");
    }

    #[test]
    fn the_subfaults_add_up_incoherently_to_the_sum_of_their_spectra() {
        // Over realizations, the record's power spectrum in 1–15 Hz is Σ_i A_i² (independent
        // phases): the weights, the placement and the truncations keep every subfault's energy.
        let f = fault();
        let p = Stochastic::default();
        let syn = Synthesis::new(&f, 6.0, MEDIUM, &p, 1);
        let (len, dt) = (8192usize, p.interval_s);
        let station = [6000.0, 0.0, 10_000.0];
        let df = 1.0 / (len as f64 * dt);
        let band: Vec<usize> = (0..=len / 2).filter(|&j| (1.0..=15.0).contains(&(j as f64 * df))).collect();
        let mut planner = rustfft::FftPlanner::new();
        let fft = planner.plan_fft_forward(len);
        let runs = 40;
        let mut measured = 0.0;
        for seed in 0..runs {
            let [x, _, _] = syn.record(station, len, seed, station_key("s"));
            let mut buf: Vec<rustfft::num_complex::Complex<f64>> =
                x.iter().map(|&v| rustfft::num_complex::Complex::new(v, 0.0)).collect();
            fft.process(&mut buf);
            measured += band.iter().map(|&j| (dt * buf[j].norm()).powi(2) * df).sum::<f64>() / runs as f64;
        }
        let expected: f64 = f
            .subfaults
            .iter()
            .enumerate()
            .map(|(k, s)| {
                let r = ((station[0] - s.x_m).powi(2) + s.depth_m.powi(2) + station[2].powi(2)).sqrt();
                let a = syn.spectrum(k, r);
                band.iter()
                    .map(|&j| {
                        let fj = j as f64 * df;
                        (a.at(fj, p.crust.amplification(fj)) * p.radiation_horizontal).powi(2) * df
                    })
                    .sum::<f64>()
            })
            .sum();
        assert!((measured / expected - 1.0).abs() < 0.05, "{measured} vs {expected}");
    }

    #[test]
    fn a_station_record_is_the_same_alone_or_among_others_and_differs_between_seeds() {
        let f = fault();
        let p = Stochastic::default();
        let syn = Synthesis::new(&f, 6.0, MEDIUM, &p, 1);
        let a = syn.record([6000.0, 0.0, 10_000.0], 3000, 7, station_key("a"));
        let _ = syn.record([9000.0, 0.0, 20_000.0], 3000, 7, station_key("b"));
        let again = syn.record([6000.0, 0.0, 10_000.0], 3000, 7, station_key("a"));
        assert_eq!(a, again);
        let other_seed = syn.record([6000.0, 0.0, 10_000.0], 3000, 8, station_key("a"));
        assert_ne!(a[0], other_seed[0]);
        // Three independent components; the vertical weaker by the radiation ratio.
        assert_ne!(a[0], a[2]);
        let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len() as f64).sqrt();
        let ratio = rms(&a[1]) / (0.5 * (rms(&a[0]) + rms(&a[2])));
        assert!((ratio / (0.075 / 0.42) - 1.0).abs() < 0.3, "{ratio}");
        // Nothing arrives long before the first S wave: R ≥ 10 km from every subfault at
        // 3464 m/s, the envelope's start ≥ half the travel time (1.44 s); the zero-phase shaping
        // spreads a little ahead of it.
        let quiet = (0.5 * 10_000.0 / 3464.0 / 0.01) as usize - 50;
        let peak = a[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(
            a[0][..quiet].iter().all(|v| v.abs() < 1e-2 * peak),
            "{:?}",
            a[0][..quiet].iter().fold(0.0f64, |m, v| m.max(v.abs())) / peak
        );
    }
}
