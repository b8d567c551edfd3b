//! `stickslip-bench part-a`, `part-a-observed` and `part-a-stations`: Part A of the Broadband
//! Platform's validation (a scenario against a real earthquake's recordings), printed.

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::{Context, Result};
use stickslip_lab::part_a::figure::part_a_figure;
use stickslip_lab::part_a::geometry::{LatLon, Trace, place};
use stickslip_lab::part_a::observed::{observed_station, read_csv, read_folder, write_csv};
use stickslip_lab::part_a::simulated::read_scenario;
use stickslip_lab::part_a::{BiasRow, PGA, PartA, part_a, residual, simulated_as_observed};
use stickslip_store::Folder;

/// Where the Landers recordings come from, for the observed CSV's header.
pub const LANDERS_SOURCE: &str = "Recordings of the 1992 Landers earthquake (Mw 7.22): PEER NGA-West2 / CSMIP strong-motion \
records as distributed in the SCEC Broadband Platform's public repository (github.com/SCECcode/bbp, \
commit f15b5a76f59c62df623daf47b2a944e5e58b8622, bbp/tests/ref_data/sdsu/MOGof/ref_inputs/landers_obs/*.bbp; \
the records themselves are not copied here). lon/lat, R_rup (the files' \"closest distance to fault\"), \
V_S30 and the usable band's corners are those of each file's header.";

/// `stickslip-bench part-a`'s arguments.
#[derive(clap::Args, Debug)]
pub struct PartAArgs {
    /// Output folder of the scenario's run (its gathered source, stations and station_spectra).
    pub folder: PathBuf,
    /// The observed RotD50 (CSV of `part-a-observed`).
    #[arg(long)]
    pub observed: PathBuf,
    /// The figure (PNG) [default: <folder>/figures/part_a.png].
    #[arg(long)]
    pub figure: Option<PathBuf>,
}

/// `stickslip-bench part-a-observed`'s arguments.
#[derive(clap::Args, Debug)]
pub struct ObservedArgs {
    /// Folder of the recordings (`.bbp` files: time, N-S, E-W, U-D acceleration in cm/s²).
    pub recordings: PathBuf,
    /// The CSV written.
    #[arg(long)]
    pub out: PathBuf,
    /// Where the recordings come from (the CSV's header) [default: the Landers records of the
    /// Broadband Platform's repository].
    #[arg(long)]
    pub source: Option<String>,
}

/// `stickslip-bench part-a-stations`' arguments.
#[derive(clap::Args, Debug)]
pub struct StationsArgs {
    /// The observed RotD50 (CSV of `part-a-observed`: its stations' lon, lat, R_rup, V_S30).
    pub observed: PathBuf,
    /// The fault trace's southern end: latitude,longitude (degrees).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true, required = true)]
    pub south: Vec<f64>,
    /// Its northern end: latitude,longitude.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true, required = true)]
    pub north: Vec<f64>,
    /// The fault's length in the scene (km) [default: the trace's].
    #[arg(long)]
    pub length_km: Option<f64>,
    /// x of the southern end in the block (m).
    #[arg(long)]
    pub x0_m: f64,
    /// The nearest a station may be to the fault plane (m): one module, so that it is not a node
    /// of the plane itself (those record the contact, not the ground).
    #[arg(long, default_value_t = 500.0)]
    pub min_aside_m: f64,
}

fn lat_lon(v: &[f64], flag: &str) -> Result<LatLon> {
    anyhow::ensure!(
        v.len() == 2 && v[0].abs() <= 90.0 && v[1].abs() <= 180.0,
        "{flag} {v:?} is not allowed: latitude,longitude in degrees (|lat| ≤ 90, |lon| ≤ 180)"
    );
    Ok(LatLon { lat: v[0], lon: v[1] })
}

/// `part-a-observed`.
pub fn observed(a: &ObservedArgs) -> Result<()> {
    let recordings = read_folder(&a.recordings).map_err(anyhow::Error::msg)?;
    let stations =
        recordings.iter().map(observed_station).collect::<Result<Vec<_>, _>>().map_err(anyhow::Error::msg)?;
    let header = format!(
        "Observed RotD50 of {} recordings, computed by `stickslip-bench part-a-observed <folder of the .bbp files> --out \
         <this file>` with the product's RotD code (crates/seismo/src/spectra/rotd, 5% damping, band-limited \
         reading, the product's periods 0.01-10 s) on the two horizontal components as recorded (no filtering, as the \
         Platform).\n{}\nperiod_s = 0: PGA. rotd50_m_s2: m/s². The Platform uses a recording from 1/f_high_hz to \
         1/f_low_hz s.",
        stations.len(),
        a.source.as_deref().unwrap_or(LANDERS_SOURCE)
    );
    let text = write_csv(&header, &stations);
    if let Some(dir) = a.out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| dir.display().to_string())?;
    }
    std::fs::write(&a.out, text).with_context(|| a.out.display().to_string())?;
    println!(
        "{} stations, {} periods each (PGA included) → {}",
        stations.len(),
        stations[0].rotd50_m_s2.len(),
        a.out.display()
    );
    Ok(())
}

