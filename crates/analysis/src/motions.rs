//! The ground motion of a fault scene's stations as engineers measure it (docs/model.md §15):
//! each station's two horizontal components processed by the records' chain and reduced to the
//! orientation-independent RotD50 and RotD100 (Boore 2010) of PGA, PGV and 5%-damped PSA, at
//! the periods of the NGA-West2 ground-motion models that lie in the record's usable band.
//!
//! - Components: on a fault scene the block lies on its side (x along strike, y down dip, z away
//!   from the fault), so a station's horizontal pair is (x, z); y is vertical.
//! - Record: the whole shear stage at the run's own sampling interval (it must be uniform).
//! - Processing (docs/model.md §8): whole-record mean removed, 5% half-cosine tapers, automatic
//!   zero pads, an acausal 4th-order Butterworth band-pass from `f_low = 2/T_record` (two cycles
//!   of the low corner in the record) to the lattice's `f_max` (waves within 5% of their
//!   long-wave speeds), at most 80% of Nyquist ([`RecordBand`]).
//! - Usable periods: from `1/f_high` to `1/(1.25·f_low)`; PSA is computed inside it, none outside,
//!   at [`spectrum_periods`]: the models' tabulated periods ([`GMM_PERIODS_S`]) and a log grid of
//!   20 per decade between them, on which a record set is matched to a design spectrum.
//! - RotD: the 180 rotations θ = 0…179° of `(a_x cos θ + a_z sin θ)`; RotD50 the median of the 180
//!   peaks, RotD100 the largest. PGA and PGV RotD50 directly on the processed acceleration and
//!   velocity; PSA by [`RotDPlan`].

use stickslip_seismo::accelerogram::processing::{Processed, ProcessingOptions, RecordBand, butterworth_gain, process};
use stickslip_seismo::fit::{BruneFit, fit_brune};
use stickslip_seismo::spectra::fourier::{Window, fourier_amplitude};
use stickslip_seismo::spectra::intensity::{Baseline, intensity};
use stickslip_seismo::spectra::response::Reading;
use stickslip_seismo::spectra::rotd::{ANGLES, RotDPlan, RotDScratch, RotDSpectrum};
use stickslip_solver::Recording;
use stickslip_solver::geometry::NodeId;
use stickslip_solver::scene::{Component, ControlChannel, Kinematic};

/// The periods (s) PSA is compared with the ground-motion models at, where usable: the 21 periods
/// of the Broadband Platform's Part-B tables (0.01–10 s), each tabulated by BSSA14 and ASK14 (CB14
/// and CY14 tabulate or interpolate them).
pub const GMM_PERIODS_S: [f64; 21] =
    [0.01, 0.02, 0.03, 0.05, 0.075, 0.1, 0.15, 0.2, 0.25, 0.3, 0.4, 0.5, 0.75, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.5, 10.0];

/// Periods per decade of the log grid of [`spectrum_periods`].
pub const PERIODS_PER_DECADE: usize = 20;

/// The periods (s) a station's PSA is computed at where usable, ascending: [`GMM_PERIODS_S`] and
/// the log grid `10^(k/20)` from 0.01 to 10 s, a grid point within 1% of a model period left out
/// (the model's period kept, bit for bit, so that the comparison reads it back exactly).
pub fn spectrum_periods() -> Vec<f64> {
    let decades = 3;
    let mut out: Vec<f64> = GMM_PERIODS_S.to_vec();
    for k in 0..=decades * PERIODS_PER_DECADE {
        let t = 0.01 * 10f64.powf(k as f64 / PERIODS_PER_DECADE as f64);
        if !GMM_PERIODS_S.iter().any(|&g| (t / g - 1.0).abs() < 0.01) {
            out.push(t);
        }
    }
    out.sort_by(f64::total_cmp);
    out
}

/// Damping ratio of the PSA.
pub const DAMPING: f64 = 0.05;

/// Departure from the long-wave speeds that defines the lattice's `f_max` here.
pub const DEPARTURE: f64 = 0.05;

