//! One checker for every section: collects every refused value with its field, value and allowed
//! range, so a file is refused once with all its errors.

use crate::error::{ConfigError, FieldError, Warning};

/// A plain enum of the domain that is written by name in files.
pub trait Named: Copy + 'static {
    /// Every value.
    const ALL: &'static [Self];
    /// Its name in files.
    fn name(self) -> &'static str;
}

pub use crate::numbers::{approx, num};

/// A value's text with a long decimal number written short (see [`num`]).
fn compact(text: String) -> String {
    match text.parse::<f64>() {
        Ok(v) if text.len() > 12 => num(v),
        _ => text,
    }
}

/// Collects every refused field.
#[derive(Default)]
pub struct Checker {
    errors: Vec<FieldError>,
    warnings: Vec<Warning>,
}

impl Checker {
    /// Refuses `field = value`, saying what is allowed (a number given as `value` is written
    /// short, see [`num`]).
    pub fn push(&mut self, field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) {
        let value = compact(value.to_string());
        self.errors.push(FieldError { field: field.into(), value, allowed: allowed.into() });
    }

    /// Accepts `field = value` with a warning: it runs, but could mislead (`why` says how).
    pub fn warn(&mut self, field: impl Into<String>, value: impl ToString, why: impl Into<String>) {
        let value = compact(value.to_string());
        self.warnings.push(Warning { field: field.into(), value, why: why.into() });
    }

    /// The warnings so far, taken out.
    pub fn take_warnings(&mut self) -> Vec<Warning> {
        std::mem::take(&mut self.warnings)
    }

    /// Accepts finite `v` with `lo (<|≤) v (<|≤) hi`.
    pub fn range(&mut self, field: &str, v: f64, lo: f64, lo_open: bool, hi: f64, hi_open: bool) -> bool {
        let ok = v.is_finite() && if lo_open { v > lo } else { v >= lo } && if hi_open { v < hi } else { v <= hi };
        if !ok {
            let name = field.rsplit('.').next().unwrap_or(field);
            let lo_s = if lo_open { "<" } else { "≤" };
            let hi_s = if hi_open { "<" } else { "≤" };
            let allowed = if hi.is_infinite() {
                format!("{} {lo_s} {name} (finite)", approx(lo))
            } else {
                format!("{} {lo_s} {name} {hi_s} {}", approx(lo), approx(hi))
            };
            self.push(field, v, allowed);
        }
        ok
    }

    /// Accepts finite `v > 0`.
    pub fn positive(&mut self, field: &str, v: f64) -> bool {
        self.range(field, v, 0.0, true, f64::INFINITY, true)
    }

    /// Accepts finite `v ≥ 0`.
    pub fn non_negative(&mut self, field: &str, v: f64) -> bool {
        self.range(field, v, 0.0, false, f64::INFINITY, true)
    }

    /// Accepts an integer count `lo ≤ v ≤ hi`.
    pub fn count(&mut self, field: &str, v: i64, lo: i64, hi: i64, why: &str) -> Option<usize> {
        if (lo..=hi).contains(&v) {
            Some(v as usize)
        } else {
            let name = field.rsplit('.').next().unwrap_or(field);
            self.push(field, v, format!("an integer, {lo} ≤ {name} ≤ {hi}{why}"));
            None
        }
    }

    /// The value of `T` named `name`, or refuses it listing the names allowed.
    pub fn named<T: Named>(&mut self, field: &str, name: &str) -> Option<T> {
        let found = T::ALL.iter().copied().find(|v| v.name() == name);
        if found.is_none() {
            let names: Vec<String> = T::ALL.iter().map(|v| format!("\"{}\"", v.name())).collect();
            self.push(field, format!("\"{name}\""), format!("one of {}", names.join(", ")));
        }
        found
    }

    /// The values of `T` named by `names` (refused ones left out).
    pub fn named_list<T: Named>(&mut self, field: &str, names: &[String]) -> Vec<T> {
        names.iter().enumerate().filter_map(|(i, n)| self.named(&format!("{field}[{i}]"), n)).collect()
    }

    /// Whether nothing was refused so far.
    pub fn is_clean(&self) -> bool {
        self.errors.is_empty()
    }

    /// Adds the errors and warnings of another checker.
    pub fn absorb(&mut self, other: Checker) {
        self.errors.extend(other.errors);
        self.warnings.extend(other.warnings);
    }

    /// `Ok` if nothing was refused.
    pub fn finish(self) -> Result<(), ConfigError> {
        if self.errors.is_empty() { Ok(()) } else { Err(ConfigError::Invalid(self.errors)) }
    }
}

macro_rules! named {
    ($($t:ty),*) => {$(
        impl Named for $t {
            const ALL: &'static [Self] = &<$t>::ALL;
            fn name(self) -> &'static str {
                <$t>::name(self)
            }
        }
    )*};
}

use stickslip_solver::geometry::{Face, NodeSet};
use stickslip_solver::scene::{Component, InterfaceQuantity, Kinematic, SettleMethod};
named!(Face, NodeSet, Component, InterfaceQuantity, Kinematic, SettleMethod);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_in_messages_are_short() {
        assert_eq!(num(5e-324), "5e-324");
        assert_eq!(num(1e300), "1e300");
        assert_eq!(num(-1e300), "-1e300");
        assert_eq!(num(0.32), "0.32");
        assert_eq!(num(0.1 + 0.2), "0.30000000000000004", "a value given is written exactly");
        assert_eq!(approx(1.9691060748051846e-6), "1.96911e-6");
        assert_eq!(approx(0.019691060748051846), "0.0196911");
        assert_eq!(approx(25.6), "25.6");
        assert_eq!(approx(2e6), "2e6");
        assert_eq!(approx(0.0), "0");
        assert_eq!(approx(-3.0), "-3");
        assert_eq!(approx(123456.7), "123457");
        let mut ck = Checker::default();
        ck.push("a.b", 1e300, "x");
        ck.range("a.c", -1e300, 0.0, true, 1.0 / 3.0, false);
        let e = ck.finish().unwrap_err().to_string();
        assert!(e.contains("a.b = 1e300") && e.contains("a.c = -1e300") && e.contains("≤ 0.333333"), "{e}");
    }
}
