//! Numbers as a reader wants them in messages: short, never 300 digits.

/// `v` as short as it reads: `{}` when that is short, else `{:e}` (`1e300`, `5e-324`, not 300
/// digits).
pub fn num(v: f64) -> String {
    let plain = format!("{v}");
    if plain.len() <= 12 {
        return plain;
    }
    let sci = format!("{v:e}");
    if sci.len() < plain.len() { sci } else { plain }
}

/// `v` to 6 significant digits, for a bound or a derived number in a message: plain between
/// 1e-4 and 1e6 (`0.032`, `25.6`), else with an exponent (`1.96911e-6`, `2e6`).
pub fn approx(v: f64) -> String {
    if v == 0.0 || !v.is_finite() {
        return format!("{v}");
    }
    let sci = format!("{v:.5e}");
    let (mantissa, exp) = sci.split_once('e').unwrap_or((&sci, "0"));
    let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
    let exp: i32 = exp.parse().unwrap_or(0);
    if (-4..6).contains(&exp) {
        let rounded: f64 = format!("{mantissa}e{exp}").parse().unwrap_or(v);
        format!("{rounded}")
    } else {
        format!("{mantissa}e{exp}")
    }
}
