//! Station and rupture-time files laid out as the SCEC/USGS spontaneous-rupture code verification
//! project asks for them (Harris et al. 2009; "Uploading data for TPV5", Barall 2007), so that a
//! fault scene's results can be compared with other dynamic-rupture codes' by the tools written
//! for those benchmarks.
//!
//! Every file: header lines starting with `#` (problem, author, date, code, element size, time
//! step, number of steps, location, one `# Column #k = …` line per column), one line naming the
//! fields (not starting with `#`), then one line per time step. Data in C's `%14.6E` form, time in
//! `%20.12E`; units MKS except stresses, in MPa.
//!
//! - **On the fault** ([`on_fault_text`]): `t h-slip h-slip-rate h-shear-stress v-slip
//!   v-slip-rate v-shear-stress`; horizontal = along strike, positive right-lateral; vertical =
//!   along dip, positive downward (the far side down relative to the near side); under
//!   rate-and-state friction also `n-stress log-theta` (MPa, compression positive; log₁₀ θ in
//!   seconds), as TPV101–104 ask.
//! - **Off the fault** ([`off_fault_text`]): `t h-disp h-vel v-disp v-vel n-disp n-vel`;
//!   horizontal along strike (positive to the right seen from the near side), vertical positive
//!   downward, normal positive from the near side toward the far side.
//! - **Rupture times** ([`cplot_text`]): `j k t`, along strike and down dip from the benchmark's
//!   origin (m) and the time the slip rate first exceeded 1 mm/s (s), `1.0E+09` where it never did.
//!
//! Names ([`fault_station_name`], [`body_station_name`]): `faultst<±strike>dp<depth>` and
//! `body<normal>st<±strike>dp<depth>`, every distance in units of 100 m, three digits.

/// What a file's header says of the run.
#[derive(Clone, Debug, PartialEq)]
pub struct Header<'a> {
    /// The benchmark problem (`TPV5`) or the pipeline that made the file.
    pub problem: &'a str,
    /// The code and its version.
    pub code: &'a str,
    /// The date the file was written (`YYYY/MM/DD`).
    pub date: &'a str,
    /// Node spacing (m).
    pub element_size_m: f64,
    /// Where the station is, in words.
    pub location: &'a str,
}

/// `v` as C's `%.{digits}E`: `7.000000E+01` for 70 with six digits.
pub fn c_exp(v: f64, digits: usize) -> String {
    if !v.is_finite() {
        return format!("{v}");
    }
    // −0 prints as 0.
    let v = if v == 0.0 { 0.0 } else { v };
    let s = format!("{v:.digits$E}");
    let (mantissa, exponent) = s.split_once('E').expect("an exponent");
    let e: i32 = exponent.parse().expect("an integer exponent");
    format!("{mantissa}E{}{:02}", if e < 0 { '-' } else { '+' }, e.abs())
}

/// A distance in units of 100 m, three digits, signed when `signed` (`-120`, `045`, `000`).
fn hectometres(v_m: f64, signed: bool) -> String {
    let k = (v_m / 100.0).round() as i64;
    if signed && k < 0 { format!("-{:03}", -k) } else { format!("{k:03}") }
}

/// `faultst<±strike>dp<depth>` of an on-fault station `strike_m` along strike from the origin and
/// `depth_m` down dip: `faultst-120dp075` for (−12 km, 7.5 km).
pub fn fault_station_name(strike_m: f64, depth_m: f64) -> String {
    format!("faultst{}dp{}", hectometres(strike_m, true), hectometres(depth_m, false))
}

/// `body<normal>st<±strike>dp<depth>` of an off-fault station `normal_m` from the fault (positive on
/// the far side): `body030st120dp000` for (3 km, 12 km, 0).
pub fn body_station_name(normal_m: f64, strike_m: f64, depth_m: f64) -> String {
    format!("body{}st{}dp{}", hectometres(normal_m, true), hectometres(strike_m, true), hectometres(depth_m, false))
}

fn header_text(h: &Header<'_>, time_s: &[f64], columns: &[&str]) -> String {
    let steps: Vec<f64> = time_s.windows(2).map(|w| w[1] - w[0]).collect();
    let dt = if steps.is_empty() { 0.0 } else { steps.iter().sum::<f64>() / steps.len() as f64 };
    let mut out = String::new();
    out.push_str("# This is the file header:\n");
    out.push_str(&format!("# problem={}\n", h.problem));
    out.push_str("# author=stickslip\n");
    out.push_str(&format!("# date={}\n", h.date));
    out.push_str(&format!("# code={}\n", h.code));
    out.push_str(&format!("# element_size={} m\n", h.element_size_m));
    out.push_str(&format!("# time_step={}\n", c_exp(dt, 12)));
    out.push_str(&format!("# num_time_steps={}\n", time_s.len()));
    out.push_str(&format!("# location= {}\n", h.location));
    for (k, c) in columns.iter().enumerate() {
        out.push_str(&format!("# Column #{} = {c}\n", k + 1));
    }
    out.push_str("#\n# The line below lists the names of the data fields:\n");
    out
}