/// Low corner as a multiple of one over the record's length: two cycles of it fit the record.
pub const LOW_CORNER_CYCLES: f64 = 2.0;

/// The horizontal motion of one station.
#[derive(Clone, Debug, PartialEq)]
pub struct Motion {
    /// Band-pass applied: low and high corners (Hz).
    pub band_hz: [f64; 2],
    /// Usable periods: shortest and longest (s).
    pub usable_s: [f64; 2],
    /// RotD50 of the peak ground acceleration (m/s²).
    pub pga_rotd50_m_s2: f64,
    /// RotD50 of the peak ground velocity (m/s).
    pub pgv_rotd50_m_s: f64,
    /// Periods of the PSA, those of [`spectrum_periods`] in the usable band (s).
    pub periods_s: Vec<f64>,
    /// RotD50 PSA at each period (m/s²).
    pub rotd50_m_s2: Vec<f64>,
    /// RotD100 PSA at each period (m/s²).
    pub rotd100_m_s2: Vec<f64>,
    /// Arias intensity, the mean of the two horizontal components' (m/s).
    pub arias_m_s: f64,
    /// Significant duration D5–95, the mean of the two components' (s).
    pub d5_95_s: f64,
    /// Cumulative absolute velocity, the mean of the two components' (m/s).
    pub cav_m_s: f64,
    /// Fourier amplitude of the horizontal displacement, `√(|X|² + |Z|²)` (m·s), divided by the
    /// band-pass's gain, at the frequencies of the usable band: `(f, amplitude)`.
    pub displacement_spectrum: Vec<(f64, f64)>,
}

/// The horizontal acceleration pair (x, z) of the station at `node` over the shear stage, and
/// its sampling interval; `None` when the stage's sampling is not uniform or too short.
fn pair(rec: &Recording, node: NodeId) -> Option<(&[f64], &[f64], f64)> {
    let span = rec.uniform_shear()?;
    let series = |component| {
        rec.control(ControlChannel { node, quantity: Kinematic::Acceleration, component }).map(|v| &v[span.clone()])
    };
    let (x, z) = (series(Component::X)?, series(Component::Z)?);
    let t = &rec.time_s[span.clone()];
    if t.len() < 8 {
        return None;
    }
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    Some((x, z, dt))
}

/// RotD50 of a pair of series: the median over θ = 0…179° of `max |x cos θ + z sin θ|`.
pub fn rotd50_peak(x: &[f64], z: &[f64]) -> f64 {
    let mut peaks: Vec<f64> = (0..ANGLES)
        .map(|t| {
            let (s, c) = (t as f64).to_radians().sin_cos();
            x.iter().zip(z).fold(0.0_f64, |m, (a, b)| m.max((a * c + b * s).abs()))
        })
        .collect();
    peaks.sort_by(f64::total_cmp);
    0.5 * (peaks[ANGLES / 2 - 1] + peaks[ANGLES / 2])
}

/// A station's horizontal pair `(x, z)` sampled every `dt` processed by the records' chain with
/// the band-pass `f_low`–`f_high` (Hz): what [`motion`] measures, and what a record set of a
/// scenario writes (the same function, so the same bits).
pub fn processed_pair(
    x: &[f64],
    z: &[f64],
    dt: f64,
    f_low: f64,
    f_high: f64,
) -> Result<(Processed, Processed), String> {
    let opts = ProcessingOptions::new(f_low, Some(f_high));
    let px = process(x, dt, &opts).map_err(|e| format!("x: {e}"))?;
    let pz = process(z, dt, &opts).map_err(|e| format!("z: {e}"))?;
    Ok((px, pz))
}

/// The motion of the station at `node`, on a lattice that resolves waves up to `resolved_hz`;
/// `Err` says why it has none (sampling, band, numerics).
pub fn motion(rec: &Recording, node: NodeId, resolved_hz: f64) -> Result<Motion, String> {
    let (x, z, dt) = pair(rec, node).ok_or_else(|| {
        "no uniform record of the shear stage (the skip-ahead sampled it sparsely, or it is shorter than 8 samples)"
            .to_string()
    })?;
    motion_of_pair(x, z, dt, resolved_hz, None)
}

