//! `stickslip pipeline` under `mpirun` or `srun` (the `mpi` feature): every seed of the pipelines
//! split over the ranks (docs/model.md §19, docs/guide/ensembles.md "One scene over MPI ranks").
//! Rank 0 runs the command as one process would (the analysis, the tables, the report, the
//! folder) and hands each seed to the other ranks, which follow it: they load the same pipeline
//! files, then step their part of each seed it names until it says the command is over.

use std::collections::HashMap;
use std::ops::ControlFlow;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};

use crate::mpi_ranks::MpiRanks;
use anyhow::{Context, Result, bail};
use mpi::Threading;
use mpi::environment::Universe;
use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, Root};
use stickslip_config::Pipeline;
use stickslip_ensemble::checkpoints::Checkpoints;
use stickslip_ensemble::split::{SplitSeeds, install};
use stickslip_solver::run::RankPart;
use stickslip_solver::split::Partition;
use stickslip_solver::{Checkpoint, Model, Perturbation, RunOptions, RunOutput, SolverError};

/// The world communicator, used by one thread at a time (MPI is initialised for serialized
/// threads: rank 0 calls it from the ensemble's stepping thread).
pub struct Comm(SimpleCommunicator);

// SAFETY: every use goes through the mutex, so one thread at a time calls MPI, as
// `MPI_THREAD_SERIALIZED` allows.
unsafe impl Send for Comm {}

/// What this process is.
pub enum Role {
    /// Not launched by an MPI launcher, or alone: the command runs as always.
    Alone,
    /// Rank 0 of several: runs the command; tells the others when it is over (on drop).
    Root { _universe: Universe, comm: Arc<Mutex<Comm>> },
    /// Another rank: has followed rank 0's seeds; nothing more to do.
    Follower,
}

impl Drop for Role {
    fn drop(&mut self) {
        // A panic has already aborted every rank (`abort_on_panic`).
        if std::thread::panicking() {
            return;
        }
        if let Role::Root { comm, .. } = self {
            let comm = comm.lock().unwrap_or_else(|e| e.into_inner());
            let mut done = [0.0; ORDER];
            comm.0.process_at_rank(0).broadcast_into(&mut done[..]);
        }
    }
}

/// Whether an MPI launcher started this process (Open MPI, MPICH/Hydra, Slurm's PMI or PMIx), or
/// `srun` started it as one of several tasks.
fn launched() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"].iter().any(|v| std::env::var_os(v).is_some()) || srun_tasks() > 1
}

/// The tasks of the `srun` step that started this process (1 outside one).
fn srun_tasks() -> usize {
    std::env::var("SLURM_STEP_NUM_TASKS").ok().and_then(|v| v.parse().ok()).unwrap_or(1)
}

/// Threads of each rank unless `--threads` says: Slurm's `SLURM_CPUS_PER_TASK`, else the cores
/// over the ranks on this node ([`local_ranks`]), at least one.
fn default_threads() -> usize {
    let var = |v: &str| std::env::var(v).ok().and_then(|s| s.parse::<usize>().ok()).filter(|&n| n > 0);
    if let Some(n) = var("SLURM_CPUS_PER_TASK") {
        return n;
    }
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    (cores / local_ranks()).max(1)
}

/// The ranks on this node: Open MPI's `OMPI_COMM_WORLD_LOCAL_SIZE`, MPICH's `MPI_LOCALNRANKS` or
/// Slurm's `SLURM_NTASKS_PER_NODE`, else 1.
fn local_ranks() -> usize {
    // Slurm writes e.g. `2(x3)` for three nodes of two tasks each.
    let leading = |s: String| s.chars().take_while(char::is_ascii_digit).collect::<String>().parse::<usize>().ok();
    ["OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS", "SLURM_NTASKS_PER_NODE"]
        .iter()
        .find_map(|v| std::env::var(v).ok().and_then(leading).filter(|&n| n > 0))
        .unwrap_or(1)
}

