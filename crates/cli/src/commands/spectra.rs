//! `stickslip spectra`: spectra and intensity measures of an outside accelerogram file.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_report::figures::RecordSpectraPlot;
use stickslip_seismo::accelerogram::{AccelUnit, Accelerogram, read_accelerogram};
use stickslip_seismo::catalogue::compact;
use stickslip_seismo::spectra::RecordSpectra;
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::intensity::Baseline;
use stickslip_seismo::spectra::response::{Reading, log_periods};
use stickslip_store::describe::{View, describe};
use stickslip_store::io::{read_parquet, write_parquet_atomic};
use stickslip_store::tables::records::Accelerograms;
use stickslip_store::tables::spectra::record_frames;

/// Units of a CSV accelerogram.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum CsvUnits {
    /// Standard gravity (9.80665 m/s²).
    G,
    /// m/s².
    #[value(name = "m/s2")]
    MS2,
    /// cm/s² (gal).
    #[value(name = "cm/s2")]
    CmS2,
}

/// Units of the PSA drawn in the figure.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub enum PlotUnits {
    /// Standard gravity (9.80665 m/s²).
    G,
    /// m/s².
    #[value(name = "m/s2")]
    MS2,
}

/// Arguments of `stickslip spectra`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The record: SAC (this product's or ObsPy's, either byte order), PEER .AT2, text with a
    /// time column and an acceleration column (comma, semicolon, tab or space separated; this
    /// product's CSV records), or a Parquet accelerograms table (with --record).
    pub record: PathBuf,
    /// Units of the acceleration in a text file, or in a SAC file that does not say its unit
    /// (IDEP unknown); a SAC acceleration trace (IDEP = IACC) is in nm/s².
    #[arg(long, value_enum, default_value = "m/s2")]
    pub units: CsvUnits,
    /// The record to take from a Parquet accelerograms table, e.g. S2-n36-z.
    #[arg(long)]
    pub record_name: Option<String>,
    /// The scale to take from a Parquet accelerograms table.
    #[arg(long, default_value = "model", value_parser = ["model", "prototype"])]
    pub scale: String,
    /// Units of the PSA in the figure (the tables are in m/s²).
    #[arg(long, value_enum, default_value = "g")]
    pub plot_units: PlotUnits,
    /// Damping ratios, comma separated.
    #[arg(long, value_delimiter = ',', default_value = "0.05", allow_negative_numbers = true)]
    pub dampings: Vec<f64>,
    /// Shortest period (s) [default: 2·Δt of the record].
    #[arg(long, allow_negative_numbers = true)]
    pub period_min_s: Option<f64>,
    /// Longest period (s) [default: half the record's duration].
    #[arg(long, allow_negative_numbers = true)]
    pub period_max_s: Option<f64>,
    /// Number of log-spaced periods.
    #[arg(long, default_value_t = 100)]
    pub period_count: usize,
    /// Read the samples band-limited (FFT resampled) instead of as straight lines.
    #[arg(long)]
    pub band_limited: bool,
    /// Remove a least-squares line from the velocity before integrating to displacement.
    #[arg(long)]
    pub baseline: bool,
    /// Output folder [default: reports/records/<file name>].
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// `stickslip spectra`.
pub fn run(a: Args) -> Result<()> {
    let unit = match a.units {
        CsvUnits::G => AccelUnit::G,
        CsvUnits::MS2 => AccelUnit::MetrePerSecond2,
        CsvUnits::CmS2 => AccelUnit::CentimetrePerSecond2,
    };
    stickslip_config::input::check_regular(&a.record, stickslip_config::input::MAX_INPUT_BYTES)
        .map_err(|why| anyhow::anyhow!("{}: {why}", a.record.display()))?;
    let is_parquet = a.record.extension().is_some_and(|e| e.eq_ignore_ascii_case("parquet"));
    let record = if is_parquet {
        parquet_record(&a.record, a.record_name.as_deref(), &a.scale)?
    } else {
        anyhow::ensure!(
            a.record_name.is_none(),
            "--record-name picks a record of a Parquet accelerograms table; {} holds one record",
            a.record.display()
        );
        read_accelerogram(&a.record, unit)?
    };
    let duration = record.dt * (record.accel.len().saturating_sub(1)) as f64;
    let usable = stated_usable_s(&record.description);
    let (tmin, tmax, periods) = periods_asked(&a, &record, usable)?;
    let approx = stickslip_config::check::approx;
    let reading = if a.band_limited { Reading::BandLimited } else { Reading::Linear };
    let baseline = if a.baseline { Baseline::Linear } else { Baseline::None };
    let r = RecordSpectra::compute(
        &record.accel,
        record.dt,
        &periods,
        &a.dampings,
        reading,
        baseline,
        Window::Rectangular,
    )?;
    let [mut spectra, mut fourier, mut intensity] =
        record_frames(&periods, &a.dampings, &r.sd, &r.fourier, &r.intensity)?;
    let mut stem = a.record.file_stem().and_then(|s| s.to_str()).unwrap_or("record").to_string();
    if let Some(name) = &a.record_name {
        stem = format!("{stem}_{name}_{}", a.scale);
    }
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from("reports").join("records").join(&stem));
    for (name, df) in [("spectra", &mut spectra), ("fourier", &mut fourier), ("intensity", &mut intensity)] {
        write_parquet_atomic(df, &out.join(format!("{name}.parquet")))?;
    }
    outln!(
        "{}: {} samples every {:.6e} s ({:.4} s){}",
        a.record.display(),
        record.accel.len(),
        record.dt,
        duration,
        if record.description.is_empty() { String::new() } else { format!(" — {}", record.description) }
    );
    if let Some((lo, hi)) = usable {
        let outside = tmin < lo * (1.0 - 1e-6) || tmax > hi * (1.0 + 1e-6);
        outln!(
            "usable from {} s to {} s (the record's header){}",
            approx(lo),
            approx(hi),
            if outside {
                ": PSA at the periods asked outside that range is computed but does not describe the ground \
                 (a lattice record, for one, holds nothing real above the lattice's f_max)"
            } else {
                ": the spectra below keep to it (--period-min-s, --period-max-s to ask for others)"
            }
        );
    }
    outln!("{}", describe(&out.join("intensity.parquet"), &View { rows: 1, columns: vec![], transpose: true })?);
    let figure = out.join("spectra.png");
    stickslip_report::figures::record_figure(
        &figure,
        &RecordSpectraPlot {
            title: &format!("Spectra of {stem}"),
            periods: &periods,
            dampings: &a.dampings,
            psa_m_s2: &r
                .sd
                .iter()
                .enumerate()
                .map(|(i, sd)| {
                    let w = 2.0 * std::f64::consts::PI / periods[i % periods.len()];
                    w * w * sd
                })
                .collect::<Vec<f64>>(),
            fourier: (&r.fourier.frequency_hz, &r.fourier.amplitude),
            in_g: matches!(a.plot_units, PlotUnits::G),
        },
    )?;
    outln!(
        "spectra ({} periods from {tmin:.4e} s to {tmax:.4e} s, {} damping) → {} (spectra, fourier and intensity \
         tables; the figure spectra.png)",
        periods.len(),
        a.dampings.iter().map(|d| format!("{}%", compact(100.0 * d))).collect::<Vec<_>>().join(", "),
        out.display()
    );
    Ok(())
}