/// The motion of a horizontal pair `(x, z)` sampled every `dt`, whose source resolves waves up to
/// `resolved_hz` (infinite: a broadband record, filtered only at 0.8 of its Nyquist frequency);
/// `shortest_s` lowers the shortest usable period below the band's top (a broadband record's PSA
/// at 0.01 s, which for a record without content above the top is its PGA).
pub fn motion_of_pair(
    x: &[f64],
    z: &[f64],
    dt: f64,
    resolved_hz: f64,
    shortest_s: Option<f64>,
) -> Result<Motion, String> {
    let duration = (x.len() - 1) as f64 * dt;
    let band = RecordBand::new(duration, dt, resolved_hz, Some(LOW_CORNER_CYCLES / duration), None)
        .map_err(|e| format!("band: {e}"))?;
    let (px, pz) = processed_pair(x, z, dt, band.f_low_hz, band.f_high_hz)?;
    let opts = ProcessingOptions::new(band.f_low_hz, Some(band.f_high_hz));
    let usable = [shortest_s.unwrap_or(1.0 / band.usable_high_hz), 1.0 / band.usable_low_hz];
    let periods: Vec<f64> =
        spectrum_periods().into_iter().filter(|&t| t >= usable[0] * (1.0 - 1e-9) && t <= usable[1]).collect();
    let (mut rotd50, mut rotd100) = (Vec::new(), Vec::new());
    if !periods.is_empty() {
        // A broadband record (shortest_s given) is read 8 times between its 0.01 s samples: 80
        // points per period at 0.1 s, where reading the peak on straight lines between them errs
        // by at most 1 − cos(π/80) = 7.7e-4; a lattice record's periods (≥ 0.4 s) have 64 or more
        // at 4.
        let oversampling = if shortest_s.is_some() { 8 } else { 4 };
        let plan = RotDPlan::new(px.dt, &periods, &[DAMPING], Reading::BandLimited, oversampling)
            .map_err(|e| format!("{e}"))?;
        let mut out = RotDSpectrum::default();
        plan.compute(&px.accel, &pz.accel, &mut RotDScratch::default(), &mut out).map_err(|e| format!("{e}"))?;
        for (k, &t) in periods.iter().enumerate() {
            let w2 = (2.0 * std::f64::consts::PI / t).powi(2);
            rotd50.push(w2 * out.rotd50[k]);
            rotd100.push(w2 * out.rotd100[k]);
        }
    }
    let [ix, iz] = [&px, &pz].map(|p| intensity(&p.accel, p.dt, Baseline::None));
    let mut planner = rustfft::FftPlanner::new();
    let fx = fourier_amplitude(&px.disp, dt, Window::Rectangular, &mut planner);
    let fz = fourier_amplitude(&pz.disp, dt, Window::Rectangular, &mut planner);
    let displacement_spectrum = fx
        .frequency_hz
        .iter()
        .zip(fx.amplitude.iter().zip(&fz.amplitude))
        .filter(|(f, _)| **f >= band.usable_low_hz && **f <= band.usable_high_hz)
        // The band-pass's own gain divided out (it is 0.71 at the corners), so that a fitted
        // corner is the source's, not the filter's.
        .map(|(f, (a, b))| (*f, a.hypot(*b) / butterworth_gain(*f, band.f_low_hz, Some(band.f_high_hz), opts.order)))
        .collect();
    Ok(Motion {
        displacement_spectrum,
        band_hz: [band.f_low_hz, band.f_high_hz],
        usable_s: usable,
        pga_rotd50_m_s2: rotd50_peak(&px.accel, &pz.accel),
        pgv_rotd50_m_s: rotd50_peak(&px.vel, &pz.vel),
        periods_s: periods,
        rotd50_m_s2: rotd50,
        rotd100_m_s2: rotd100,
        arias_m_s: 0.5 * (ix.arias + iz.arias),
        d5_95_s: 0.5 * (ix.d5_95() + iz.d5_95()),
        cav_m_s: 0.5 * (ix.cav + iz.cav),
    })
}