/// Starts MPI when launched by `mpirun`/`srun`: rank 0 installs the split runner and returns to
/// run the command with `threads` threads (this node's cores over its ranks unless given); the
/// others follow its seeds of `pipelines` here, with as many, and return [`Role::Follower`].
pub fn start(pipelines: &[PathBuf], threads: &mut Option<usize>) -> Result<Role> {
    if !launched() {
        return Ok(Role::Alone);
    }
    let (universe, threading) =
        mpi::initialize_with_threading(Threading::Serialized).context("MPI initialises once per process")?;
    if threading < Threading::Serialized {
        bail!("the MPI library gives threading level {threading:?}; stickslip needs MPI_THREAD_SERIALIZED");
    }
    let world = universe.world();
    if world.size() == 1 && srun_tasks() > 1 {
        // Each task alone would run the whole pipeline into the same folder.
        bail!(
            "srun started {} tasks but MPI sees each alone: srun needs the MPI plugin its MPI library was built for \
             (e.g. `srun --mpi=pmix`; `srun --mpi=list` lists them), or start the ranks with mpirun inside the job",
            srun_tasks()
        );
    }
    if world.size() == 1 {
        return Ok(Role::Alone);
    }
    abort_on_panic(world.rank());
    let threads = *threads.get_or_insert_with(default_threads);
    if world.rank() > 0 {
        // A follower that cannot start would leave rank 0 waiting for it: every rank stops.
        let started = pipelines
            .iter()
            .map(|p| Pipeline::load(p))
            .collect::<Result<Vec<_>, _>>()
            .map_err(anyhow::Error::from)
            .and_then(|scenes| {
                // The steps on the global pool, MPI from this thread.
                rayon::ThreadPoolBuilder::new().num_threads(threads).build_global().context("the thread pool")?;
                Ok(scenes)
            });
        match started {
            Ok(scenes) => follow(&world, &scenes),
            Err(e) => abort(world.rank(), &format!("{e:#}")),
        }
        return Ok(Role::Follower);
    }
    let scenes: Vec<Pipeline> = pipelines.iter().map(|p| Pipeline::load(p)).collect::<Result<_, _>>()?;
    let comm = Arc::new(Mutex::new(Comm(world)));
    install(Box::new(RootRunner { comm: comm.clone(), pipelines: scenes, windows: Mutex::new(HashMap::new()) }));
    Ok(Role::Root { _universe: universe, comm })
}

/// Makes a panic on any thread of this rank abort every rank: the others would otherwise wait in
/// their next exchange for ever.
fn abort_on_panic(rank: i32) {
    let report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        report(info);
        abort(rank, "it panicked");
    }));
}

/// Stops every rank of the job, saying why on this rank's standard error.
fn abort(rank: i32, why: &str) -> ! {
    eprintln!("error: MPI rank {rank} stops every rank: {why}");
    // SAFETY: MPI is initialised (the world has several ranks) and MPI_Abort may be called from
    // any thread at any time; it does not return.
    unsafe {
        mpi::ffi::MPI_Abort(mpi::ffi::RSMPI_COMM_WORLD, 70);
    }
    std::process::exit(70)
}

/// Numbers in rank 0's order for a seed.
const ORDER: usize = 10;

/// What rank 0 sends each follower for a seed: the pipeline, the seed, the run options that are
/// not the rank's own (`parallel_step` is: it follows its own threads), and how often the seed's
/// checkpoints are written with the length of the output folder's path (sent next), or −1.
fn order(index: usize, seed: u64, options: &RunOptions, checkpoint: Option<(f64, usize)>) -> [f64; ORDER] {
    let perturb = options.perturb.map_or([0.0; 3], |p| [1.0, p.at_s, p.relative]);
    let (every_s, path) = checkpoint.map_or((-1.0, 0.0), |(s, n)| (s, n as f64));
    [
        1.0,
        index as f64,
        f64::from_bits(seed),
        f64::from(u8::from(options.allow_unstable_time_step)),
        options.max_jumps.map_or(-1.0, |m| m as f64),
        perturb[0],
        perturb[1],
        perturb[2],
        every_s,
        path,
    ]
}

/// The inverse of [`order`]: the pipeline, the seed, the options, and the checkpoints' period
/// with the length of the folder's path.
fn ordered(order: &[f64; ORDER], parallel_step: bool) -> (usize, u64, RunOptions, Option<(f64, usize)>) {
    let options = RunOptions {
        allow_unstable_time_step: order[3] != 0.0,
        parallel_step,
        max_jumps: (order[4] >= 0.0).then_some(order[4] as u64),
        perturb: (order[5] != 0.0).then_some(Perturbation { at_s: order[6], relative: order[7] }),
    };
    let checkpoint = (order[8] > 0.0).then_some((order[8], order[9] as usize));
    (order[1] as usize, order[2].to_bits(), options, checkpoint)
}

/// Rank 0's side of each seed.
struct RootRunner {
    comm: Arc<Mutex<Comm>>,
    pipelines: Vec<Pipeline>,
    /// Each pipeline's partition and rank 0's window, built at its first seed.
    windows: Mutex<HashMap<usize, Arc<(Partition, Model)>>>,
}

impl SplitSeeds for RootRunner {
    fn ranks(&self) -> usize {
        self.comm.lock().map_or(1, |c| c.0.size() as usize)
    }

    fn local_ranks(&self) -> usize {
        local_ranks()
    }

