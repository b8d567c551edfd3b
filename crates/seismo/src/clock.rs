//! The product's nominal clock. A simulated event has no date: time 0 of a run is
//! 2000-01-01T00:00:00Z, in every record (SAC, MiniSEED) and catalogue (QuakeML) it writes, and a
//! time on the run's clock is that date plus its seconds. [`UtcTime`] turns such an offset into a
//! calendar date and time (proleptic Gregorian, UTC, leap seconds ignored as in POSIX time).

use crate::error::SeismoError;

/// Days from 0000-03-01 (proleptic Gregorian) to 2000-01-01, the nominal time 0 of a run.
const NOMINAL_DAYS: i64 = 730_425;

/// A date and time on the proleptic Gregorian calendar, UTC, to the microsecond.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct UtcTime {
    /// Year.
    pub year: i32,
    /// Day of the year, 1–366.
    pub day_of_year: u16,
    /// Month, 1–12.
    pub month: u8,
    /// Day of the month, 1–31.
    pub day: u8,
    /// Hour.
    pub hour: u8,
    /// Minute.
    pub minute: u8,
    /// Second.
    pub second: u8,
    /// Microseconds.
    pub microsecond: u32,
}

impl UtcTime {
    /// The time `offset_s` seconds after the nominal 2000-01-01T00:00:00Z, rounded to the
    /// microsecond (days from the civil calendar as in H. Hinnant, "chrono-compatible low-level
    /// date algorithms").
    pub fn from_nominal(offset_s: f64) -> Result<UtcTime, SeismoError> {
        if !offset_s.is_finite() || offset_s.abs() > 3.0e11 {
            return Err(SeismoError::parameter("time", offset_s, "a finite time within ±9 500 years of 2000"));
        }
        let micros = (offset_s * 1e6).round() as i64;
        let (days, in_day) = (micros.div_euclid(86_400_000_000), micros.rem_euclid(86_400_000_000));
        let z = NOMINAL_DAYS + days;
        let era = z.div_euclid(146_097);
        let doe = z - era * 146_097;
        let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
        let doy_march = doe - (365 * yoe + yoe / 4 - yoe / 100);
        let mp = (5 * doy_march + 2) / 153;
        let day = (doy_march - (153 * mp + 2) / 5 + 1) as u8;
        let month = if mp < 10 { mp + 3 } else { mp - 9 } as u8;
        let year = (yoe + era * 400 + i64::from(month <= 2)) as i32;
        let leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
        const BEFORE: [u16; 12] = [0, 31, 59, 90, 120, 151, 181, 212, 243, 273, 304, 334];
        let day_of_year = BEFORE[month as usize - 1] + u16::from(day) + u16::from(leap && month > 2);
        let secs = in_day / 1_000_000;
        Ok(UtcTime {
            year,
            day_of_year,
            month,
            day,
            hour: (secs / 3600) as u8,
            minute: (secs / 60 % 60) as u8,
            second: (secs % 60) as u8,
            microsecond: (in_day % 1_000_000) as u32,
        })
    }

    /// ISO 8601 with microseconds and `Z`, e.g. `2000-01-01T00:00:12.345679Z`.
    pub fn iso(&self) -> String {
        format!(
            "{:04}-{:02}-{:02}T{:02}:{:02}:{:02}.{:06}Z",
            self.year, self.month, self.day, self.hour, self.minute, self.second, self.microsecond
        )
    }
}
