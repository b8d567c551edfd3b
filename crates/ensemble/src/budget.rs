//! What a scene will cost, checked before it is built: its memory against what the machine has
//! available, and the length of its runs against [`LONG_RUN_BAR_UPDATES`].

use crate::error::EnsembleError;
use stickslip_config::describe::duration;
use stickslip_solver::Scene;
use stickslip_solver::error::MAX_STEPS;
use stickslip_solver::memory::{
    Batches, LONG_RUN_BAR_UPDATES, MemoryEstimate, dt_estimate, estimate, estimate_rank, human, run_steps, samples,
};

/// Environment variable that sets the memory limit in bytes (a suffix k, M, G or T multiplies by
/// 1024's powers), instead of what the machine reports available.
pub const MEMORY_LIMIT_VAR: &str = "STICKSLIP_MEMORY_LIMIT";

/// The memory a run may use (bytes) and where the number comes from: [`MEMORY_LIMIT_VAR`] if
/// set, else the smallest of the kernel's `MemAvailable`, the room left under the cgroup's
/// `memory.max` (a Slurm job's limit) and the room left under the process's address-space limit
/// (`ulimit -v`); `None` where none can be read.
pub fn available_memory() -> Result<Option<(u64, String)>, EnsembleError> {
    if let Ok(v) = std::env::var(MEMORY_LIMIT_VAR) {
        let bytes = parse_bytes(&v).ok_or_else(|| {
            refused(format!("{MEMORY_LIMIT_VAR} = {v:?}: give a number of bytes, e.g. 16G or 17179869184"))
        })?;
        return Ok(Some((bytes, format!("{MEMORY_LIMIT_VAR}={v}"))));
    }
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok().and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("MemAvailable:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let read = |p: &str| std::fs::read_to_string(p).ok().and_then(|t| t.trim().parse::<u64>().ok());
    let cgroup = read("/sys/fs/cgroup/memory.max")
        .map(|max| max.saturating_sub(read("/sys/fs/cgroup/memory.current").unwrap_or(0)));
    let limits = [
        meminfo.map(|m| (m, "MemAvailable of /proc/meminfo")),
        cgroup.map(|c| (c, "the room left under the cgroup's memory.max")),
        address_space_room().map(|a| (a, "the room left under the address-space limit, ulimit -v")),
    ];
    Ok(limits.into_iter().flatten().min_by_key(|(b, _)| *b).map(|(b, source)| (b, source.to_string())))
}

/// Bytes of address space this process may still map under its `RLIMIT_AS` (`ulimit -v`): the
/// limit less the process's virtual size (`VmSize` of /proc/self/status); `None` without a limit.
/// A run's arrays are mapped address space before they are resident memory, so a scene that does
/// not fit under it would abort at its first large allocation.
fn address_space_room() -> Option<u64> {
    let mut lim = libc::rlimit { rlim_cur: 0, rlim_max: 0 };
    // SAFETY: getrlimit writes the limit into the struct it is given.
    if unsafe { libc::getrlimit(libc::RLIMIT_AS, &mut lim) } != 0 || lim.rlim_cur == libc::RLIM_INFINITY {
        return None;
    }
    let size = std::fs::read_to_string("/proc/self/status").ok().and_then(|t| {
        t.lines()
            .find_map(|l| l.strip_prefix("VmSize:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    Some(lim.rlim_cur.saturating_sub(size.unwrap_or(0)))
}

/// A refusal of the budget: its message says what to change.
fn refused(message: String) -> EnsembleError {
    EnsembleError::Refused(message)
}

fn parse_bytes(v: &str) -> Option<u64> {
    let v = v.trim();
    let (digits, shift) = match v.chars().last()? {
        'k' | 'K' => (&v[..v.len() - 1], 10),
        'm' | 'M' => (&v[..v.len() - 1], 20),
        'g' | 'G' => (&v[..v.len() - 1], 30),
        't' | 'T' => (&v[..v.len() - 1], 40),
        _ => (v, 0),
    };
    digits.trim().parse::<u64>().ok()?.checked_mul(1u64 << shift)
}

/// The memory of `seeds` seeds of `scene` on `threads` threads, refused (with what to change)
/// when it does not fit what the machine has available. `what` names the run in the message.
pub fn check_memory(scene: &Scene, seeds: usize, threads: usize, what: &str) -> Result<MemoryEstimate, EnsembleError> {
    let batches = Batches::of_ensemble(seeds, threads, scene.skip_ahead.enabled);
    let dt = dt_estimate(scene);
    let n_samples = samples(scene, dt);
    // What the run holds without its records: when that fits and the whole does not, the records
    // are what to cut (a long stage sampled finely), not the modules.
    let bare = estimate(scene, batches, 2).ok();
    let records = |total: &str, limit: &str| {
        refused(format!(
            "{what}: the records of a seed, {n_samples} samples of every recorded channel (shear.duration_s / \
             record.interval_s, every step without it), need {total}, and {limit}: record less — a longer \
             record.interval_s or a shorter shear.duration_s (pipeline keys: record.interval_s, shear.duration_s)"
        ))
    };
    let est = match (estimate(scene, batches, n_samples), &bare) {
        (Ok(e), _) => e,
        (Err(_), Some(_)) => return Err(records("more bytes than 64 bits count", "the lattice alone fits")),
        (Err(e), None) => {
            return Err(refused(format!(
                "{what}: {e}: use fewer modules (pipeline keys: block.nx, block.ny, block.nz)"
            )));
        }
    };
    let Some((limit, source)) = available_memory()? else { return Ok(est) };
    if est.total <= limit {
        return Ok(est);
    }
    if let Some(b) = bare.filter(|b| b.total <= limit) {
        return Err(records(
            &format!("about {} of the {} a run needs", human(est.total - b.total), human(est.total)),
            &format!("{} is available ({source})", human(limit)),
        ));
    }
    let one = estimate(scene, Batches::ONE, n_samples)
        .map_err(|e| refused(format!("{what}: {e} (pipeline keys: block.nx, block.ny, block.nz)")))?;
    let d = scene.dims;
    let per_module = (est.total.saturating_sub(est.model) as f64) / (d.nx as f64 * d.ny as f64 * d.nz as f64);
    let modules = (limit as f64 * 0.9 / per_module.max(1.0)).max(1.0);
    let mut change = Vec::new();
    if batches.concurrent > 1 || batches.lanes > 1 {
        if one.total <= limit {
            let fits = (1..=batches.concurrent)
                .rev()
                .find(|&t| {
                    estimate(scene, Batches::of_ensemble(seeds, t, scene.skip_ahead.enabled), n_samples)
                        .is_ok_and(|e| e.total <= limit)
                })
                .unwrap_or(1);
            change
                .push(format!("run fewer seeds at once (--threads {fits}; one seed alone needs {})", human(one.total)));
        } else {
            change.push(format!("even one seed alone needs {}", human(one.total)));
        }
    }
    change.push(format!(
        "use fewer modules (about {:.3e} modules fit, the block has {}×{}×{} = {:.3e}; a larger block.lc_m over the same extent \
         has fewer)",
        modules,
        d.nx,
        d.ny,
        d.nz,
        d.nx as f64 * d.ny as f64 * d.nz as f64
    ));
    change.push(
        "or run on a machine with more memory (or set STICKSLIP_MEMORY_LIMIT if the machine has more than it reports)"
            .into(),
    );
    Err(refused(format!(
        "{what} does not fit in memory: it needs about {} ({} nodes, {} bars: {} for the lattice, {} per batch of {} seed{} \
         × {} at once, {} while a batch is set up), and {} is available ({source}); {} (pipeline keys: block.nx, \
         block.ny, block.nz, block.lc_m)",
        human(est.total),
        est.nodes,
        est.bars,
        human(est.model),
        human(est.batch),
        batches.lanes,
        if batches.lanes == 1 { "" } else { "s" },
        batches.concurrent,
        human(est.setup),
        human(limit),
        change.join("; ")
    )))
}

/// Bar-updates per second of one thread of the development machine on a large lattice (whole
/// runs of 2.8–50 M bars, 3.3·10⁸: BENCHMARKS.md §8): the rate of what a run will take, estimated
/// before its lattice is built (`check` then times this machine).
pub const NOMINAL_RATE: f64 = 3.3e8;

/// The keys of a pipeline file that set a run's length.
const LENGTH_KEYS: &str =
    "shear.duration_s, self_weight.max_duration_s, time.dt_fraction, time.dt_s, block.nx, block.ny, block.nz";

/// Refuses, whatever `--allow-long` says, a run of `scene` at Δt = `dt` with a stage of more steps
/// than it can count ([`MAX_STEPS`], or 2^64 bar-updates of `bars` bars): the limit the run of
/// each seed enforces (`run::check_step_count`), checked before anything is built or estimated.
pub fn check_count(scene: &Scene, bars: u64, dt: f64, what: &str) -> Result<(), EnsembleError> {
    let (settle, shear) = run_steps(scene, dt);
    let updates = (settle as f64 + shear as f64) * bars as f64;
    if settle as f64 > MAX_STEPS || shear as f64 > MAX_STEPS || updates >= u64::MAX as f64 {
        return Err(refused(format!(
            "{what}: one seed is {:.3e} steps at Δt = {dt:.3e} s ({}shear {:.3e}) of {bars} bars, more than a run \
             can count (2^53 steps, 2^64 bar-updates; --allow-long does not lift this): lengthen the step \
             (time.dt_s or time.dt_fraction) or shorten shear.duration_s (pipeline keys: {LENGTH_KEYS})",
            settle as f64 + shear as f64,
            if settle > 0 { format!("self-weight up to {:.3e} + ", settle as f64) } else { String::new() },
            shear as f64
        )));
    }
    Ok(())
}

/// The bar-updates of one seed of `scene` at Δt = `dt` (the self-weight stage counted at its
/// longest): refused above [`LONG_RUN_BAR_UPDATES`] without `allow_long`, and refused whatever
/// `allow_long` says when a stage has more steps than a run can count ([`MAX_STEPS`], or 2^64
/// bar-updates: the limit the run of each seed enforces, `run::check_step_count`).
/// `rate` is the bar-updates per second of a timed probe ([`NOMINAL_RATE`] when none was made).
pub fn check_length(
    scene: &Scene,
    bars: u64,
    dt: f64,
    rate: Option<f64>,
    allow_long: bool,
    what: &str,
) -> Result<f64, EnsembleError> {
    check_count(scene, bars, dt, what)?;
    let (settle, shear) = run_steps(scene, dt);
    let updates = (settle as f64 + shear as f64) * bars as f64;
    // Both below 2^53 from here: their sum cannot overflow.
    // With the skip-ahead the quasi-static stretches between events are jumped, not stepped:
    // the count above is a bound that says nothing of the run's length (slow-loading.toml bounds
    // 3.7e9 steps and steps about 1e7).
    if updates > LONG_RUN_BAR_UPDATES && !allow_long && !scene.skip_ahead.enabled {
        return Err(refused(format!(
            "{what}: one seed is {} steps ({}shear {shear}) of {bars} bars, {updates:.3e} bar-updates, above the limit of \
             {LONG_RUN_BAR_UPDATES:.0e} for a run nobody asked to be long (about {} at {:.1e} bar-updates/s{}): pass \
             --allow-long to run it, or shorten shear.duration_s, or use fewer modules (pipeline keys: {LENGTH_KEYS})",
            settle + shear,
            if settle > 0 { format!("self-weight up to {settle} + ") } else { String::new() },
            duration(updates / rate.unwrap_or(NOMINAL_RATE)),
            rate.unwrap_or(NOMINAL_RATE),
            if rate.is_some() { ", a timed probe" } else { "" }
        )));
    }
    Ok(updates)
}

/// Whether a scene is refused before it is built: its memory, and its length at the Δt estimated
/// from the paper's bound (`pipeline` does not build the lattice twice).
pub fn check_before_build(
    scene: &Scene,
    seeds: usize,
    threads: usize,
    allow_long: bool,
    what: &str,
) -> Result<(), EnsembleError> {
    if let Ok(e) = estimate(scene, Batches::ONE, 2) {
        check_count(scene, e.bars, dt_estimate(scene), what)?;
    }
    let est = check_memory(scene, seeds, threads, what)?;
    check_length(scene, est.bars, dt_estimate(scene), None, allow_long, what)?;
    Ok(())
}

/// [`check_before_build`] for a seed split over `ranks` MPI ranks, `local` of them on this node:
/// rank 0's part (the largest: its slab, the recording and the whole block's model, as
/// `stickslip check --ranks` counts it) against this node's available memory over its ranks, and
/// the run's length as one process's.
pub fn check_before_build_split(
    scene: &Scene,
    ranks: usize,
    local: usize,
    allow_long: bool,
    what: &str,
) -> Result<(), EnsembleError> {
    use stickslip_solver::split::Partition;
    let e = estimate(scene, Batches::ONE, 2).map_err(|e| refused(format!("{what}: {e}")))?;
    check_count(scene, e.bars, dt_estimate(scene), what)?;
    let partition = Partition::new(scene.dims, ranks).map_err(|e| refused(format!("{what}: {e}")))?;
    let root = estimate_rank(scene, &partition, 0, samples(scene, dt_estimate(scene)))
        .map_err(|e| refused(format!("{what}: {e}")))?;
    if let Some((limit, source)) = available_memory()? {
        let share = limit / local.max(1) as u64;
        if root.total > share {
            return Err(refused(format!(
                "{what}: rank 0 of {ranks} MPI ranks needs about {} but this node has {} for each of its {local} ranks \
                 ({source}): use more ranks, fewer ranks per node or more memory (`stickslip check PIPELINE --ranks \
                 {ranks}` sizes every rank)",
                human(root.total),
                human(share)
            )));
        }
    }
    check_length(scene, e.bars, dt_estimate(scene), None, allow_long, what)?;
    Ok(())
}

/// A `[cycles]` run's memory ([`stickslip_solver::cycles::CycleSpec::memory_bytes`]) against
/// what is available, before anything is built.
pub fn check_cycles(
    scene: &Scene,
    spec: &stickslip_solver::cycles::CycleSpec,
    what: &str,
) -> Result<u64, EnsembleError> {
    let need = spec.memory_bytes(scene);
    let Some((limit, source)) = available_memory()? else { return Ok(need) };
    if need <= limit {
        return Ok(need);
    }
    let grid = if spec.dynamic.is_some() { ", a smaller cycles.dynamic_block_m" } else { "" };
    Err(refused(format!(
        "{what}: the cycle run needs about {:.0} MB (the fault's stiffness over its {} frictional nodes, the explicit \
         grid, the files) and {:.0} MB is available ({source}): use larger modules or a shallower frictional part{grid} \
         (pipeline keys: block.lc_m, cycles.frictional_depth_m{})",
        need as f64 / 1e6,
        spec.frictional_nodes(scene.lc_m, scene.dims.ny),
        limit as f64 / 1e6,
        if spec.dynamic.is_some() { ", cycles.dynamic_block_m" } else { "" }
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn byte_counts_with_suffixes() {
        assert_eq!(parse_bytes("1024"), Some(1024));
        assert_eq!(parse_bytes("16G"), Some(16 << 30));
        assert_eq!(parse_bytes("512m"), Some(512 << 20));
        assert_eq!(parse_bytes("lots"), None);
        assert_eq!(parse_bytes("99999999999T"), None);
    }
}
