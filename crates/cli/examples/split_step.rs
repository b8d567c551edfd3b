//! Steps one scene split over MPI ranks and, with `--check`, compares every node's three time
//! levels with the same steps on one process, bit for bit (docs/model.md §19):
//!
//! ```text
//! mpirun -n 3 target/release/examples/split_step pipelines/tpv5-500m.toml --steps 120 --check
//! ```
//!
//! The scene starts as the split tests start theirs (a smooth displacement everywhere, damping,
//! the pipeline's gravity, drivers on); each rank steps its slab with `--threads` threads and
//! prints what a step cost it and how much of that was the exchange. Exit status 1 when a node
//! differs.

use std::time::{Duration, Instant};

use mpi::traits::{Communicator, CommunicatorCollectives, Destination, Root, Source};
use stickslip_config::Pipeline;
use stickslip_solver::field::Field;
// The command line's MPI ranks (the package has no library to import them from).
#[path = "../src/mpi_ranks.rs"]
mod mpi_ranks;
use mpi_ranks::MpiRanks;
use stickslip_solver::split::{Halo, Partition};
use stickslip_solver::statics::critical_step;
use stickslip_solver::step::{Batch, LaneSetup, start_drivers};
use stickslip_solver::{Model, Scene};

struct Args {
    pipeline: String,
    steps: usize,
    check: bool,
    threads: usize,
}

fn args() -> Result<Args, String> {
    let mut out = Args { pipeline: String::new(), steps: 100, check: false, threads: 1 };
    let mut it = std::env::args().skip(1);
    while let Some(a) = it.next() {
        match a.as_str() {
            "--steps" => out.steps = it.next().and_then(|v| v.parse().ok()).ok_or("--steps takes a count")?,
            "--threads" => out.threads = it.next().and_then(|v| v.parse().ok()).ok_or("--threads takes a count")?,
            "--check" => out.check = true,
            p if !p.starts_with('-') && out.pipeline.is_empty() => out.pipeline = p.to_string(),
            other => return Err(format!("unknown argument {other:?}")),
        }
    }
    if out.pipeline.is_empty() {
        return Err("usage: split_step <pipeline.toml> [--steps N] [--threads T] [--check]".into());
    }
    Ok(out)
}

fn setup(model: &Model, dt_s: f64) -> LaneSetup {
    let seed = 1;
    LaneSetup {
        dt_s,
        stiffness: model.lane_stiffness(seed).expect("stiffness"),
        friction: model.friction_factors(seed).expect("friction"),
        strength: None,
        fault: model.fault_loads(seed).expect("fault loads"),
    }
}

fn start(p: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let w = |p: [f64; 3], s: f64| 1e-6 * ((0.37 * p[0] + 0.11 * s).sin() + (0.23 * p[1] - 0.7 * p[2]).cos());
    ([w(p, 0.0), w(p, 1.0), w(p, 2.0)], [w(p, 0.1), w(p, 1.1), w(p, 2.1)])
}

fn prepare(batch: &mut Batch<'_, 1>) {
    let g = batch.params.model.scene().self_weight.gravity_m_s2;
    batch.params.set_damping(0, 50.0);
    batch.params.set_body_acceleration(0, [0.0, 0.0, -g]);
    batch.initialize(0, start);
    start_drivers(batch.params.model, &mut batch.state, 0);
}

/// The whole block's time step, from its critical step (rank 0 builds the whole model for it).
fn time_step(scene: &Scene) -> f64 {
    let model = Model::new(scene.clone());
    let lane = setup(&model, 1.0);
    0.5 * critical_step(&model, &lane.stiffness).expect("critical step").dt_s
}

fn levels(u: &[&Field<1>; 3], nodes: std::ops::Range<usize>) -> Vec<f64> {
    let mut out = Vec::with_capacity(9 * nodes.len());
    for f in u {
        for c in 0..3 {
            out.extend(f.c[c][nodes.clone()].iter().map(|v| v[0]));
        }
    }
    out
}

