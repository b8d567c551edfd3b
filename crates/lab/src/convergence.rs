//! Statistical convergence: are the distributions of event measures over seeds the same when Δt
//! shrinks, and when the lattice is refined?
//!
//! A chaotic history cannot be compared sample by sample (a change of one part in 10⁹ changes
//! the paper scene's drops by tens of percent), so each cell of the sweep — a loading, a lattice
//! refinement `r` (`r·nx × r·ny × r·nz` modules of side `Lc/r`, the same block) and a Δt fraction
//! — runs `N` seeds (seeds 1…N, each with its own Weibull field, drawn bar by bar on its own
//! lattice) and every per-seed quantity is compared as a distribution:
//! - the mean and the median over seeds, each with a 95% percentile-bootstrap interval (2,000
//!   resamples of the seeds);
//! - the two-sample Kolmogorov–Smirnov test against the smallest Δt of the same lattice and
//!   loading, and against the finest lattice at the same Δt fraction and loading: `p < 0.05`
//!   says the distributions differ.
//!
//! Per-seed quantities (means over the seed's main shocks unless said; main shocks as the
//! pipeline's `[events]` defines them):
//! - `main_drop_kpa`, `main_duration_ms`, `main_recurrence_ms` (S2 onwards);
//! - `m_paper` (Riera interplate with the paper's moment, Eq. 15) and `mw` (Mw from
//!   `M0 = Δσ·L·A`), at the pipeline's similarity;
//! - `sigma_swing`: the largest range of the normal stress within a main shock (from its start to
//!   its end, on the solver's event trace), over the self-weight stress `ρ·g·h`;
//! - `pga_m_s2`: peak |a_x| during main shocks at the control point (0.2, 0.1, 0.1) m (the
//!   paper's node 36) — present in every refinement;
//! - `all_drop_kpa`: mean stress drop of every catalogued event; `events`, `main_shocks`: counts.
//!
//! Loadings: `point`, the pipeline's driver nodes by position (the paper's single node — a point
//! load whose share of the face shrinks as the lattice is refined); `patch`, every node of the
//! trailing face `x = 0` with `0.1 ≤ z ≤ 0.3` m (a 0.2 × 0.1 m patch: the same load at every
//! refinement). Damping rates (per second), velocities and durations are the pipeline's: they do
//! not depend on the module size. Nothing is recorded but the event trace.

use std::ops::ControlFlow;
use std::path::Path;
use std::time::Instant;

use polars::prelude::DataFrame;
use rayon::prelude::*;
use stickslip_analysis::events::{catalogue, scaled_events};
use stickslip_config::scene::ControlSection;
use stickslip_config::{Pipeline, PipelineFile};
use stickslip_report::charts::{Line, Panel, Sheet, draw};
use stickslip_seismo::stats::{bootstrap_ci, ks_two_sample, median};
use stickslip_solver::{BATCH, Model, RunOptions, run_batched};
use stickslip_store::frame::Frame;

use crate::LabError;
use crate::accuracy::refined;

/// How the block is sheared.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Loading {
    /// The pipeline's driver nodes (by position).
    Point,
    /// The trailing-face patch `x = 0`, `0.1 ≤ z ≤ 0.3` m.
    Patch,
}

impl Loading {
    /// `"point"` or `"patch"`.
    pub fn name(self) -> &'static str {
        match self {
            Loading::Point => "point",
            Loading::Patch => "patch",
        }
    }

    /// By name.
    pub fn parse(s: &str) -> Option<Loading> {
        [Loading::Point, Loading::Patch].into_iter().find(|l| l.name() == s)
    }
}

/// One cell of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// Loading.
    pub loading: Loading,
    /// Refinement factor.
    pub refinement: u32,
    /// Δt over the critical step.
    pub dt_fraction: f64,
    /// Seeds (1…N).
    pub seeds: usize,
}

/// The per-seed quantities, in table order.
pub const QUANTITIES: [&str; 10] = [
    "main_drop_kpa",
    "main_duration_ms",
    "main_recurrence_ms",
    "m_paper",
    "mw",
    "sigma_swing",
    "pga_m_s2",
    "all_drop_kpa",
    "events",
    "main_shocks",
];

/// What one cell gave: the per-seed values of every quantity and the cost.
#[derive(Clone, Debug)]
pub struct CellResult {
    /// The cell.
    pub cell: Cell,
    /// Modules.
    pub dims: [usize; 3],
    /// Bars.
    pub bars: usize,
    /// Mean Δt over the seeds (s).
    pub dt_s: f64,
    /// Compute time per seed (s of one core: the batches' wall times summed, over N).
    pub core_s_per_seed: f64,
    /// Per quantity ([`QUANTITIES`] order), the value of every seed (NaN where undefined).
    pub values: Vec<Vec<f64>>,
}