fn rows(out: &mut String, time_s: &[f64], series: &[&[f64]]) {
    for s in series {
        assert_eq!(s.len(), time_s.len(), "every series as long as the time");
    }
    for (i, t) in time_s.iter().enumerate() {
        out.push_str(&c_exp(*t, 12));
        for s in series {
            out.push(' ');
            out.push_str(&c_exp(s[i], 6));
        }
        out.push('\n');
    }
}

/// An on-fault station's history: slip, slip rate and shear stress along strike (`h`, positive
/// right-lateral) and along dip (`v`, positive downward), every series as long as `time_s`.
#[derive(Clone, Copy, Debug)]
pub struct OnFault<'a> {
    /// Time (s).
    pub time_s: &'a [f64],
    /// Slip (m), along strike and along dip.
    pub slip_m: [&'a [f64]; 2],
    /// Slip rate (m/s).
    pub slip_rate_m_s: [&'a [f64]; 2],
    /// Shear stress (Pa).
    pub shear_stress_pa: [&'a [f64]; 2],
    /// Under rate-and-state friction (TPV101–104's layout): the normal stress (Pa, compression
    /// positive) and the state θ (s), written `n-stress` (MPa) and `log-theta` (log₁₀ θ).
    pub rate_state: Option<[&'a [f64]; 2]>,
}

/// The text of an on-fault station file.
pub fn on_fault_text(h: &Header<'_>, s: &OnFault<'_>) -> String {
    let mut columns = vec![
        "Time (s)",
        "horizontal slip (m)",
        "horizontal slip rate (m/s)",
        "horizontal shear stress (MPa)",
        "vertical slip (m)",
        "vertical slip rate (m/s)",
        "vertical shear stress (MPa)",
    ];
    if s.rate_state.is_some() {
        columns.extend(["normal stress (MPa)", "log10 of state variable (log10 s)"]);
    }
    let mut out = header_text(h, s.time_s, &columns);
    out.push_str("t h-slip h-slip-rate h-shear-stress v-slip v-slip-rate v-shear-stress");
    out.push_str(if s.rate_state.is_some() { " n-stress log-theta\n" } else { "\n" });
    out.push_str("#\n# Here is the time-series data.\n");
    let mpa = |v: &[f64]| v.iter().map(|x| x * 1e-6).collect::<Vec<f64>>();
    let (th, tv) = (mpa(s.shear_stress_pa[0]), mpa(s.shear_stress_pa[1]));
    let mut series: Vec<&[f64]> = vec![s.slip_m[0], s.slip_rate_m_s[0], &th, s.slip_m[1], s.slip_rate_m_s[1], &tv];
    let extra =
        s.rate_state.map(|[normal, theta]| (mpa(normal), theta.iter().map(|t| t.log10()).collect::<Vec<f64>>()));
    if let Some((normal, log_theta)) = &extra {
        series.extend([&normal[..], &log_theta[..]]);
    }
    rows(&mut out, s.time_s, &series);
    out
}

/// An off-fault station's history: displacement and velocity along strike (`h`), down (`v`) and
/// across the fault (`n`).
#[derive(Clone, Copy, Debug)]
pub struct OffFault<'a> {
    /// Time (s).
    pub time_s: &'a [f64],
    /// Displacement (m): along strike, down, across.
    pub displacement_m: [&'a [f64]; 3],
    /// Velocity (m/s), the same components.
    pub velocity_m_s: [&'a [f64]; 3],
}

/// The text of an off-fault station file.
pub fn off_fault_text(h: &Header<'_>, s: &OffFault<'_>) -> String {
    let mut out = header_text(
        h,
        s.time_s,
        &[
            "Time (s)",
            "horizontal displacement (m)",
            "horizontal velocity (m/s)",
            "vertical displacement (m)",
            "vertical velocity (m/s)",
            "normal displacement (m)",
            "normal velocity (m/s)",
        ],
    );
    out.push_str("t h-disp h-vel v-disp v-vel n-disp n-vel\n");
    out.push_str("#\n# Here is the time-series data.\n");
    let (d, v) = (s.displacement_m, s.velocity_m_s);
    rows(&mut out, s.time_s, &[d[0], v[0], d[1], v[1], d[2], v[2]]);
    out
}

/// The rupture-time (contour plot) file: every fault node at `(strike, down dip)` from the
/// benchmark's origin (m) with its rupture time (s; NaN where it never ruptured, written
/// `1.0E+09`).
pub fn cplot_text(h: &Header<'_>, nodes: &[([f64; 2], f64)]) -> String {
    let mut out = String::new();
    out.push_str("# This is the file header:\n");
    out.push_str(&format!("# problem={}\n", h.problem));
    out.push_str("# author=stickslip\n");
    out.push_str(&format!("# date={}\n", h.date));
    out.push_str(&format!("# code={}\n", h.code));
    out.push_str(&format!("# element_size={} m\n", h.element_size_m));
    out.push_str("# Column #1 = horizontal coordinate, distance along strike (m)\n");
    out.push_str("# Column #2 = vertical coordinate, distance down-dip (m)\n");
    out.push_str("# Column #3 = rupture time (s)\n");
    out.push_str("#\n# The line below lists the names of the data fields.\n");
    out.push_str("j k t\n");
    out.push_str("#\n# Here is the rupture history\n");
    for ([j, k], t) in nodes {
        let t = if t.is_finite() { *t } else { 1.0e9 };
        out.push_str(&format!("{} {} {}\n", c_exp(*j, 6), c_exp(*k, 6), c_exp(t, 6)));
    }
    out
}

/// The numbers of a file in this layout: the field names and one row per time step.
pub fn read_table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines().filter(|l| !l.trim().is_empty() && !l.starts_with('#'));
    let names = lines.next().map_or_else(Vec::new, |l| l.split_whitespace().map(str::to_string).collect());
    let rows = lines.map(|l| l.split_whitespace().map(|v| v.parse().unwrap_or(f64::NAN)).collect()).collect();
    (names, rows)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_are_written_as_c_does() {
        assert_eq!(c_exp(70.0, 6), "7.000000E+01");
        assert_eq!(c_exp(0.0, 6), "0.000000E+00");
        assert_eq!(c_exp(-1.25e-7, 6), "-1.250000E-07");
        assert_eq!(c_exp(0.05, 12), "5.000000000000E-02");
        assert_eq!(c_exp(1.0e9, 6), "1.000000E+09");
        assert_eq!(c_exp(3.2e123, 2), "3.20E+123");
    }

    #[test]
    fn station_names_are_the_benchmarks() {
        assert_eq!(fault_station_name(-12000.0, 7500.0), "faultst-120dp075");
        assert_eq!(fault_station_name(0.0, 0.0), "faultst000dp000");
        assert_eq!(fault_station_name(4500.0, 3000.0), "faultst045dp030");
        assert_eq!(body_station_name(3000.0, 12000.0, 0.0), "body030st120dp000");
        assert_eq!(body_station_name(3000.0, -12000.0, 7500.0), "body030st-120dp075");
    }

    #[test]
    fn files_read_back_in_their_units() {
        let t = [0.0, 0.01, 0.02];
        let (z, s, r) = ([0.0; 3], [0.0, 0.1, 0.3], [0.0, 10.0, 20.0]);
        let tau = [70e6, 68e6, 63e6];
        let h =
            Header { problem: "TPV5", code: "stickslip 0", date: "2026/11/26", element_size_m: 100.0, location: "x" };
        let text_with = |rate_state| {
            let s = OnFault {
                time_s: &t,
                slip_m: [&s, &z],
                slip_rate_m_s: [&r, &z],
                shear_stress_pa: [&tau, &z],
                rate_state,
            };
            on_fault_text(&h, &s)
        };
        let text = text_with(None);
        assert!(text.contains("# num_time_steps=3\n") && text.contains("# time_step=1.000000000000E-02\n"));
        let (names, rows) = read_table(&text);
        assert_eq!(names, ["t", "h-slip", "h-slip-rate", "h-shear-stress", "v-slip", "v-slip-rate", "v-shear-stress"]);
        assert_eq!(rows.len(), 3);
        assert_eq!(rows[2], vec![0.02, 0.3, 20.0, 63.0, 0.0, 0.0, 0.0]);
        let cplot = cplot_text(&h, &[([-100.0, 7500.0], 0.25), ([15000.0, 0.0], f64::NAN)]);
        let (names, rows) = read_table(&cplot);
        assert_eq!(names, ["j", "k", "t"]);
        assert_eq!(rows, vec![vec![-100.0, 7500.0, 0.25], vec![15000.0, 0.0, 1.0e9]]);
        // Under rate and state, TPV101's two more columns: n-stress (MPa) and log-theta (log₁₀ s).
        let (normal, theta) = ([120e6; 3], [1.606238999213454e9, 1e3, 0.5]);
        let text = text_with(Some([&normal, &theta]));
        let (names, rows) = read_table(&text);
        assert_eq!(&names[7..], ["n-stress", "log-theta"]);
        assert_eq!(rows[0][7..], [120.0, 9.20581]);
        assert_eq!(rows[1][7..], [120.0, 3.0]);
        assert!(text.contains("# Column #9 = log10 of state variable"));
    }
}
