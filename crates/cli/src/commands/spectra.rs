//! `stickslip spectra`: spectra and intensity measures of an outside accelerogram file.

use std::path::PathBuf;

use anyhow::Result;
use stickslip_seismo::accelerogram::{AccelUnit, read_accelerogram};
use stickslip_seismo::spectra::RecordSpectra;
use stickslip_seismo::spectra::fourier::Window;
use stickslip_seismo::spectra::intensity::Baseline;
use stickslip_seismo::spectra::response::{Reading, log_periods};
use stickslip_store::describe::{View, describe};
use stickslip_store::io::write_parquet_atomic;
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

/// Arguments of `stickslip spectra`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The record: a PEER .AT2 file, or a CSV file (time in s, then acceleration).
    pub record: PathBuf,
    /// Units of the acceleration column of a CSV file.
    #[arg(long, value_enum, default_value = "m/s2")]
    pub units: CsvUnits,
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
    let record = read_accelerogram(&a.record, unit)?;
    let duration = record.dt * (record.accel.len().saturating_sub(1)) as f64;
    let tmin = a.period_min_s.unwrap_or(2.0 * record.dt);
    let tmax = a.period_max_s.unwrap_or(0.5 * duration);
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
    let periods = log_periods(tmin, tmax, a.period_count);
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
    let stem = a.record.file_stem().and_then(|s| s.to_str()).unwrap_or("record").to_string();
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from("reports").join("records").join(&stem));
    for (name, df) in [("spectra", &mut spectra), ("fourier", &mut fourier), ("intensity", &mut intensity)] {
        write_parquet_atomic(df, &out.join(format!("{name}.parquet")))?;
    }
    println!(
        "{}: {} samples every {:.6e} s ({:.4} s){}",
        a.record.display(),
        record.accel.len(),
        record.dt,
        duration,
        if record.description.is_empty() { String::new() } else { format!(" — {}", record.description) }
    );
    println!("{}", describe(&out.join("intensity.parquet"), &View { rows: 1, columns: vec![], transpose: true })?);
    println!(
        "spectra ({} periods from {tmin:.4e} s to {tmax:.4e} s, dampings {:?}) → {}",
        periods.len(),
        a.dampings,
        out.display()
    );
    Ok(())
}