/// The scene file of a cell.
fn variant(file: &PipelineFile, cell: &Cell, duration: Option<f64>) -> Result<Pipeline, LabError> {
    let r = cell.refinement;
    let mut file = refined(file, r, cell.dt_fraction, duration, "convergence")?;
    let lc = file.block.lc_m;
    if cell.loading == Loading::Patch {
        file.shear.driver_face = None;
        file.shear.driver_at_m.clear();
        let (ny, nz) = (file.block.ny, file.block.nz);
        for j in 0..=ny {
            for k in 0..=nz {
                let z = k as f64 * lc;
                if (0.1 - 1e-9..=0.3 + 1e-9).contains(&z) {
                    file.shear.driver_at_m.push([0.0, j as f64 * lc, z]);
                }
            }
        }
    }
    // Nothing recorded but the event trace (and one sample at the start).
    file.record.interval_s = Some(file.shear.duration_s);
    file.record.interface = vec!["shear_stress".into()];
    file.record.energy = false;
    file.record.settling = false;
    file.record.slip_onsets = false;
    file.record.control.clear();
    file.record.control.push(ControlSection {
        nodes: Vec::new(),
        at_m: vec![[0.2, 0.1, 0.1]],
        set: None,
        quantities: vec!["acceleration".into()],
        components: vec!["x".into()],
    });
    file.accelerograms = None;
    file.spectra = None;
    file.set = None;
    file.seeds.target = None;
    let name =
        format!("{}-{}-r{}-f{}", file.name.as_deref().unwrap_or("bench"), cell.loading.name(), r, cell.dt_fraction);
    Pipeline::from_file(file, &name).map_err(|e| LabError::Setup(format!("{name}: {e}")))
}

/// Runs one cell: seeds 1…N in batches of eight lanes, the batches spread over the rayon pool.
pub fn run_cell(file: &PipelineFile, cell: &Cell, duration: Option<f64>) -> Result<CellResult, LabError> {
    let pipeline = variant(file, cell, duration)?;
    let model = Model::new(pipeline.scene.clone());
    let seeds: Vec<u64> = (1..=cell.seeds as u64).collect();
    let batches: Vec<Result<(f64, Vec<stickslip_solver::RunOutput>), LabError>> = seeds
        .par_chunks(BATCH)
        .map(|chunk| {
            let start = Instant::now();
            let outs = run_batched(&model, chunk, RunOptions::default(), &mut |_| ControlFlow::Continue(()));
            let wall = start.elapsed().as_secs_f64();
            let outs = outs.into_iter().collect::<Result<Vec<_>, _>>().map_err(|e| LabError::Setup(e.to_string()))?;
            Ok((wall, outs))
        })
        .collect();
    let mut core_s = 0.0;
    let mut values = vec![Vec::with_capacity(cell.seeds); QUANTITIES.len()];
    let mut dt_sum = 0.0;
    let sigma0 = pipeline.scene.density_kg_m3 * pipeline.scene.self_weight.gravity_m_s2 * model.lattice().extent()[2];
    for batch in batches {
        let (wall, outs) = batch?;
        core_s += wall;
        for out in outs {
            dt_sum += out.dt_s;
            let cat = catalogue(&out.recording, &model, &pipeline.analysis.events);
            let scaled = scaled_events(&cat, &model, &pipeline.analysis.similarity);
            let trace = &out.recording.trace;
            let mains: Vec<usize> = (0..cat.events.len()).filter(|&i| cat.events[i].kind.is_main()).collect();
            let mean = |f: &dyn Fn(usize) -> Option<f64>| {
                let v: Vec<f64> = mains.iter().filter_map(|&i| f(i)).filter(|v| v.is_finite()).collect();
                if v.is_empty() { f64::NAN } else { v.iter().sum::<f64>() / v.len() as f64 }
            };
            let burst = |i: usize| &cat.events[i].burst;
            let swing = |i: usize| {
                let (a, b) = burst(i).samples;
                let s = &trace.normal_stress_pa[a..=b.min(trace.len() - 1)];
                let (lo, hi) = s.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |m, &v| (m.0.min(v), m.1.max(v)));
                (hi - lo) / sigma0
            };
            let all: Vec<f64> = cat.events.iter().map(|e| e.burst.stress_drop_pa / 1e3).collect();
            let row = [
                mean(&|i| Some(burst(i).stress_drop_pa / 1e3)),
                mean(&|i| Some(burst(i).duration_s() * 1e3)),
                mean(&|i| cat.events[i].recurrence_s.map(|r| r * 1e3)),
                mean(&|i| Some(scaled[i].magnitudes.riera_paper_interplate)),
                mean(&|i| Some(scaled[i].magnitudes.mw_consistent)),
                mains.iter().map(|&i| swing(i)).fold(f64::NAN, f64::max),
                mean(&|i| burst(i).peak_acceleration.first().copied()),
                if all.is_empty() { f64::NAN } else { all.iter().sum::<f64>() / all.len() as f64 },
                cat.events.len() as f64,
                mains.len() as f64,
            ];
            for (k, v) in row.into_iter().enumerate() {
                values[k].push(v);
            }
        }
    }
    let d = model.scene().dims;
    Ok(CellResult {
        cell: *cell,
        dims: [d.nx, d.ny, d.nz],
        bars: model.bar_count(),
        dt_s: dt_sum / cell.seeds as f64,
        core_s_per_seed: core_s / cell.seeds as f64,
        values,
    })
}

