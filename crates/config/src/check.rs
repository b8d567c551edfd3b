//! One checker for every section: collects every refused value with its field, value and allowed
//! range, so a file is refused once with all its errors.

use crate::error::{ConfigError, FieldError};

/// A plain enum of the domain that is written by name in files.
pub trait Named: Copy + 'static {
    /// Every value.
    const ALL: &'static [Self];
    /// Its name in files.
    fn name(self) -> &'static str;
}

/// Collects every refused field.
#[derive(Default)]
pub struct Checker {
    errors: Vec<FieldError>,
}

impl Checker {
    /// Refuses `field = value`, saying what is allowed.
    pub fn push(&mut self, field: impl Into<String>, value: impl ToString, allowed: impl Into<String>) {
        self.errors.push(FieldError { field: field.into(), value: value.to_string(), allowed: allowed.into() });
    }

    /// Accepts finite `v` with `lo (<|≤) v (<|≤) hi`.
    pub fn range(&mut self, field: &str, v: f64, lo: f64, lo_open: bool, hi: f64, hi_open: bool) -> bool {
        let ok = v.is_finite() && if lo_open { v > lo } else { v >= lo } && if hi_open { v < hi } else { v <= hi };
        if !ok {
            let name = field.rsplit('.').next().unwrap_or(field);
            let lo_s = if lo_open { "<" } else { "≤" };
            let hi_s = if hi_open { "<" } else { "≤" };
            let allowed = if hi.is_infinite() {
                format!("{lo} {lo_s} {name} (finite)")
            } else {
                format!("{lo} {lo_s} {name} {hi_s} {hi}")
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

    /// Adds the errors of another checker.
    pub fn absorb(&mut self, other: Checker) {
        self.errors.extend(other.errors);
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