/// `part-a-stations`.
pub fn stations(a: &StationsArgs) -> Result<()> {
    let text = std::fs::read_to_string(&a.observed).with_context(|| a.observed.display().to_string())?;
    let obs = read_csv(&text, &a.observed.display().to_string()).map_err(anyhow::Error::msg)?;
    let trace = Trace { start: lat_lon(&a.south, "--south")?, end: lat_lon(&a.north, "--north")? };
    let length = a.length_km.unwrap_or(trace.length_km());
    anyhow::ensure!(length > 0.0 && length.is_finite(), "--length-km = {length} is not allowed: a positive length");
    println!(
        "# Trace {:.4}°N {:.4}°E → {:.4}°N {:.4}°E: {:.2} km, strike {:.1}°; fault length {length} km, x0 = {} m",
        trace.start.lat,
        trace.start.lon,
        trace.end.lat,
        trace.end.lon,
        trace.length_km(),
        trace.strike_deg(),
        a.x0_m
    );
    for o in &obs {
        let p = place(trace.project(LatLon { lat: o.lon_lat[1], lon: o.lon_lat[0] }), length, o.r_rup_km);
        println!(
            "\n# {}: projected {:.1} km along strike, {:.1} km aside (trace distance {:.1} km); R_rup {} km, V_S30 {} m/s",
            o.name, p.projected_km[0], p.projected_km[1], p.trace_distance_km, o.r_rup_km, o.vs30_m_s
        );
        let mut z = p.at_km[1] * 1e3;
        if z < a.min_aside_m {
            println!(
                "# (moved from {z:.0} m to {} m off the fault plane: a node of the plane records the contact)",
                a.min_aside_m
            );
            z = a.min_aside_m;
        }
        println!("[[stations]]\nname = \"{}\"", o.name);
        println!("at_m = [{:.0}.0, 0.0, {z:.0}.0]", a.x0_m + p.at_km[0] * 1e3);
        println!("vs30_m_s = {:.1}", o.vs30_m_s);
    }
    Ok(())
}

fn interval(r: &BiasRow) -> String {
    r.ci90.map_or("–".into(), |[lo, hi]| format!("[{lo:+.2}, {hi:+.2}]"))
}

fn period_label(t: [f64; 2]) -> String {
    if t[0] == PGA {
        "PGA".into()
    } else if t[0] == t[1] {
        format!("{:.3} s", t[0])
    } else {
        format!("{}–{} s", t[0], t[1])
    }
}