/// The periods asked (`--period-min-s`, `--period-max-s`, `--period-count`) or, by default, the
/// record's `usable` range stated in its header within 2·Δt … half its duration; refused when
/// they are not a range of positive periods an oscillator can read, or the dampings not in
/// [0, 1). Returns the shortest and longest periods and the log-spaced periods.
fn periods_asked(a: &Args, record: &Accelerogram, usable: Option<(f64, f64)>) -> Result<(f64, f64, Vec<f64>)> {
    let duration = record.dt * (record.accel.len().saturating_sub(1)) as f64;
    // A record of this product says in its header the periods it describes the ground over (a
    // lattice record holds nothing real above the lattice's f_max): the default range keeps to
    // them, and periods asked outside are computed with a warning.
    let tmin = a.period_min_s.unwrap_or(usable.map_or(2.0 * record.dt, |u| u.0.max(2.0 * record.dt)));
    let tmax = a.period_max_s.unwrap_or(usable.map_or(0.5 * duration, |u| u.1.min(0.5 * duration)));
    let approx = stickslip_config::check::approx;
    anyhow::ensure!(
        tmin > 0.0 && tmax >= tmin && tmax.is_finite(),
        "--period-min-s = {}, --period-max-s = {} are not allowed: 0 < period-min-s ≤ period-max-s (finite)",
        approx(tmin),
        approx(tmax)
    );
    // Far below the sampling interval an oscillator reads only the peak acceleration, and costs
    // steps in proportion to the interval over the period.
    anyhow::ensure!(
        tmin >= 0.01 * record.dt,
        "--period-min-s = {} is not allowed: at least a hundredth of the record's sampling interval ({} s)",
        approx(tmin),
        approx(0.01 * record.dt)
    );
    anyhow::ensure!(a.period_count >= 1, "--period-count = 0 is not allowed: at least 1");
    anyhow::ensure!(
        a.period_count <= 10_000,
        "--period-count = {} is not allowed: at most 10000 periods",
        a.period_count
    );
    anyhow::ensure!(a.period_count == 1 || tmax > tmin, "--period-count > 1 needs period-min-s < period-max-s");
    for d in &a.dampings {
        anyhow::ensure!((0.0..1.0).contains(d), "--dampings: {d} is not allowed: 0 ≤ damping < 1");
    }
    Ok((tmin, tmax, log_periods(tmin, tmax, a.period_count)))
}