    fn run(
        &self,
        pipeline: &Pipeline,
        seed: u64,
        options: RunOptions,
        checkpoint: Option<&Checkpoint>,
        progress: &mut dyn FnMut(f64) -> ControlFlow<()>,
    ) -> Result<RunOutput, SolverError> {
        let comm = self.comm.lock().unwrap_or_else(|e| e.into_inner());
        let index = self
            .pipelines
            .iter()
            .position(|p| p.hash == pipeline.hash)
            .ok_or_else(|| SolverError::Unsupported("a pipeline not named on the command line".into()))?;
        let ranks = comm.0.size() as usize;
        let part = {
            let mut windows = self.windows.lock().unwrap_or_else(|e| e.into_inner());
            match windows.get(&index) {
                Some(w) => w.clone(),
                None => {
                    let partition = Partition::new(pipeline.scene.dims, ranks).map_err(|e| {
                        SolverError::Unsupported(format!(
                            "this scene split over {ranks} MPI ranks: {e} (block.nz = {})",
                            pipeline.scene.dims.nz
                        ))
                    })?;
                    if pipeline.scene.rupture.is_some() {
                        return Err(SolverError::Unsupported(
                            "a scene whose bars crack ([rupture]) is not split over MPI ranks: run it on one process"
                                .into(),
                        ));
                    }
                    let window = Model::window(pipeline.scene.clone(), partition.window(0));
                    let w = Arc::new((partition, window));
                    windows.insert(index, w.clone());
                    w
                }
            }
        };
        // The output folder: `<out>/checkpoints/<file>`.
        let out = checkpoint.and_then(|c| c.path.parent()?.parent().map(|p| p.as_os_str().as_encoded_bytes().to_vec()));
        // Infinite: written only when stopped.
        let every = checkpoint.map(|c| c.every_s.unwrap_or(f64::INFINITY)).zip(out.as_ref().map(Vec::len));
        let mut order = order(index, seed, &options, every);
        comm.0.process_at_rank(0).broadcast_into(&mut order[..]);
        if let Some(mut out) = out {
            comm.0.process_at_rank(0).broadcast_into(&mut out[..]);
        }
        let mut link = MpiRanks::new(&comm.0);
        let (partition, window) = (&part.0, &part.1);
        let part = RankPart { model: window, partition };
        stickslip_solver::run::run_split(part, seed, options, progress, &mut link, checkpoint)
            .expect("rank 0 has the run's output")
    }
}

/// A rank other than 0: steps its part of each seed rank 0 names, until rank 0 says it is over.
fn follow(world: &SimpleCommunicator, pipelines: &[Pipeline]) {
    // mpirun hands a Ctrl-C to every rank: rank 0's decides, and stops every rank at one step.
    let _ = ctrlc::set_handler(|| {});
    let rank = world.rank() as usize;
    let mut windows: HashMap<usize, (Partition, Model)> = HashMap::new();
    let threads = rayon::current_num_threads() > 1;
    loop {
        let mut order = [0.0f64; ORDER];
        world.process_at_rank(0).broadcast_into(&mut order[..]);
        if order[0] == 0.0 {
            return;
        }
        let (index, seed, options, every) = ordered(&order, threads);
        let checkpoint = every.map(|(every_s, length)| {
            let mut out = vec![0u8; length];
            world.process_at_rank(0).broadcast_into(&mut out[..]);
            // SAFETY: rank 0's `as_encoded_bytes` of a path, on the same platform.
            let out = PathBuf::from(unsafe { std::ffi::OsString::from_encoded_bytes_unchecked(out) });
            let c = Checkpoints { out, every_s, key: pipelines[index].hash.clone() };
            c.of(seed, rank, world.size() as usize)
        });
        let (partition, model) = windows.entry(index).or_insert_with(|| {
            let scene = &pipelines[index].scene;
            let partition = Partition::new(scene.dims, world.size() as usize).expect("rank 0 split it");
            let model = Model::window(scene.clone(), partition.window(rank));
            (partition, model)
        });
        let options = RunOptions { parallel_step: options.parallel_step && model.layout().splits(), ..options };
        let mut link = MpiRanks::new(world);
        let mut go_on = |_| ControlFlow::Continue(());
        let part = RankPart { model, partition };
        match stickslip_solver::run::run_split(part, seed, options, &mut go_on, &mut link, checkpoint.as_ref()) {
            // Rank 0 says it was stopped.
            Some(Err(SolverError::Cancelled)) => {}
            Some(Err(e)) => eprintln!("MPI rank {rank}, seed {seed}: {e}"),
            // Run through: rank 0 removes every rank's checkpoint once the seed is written (a
            // stop before that resumes from them).
            _ => {}
        }
        if let Some(why) = checkpoint.as_ref().and_then(Checkpoint::failure) {
            eprintln!("warning: MPI rank {rank}, seed {seed}'s checkpoint: {why}");
        }
    }
}
