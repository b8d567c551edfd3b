//! Fault station files laid out as the SCEC SEAS benchmarks (Erickson et al., 2020; BP1–BP7)
//! ask participants to upload them, so that a station's history can be read by the tools written
//! for those benchmarks beside other earthquake-cycle codes.
//!
//! The layout: header lines starting with `#` (problem, code, element size, location, time-step
//! range and count, one `# Column #k = …` line per column), a line naming the fields, a `#` line,
//! then one line per time with every value in `%.15E`-style scientific notation, separated by
//! spaces. The columns follow BP3's station files without its state variable (the friction laws
//! here have none):
//!
//! | field | unit |
//! |---|---|
//! | `t` | s |
//! | `slip` | m |
//! | `slip_rate` | log10 of |V| in m/s (|V| floored at [`RATE_FLOOR_M_S`]: a sticking node has V = 0) |
//! | `shear_stress` | MPa |
//! | `normal_stress` | MPa (compression positive) |
//!
//! File names follow the benchmarks' `fltst_strk<±along strike>dp<down dip>`; here the along-
//! strike distance is x and the across-fault distance y, both in millimetres at model scale
//! ([`station_file_name`]).

/// The smallest |slip rate| written (m/s): log10 of it (−20) stands for a node at rest.
pub const RATE_FLOOR_M_S: f64 = 1e-20;

/// What the header of one station file says.
#[derive(Clone, Debug, PartialEq)]
pub struct StationHeader<'a> {
    /// The problem (pipeline name, seed).
    pub problem: &'a str,
    /// The code and its version.
    pub code: &'a str,
    /// Element size (m): the module side.
    pub element_size_m: f64,
    /// Where the station is, in words.
    pub location: &'a str,
}

/// One station's history, every series as long as `time_s`.
#[derive(Clone, Copy, Debug)]
pub struct StationSeries<'a> {
    /// Time (s).
    pub time_s: &'a [f64],
    /// Slip (m).
    pub slip_m: &'a [f64],
    /// Slip rate (m/s).
    pub slip_rate_m_s: &'a [f64],
    /// Shear stress (Pa).
    pub shear_stress_pa: &'a [f64],
    /// Normal stress (Pa).
    pub normal_stress_pa: &'a [f64],
}

/// The benchmark file name of a station at `x_m` along strike and `y_m` across (model metres,
/// written in millimetres): `fltst_strk+0200dp050` for (0.2, 0.05) m.
pub fn station_file_name(x_m: f64, y_m: f64) -> String {
    format!("fltst_strk{:+05}dp{:03}", (x_m * 1e3).round() as i64, (y_m * 1e3).round() as i64)
}

/// The text of one station file.
pub fn station_text(h: &StationHeader<'_>, s: &StationSeries<'_>) -> String {
    let n = s.time_s.len();
    for v in [s.slip_m, s.slip_rate_m_s, s.shear_stress_pa, s.normal_stress_pa] {
        assert_eq!(v.len(), n, "every series as long as the time");
    }
    let steps: Vec<f64> = s.time_s.windows(2).map(|w| w[1] - w[0]).collect();
    let (lo, hi) = steps.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), &d| (lo.min(d), hi.max(d)));
    let lo = if steps.is_empty() { 0.0 } else { lo };
    let mut out = String::with_capacity(100 * (n + 20));
    out.push_str("# This is the file header:\n");
    out.push_str(&format!("# problem={}\n", h.problem));
    out.push_str(&format!("# code={}\n", h.code));
    out.push_str(&format!("# element_size={:.6E} m\n", h.element_size_m));
    out.push_str(&format!("# location={}\n", h.location));
    out.push_str(&format!("# minimum_time_step={lo:.6E}\n"));
    out.push_str(&format!("# maximum_time_step={hi:.6E}\n"));
    out.push_str(&format!("# num_time_steps={n}\n"));
    out.push_str("# Column #1 = Time (s)\n");
    out.push_str("# Column #2 = Slip (m)\n");
    out.push_str(&format!("# Column #3 = Slip rate (log10 m/s; |V| floored at {RATE_FLOOR_M_S:.0E} m/s)\n"));
    out.push_str("# Column #4 = Shear stress (MPa)\n");
    out.push_str("# Column #5 = Normal stress (MPa, compression positive)\n");
    out.push_str("# (no state column: the friction laws have no state variable)\n");
    out.push_str("#\n# The line below lists the names of the data fields:\n");
    out.push_str("t slip slip_rate shear_stress normal_stress\n");
    out.push_str("#\n# Here is the time-series data.\n");
    for i in 0..n {
        let rate = s.slip_rate_m_s[i].abs().max(RATE_FLOOR_M_S).log10();
        out.push_str(&format!(
            "{:.15E} {:.15E} {:.15E} {:.15E} {:.15E}\n",
            s.time_s[i],
            s.slip_m[i],
            rate,
            s.shear_stress_pa[i] * 1e-6,
            s.normal_stress_pa[i] * 1e-6
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The layout a SEAS reader expects: `#` header, the field-name line, then numbers only; the
    /// values read back in the stated units.
    #[test]
    fn station_file_reads_back() {
        let t = [0.0, 1e-5, 3e-5];
        let slip = [0.0, 1e-6, 3e-6];
        let rate = [0.0, 0.1, -0.2];
        let tau = [5e4, 4e4, 3e4];
        let sigma = [1e5, 1e5, 1.1e5];
        let h = StationHeader { problem: "p", code: "stickslip", element_size_m: 0.1, location: "x" };
        let s = StationSeries {
            time_s: &t,
            slip_m: &slip,
            slip_rate_m_s: &rate,
            shear_stress_pa: &tau,
            normal_stress_pa: &sigma,
        };
        let text = station_text(&h, &s);
        let mut lines = text.lines().skip_while(|l| l.starts_with('#'));
        assert_eq!(lines.next(), Some("t slip slip_rate shear_stress normal_stress"));
        let rows: Vec<Vec<f64>> = lines
            .filter(|l| !l.starts_with('#'))
            .map(|l| l.split_whitespace().map(|v| v.parse().unwrap()).collect())
            .collect();
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[0][2], -20.0);
        assert!((rows[1][2] - (-1.0)).abs() < 1e-14);
        assert!((rows[2][2] - 0.2f64.log10()).abs() < 1e-14);
        assert!((rows[2][3] - 0.03).abs() < 1e-15 && (rows[2][4] - 0.11).abs() < 1e-15);
        assert!(text.contains("# num_time_steps=3\n") && text.contains("# minimum_time_step=1.000000E-5\n"));
        assert_eq!(station_file_name(0.2, 0.05), "fltst_strk+0200dp050");
        assert_eq!(station_file_name(-0.1, 0.0), "fltst_strk-0100dp000");
    }
}