/// The usable periods (s) a record's header states: `usable A … B s` (a set's files) or
/// `usable A-B Hz` (a run's record files); `None` for other records.
fn stated_usable_s(description: &str) -> Option<(f64, f64)> {
    let rest = &description[description.find("usable ")? + "usable ".len()..];
    let words: Vec<&str> = rest.split_whitespace().take(4).collect();
    let num = |w: &str| w.trim_end_matches([',', ')']).parse::<f64>().ok().filter(|v| *v > 0.0 && v.is_finite());
    let band = match words.as_slice() {
        [a, "…", b, unit, ..] if unit.starts_with('s') => (num(a)?, num(b)?),
        [ab, unit, ..] if unit.starts_with("Hz") => {
            let (a, b) = ab.split_once('-')?;
            (1.0 / num(b)?, 1.0 / num(a)?)
        }
        _ => return None,
    };
    (band.0 < band.1).then_some(band)
}

/// One record of a Parquet accelerograms table (a seed's part, or any table with its columns).
fn parquet_record(path: &std::path::Path, name: Option<&str>, scale: &str) -> Result<Accelerogram> {
    let acc = Accelerograms::read(&read_parquet(path)?)?;
    let mut names: Vec<&str> = acc.record.iter().map(String::as_str).collect();
    names.sort_unstable();
    names.dedup();
    let Some(name) = name else {
        anyhow::bail!(
            "{} is a table of {} records: name one with --record-name ({})",
            path.display(),
            names.len(),
            names.iter().take(12).copied().collect::<Vec<_>>().join(", ") + if names.len() > 12 { ", …" } else { "" }
        );
    };
    // The table holds each record once, at model scale (the prototype's follows by similarity).
    anyhow::ensure!(
        scale == "model",
        "{}: the accelerograms table holds records at model scale only: give --scale model (a prototype record \
         is the model's with times ×λ and accelerations ÷λ), or read the record's AT2/SAC file",
        path.display()
    );
    let rows: Vec<usize> = (0..acc.record.len()).filter(|&i| acc.record[i] == name).collect();
    anyhow::ensure!(
        rows.len() >= 2,
        "{}: no record {name:?} at {scale} scale (its records: {})",
        path.display(),
        names.join(", ")
    );
    let mut seeds: Vec<u64> = rows.iter().map(|&i| acc.seed[i]).collect();
    seeds.dedup();
    anyhow::ensure!(seeds.len() == 1, "{}: record {name:?} of several seeds: give one seed's part", path.display());
    let t: Vec<f64> = rows.iter().map(|&i| acc.time_s[i]).collect();
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    anyhow::ensure!(
        t.windows(2).all(|w| ((w[1] - w[0]) - dt).abs() <= 1e-6 * dt),
        "{}: record {name:?} is not evenly sampled",
        path.display()
    );
    Ok(Accelerogram {
        dt,
        accel: rows.iter().map(|&i| acc.acceleration_m_s2[i]).collect(),
        description: format!("seed {} {name} ({scale} scale)", seeds[0]),
    })
}

#[cfg(test)]
mod tests {
    use super::stated_usable_s;

    #[test]
    fn the_usable_band_is_read_from_either_header() {
        let set = "stickslip scenario-m6 set record 1 of 11: seed 6 station x (HN2), Mw 6.45, R_rup 19.8 km, usable \
                   0.4310 … 12.0 s (band-pass 0.0666 … 2.0000 Hz), matched to ASCE 7-16";
        assert_eq!(stated_usable_s(set), Some((0.431, 12.0)));
        let record = "stickslip paper seed 1 record S2-n36-z (model scale, lambda = 1): node 36 at (1, 2, 3) m, \
                      component z, band-pass 0.5000-400.0000 Hz, usable 0.6250-50.0000 Hz";
        assert_eq!(stated_usable_s(record), Some((0.02, 1.6)));
        assert_eq!(stated_usable_s("a record from elsewhere"), None);
        assert_eq!(stated_usable_s("usable 5 … 1 s"), None);
    }
}