/// The corner frequency of the rupture seen by the surface stations (docs/model.md §16.2): each
/// station's horizontal displacement spectrum (`stations`: its motion and its hypocentral
/// distance) times that distance (undoing the 1/R spreading of body waves), stacked as a
/// geometric mean over the stations on a common frequency grid, fitted with an ω-square spectrum
/// in the band all of them resolve ([`fit_brune`]). `None` with fewer than 3 stations or no fit.
pub fn fitted_corner<'a>(stations: impl IntoIterator<Item = (&'a Motion, f64)>) -> Option<BruneFit> {
    let used: Vec<(&Motion, f64)> =
        stations.into_iter().filter(|(m, r)| !m.displacement_spectrum.is_empty() && *r > 0.0).collect();
    if used.len() < 3 {
        return None;
    }
    let grid = &used[0].0.displacement_spectrum;
    if used.iter().any(|(m, _)| m.displacement_spectrum.len() != grid.len()) {
        return None;
    }
    let stacked: Vec<f64> = (0..grid.len())
        .map(|k| {
            let ln = used.iter().map(|(m, r)| (m.displacement_spectrum[k].1 * r).max(f64::MIN_POSITIVE).ln());
            (ln.sum::<f64>() / used.len() as f64).exp()
        })
        .collect();
    let f: Vec<f64> = grid.iter().map(|p| p.0).collect();
    fit_brune(&f, &stacked, f[0], f[f.len() - 1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotd50_of_a_linearly_polarised_pair_is_its_peak_times_the_median_cosine() {
        // A pulse polarised along 30°: at angle θ its projection peaks at A·|cos(θ − 30°)|; the
        // median of |cos| over 180 equally spaced angles is cos 45° (between the 89th and 90th
        // of the sorted values, both within half a degree of 45°).
        let a = 2.0;
        let s: Vec<f64> = (0..400).map(|i| (-(i as f64 - 200.0).powi(2) / 200.0).exp()).collect();
        let (s30, c30) = 30f64.to_radians().sin_cos();
        let x: Vec<f64> = s.iter().map(|v| a * c30 * v).collect();
        let z: Vec<f64> = s.iter().map(|v| a * s30 * v).collect();
        let r = rotd50_peak(&x, &z);
        let lo = a * 45.5f64.to_radians().cos();
        let hi = a * 44.5f64.to_radians().cos();
        assert!(r >= lo && r <= hi, "{r} not in [{lo}, {hi}]");
    }

    #[test]
    fn the_spectrum_grid_holds_every_model_period_bit_for_bit_and_no_gap_wider_than_a_twentieth_decade() {
        let t = spectrum_periods();
        for g in GMM_PERIODS_S {
            assert_eq!(t.iter().filter(|p| p.to_bits() == g.to_bits()).count(), 1, "{g} s");
        }
        assert_eq!((t[0], t[t.len() - 1]), (0.01, 10.0));
        for w in t.windows(2) {
            let step = (w[1] / w[0]).log10();
            // Ascending; a log-grid point dropped beside a model period leaves at most a step of
            // 1/20 decade + 1%.
            assert!(step > 0.0 && step <= 0.05 + 0.0044, "{} → {}", w[0], w[1]);
        }
        // 61 grid points, those within 1% of a model period dropped (0.01, 0.02, 0.05, 0.1, 0.2,
        // 0.5, 1, 2, 5, 10 and a few neighbours on the grid), plus the 21 model periods.
        assert!((66..=82).contains(&t.len()), "{}", t.len());
    }

    #[test]
    fn rotd50_of_a_circular_motion_is_its_radius() {
        let n = 2000;
        let w = 2.0 * std::f64::consts::PI / 100.0;
        let x: Vec<f64> = (0..n).map(|i| 3.0 * (w * i as f64).cos()).collect();
        let z: Vec<f64> = (0..n).map(|i| 3.0 * (w * i as f64).sin()).collect();
        let r = rotd50_peak(&x, &z);
        assert!((r - 3.0).abs() < 3.0 * 1e-3, "{r}");
    }
}
