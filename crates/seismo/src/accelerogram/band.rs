//! The band of a record: the corners it is filtered at and the band its spectra may be used in
//! (docs/model.md §8), and the interval records are written at.

use crate::error::SeismoError;

/// The interval records are written at: `requested` (the pipeline's `record.interval_s`) when
/// given, else the largest of 1, 2, 2.5 and 5 × 10^k s at or below `0.4/resolved_hz` (the usable
/// band's top at 80% of the Nyquist frequency). It does not depend on a seed's time step, so every
/// seed's records share it.
pub fn record_interval(requested: Option<f64>, resolved_hz: f64) -> f64 {
    if let Some(dt) = requested.filter(|d| *d > 0.0 && d.is_finite()) {
        return dt;
    }
    let target = 0.4 / resolved_hz;
    let decade = 10f64.powf(target.log10().floor());
    [5.0, 2.5, 2.0, 1.0].into_iter().map(|m| m * decade).find(|&d| d <= target * (1.0 + 1e-12)).unwrap_or(decade)
}

/// The lowest usable frequency of a record low-cut at `f_low` is `USABLE_LOW_FACTOR·f_low`
/// (PEER NGA-West2, Ancheta et al. 2014: 1.25).
pub const USABLE_LOW_FACTOR: f64 = 1.25;

/// The highest filter corner used, as a fraction of the Nyquist frequency `1/(2Δt)`.
pub const MAX_CORNER_OF_NYQUIST: f64 = 0.8;

/// The band a record is filtered to and the band its spectra may be used in (docs/model.md §8).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RecordBand {
    /// Low corner of the band-pass (Hz).
    pub f_low_hz: f64,
    /// High corner of the band-pass (Hz).
    pub f_high_hz: f64,
    /// Lowest usable frequency, `USABLE_LOW_FACTOR·f_low` (Hz).
    pub usable_low_hz: f64,
    /// Highest usable frequency: the high corner, or what the source resolves if lower (Hz).
    pub usable_high_hz: f64,
}

impl RecordBand {
    /// The band of a record of `duration_s` seconds sampled every `dt` seconds whose source
    /// resolves frequencies up to `resolved_hz` (the lattice's `f_max`; infinite for none):
    /// low corner `low` or `1/duration` (one cycle of the corner fits in the record), high corner
    /// `high` or `resolved_hz`, at most `MAX_CORNER_OF_NYQUIST` of Nyquist. Refused when nothing
    /// usable remains (a record too short for the band).
    pub fn new(
        duration_s: f64,
        dt: f64,
        resolved_hz: f64,
        low: Option<f64>,
        high: Option<f64>,
    ) -> Result<RecordBand, SeismoError> {
        if !(duration_s > 0.0 && duration_s.is_finite()) {
            return Err(SeismoError::parameter("duration", format!("{duration_s} s"), "a finite duration > 0 s"));
        }
        if !(dt > 0.0 && dt.is_finite()) {
            return Err(SeismoError::parameter("dt", format!("{dt} s"), "a finite interval > 0 s"));
        }
        let nyquist = 0.5 / dt;
        let f_low = low.unwrap_or(1.0 / duration_s);
        let f_high = high.unwrap_or(resolved_hz).min(MAX_CORNER_OF_NYQUIST * nyquist);
        let usable_high = f_high.min(resolved_hz);
        let usable_low = USABLE_LOW_FACTOR * f_low;
        if !(f_low > 0.0 && usable_low < usable_high) {
            return Err(SeismoError::parameter(
                "low corner",
                format!("{f_low} Hz"),
                format!(
                    "below {} Hz ({USABLE_LOW_FACTOR}× it must stay under the usable high end {usable_high} Hz): \
                     a longer record (post_event_s) or a lower corner",
                    usable_high / USABLE_LOW_FACTOR
                ),
            ));
        }
        Ok(RecordBand { f_low_hz: f_low, f_high_hz: f_high, usable_low_hz: usable_low, usable_high_hz: usable_high })
    }

    /// Whether period `t` (s) lies in the usable band.
    pub fn holds_period(&self, t: f64) -> bool {
        let eps = 1e-12;
        t * self.usable_high_hz >= 1.0 - eps && t * self.usable_low_hz <= 1.0 + eps
    }

    /// The same band with frequencies divided by `lambda` (the prototype's, times ×λ).
    pub fn scaled(&self, lambda: f64) -> RecordBand {
        RecordBand {
            f_low_hz: self.f_low_hz / lambda,
            f_high_hz: self.f_high_hz / lambda,
            usable_low_hz: self.usable_low_hz / lambda,
            usable_high_hz: self.usable_high_hz / lambda,
        }
    }

    /// The band both records can be used in.
    pub fn intersect(&self, other: &RecordBand) -> RecordBand {
        RecordBand {
            f_low_hz: self.f_low_hz.max(other.f_low_hz),
            f_high_hz: self.f_high_hz.min(other.f_high_hz),
            usable_low_hz: self.usable_low_hz.max(other.usable_low_hz),
            usable_high_hz: self.usable_high_hz.min(other.usable_high_hz),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn record_interval_is_the_pipelines_or_a_round_one_below_the_band() {
        assert_eq!(record_interval(Some(2e-5), 5078.4), 2e-5);
        // 0.4/5078.4 Hz = 7.9e-5 s: 5e-5 s.
        assert!((record_interval(None, 5078.4) - 5e-5).abs() < 1e-18);
        assert!((record_interval(None, 1000.0) - 2.5e-4).abs() < 1e-18);
        assert!((record_interval(None, 0.4) - 1.0).abs() < 1e-15);
        assert!((record_interval(None, 0.2) - 2.0).abs() < 1e-15);
    }

    #[test]
    fn record_band_defaults_and_refusals() {
        // 0.1 s at 1e-4 s, lattice resolving 5 kHz: corners 10 Hz and 4 kHz (0.8 of Nyquist 5 kHz).
        let b = RecordBand::new(0.1, 1e-4, 5000.0, None, None).unwrap();
        assert_eq!(b.f_low_hz, 10.0);
        assert_eq!(b.f_high_hz, 4000.0);
        assert_eq!((b.usable_low_hz, b.usable_high_hz), (12.5, 4000.0));
        assert!(
            b.holds_period(1.0 / 4000.0) && b.holds_period(0.08) && !b.holds_period(0.081) && !b.holds_period(2e-4)
        );
        // A finer sampling: the lattice sets the top.
        let b = RecordBand::new(0.1, 1e-5, 5000.0, None, None).unwrap();
        assert_eq!(b.usable_high_hz, 5000.0);
        // A corner above f_max filters there but the band stops at f_max.
        let b = RecordBand::new(0.1, 1e-5, 5000.0, None, Some(8000.0)).unwrap();
        assert_eq!((b.f_high_hz, b.usable_high_hz), (8000.0, 5000.0));
        assert_eq!(b.scaled(100.0).usable_high_hz, 50.0);
        // Too short for anything: refused, saying why.
        let e = RecordBand::new(1e-3, 1e-5, 1000.0, None, None).unwrap_err().to_string();
        assert!(e.contains("low corner") && e.contains("longer record"), "{e}");
    }
}
