//! A station's hybrid record (the Platform's order: stochastic part → site terms on each part →
//! join): the deterministic record resampled to the stochastic part's interval, each part
//! multiplied by its BSSA14 site factor from its own reference site to the station's V_S30, then
//! low- and high-passed at the crossover and added, component by component.

use super::merge::{Crossover, join};
use super::site::{SiteFactor, pga_760_g};
use crate::accelerogram::processing::resample_together;

/// The sites of a hybrid record (m/s).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HybridSite {
    /// The station's V_S30.
    pub vs30_m_s: f64,
    /// The reference site of the deterministic part (the lattice's surface V_S).
    pub deterministic_vref_m_s: f64,
    /// The reference site of the stochastic part (its crust's V_S30).
    pub stochastic_vref_m_s: f64,
}

/// One component of a hybrid record: each part as it enters the sum, and the sum.
#[derive(Clone, Debug, PartialEq)]
pub struct HybridComponent {
    /// The deterministic part, site-amplified and low-passed (m/s²).
    pub deterministic: Vec<f64>,
    /// The stochastic part, site-amplified and high-passed (m/s²).
    pub stochastic: Vec<f64>,
    /// Their sum (m/s²).
    pub broadband: Vec<f64>,
    /// The reference-rock PGA of the nonlinear site term (g).
    pub pga_760_g: f64,
}

/// A station's three components (along strike, vertical, fault-normal), sampled every `dt_s` from
/// the rupture's start.
#[derive(Clone, Debug, PartialEq)]
pub struct HybridRecord {
    /// Sampling interval (s).
    pub dt_s: f64,
    /// x, y, z.
    pub components: [HybridComponent; 3],
}

/// The hybrid record of the deterministic components `deterministic` (x, y, z; sampled every
/// `deterministic_dt` from `t0_s` after the rupture's start, t0 ≥ 0) and the stochastic ones
/// `stochastic` (x, y, z; every `dt` from the start), joined at `crossover` on `site`. The record
/// is as long as the stochastic part.
pub fn hybrid(
    deterministic: [&[f64]; 3],
    deterministic_dt: f64,
    t0_s: f64,
    stochastic: &[Vec<f64>; 3],
    dt: f64,
    crossover: Crossover,
    site: HybridSite,
) -> HybridRecord {
    let len = stochastic[0].len();
    let resampled = resample_together(deterministic, deterministic_dt, dt);
    let shift = (t0_s.max(0.0) / dt).round() as usize;
    let components = std::array::from_fn(|c| {
        let mut low = vec![0.0; len];
        for (k, v) in resampled[c].iter().enumerate() {
            if let Some(slot) = low.get_mut(k + shift) {
                *slot = *v;
            }
        }
        let high = &stochastic[c];
        let peak = high.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let pga = pga_760_g(peak, site.stochastic_vref_m_s);
        let low_site = SiteFactor::bssa14(site.vs30_m_s, site.deterministic_vref_m_s, pga);
        let high_site = SiteFactor::bssa14(site.vs30_m_s, site.stochastic_vref_m_s, pga);
        let j = join(&low, high, dt, crossover, |f| low_site.at(f), |f| high_site.at(f));
        HybridComponent { deterministic: j.low, stochastic: j.high, broadband: j.broadband, pga_760_g: pga }
    });
    HybridRecord { dt_s: dt, components }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn on_its_reference_sites_the_record_is_the_two_parts_filtered_and_added() {
        // A 0.3 Hz sine in the deterministic part (sampled at 0.025 s) and a 6 Hz sine in the
        // stochastic one: on a site equal to both references (no site term) the broadband record
        // is each sine through its own filter.
        let (dt_l, dt) = (0.025, 0.01);
        let n_l = 2400;
        let slow: Vec<f64> = (0..n_l).map(|k| (2.0 * std::f64::consts::PI * 0.3 * k as f64 * dt_l).sin()).collect();
        let len = 6000;
        let fast: Vec<f64> = (0..len).map(|k| 0.2 * (2.0 * std::f64::consts::PI * 6.0 * k as f64 * dt).sin()).collect();
        let st = [fast.clone(), fast.clone(), fast.clone()];
        let site = HybridSite { vs30_m_s: 760.0, deterministic_vref_m_s: 760.0, stochastic_vref_m_s: 760.0 };
        let r = hybrid([&slow, &slow, &slow], dt_l, 0.0, &st, dt, Crossover::new(1.0), site);
        let c = &r.components[2];
        for k in 2000..4000 {
            let t = k as f64 * dt;
            let expected = (2.0 * std::f64::consts::PI * 0.3 * t).sin() + fast[k];
            assert!((c.broadband[k] - expected).abs() < 5e-3, "{k}: {} vs {expected}", c.broadband[k]);
        }
        // PGA_r of the nonlinear term: the stochastic peak (0.2 m/s², sampled) in g on 760 m/s.
        assert!((c.pga_760_g / (0.2 / 9.80665) - 1.0).abs() < 5e-3, "{}", c.pga_760_g);
        // A softer site amplifies both parts.
        let soft = HybridSite { vs30_m_s: 400.0, ..site };
        let s = hybrid([&slow, &slow, &slow], dt_l, 0.0, &st, dt, Crossover::new(1.0), soft);
        let rms = |v: &[f64]| (v[2000..4000].iter().map(|x| x * x).sum::<f64>() / 2000.0).sqrt();
        assert!(rms(&s.components[0].stochastic) > 1.3 * rms(&r.components[0].stochastic));
        assert!(rms(&s.components[0].deterministic) > 1.3 * rms(&r.components[0].deterministic));
    }
}