/// `part-a`.
pub fn run(a: &PartAArgs) -> Result<()> {
    let text = std::fs::read_to_string(&a.observed).with_context(|| a.observed.display().to_string())?;
    let obs = read_csv(&text, &a.observed.display().to_string()).map_err(anyhow::Error::msg)?;
    let sim = read_scenario(&Folder::new(&a.folder))?;
    let p = part_a(&obs, &sim.stations);
    let mw: Vec<f64> = sim.mw.values().copied().collect();
    let (lo, hi) = mw.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &m| (l.min(m), h.max(m)));
    println!(
        "Part A: {} seeds (Mw {lo:.2}–{hi:.2}), {} of {} recorded stations simulated; residual ln(observed/simulated) \
         of RotD50, each station's averaged in ln over the seeds, 90% Student interval over the stations",
        mw.len(),
        obs.len() - p.unmatched.len(),
        obs.len()
    );
    if !p.unmatched.is_empty() {
        println!("not simulated (left out): {}", p.unmatched.join(", "));
    }
    println!("\n{:>12} {:>4} {:>7} {:>16} {:>6}", "period", "n", "bias", "90% interval", "σ");
    let line = |r: &BiasRow| {
        println!(
            "{:>12} {:>4} {:>+7.2} {:>16} {:>6}",
            period_label(r.periods_s),
            r.stations.len(),
            r.mean,
            interval(r),
            r.std.map_or("–".into(), |s| format!("{s:.2}"))
        )
    };
    p.periods.iter().for_each(line);
    println!("{:-<50}", "");
    p.bins.iter().for_each(line);
    // Per station: the recording's and the scenario's R_rup, V_S30, and the residual at PGA and
    // averaged over each bin.
    let bins: Vec<BTreeMap<&str, f64>> = p
        .bins
        .iter()
        .map(|b| b.stations.iter().map(String::as_str).zip(b.residual_ln.iter().copied()).collect())
        .collect();
    print!("\n{:>8} {:>8} {:>8} {:>6} {:>7}", "station", "R_rup", "sim", "V_S30", "PGA");
    for b in &p.bins {
        print!(" {:>9}", format!("{}–{}", b.periods_s[0], b.periods_s[1]));
    }
    println!();
    let mut order: Vec<_> = obs.iter().filter(|o| sim.stations.contains_key(&o.name)).collect();
    order.sort_by(|x, y| x.r_rup_km.total_cmp(&y.r_rup_km));
    for o in order {
        let s = &sim.stations[&o.name];
        let r_sim = s.r_rup_km.iter().sum::<f64>() / s.r_rup_km.len().max(1) as f64;
        let pga = o.rotd50_m_s2.get(&PGA.to_bits()).zip(s.rotd50_m_s2.get(&PGA.to_bits()));
        let pga = pga.and_then(|(o, s)| residual(*o, s)).map_or("–".into(), |r| format!("{r:+.2}"));
        print!("{:>8} {:>8.2} {:>8.2} {:>6.0} {:>7}", o.name, o.r_rup_km, r_sim, o.vs30_m_s, pga);
        for b in &bins {
            print!(" {:>9}", b.get(o.name.as_str()).map_or("–".into(), |r| format!("{r:+.2}")));
        }
        println!();
    }
    if !sim.models.is_empty() {
        // The recordings at the models' periods only, so that the three columns have the same
        // stations and periods (also in the bins).
        let at_models: Vec<_> = obs
            .iter()
            .map(|o| {
                let mut o = o.clone();
                let keys = sim.models.get(&o.name).map(|m| &m.rotd50_m_s2);
                o.rotd50_m_s2.retain(|k, _| keys.is_some_and(|m| m.contains_key(k)));
                o
            })
            .collect();
        let obs_models = part_a(&at_models, &sim.models);
        let sim_models = part_a(&simulated_as_observed(&at_models, &sim.stations), &sim.models);
        let obs_sim = part_a(&at_models, &sim.stations);
        println!(
            "\nThe same stations against the NGA-West2 models' average (BSSA14, ASK14, CB14, CY14 at each seed's Mw and \
             the scenario's distances, the recordings' V_S30; table gmm_residuals): ln(observed/models) − \
             ln(simulated/models) = ln(observed/simulated)"
        );
        println!(
            "{:>12} {:>4} {:>7} {:>16} {:>7} {:>16} {:>7}",
            "period", "n", "obs/mod", "90% interval", "sim/mod", "90% interval", "obs/sim"
        );
        let find = |p: &PartA, t: [f64; 2], bins: bool| {
            (if bins { &p.bins } else { &p.periods }).iter().find(|r| r.periods_s == t).cloned()
        };
        for (bins, rows) in [(false, &obs_models.periods), (true, &obs_models.bins)] {
            if bins {
                println!("{:-<76}", "");
            }
            for r in rows {
                let (Some(s), Some(o)) = (find(&sim_models, r.periods_s, bins), find(&obs_sim, r.periods_s, bins))
                else {
                    continue;
                };
                println!(
                    "{:>12} {:>4} {:>+7.2} {:>16} {:>+7.2} {:>16} {:>+7.2}",
                    period_label(r.periods_s),
                    r.stations.len(),
                    r.mean,
                    interval(r),
                    s.mean,
                    interval(&s),
                    o.mean
                );
            }
        }
    }
    let figure = a.figure.clone().unwrap_or_else(|| a.folder.join("figures").join("part_a.png"));
    if let Some(dir) = figure.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).with_context(|| dir.display().to_string())?;
    }
    let title = format!("Part A: {} stations, {} seeds (Mw {lo:.2}–{hi:.2})", obs.len() - p.unmatched.len(), mw.len());
    part_a_figure(&p, &obs, &title, &figure).map_err(anyhow::Error::msg)?;
    println!("\nfigure → {}", figure.display());
    Ok(())
}