fn main() {
    let args = match args() {
        Ok(a) => a,
        Err(e) => {
            eprintln!("{e}");
            std::process::exit(2);
        }
    };
    let universe = mpi::initialize().expect("MPI initialises once");
    let world = universe.world();
    let (rank, size) = (world.rank() as usize, world.size() as usize);
    let root = world.process_at_rank(0);
    let scene = Pipeline::load(std::path::Path::new(&args.pipeline)).unwrap_or_else(|e| panic!("{e}")).scene;
    let partition = Partition::new(scene.dims, size).unwrap_or_else(|e| {
        if rank == 0 {
            eprintln!("{e}");
        }
        std::process::exit(2)
    });
    let mut dt = if rank == 0 { time_step(&scene) } else { 0.0 };
    root.broadcast_into(&mut dt);
    let window = partition.window(rank);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(args.threads).build().expect("a pool");
    let model = Model::window(scene.clone(), window.clone());
    let mut batch = Batch::new(&model, &[setup(&model, dt)]);
    batch.stepper.set_parallel(args.threads > 1);
    prepare(&mut batch);
    let mut halo = Halo::default();
    let mut link = MpiRanks::new(&world);
    let (mut stepping, mut exchanging) = (Duration::ZERO, Duration::ZERO);
    world.barrier();
    let t0 = Instant::now();
    for _ in 0..args.steps {
        // The step on the rank's pool, MPI on this thread only.
        let t = Instant::now();
        pool.install(|| batch.step());
        stepping += t.elapsed();
        let t = Instant::now();
        halo.exchange(&window, &mut batch.state.u.np1, &mut link);
        exchanging += t.elapsed();
    }
    world.barrier();
    let wall = t0.elapsed();
    let bytes = 8 * 3 * (window.send_below().len() + window.send_above().len());
    let per_step = |d: Duration| 1e3 * d.as_secs_f64() / args.steps as f64;
    let line = format!(
        "rank {rank}/{size}: layers {:?}, {} nodes held ({} owned), step {:.3} ms, exchange {:.3} ms ({:.1}%), {} B sent per step",
        partition.owned_layers(rank),
        window.nodes,
        window.owned.len(),
        per_step(stepping),
        per_step(exchanging),
        100.0 * exchanging.as_secs_f64() / (stepping + exchanging).as_secs_f64(),
        bytes
    );
    // Every rank's line and owned levels to rank 0, in rank order.
    let u = &batch.state.u;
    let mine = levels(&[&u.nm1, &u.n, &u.np1], window.owned.clone());
    if rank > 0 {
        root.send(line.as_bytes());
        root.send(&mine[..]);
        return;
    }
    println!(
        "{} over {size} ranks, {} steps of {dt:e} s: {:.3} s wall, {:.3} ms per step",
        args.pipeline,
        args.steps,
        wall.as_secs_f64(),
        1e3 * wall.as_secs_f64() / args.steps as f64
    );
    println!("{line}");
    let mut parts = vec![(window.clone(), mine)];
    for r in 1..size {
        let (text, _) = world.process_at_rank(r as i32).receive_vec::<u8>();
        println!("{}", String::from_utf8_lossy(&text));
        let (data, _) = world.process_at_rank(r as i32).receive_vec::<f64>();
        parts.push((partition.window(r), data));
    }
    if !args.check {
        return;
    }
    let whole = Model::new(scene);
    let mut single = Batch::new(&whole, &[setup(&whole, dt)]);
    prepare(&mut single);
    let t = Instant::now();
    for _ in 0..args.steps {
        single.step();
    }
    let one = t.elapsed();
    let s = &single.state.u;
    let reference = levels(&[&s.nm1, &s.n, &s.np1], 0..whole.node_count());
    let n = whole.node_count();
    let mut differ = 0usize;
    for (w, data) in &parts {
        let m = w.owned.len();
        for level in 0..3 {
            for c in 0..3 {
                for (k, i) in w.owned.clone().enumerate() {
                    let (a, b) = (data[(3 * level + c) * m + k], reference[(3 * level + c) * n + w.global(i)]);
                    differ += usize::from(a.to_bits() != b.to_bits());
                }
            }
        }
    }
    println!(
        "one process: {:.3} ms per step; {} of {} node values differ from it",
        1e3 * one.as_secs_f64() / args.steps as f64,
        differ,
        9 * n
    );
    if differ > 0 {
        std::process::exit(1);
    }
}