/// One row of the comparison table: a cell and a quantity.
#[derive(Clone, Debug)]
pub struct Compared {
    /// The cell's index in the results.
    pub cell: usize,
    /// Quantity.
    pub quantity: &'static str,
    /// Seeds with a finite value.
    pub n: usize,
    /// Mean, and its 95% bootstrap interval.
    pub mean: (f64, f64, f64),
    /// Median, and its 95% bootstrap interval.
    pub median: (f64, f64, f64),
    /// KS statistic and p-value against the smallest Δt of the same lattice and loading (NaN for
    /// that cell itself).
    pub ks_dt: (f64, f64),
    /// … against the finest lattice at the same Δt fraction and loading.
    pub ks_lattice: (f64, f64),
}

/// Every cell and quantity against its references.
pub fn compare(results: &[CellResult]) -> Vec<Compared> {
    let mut out = Vec::new();
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    for (i, r) in results.iter().enumerate() {
        let c = &r.cell;
        let finest_dt = results
            .iter()
            .filter(|x| x.cell.loading == c.loading && x.cell.refinement == c.refinement)
            .min_by(|a, b| a.cell.dt_fraction.total_cmp(&b.cell.dt_fraction));
        let finest_lattice = results
            .iter()
            .filter(|x| x.cell.loading == c.loading && x.cell.dt_fraction == c.dt_fraction)
            .max_by_key(|x| x.cell.refinement);
        for (k, &q) in QUANTITIES.iter().enumerate() {
            let v = &r.values[k];
            let finite: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
            let seed = 1000 + (i * QUANTITIES.len() + k) as u64;
            let ci = |f: &dyn Fn(&[f64]) -> f64| {
                let centre = if finite.is_empty() { f64::NAN } else { f(&finite) };
                let (lo, hi) = bootstrap_ci(&finite, f, 0.95, 2000, seed).unwrap_or((f64::NAN, f64::NAN));
                (centre, lo, hi)
            };
            let ks = |other: Option<&CellResult>| match other {
                Some(o) if !std::ptr::eq(o, r) => ks_two_sample(v, &o.values[k]).unwrap_or((f64::NAN, f64::NAN)),
                _ => (f64::NAN, f64::NAN),
            };
            out.push(Compared {
                cell: i,
                quantity: q,
                n: finite.len(),
                mean: ci(&mean),
                median: ci(&median),
                ks_dt: ks(finest_dt),
                ks_lattice: ks(finest_lattice),
            });
        }
    }
    out
}

