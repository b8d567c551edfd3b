//! `stickslip-bench`: the benchmarks of the lab crate, printed (tables and figures under
//! `reports/bench/`). A developers' tool beside the product's `stickslip` binary, which does not
//! link the lab: `cargo run --release -p stickslip-lab --bin stickslip-bench -- <command>`.

mod large;
mod medium;
mod part_a;

use std::path::{Path, PathBuf};

use anyhow::Result;
use stickslip_config::Pipeline;
use stickslip_lab::accuracy::{AccuracyPlan, accuracy_figure, accuracy_frame, observed_order, run_accuracy};
use stickslip_lab::calibrate::sweep;
use stickslip_lab::convergence::{Cell, Loading, QUANTITIES, compare, convergence_figure, convergence_frame, run_cell};
use stickslip_lab::peer::peer;
use stickslip_lab::recording_cost::recording_cost;
use stickslip_lab::scec::{self, Reference, read_run};
use stickslip_lab::skip::{JumpCheck, SkipBench, compare_skip, jumps_frame, runs_frame};
use stickslip_store::io::write_parquet_atomic;

use stickslip_config::seeds::parse_seeds;

/// Benchmarks of stickslip: accuracy, convergence, skip-ahead, recording cost, the LAMMPS peer,
/// calibration sweeps (tables and figures under reports/bench/).
#[derive(clap::Parser, Debug)]
#[command(name = "stickslip-bench", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// The benchmarks.
#[derive(clap::Subcommand, Debug)]
enum Command {
    /// Run time against error: the pipeline's scene over Δt fractions and lattice refinements
    /// of the same block, each against the finest run.
    Accuracy {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Δt fractions of the critical step.
        #[arg(long, value_delimiter = ',', default_value = "0.9,0.5,0.25,0.1", allow_negative_numbers = true)]
        fractions: Vec<f64>,
        /// Lattice refinements (modules per side multiplied, Lc divided).
        #[arg(long, value_delimiter = ',', default_value = "1,2,4")]
        refinements: Vec<u32>,
        /// Shear duration (s) [default: the pipeline's].
        #[arg(long, allow_negative_numbers = true)]
        duration_s: Option<f64>,
        /// Output folder [default: reports/bench/<pipeline name>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Statistical convergence of event measures: N seeds per cell over Δt fractions and lattice
    /// refinements of the same block, for the pipeline's point driver and a driven patch; means
    /// and medians with bootstrap 95% intervals, Kolmogorov–Smirnov tests against the finest Δt
    /// and the finest lattice (table and figure).
    Convergence(ConvergenceArgs),
    /// Quasi-static skip-ahead against full integration: whole runs, and each of the first
    /// jumps against integrating through it from the same state.
    Skip {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Seeds [default: the pipeline's], e.g. "1,5,10-20".
        #[arg(long)]
        seeds: Option<String>,
        /// Jumps checked one by one per seed (those followed by an event first).
        #[arg(long, default_value_t = 4)]
        jumps: usize,
        /// How long the compared runs go on after a jump (s).
        #[arg(long, default_value_t = 0.05, allow_negative_numbers = true)]
        window_s: f64,
        /// Output folder [default: reports/bench/<pipeline name>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// What recording costs: the pipeline's scene with everything it records, then one thing
    /// less at a time (best of several runs, one seed, one thread).
    Recording {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// Runs of each variant (the best counts).
        #[arg(long, default_value_t = 7)]
        repeats: usize,
    },
    /// Our side of the LAMMPS comparison (crates/lab/lammps/compare.sh runs both): writes the
    /// homogeneous NX×NY×NZ lattice as a LAMMPS data file and input script into OUT and prints
    /// our bar-updates per second with one seed and with eight side by side.
    Peer {
        /// Modules along x.
        nx: i64,
        /// Modules along y.
        ny: i64,
        /// Modules along z.
        nz: i64,
        /// Steps timed.
        steps: usize,
        /// Folder for lattice.data and in.lattice.
        out: PathBuf,
    },
    /// What an ensemble costs end to end, side by side with a previous build of the product:
    /// `stickslip pipeline` on 1 and 2 threads for each build, alternately (best of the
    /// repeats), the size of what each writes, a profile by stage of this build (in this
    /// process), and `stickslip merge` (gathering and report) of a large pipeline's folder with
    /// each build. Folders go under --out and are removed at the end.
    Ensemble {
        /// Pipeline file (TOML), e.g. pipelines/paper-100.toml.
        pipeline: PathBuf,
        /// The previous build's `stickslip` binary (a checkout of an earlier commit built with
        /// `cargo build --release`); without it only this build is measured.
        #[arg(long)]
        before: Option<PathBuf>,
        /// This build's `stickslip` binary [default: the one beside stickslip-bench].
        #[arg(long)]
        after: Option<PathBuf>,
        /// A large pipeline whose gathering and report are timed, e.g. pipelines/paper-1000.toml.
        #[arg(long)]
        large: Option<PathBuf>,
        /// Runs of each build and thread count (the best counts).
        #[arg(long, default_value_t = 3)]
        repeats: usize,
        /// Also time this build on 2 threads without records, without spectra, without RotD
        /// (variants of the pipeline, see `ensemble_cost::floors`) and as given, in one loop:
        /// what each analysis stage adds to the run.
        #[arg(long)]
        floors: bool,
        /// Scratch folder for the outputs [default: the system's temporary folder].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// What broadband records cost: a pipeline with `[broadband]` on 2 threads side by side with
    /// the same pipeline without it, alternately (best of the repeats), and the CPU seconds of the
    /// stochastic synthesis and the joins against the whole run's (in this process).
    Broadband {
        /// Pipeline file with a `[broadband]` section, e.g. pipelines/scenario-m6.toml.
        pipeline: PathBuf,
        /// Runs of each variant (the best counts).
        #[arg(long, default_value_t = 2)]
        repeats: usize,
        /// Scratch folder [default: the system's temporary folder].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// What a run does before its first step against a step: the pipeline's scene at the given
    /// size (e.g. `large-block.toml 500 150 48`), its first seed, on one thread and on all of them.
    Setup(large::SizeArgs),
    /// A step against what memory allows, measured in one run: the step of the pipeline's scene
    /// at the given size (e.g. `large-block.toml 500 150 48`, 50.5 M bars) on every thread, a
    /// triad over the same bytes on the same threads, and their ratio.
    Bandwidth(large::SizeArgs),
    /// What the medium costs a step (docs/model.md §18, BENCHMARKS.md §11).
    Medium(medium::MediumArgs),
    /// Sweeps assumed values of a pipeline's scene over seeds and prints the main shocks of each
    /// combination, e.g. `d2=100,400,900 t0=0.002,0.02` (keys: z, y, d2, d1, t0, frac, dur, vel,
    /// mud, dc).
    Calibrate {
        /// Pipeline file (TOML).
        pipeline: PathBuf,
        /// KEY=V1,V2,… for each value swept.
        values: Vec<String>,
        /// Seeds.
        #[arg(long, default_value = "123,200,7,1,2,3")]
        seeds: String,
    },
    /// Rewrites the generated blocks of README.md and docs/guide/*.md (their printed outputs,
    /// tables, wall times and disk use) from real runs of the product's `stickslip` binary, from
    /// the repository's root into reports/ (minutes: it runs the main command, paper-precise,
    /// slow-loading and paper-100 twice more, timed).
    Readme {
        /// Compare instead of writing: exit 1 when a block that does not depend on the machine
        /// differs.
        #[arg(long)]
        check: bool,
        /// Only these blocks (comma separated keys).
        #[arg(long, value_delimiter = ',')]
        only: Vec<String>,
        /// The `stickslip` binary [default: $STICKSLIP, or the one beside this binary].
        #[arg(long)]
        binary: Option<PathBuf>,
    },
    /// A fault scene's run against a reference solution of a SCEC dynamic-rupture benchmark
    /// (TPV5): rupture time, final slip and peak slip rate at every on-fault station, the
    /// rupture-time field, and figures (written beside each run's files, in <run>/scec/).
    DynamicRupture(RuptureArgs),
    /// Part A of the Broadband Platform's validation: a scenario's broadband RotD50 against a real
    /// earthquake's recordings, ln(observed/simulated) per period (PGA, 0.01–10 s) and over the
    /// bins 0.01–0.1, 0.1–1, 1–3 and 3.5–10 s, with the 90% Student interval over the stations;
    /// then each station's residuals.
    PartA(part_a::PartAArgs),
    /// The observed side of Part A: RotD50 (PGA, PSA at the product's periods) of recordings in the
    /// Platform's .bbp format by the product's RotD code, written as a CSV with each station's
    /// position, R_rup, V_S30 and usable band.
    PartAObserved(part_a::ObservedArgs),
    /// The `[[stations]]` of a planar vertical strike-slip scenario at the recordings' R_rup, along-strike
    /// positions and V_S30 (from the CSV of part-a-observed and the fault trace's ends), printed as TOML.
    PartAStations(part_a::StationsArgs),
}

/// `stickslip-bench dynamic-rupture`'s arguments.
#[derive(clap::Args, Debug)]
struct RuptureArgs {
    /// Output folders of runs of the benchmark (e.g. reports/tpv5 and reports/tpv5-100m).
    #[arg(required = true)]
    runs: Vec<PathBuf>,
    /// Seed of the runs.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// The reference solution's folder.
    #[arg(long, default_value = "pipelines/reference/tpv5")]
    reference: PathBuf,
}

fn bench_out(pipeline: &Pipeline, out: Option<PathBuf>) -> PathBuf {
    out.unwrap_or_else(|| PathBuf::from("reports").join("bench").join(&pipeline.name))
}

fn main() {
    if let Err(e) = run(<Cli as clap::Parser>::parse().command) {
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}

/// Runs one benchmark.
fn run(c: Command) -> Result<()> {
    match c {
        Command::Accuracy { pipeline, fractions, refinements, duration_s, out } => {
            accuracy(&pipeline, fractions, refinements, duration_s, out)
        }
        Command::Convergence(args) => convergence(args),
        Command::Skip { pipeline, seeds, jumps, window_s, out } => {
            skip(&pipeline, seeds.as_deref(), jumps, window_s, out)
        }
        Command::Recording { pipeline, repeats } => {
            anyhow::ensure!(repeats >= 1, "--repeats = 0 is not allowed: at least 1");
            let p = Pipeline::load(&pipeline)?;
            let rows = recording_cost(&p.file, repeats)?;
            let base = rows[0].wall_s;
            println!("{:<50} {:>10} {:>10} {:>10}", "variant", "steps", "wall (ms)", "speed-up");
            for r in &rows {
                println!("{:<50} {:>10} {:>10.1} {:>9.2}×", r.name, r.steps, r.wall_s * 1e3, base / r.wall_s);
            }
            Ok(())
        }
        Command::DynamicRupture(a) => dynamic_rupture(&a),
        Command::PartA(a) => part_a::run(&a),
        Command::PartAObserved(a) => part_a::observed(&a),
        Command::PartAStations(a) => part_a::stations(&a),
        Command::Peer { nx, ny, nz, steps, out } => {
            anyhow::ensure!(nx >= 1 && ny >= 1 && nz >= 1, "NX NY NZ must be at least 1");
            let t = peer(nx, ny, nz, steps, &out)?;
            println!("bars {}", t.bars);
            println!("dt {:e}", t.dt_s);
            println!("ours_1 {:e}", t.one_seed);
            println!("ours_8 {:e}", t.eight_seeds);
            Ok(())
        }
        Command::Ensemble { pipeline, before, after, large, repeats, floors, out } => {
            anyhow::ensure!(repeats >= 1, "--repeats = 0 is not allowed: at least 1");
            ensemble(&pipeline, before, after, large.as_deref(), repeats, floors, out)
        }
        Command::Readme { check, only, binary } => readme(check, &only, binary),
        Command::Broadband { pipeline, repeats, out } => {
            anyhow::ensure!(repeats >= 1, "--repeats = 0 is not allowed: at least 1");
            let binary = std::env::current_exe()?.with_file_name("stickslip");
            anyhow::ensure!(binary.exists(), "{}: no such binary (build it)", binary.display());
            let build = stickslip_lab::ensemble_cost::Build { label: "this build".into(), binary };
            let out = out.unwrap_or_else(|| std::env::temp_dir().join("stickslip-bench-broadband"));
            let c = stickslip_lab::broadband_cost::measure(&pipeline, &build, repeats, &out)?;
            println!("| {} on 2 threads (best of {repeats}) | wall time |", pipeline.display());
            println!("|---|---|");
            println!("| with [broadband] | {:.1} s |", c.wall_s[0]);
            println!("| without it (the lattice's records only) | {:.1} s |", c.wall_s[1]);
            println!(
                "| added | {:+.1} s ({:+.1}%) |",
                c.wall_s[0] - c.wall_s[1],
                100.0 * (c.wall_s[0] / c.wall_s[1] - 1.0)
            );
            println!(
                "profile (2 threads, in this process, wall {:.1} s): stochastic synthesis and joins {:.1} CPU-s ({:.1}% of \
                 {:.1} CPU-s), the broadband records' processing, RotD and measures {:.1} CPU-s ({:.1}%)",
                c.profile_wall_s,
                c.synthesis_cpu_s,
                100.0 * c.synthesis_cpu_s / c.total_cpu_s,
                c.total_cpu_s,
                c.motions_cpu_s,
                100.0 * c.motions_cpu_s / c.total_cpu_s
            );
            let _ = std::fs::remove_dir_all(&out);
            Ok(())
        }
        Command::Medium(a) => medium::run(a),
        Command::Setup(a) => large::setup(a),
        Command::Bandwidth(a) => large::bandwidth(a),
        Command::Calibrate { pipeline, values, seeds } => {
            let p = Pipeline::load(&pipeline)?;
            let mut grid = Vec::new();
            for spec in &values {
                let (k, vs) = spec
                    .split_once('=')
                    .ok_or_else(|| anyhow::anyhow!("{spec:?}: expected KEY=V1,V2,… (e.g. d2=100,400)"))?;
                let vals = vs
                    .split(',')
                    .map(|v| v.trim().parse::<f64>().map_err(|_| anyhow::anyhow!("{spec:?}: {v:?} is not a number")))
                    .collect::<Result<Vec<f64>>>()?;
                grid.push((k.to_string(), vals));
            }
            for combo in sweep(&p.file, &grid, &parse_seeds(&seeds).map_err(anyhow::Error::msg)?)? {
                let values: Vec<String> = combo.values.iter().map(|(k, v)| format!("{k} = {v}")).collect();
                println!("== {}", values.join(", "));
                let mut s2 = Vec::new();
                for (s, cat) in &combo.seeds {
                    let mains: Vec<_> = cat.main_shocks().collect();
                    let desc: Vec<String> = mains
                        .iter()
                        .map(|e| {
                            format!(
                                "{:.1}kPa/{:.1}ms/{:.1}ms@{:.3}({})",
                                e.burst.stress_drop_pa / 1e3,
                                e.burst.duration_s() * 1e3,
                                e.burst.drop_time_s() * 1e3,
                                e.burst.start_s,
                                e.sub_events.len()
                            )
                        })
                        .collect();
                    println!("  seed {s}: {} events, mains: {}", cat.events.len(), desc.join(" "));
                    if let Some(e) = mains.get(1) {
                        s2.push((e.burst.stress_drop_pa, e.burst.drop_time_s(), e.recurrence_s.unwrap_or(f64::NAN)));
                    }
                }
                if s2.is_empty() {
                    println!("  S2: none in any seed (fewer than two main shocks)");
                    continue;
                }
                let mean = |f: &dyn Fn(&S2) -> Option<f64>| {
                    let v: Vec<f64> = s2.iter().filter_map(f).collect();
                    (!v.is_empty()).then(|| v.iter().sum::<f64>() / v.len() as f64)
                };
                let ms = |v: Option<f64>| v.map_or("–".into(), |v| format!("{:.1} ms", v * 1e3));
                println!(
                    "  S2 in {} of {} seeds: drop {:.0} Pa, stress falls in {:.2} ms, S1→S2 {}",
                    s2.len(),
                    combo.seeds.len(),
                    mean(&|v| Some(v.0)).unwrap_or(f64::NAN),
                    mean(&|v| Some(v.1)).unwrap_or(f64::NAN) * 1e3,
                    ms(mean(&|v| v.2.is_finite().then_some(v.2)))
                );
            }
            Ok(())
        }
    }
}

fn accuracy(
    path: &Path,
    fractions: Vec<f64>,
    refinements: Vec<u32>,
    duration_s: Option<f64>,
    out: Option<PathBuf>,
) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    for f in &fractions {
        anyhow::ensure!(
            *f > 0.0 && *f <= 1.0,
            "--fractions: {f} is not allowed: 0 < fraction ≤ 1 (of the critical step)"
        );
    }
    for r in &refinements {
        anyhow::ensure!((1..=16).contains(r), "--refinements: {r} is not allowed: 1 ≤ r ≤ 16");
    }
    if let Some(d) = duration_s {
        anyhow::ensure!(d > 0.0 && d.is_finite(), "--duration-s = {d} is not allowed: a positive number of seconds");
    }
    let out = bench_out(&pipeline, out);
    let plan = AccuracyPlan { fractions, refinements, duration_s, seed: pipeline.seeds[0] };
    let rows = run_accuracy(&pipeline.file, &pipeline.analysis.events, &plan, &mut |m| eprintln!("{m}"))?;
    let table = out.join("accuracy.parquet");
    write_parquet_atomic(&mut accuracy_frame(&rows)?, &table)?;
    let figure = out.join("accuracy.png");
    accuracy_figure(&rows, &figure)?;
    println!(
        "{:>10} {:>8} {:>10} {:>9} {:>12} {:>12} {:>12} {:>12} {:>12}",
        "lattice", "Δt/crit", "steps", "wall s", "linear τ", "loading τ", "S1 τ", "S1 drop", "E1 onset"
    );
    for r in &rows {
        let e = &r.errors;
        println!(
            "{:>10} {:>8} {:>10} {:>9.2} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e}",
            format!("{}×{}×{}", r.dims[0], r.dims[1], r.dims[2]),
            r.dt_fraction,
            r.steps,
            r.wall_s,
            e.linear_tau,
            e.loading_tau,
            e.s1_tau,
            e.s1_drop,
            e.e1_onset
        );
    }
    for &r in &plan.refinements {
        let shown = |p: Option<f64>| p.map_or("n/a".to_string(), |p| format!("{p:.2}"));
        println!(
            "refinement {r}: observed order in Δt — τ while linear {} (against its own smallest Δt: {}), \
             before the first event {}, around S1 {}",
            shown(observed_order(&rows, r, |x| x.errors.linear_tau)),
            shown(observed_order(&rows, r, |x| x.linear_tau_error_dt)),
            shown(observed_order(&rows, r, |x| x.errors.loading_tau)),
            shown(observed_order(&rows, r, |x| x.errors.s1_tau))
        );
    }
    if let Some(r) = rows.first() {
        println!(
            "(the reference run is linear until t = {:.4} s: no base node slides, lifts or lands before)",
            r.linear_until_s
        );
    }
    println!("→ {}, {}", table.display(), figure.display());
    Ok(())
}

fn skip(path: &Path, seeds: Option<&str>, jumps: usize, window_s: f64, out: Option<PathBuf>) -> Result<()> {
    let pipeline = Pipeline::load(path)?;
    anyhow::ensure!(
        window_s > 0.0 && window_s.is_finite(),
        "--window-s = {window_s} is not allowed: a positive number of seconds"
    );
    let seeds = match seeds {
        Some(s) => parse_seeds(s).map_err(anyhow::Error::msg)?,
        None => pipeline.seeds.clone(),
    };
    let out = bench_out(&pipeline, out);
    let bench = SkipBench { jumps_per_seed: jumps, window_s };
    let (runs, checks) =
        compare_skip(&pipeline.file, &pipeline.analysis.events, &seeds, bench, &mut |m| eprintln!("{m}"))?;
    let runs_path = out.join("skip_runs.parquet");
    write_parquet_atomic(&mut runs_frame(&runs)?, &runs_path)?;
    let jumps_path = out.join("skip_jumps.parquet");
    write_parquet_atomic(&mut jumps_frame(&checks)?, &jumps_path)?;
    let (full, skip): (f64, f64) = runs.iter().fold((0.0, 0.0), |a, r| (a.0 + r.full_wall_s, a.1 + r.skip_wall_s));
    let (skipped, steps): (u64, u64) = runs.iter().fold((0, 0), |a, r| (a.0 + r.skipped_steps, a.1 + r.shear_steps));
    println!(
        "{} seeds: full integration {full:.2} s, with skip-ahead {skip:.2} s ({:.2}×); {:.1}% of {} shear steps skipped in {} jumps",
        runs.len(),
        full / skip,
        100.0 * skipped as f64 / steps.max(1) as f64,
        steps,
        runs.iter().map(|r| r.jumps).sum::<u64>()
    );
    for r in &runs {
        println!(
            "  seed {}: main shocks full/skip/perturbed {}/{}/{}, mean main drop {:.0}/{:.0}/{:.0} Pa",
            r.seed,
            r.main_shocks[0],
            r.main_shocks[1],
            r.main_shocks[2],
            r.mean_drop_pa[0],
            r.mean_drop_pa[1],
            r.mean_drop_pa[2]
        );
    }
    let max = |f: &dyn Fn(&JumpCheck) -> f64| checks.iter().map(f).filter(|v| v.is_finite()).fold(f64::NAN, f64::max);
    let shown = |v: f64| if v.is_nan() { "n/a".to_string() } else { format!("{v:.2e}") };
    let with_events = checks.iter().filter(|c| c.event[0].is_some() && c.event[1].is_some()).count();
    println!(
        "{} jumps checked one by one: onset error ≤ {} of the recurrence (run perturbed by 1e-9: {}); \
         {with_events} followed by an event: drop error ≤ {} (perturbed run {}); event or none alike in {}/{}",
        checks.len(),
        shown(max(&|c| c.onset_error(1))),
        shown(max(&|c| c.onset_error(2))),
        shown(max(&|c| c.drop_error(1))),
        shown(max(&|c| c.drop_error(2))),
        checks.iter().filter(|c| c.same_events()).count(),
        checks.len()
    );
    println!("→ {}, {}", runs_path.display(), jumps_path.display());
    Ok(())
}

/// The sweep `stickslip-bench convergence` is asked for.
#[derive(clap::Args, Debug)]
struct ConvergenceArgs {
    /// Pipeline file (TOML).
    pipeline: PathBuf,
    /// Loadings: `point` (the pipeline's driver nodes) and/or `patch` (the trailing-face patch
    /// 0.1 ≤ z ≤ 0.3 m).
    #[arg(long, value_delimiter = ',', default_value = "point,patch")]
    loadings: Vec<String>,
    /// Lattice refinements (modules per side multiplied, Lc divided), run at
    /// `--lattice-fraction`.
    #[arg(long, value_delimiter = ',', default_value = "1,2,4")]
    refinements: Vec<u32>,
    /// Seeds per refinement, in the order of `--refinements` (seeds 1…N).
    #[arg(long, value_delimiter = ',', default_value = "64,24,6")]
    seeds: Vec<usize>,
    /// Δt fraction of the lattice sweep [default: the pipeline's].
    #[arg(long, allow_negative_numbers = true)]
    lattice_fraction: Option<f64>,
    /// Δt fractions of the Δt sweep.
    #[arg(long, value_delimiter = ',', default_value = "0.9,0.5,0.25,0.1", allow_negative_numbers = true)]
    fractions: Vec<f64>,
    /// Refinements that get the Δt sweep.
    #[arg(long, value_delimiter = ',', default_value = "1,2")]
    dt_refinements: Vec<u32>,
    /// Shear duration (s) [default: the pipeline's].
    #[arg(long, allow_negative_numbers = true)]
    duration_s: Option<f64>,
    /// Output folder [default: reports/bench/<pipeline name>].
    #[arg(long)]
    out: Option<PathBuf>,
}

fn convergence(a: ConvergenceArgs) -> Result<()> {
    let pipeline = Pipeline::load(&a.pipeline)?;
    let lattice_fraction = a.lattice_fraction.or(pipeline.file.time.dt_fraction).unwrap_or(0.5);
    for f in a.fractions.iter().chain([&lattice_fraction]) {
        anyhow::ensure!(
            *f > 0.0 && *f <= 1.0,
            "Δt fraction {f} is not allowed: 0 < fraction ≤ 1 (of the critical step)"
        );
    }
    for r in a.refinements.iter().chain(&a.dt_refinements) {
        anyhow::ensure!((1..=16).contains(r), "refinement {r} is not allowed: 1 ≤ r ≤ 16");
    }
    anyhow::ensure!(
        a.seeds.len() == a.refinements.len(),
        "--seeds has {} counts for {} refinements: one count per refinement",
        a.seeds.len(),
        a.refinements.len()
    );
    for n in &a.seeds {
        anyhow::ensure!(*n >= 5, "--seeds: {n} is not allowed: at least 5 seeds per cell (a KS test needs them)");
    }
    for r in &a.dt_refinements {
        anyhow::ensure!(a.refinements.contains(r), "--dt-refinements: {r} is not among --refinements");
    }
    if let Some(d) = a.duration_s {
        anyhow::ensure!(d > 0.0 && d.is_finite(), "--duration-s = {d} is not allowed: a positive number of seconds");
    }
    let loadings = a
        .loadings
        .iter()
        .map(|l| Loading::parse(l).ok_or_else(|| anyhow::anyhow!("--loadings: {l:?} is not allowed: point or patch")))
        .collect::<Result<Vec<_>>>()?;
    let mut cells = Vec::new();
    for &loading in &loadings {
        for (&r, &n) in a.refinements.iter().zip(&a.seeds) {
            let mut fs = vec![lattice_fraction];
            if a.dt_refinements.contains(&r) {
                fs.extend(a.fractions.iter().copied().filter(|f| *f != lattice_fraction));
            }
            fs.sort_by(|x, y| y.total_cmp(x));
            cells.extend(fs.into_iter().map(|f| Cell { loading, refinement: r, dt_fraction: f, seeds: n }));
        }
    }
    let out = bench_out(&pipeline, a.out);
    let started = std::time::Instant::now();
    let mut results = Vec::new();
    for c in &cells {
        eprintln!(
            "{} loading, refinement {}, Δt = {} of critical, {} seeds …",
            c.loading.name(),
            c.refinement,
            c.dt_fraction,
            c.seeds
        );
        let r = run_cell(&pipeline.file, c, a.duration_s)?;
        eprintln!("  {}×{}×{}: {:.2} core-s per seed", r.dims[0], r.dims[1], r.dims[2], r.core_s_per_seed);
        results.push(r);
    }
    let rows = compare(&results);
    let table = out.join("convergence.parquet");
    write_parquet_atomic(&mut convergence_frame(&results, &rows)?, &table)?;
    let figure = out.join("convergence.png");
    convergence_figure(&results, &rows, &figure)?;
    let shown = ["main_drop_kpa", "main_recurrence_ms", "main_duration_ms", "m_paper", "pga_m_s2", "sigma_swing"];
    println!(
        "{:<7} {:>9} {:>5} {:>4} {:>7}  {:<19} {:>26} {:>9} {:>9}",
        "loading", "lattice", "Δt", "N", "core-s", "quantity", "mean [95% CI]", "KS p Δt", "KS p lat"
    );
    for c in rows.iter().filter(|c| shown.contains(&c.quantity)) {
        let r = &results[c.cell];
        let p = |x: f64| if x.is_nan() { "–".to_string() } else { format!("{x:.3}") };
        println!(
            "{:<7} {:>9} {:>5} {:>4} {:>7.2}  {:<19} {:>9.3} [{:.3}, {:.3}] {:>9} {:>9}",
            r.cell.loading.name(),
            format!("{}×{}×{}", r.dims[0], r.dims[1], r.dims[2]),
            r.cell.dt_fraction,
            c.n,
            r.core_s_per_seed,
            c.quantity,
            c.mean.0,
            c.mean.1,
            c.mean.2,
            p(c.ks_dt.1),
            p(c.ks_lattice.1)
        );
    }
    debug_assert_eq!(QUANTITIES.len(), results[0].values.len());
    println!(
        "({} cells in {:.0} s) → {} and {}",
        cells.len(),
        started.elapsed().as_secs_f64(),
        table.display(),
        figure.display()
    );
    Ok(())
}

/// `stickslip-bench ensemble`.
fn ensemble(
    pipeline: &Path,
    before: Option<PathBuf>,
    after: Option<PathBuf>,
    large: Option<&Path>,
    repeats: usize,
    floors: bool,
    out: Option<PathBuf>,
) -> Result<()> {
    use stickslip_lab::ensemble_cost::{
        Build, number_after, profile, remove_set_aside, sizes, time_merge, time_pipeline,
    };
    let p = Pipeline::load(pipeline)?;
    let beside = std::env::current_exe()?.with_file_name("stickslip");
    let after = Build { label: "after".into(), binary: after.unwrap_or(beside) };
    anyhow::ensure!(after.binary.exists(), "{}: no such binary (build it, or give --after)", after.binary.display());
    let mut builds = vec![];
    if let Some(b) = before {
        anyhow::ensure!(b.exists(), "--before {}: no such binary", b.display());
        builds.push(Build { label: "before".into(), binary: b });
    }
    builds.push(after);
    let default_out = out.is_none();
    let out = out.unwrap_or_else(|| std::env::temp_dir().join("stickslip-bench-ensemble"));
    std::fs::create_dir_all(&out)?;
    let folder = |b: &Build, t: usize| out.join(format!("{}-{}-{t}", p.name, b.label));
    // The variants are checked before anything is timed.
    let rungs = if floors { stickslip_lab::ensemble_cost::floors(&p, &out.join("floors"))? } else { Vec::new() };
    let rung_folder = |k: usize| out.join(format!("{}-floor-{k}", p.name));
    // Wall times, the builds alternating.
    let mut best = vec![[f64::INFINITY; 2]; builds.len()];
    for rep in 0..repeats {
        for (t, threads) in [1usize, 2].into_iter().enumerate() {
            for (k, b) in builds.iter().enumerate() {
                let (wall, _) = time_pipeline(b, pipeline, threads, &folder(b, threads))?;
                eprintln!("run {}: {} on {threads} thread(s): {wall:.2} s", rep + 1, b.label);
                best[k][t] = best[k][t].min(wall);
            }
        }
    }
    println!("{}: wall time of `stickslip pipeline` (best of {repeats}), and what it writes", p.name);
    println!("| build | 1 thread | 2 threads | 2 threads / 1 | output |");
    println!("|---|---|---|---|---|");
    for (k, b) in builds.iter().enumerate() {
        let (bytes, _) = sizes(&folder(b, 2));
        println!(
            "| {} | {:.2} s | {:.2} s | {:.2}× | {:.1} MB |",
            b.label,
            best[k][0],
            best[k][1],
            best[k][0] / best[k][1],
            bytes as f64 / 1e6
        );
    }
    if builds.len() == 2 {
        println!(
            "after against before: {:.2}× faster on 1 thread, {:.2}× on 2",
            best[0][0] / best[1][0],
            best[0][1] / best[1][1]
        );
    }
    if !rungs.is_empty() {
        let after = builds.last().expect("this build is always timed");
        let mut rung_best = vec![f64::INFINITY; rungs.len()];
        for rep in 0..repeats {
            for (k, f) in rungs.iter().enumerate() {
                let (wall, _) = time_pipeline(after, &f.pipeline, 2, &rung_folder(k))?;
                eprintln!("run {}: {} on 2 threads: {wall:.2} s", rep + 1, f.label);
                rung_best[k] = rung_best[k].min(wall);
            }
        }
        println!(
            "\n{}: what each analysis stage adds to this build's run (2 threads, best of {repeats}; each row adds \
             its stage to the row above)",
            p.name
        );
        println!("| run | 2 threads | added |");
        println!("|---|---|---|");
        for (k, f) in rungs.iter().enumerate() {
            let added = if k == 0 { String::new() } else { format!("{:+.2} s", rung_best[k] - rung_best[k - 1]) };
            println!("| {} | {:.2} s | {added} |", f.label, rung_best[k]);
        }
    }
    for b in &builds {
        let (bytes, parts) = sizes(&folder(b, 2));
        let largest: Vec<String> =
            parts.iter().take(6).map(|(n, s)| format!("{n} {:.1} MB", *s as f64 / 1e6)).collect();
        println!("{} writes {:.1} MB; largest: {}", b.label, bytes as f64 / 1e6, largest.join(", "));
    }
    // Where this build's time goes, one thread, in this process.
    let dir = out.join(format!("{}-profile", p.name));
    let (prof, wall, report) = profile(&p, 1, &dir)?;
    let rows = [
        ("stepping", prof.stepping_s),
        ("events", prof.events_s),
        ("records (processing, intensity, Fourier)", prof.records_s),
        ("response spectra (records alone)", prof.spectra_s),
        ("RotD (with its pair's x and y spectra)", prof.rotd_s),
        ("broadband: stochastic synthesis and joins", prof.broadband_s),
        ("broadband: the records' processing, RotD, measures", prof.broadband_motions_s),
        ("writing (its own thread)", prof.writing_s),
        ("gathering", prof.gather_s),
        ("report (wall)", report),
    ];
    let total: f64 = rows.iter().map(|r| r.1).sum();
    println!(
        "\nprofile of this build, `--threads 1` in this process: CPU seconds by stage ({total:.2} s in all; wall time \
         {:.2} s, the writing thread overlapping the stepping)",
        wall + report
    );
    println!("| stage | CPU seconds | share |");
    println!("|---|---|---|");
    for (name, sec) in rows {
        println!("| {name} | {sec:.2} | {:.0}% |", 100.0 * sec / total);
    }
    if prof.pairs > 0 && prof.alone > 0 {
        let alone = prof.spectra_s / prof.alone as f64;
        let pair = prof.rotd_s / prof.pairs as f64;
        println!(
            "RotD: {:.2} ms per pair with both components' spectra ({} pairs), against {:.2} ms for the spectra of one record alone ({} records): RotD itself costs {:.2} ms per pair ({:.2}× two records' spectra)",
            pair * 1e3,
            prof.pairs,
            alone * 1e3,
            prof.alone,
            (pair - 2.0 * alone) * 1e3,
            pair / (2.0 * alone)
        );
    }
    // Gathering and report of a large folder (every folder is deleted at the end, after the
    // last timed run).
    if let Some(large) = large {
        let lp = Pipeline::load(large)?;
        println!(
            "\n{}: `stickslip merge` of a finished folder (gathering, then the report), best of {repeats}",
            lp.name
        );
        println!("| build | merge | gathering | report | folder |");
        println!("|---|---|---|---|---|");
        let large_folder = |b: &Build| out.join(format!("{}-{}", lp.name, b.label));
        for b in &builds {
            let dir = large_folder(b);
            let (wall, _) = time_pipeline(b, large, 2, &dir)?;
            eprintln!("{}: {} ran in {wall:.1} s", b.label, lp.name);
            let (mut m, mut g, mut r) = (f64::INFINITY, f64::INFINITY, f64::INFINITY);
            for _ in 0..repeats {
                let (wall, text) = time_merge(b, &dir)?;
                m = m.min(wall);
                g = g.min(number_after(&text, "failed) in").unwrap_or(f64::NAN));
                r = r.min(number_after(&text, "figures in").unwrap_or(f64::NAN));
            }
            let (bytes, _) = sizes(&dir);
            println!("| {} | {m:.2} s | {g:.2} s | {r:.2} s | {:.0} MB |", b.label, bytes as f64 / 1e6);
        }
        for b in &builds {
            std::fs::remove_dir_all(large_folder(b)).ok();
        }
    }
    // Deleted once everything is timed (see `ensemble_cost::set_aside`).
    std::fs::remove_dir_all(&dir).ok();
    for b in &builds {
        for t in [1, 2] {
            std::fs::remove_dir_all(folder(b, t)).ok();
        }
    }
    for k in 0..rungs.len() {
        std::fs::remove_dir_all(rung_folder(k)).ok();
    }
    std::fs::remove_dir_all(out.join("floors")).ok();
    remove_set_aside(&out);
    if default_out {
        // Only if empty (two runs with the default folder would set each other's outputs aside:
        // give each its own --out to run them side by side).
        std::fs::remove_dir(&out).ok();
    }
    Ok(())
}

/// An S2's stress drop (Pa), the time its stress falls in (s) and its recurrence (s, NaN if none).
type S2 = (f64, f64, f64);

/// `stickslip-bench readme`.
fn readme(check: bool, only: &[String], binary: Option<PathBuf>) -> Result<()> {
    use stickslip_lab::readme::{Runner, read_docs, remove_main_set_aside, rewrite};
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..").canonicalize()?;
    let binary = binary
        .or_else(|| std::env::var_os("STICKSLIP").map(PathBuf::from))
        .or_else(|| std::env::current_exe().ok().and_then(|e| Some(e.parent()?.join("stickslip"))))
        .filter(|b| b.is_file())
        .ok_or_else(|| {
            anyhow::anyhow!("no stickslip binary: build it (cargo build --release -p stickslip) or give --binary")
        })?;
    let old = read_docs(&root)?;
    let rewritten = rewrite(&old, &Runner::new(binary, root.clone()), only);
    remove_main_set_aside(&root);
    let (new, outcomes) = rewritten?;
    for o in &outcomes {
        println!(
            "{:<14} {:<28} {}{}",
            o.key,
            o.file.display(),
            if o.changed { "changed" } else { "as before" },
            if o.measured { " (measured on this machine)" } else { "" }
        );
    }
    if check {
        let stale: Vec<String> = outcomes
            .iter()
            .filter(|o| o.changed && !o.measured)
            .map(|o| format!("{} ({})", o.key, o.file.display()))
            .collect();
        anyhow::ensure!(stale.is_empty(), "stale blocks: {} (run stickslip-bench readme)", stale.join(", "));
        println!("generated blocks current (measured ones may differ from machine to machine)");
    } else {
        for (before, after) in old.iter().zip(&new) {
            if before.text != after.text {
                std::fs::write(root.join(&after.path), &after.text)?;
                println!("{} rewritten", after.path.display());
            }
        }
    }
    Ok(())
}

/// Each run against the reference, printed as Markdown, with its figures.
fn dynamic_rupture(a: &RuptureArgs) -> Result<()> {
    let reference = Reference::load(&a.reference)?;
    for run in &a.runs {
        let dir = run.join("scec").join(format!("seed{}", a.seed));
        let (stations, field) = read_run(&dir)?;
        let c = scec::compare(&stations, &field, &reference);
        let label = run.file_name().and_then(|s| s.to_str()).unwrap_or("run").to_string();
        println!("## {label} against {}\n", a.reference.display());
        println!("{}", scec::table(&c));
        let png = run.join("scec").join(format!("comparison_seed{}.png", a.seed));
        scec::figure(&png, &label, &stations, &field, &reference)?;
        println!("figures: {} and its _slip_rates companion\n", png.display());
    }
    Ok(())
}