/// The comparison as a table: `loading` str, `refinement`, `nx`, `ny`, `nz` u32, `bars` u64,
/// `dt_fraction`, `dt_s` f64, `seeds` u32, `core_s_per_seed` f64, `quantity` str, `n` u32,
/// `mean`, `mean_ci_low`, `mean_ci_high`, `median`, `median_ci_low`, `median_ci_high`,
/// `ks_d_vs_finest_dt`, `ks_p_vs_finest_dt`, `ks_d_vs_finest_lattice`, `ks_p_vs_finest_lattice`
/// f64 (NaN: the cell is its own reference).
pub fn convergence_frame(results: &[CellResult], rows: &[Compared]) -> Result<DataFrame, LabError> {
    let cell = |c: &Compared| &results[c.cell];
    let f64s = |f: &dyn Fn(&Compared) -> f64| rows.iter().map(f).collect::<Vec<f64>>();
    let u32s = |f: &dyn Fn(&Compared) -> u32| rows.iter().map(f).collect::<Vec<u32>>();
    let frame = Frame::new(rows.len())
        .str("loading", rows.iter().map(|c| cell(c).cell.loading.name().to_string()).collect())
        .u32("refinement", u32s(&|c| cell(c).cell.refinement))
        .u32("nx", u32s(&|c| cell(c).dims[0] as u32))
        .u32("ny", u32s(&|c| cell(c).dims[1] as u32))
        .u32("nz", u32s(&|c| cell(c).dims[2] as u32))
        .u64("bars", rows.iter().map(|c| cell(c).bars as u64).collect())
        .f64("dt_fraction", f64s(&|c| cell(c).cell.dt_fraction))
        .f64("dt_s", f64s(&|c| cell(c).dt_s))
        .u32("seeds", u32s(&|c| cell(c).cell.seeds as u32))
        .f64("core_s_per_seed", f64s(&|c| cell(c).core_s_per_seed))
        .str("quantity", rows.iter().map(|c| c.quantity.to_string()).collect())
        .u32("n", u32s(&|c| c.n as u32))
        .f64("mean", f64s(&|c| c.mean.0))
        .f64("mean_ci_low", f64s(&|c| c.mean.1))
        .f64("mean_ci_high", f64s(&|c| c.mean.2))
        .f64("median", f64s(&|c| c.median.0))
        .f64("median_ci_low", f64s(&|c| c.median.1))
        .f64("median_ci_high", f64s(&|c| c.median.2))
        .f64("ks_d_vs_finest_dt", f64s(&|c| c.ks_dt.0))
        .f64("ks_p_vs_finest_dt", f64s(&|c| c.ks_dt.1))
        .f64("ks_d_vs_finest_lattice", f64s(&|c| c.ks_lattice.0))
        .f64("ks_p_vs_finest_lattice", f64s(&|c| c.ks_lattice.1));
    Ok(frame.finish("convergence")?)
}

/// One panel per quantity: the mean over seeds with its 95% interval (a band) against compute
/// time per seed, one line per loading and lattice through its Δt fractions.
pub fn convergence_figure(results: &[CellResult], rows: &[Compared], path: &Path) -> Result<(), LabError> {
    stickslip_report::plot::register_fonts();
    if let Some(dir) = path.parent() {
        std::fs::create_dir_all(dir).map_err(|e| LabError::Setup(format!("{}: {e}", dir.display())))?;
    }
    let mut groups: Vec<(Loading, u32)> = results.iter().map(|r| (r.cell.loading, r.cell.refinement)).collect();
    groups.sort_by_key(|g| (g.0.name(), g.1));
    groups.dedup();
    let panels: Vec<Panel> = QUANTITIES[..8]
        .iter()
        .map(|&q| {
            let mut lines = Vec::new();
            let mut bands = Vec::new();
            for (gi, &(loading, r)) in groups.iter().enumerate() {
                let mut pts: Vec<(f64, f64, f64, f64)> = rows
                    .iter()
                    .filter(|c| {
                        let x = &results[c.cell];
                        c.quantity == q && x.cell.loading == loading && x.cell.refinement == r && c.mean.0.is_finite()
                    })
                    .map(|c| (results[c.cell].core_s_per_seed, c.mean.0, c.mean.1, c.mean.2))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                let d = results
                    .iter()
                    .find(|x| x.cell.loading == loading && x.cell.refinement == r)
                    .map_or([0; 3], |x| x.dims);
                let line = Line::new(
                    format!("{} {}×{}×{}", loading.name(), d[0], d[1], d[2]),
                    pts.iter().map(|p| (p.0, p.1)).collect(),
                    gi,
                );
                if pts.iter().all(|p| p.2.is_finite() && p.3.is_finite()) && pts.len() > 1 {
                    bands.push(stickslip_report::charts::Band {
                        points: pts.iter().map(|p| (p.0, p.2, p.3)).collect(),
                        colour: line.colour,
                        label: String::new(),
                    });
                }
                lines.push(line);
            }
            let mut panel = Panel::linear("core-seconds per seed", "mean over seeds");
            panel.x_scale = stickslip_report::charts::Scale::Log;
            Panel { title: q.to_string(), lines, bands, dots: true, legend: q == QUANTITIES[0], ..panel }
        })
        .collect();
    draw(path, &Sheet::new("", 2, panels).with_height(2000))?;
    Ok(())
}
