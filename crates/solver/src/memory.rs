//! What a run of a scene holds in memory, estimated from the scene alone, before anything is
//! built: `stickslip check` and `stickslip pipeline` refuse a scene that would not fit.
//!
//! Every size is computed with checked arithmetic: a scene whose arrays could not even be
//! addressed gets [`MemoryEstimate::overflow`] instead of a wrapped number.
//!
//! The estimate counts the arrays of [`crate::Model`] (shared by every seed), those of one batch
//! of `L` seeds advanced side by side (time levels, forces, bar stiffness, the static solves and
//! the skip-ahead when the scene asks for them, the recorded series) and what setting a batch up
//! holds before its state exists (the lanes' stiffness, the critical step's Lanczos vectors, the
//! sort of a listed lattice's bars). The
//! recording of the fault through bursts of slip (`record.fault`) grows with the events and is
//! not counted; nor are the tables written after the run, which are a few times the recording.

use crate::geometry::Dims;
use crate::model::STENCIL_MIN_BARS;
use crate::scene::{Scene, SettleMethod, TimeStep};

/// Resident memory of the process before any scene: the binary, its libraries, the thread stacks
/// (measured: `stickslip check pipelines/paper.toml` peaks at about 20 MB).
pub const PROCESS_BYTES: u64 = 32 << 20;

/// How the seeds of a run share the machine: `concurrent` batches of `lanes` seeds each at once.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Batches {
    /// Seeds advanced side by side in one batch (1, 4 or 8).
    pub lanes: usize,
    /// Batches running at once (one per worker thread at most).
    pub concurrent: usize,
}

impl Batches {
    /// One seed alone.
    pub const ONE: Batches = Batches { lanes: 1, concurrent: 1 };

    /// How `stickslip pipeline` runs `seeds` seeds on `threads` threads: batches of 8 seeds when
    /// each thread has at least 8, of 4 when at least 4, else one seed each (and with fewer
    /// seeds than threads, one step split over the threads); at most `threads` batches at once.
    pub fn of_ensemble(seeds: usize, threads: usize, skip_ahead: bool) -> Batches {
        let threads = threads.max(1);
        let per_thread = seeds.div_ceil(threads);
        let lanes = if skip_ahead {
            1
        } else if per_thread >= 8 {
            8
        } else if per_thread >= 4 {
            4
        } else {
            1
        };
        Batches { lanes, concurrent: seeds.div_ceil(lanes).clamp(1, threads) }
    }
}

/// The estimate, in bytes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct MemoryEstimate {
    /// Nodes of the lattice.
    pub nodes: u64,
    /// Bars of the lattice.
    pub bars: u64,
    /// The model, shared by every batch.
    pub model: u64,
    /// One batch while it steps (state, forces, stiffness, recording, static solves).
    pub batch: u64,
    /// Setting up one batch, before its state exists.
    pub setup: u64,
    /// The whole process: [`PROCESS_BYTES`], the model, `concurrent − 1` batches stepping and one
    /// more stepping or being set up, whichever is larger.
    pub total: u64,
}

impl MemoryEstimate {
    /// Bytes per bar of the whole process.
    pub fn bytes_per_bar(&self) -> f64 {
        self.total as f64 / self.bars.max(1) as f64
    }
}

/// Why there is no estimate: a size that does not fit in 64 bits.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Overflow(pub String);

impl std::fmt::Display for Overflow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} does not fit in 64 bits", self.0)
    }
}

/// Node and bar counts of `dims`, overflow-checked.
pub fn counts(dims: Dims) -> Result<(u64, u64), Overflow> {
    let [nx, ny, nz] = [dims.nx, dims.ny, dims.nz].map(|v| v as u64);
    let over = |what: &str| Overflow(format!("the {what} of a {nx}×{ny}×{nz} block"));
    let mul = |a: u64, b: u64| a.checked_mul(b);
    let modules = mul(nx, ny).and_then(|v| mul(v, nz)).ok_or_else(|| over("module count"))?;
    let corners = mul(nx + 1, ny + 1).and_then(|v| mul(v, nz + 1)).ok_or_else(|| over("node count"))?;
    let nodes = corners.checked_add(modules).ok_or_else(|| over("node count"))?;
    let edges = [mul(nx, ny + 1), mul(nx + 1, ny), mul(nx + 1, ny + 1)]
        .into_iter()
        .zip([nz + 1, nz + 1, nz])
        .try_fold(0u64, |acc, (a, b)| a.and_then(|a| mul(a, b)).and_then(|v| acc.checked_add(v)))
        .ok_or_else(|| over("bar count"))?;
    let centre = [mul(nx.saturating_sub(1), ny), mul(nx, ny.saturating_sub(1)), mul(nx, ny)]
        .into_iter()
        .zip([nz, nz, nz.saturating_sub(1)])
        .try_fold(0u64, |acc, (a, b)| a.and_then(|a| mul(a, b)).and_then(|v| acc.checked_add(v)))
        .ok_or_else(|| over("bar count"))?;
    let bars = mul(8, modules)
        .and_then(|d| d.checked_add(edges))
        .and_then(|v| v.checked_add(centre))
        .ok_or_else(|| over("bar count"))?;
    Ok((nodes, bars))
}

/// Bytes of a run of `scene` in `batches`, each recording about `samples` samples.
pub fn estimate(scene: &Scene, batches: Batches, samples: u64) -> Result<MemoryEstimate, Overflow> {
    let (n, b) = counts(scene.dims)?;
    let contact = (scene.dims.nx as u64 + 1) * (scene.dims.ny as u64 + 1);
    let stencil = scene.rupture.is_none() && b >= STENCIL_MIN_BARS as u64;
    estimate_counts(scene, (n, b, contact), stencil, batches, samples)
}

/// Bytes of rank `rank` of `scene` split by `partition` ([`crate::split`]): its window's nodes and
/// bars (a stencil), one seed, with the seed's critical step found by the ranks together (its
/// Lanczos vectors over the window, and one more for the terms of the sums). Rank 0 also holds
/// the base's contact nodes, the recording (about `samples` samples) and the whole block's model,
/// which the analyses of each seed read.
pub fn estimate_rank(
    scene: &Scene,
    partition: &crate::split::Partition,
    rank: usize,
    samples: u64,
) -> Result<MemoryEstimate, Overflow> {
    let w = partition.window(rank);
    let nodes = w.nodes as u64;
    // A block below STENCIL_MIN_BARS is small: its window's listed bars are counted.
    let stencil = scene.dims.bar_count() >= STENCIL_MIN_BARS;
    let bars = if stencil {
        crate::stencil::StencilLayout::window(scene.dims, w.lo, w.hi).bars() as u64
    } else {
        crate::model::window_bar_count(&scene.lattice(), &w) as u64
    };
    let over = || Overflow(format!("the memory of rank {rank} of a {nodes}-node, {bars}-bar window"));
    let root = rank == 0;
    let contact = if root { (scene.dims.nx as u64 + 1) * (scene.dims.ny as u64 + 1) } else { 0 };
    let part = estimate_counts(scene, (nodes, bars, contact), stencil, Batches::ONE, if root { samples } else { 0 })?;
    let setup = nodes.checked_mul(24).and_then(|t| part.setup.checked_add(t)).ok_or_else(over)?;
    let whole = if root { estimate(scene, Batches::ONE, 0)?.model } else { 0 };
    let model = part.model.checked_add(whole).ok_or_else(over)?;
    let total = part.batch.max(setup).checked_add(model).and_then(|v| v.checked_add(PROCESS_BYTES)).ok_or_else(over)?;
    Ok(MemoryEstimate { nodes, bars, model, batch: part.batch, setup, total })
}

fn estimate_counts(
    scene: &Scene,
    (n, b, contact): (u64, u64, u64),
    stencil: bool,
    batches: Batches,
    samples: u64,
) -> Result<MemoryEstimate, Overflow> {
    let over = || Overflow(format!("the memory of a {n}-node, {b}-bar scene"));
    let l = batches.lanes as u64;
    // Sums and products of terms `(count, bytes)`, checked.
    let sum = |terms: &[(u64, u64)]| -> Result<u64, Overflow> {
        terms.iter().try_fold(0u64, |acc, &(c, s)| c.checked_mul(s).and_then(|v| acc.checked_add(v))).ok_or_else(over)
    };

    // The model: internal ↔ canonical order (4 + 4), mass and inverse mass (8 + 8) per node; a
    // listed lattice's ends (8) and canonical index (4) per bar; the stencil's runs are a few per
    // row of nodes.
    let model = if stencil {
        sum(&[(n, 24), (n / (scene.dims.nx as u64).max(1), 56), (contact, 4)])?
    } else {
        sum(&[(n, 24), (b, 12), (contact, 4)])?
    };

    // One batch: three time levels and the forces (3 components × L lanes × 8 bytes each), the
    // bar stiffness (per bar: L f64 listed, L f32 factors on a stencil, none when homogeneous),
    // bars that crack (peak, secant, reach and flags), contact state per node and lane, the
    // recording (channels × samples), a static self-weight or the skip-ahead (per-bar stiffness and
    // the conjugate-gradient vectors).
    let per_bar_k = if stencil { if scene.young_cv > 0.0 { 4 * l } else { 0 } } else { 8 * l };
    let rupture = if scene.rupture.is_some() { 8 * 3 * l + 2 * l } else { 0 };
    // The medium's memory variables (f32 per mechanism and lane), and a listed lattice's zone per
    // bar (docs/model.md §18).
    let anelastic = if scene.medium.attenuation.is_some() { 4 * crate::medium::MECHANISMS as u64 * l } else { 0 }
        + if scene.medium.is_dissipative() && !stencil { 1 } else { 0 };
    let channels = 24 + scene.record.control.len() as u64 * 3;
    let statics = scene.self_weight.method == SettleMethod::Static || scene.skip_ahead.enabled;
    let (statics_per_bar, statics_per_node) = if statics { (8, 6 * 24) } else { (0, 0) };
    let batch = sum(&[
        (n, 4 * 24 * l + statics_per_node),
        (b, per_bar_k + rupture + statics_per_bar + anelastic),
        (contact, 8 * 8 * l),
        (samples.saturating_mul(l), 8 * channels),
    ])?;

    // Setting up a batch, before its state exists: each lane's own stiffness (and, listed, the
    // Weibull factors it is drawn from), the critical step of one lane at a time (Lanczos: four
    // vectors per node and the inverse square roots of the masses), then the lanes' stiffness interleaved while theirs still exist; a listed
    // lattice's sort of its bars (16 bytes each, and 4 for the canonical index) while the model
    // is built.
    let lane_k = if stencil { per_bar_k / l.max(1) } else { 8 };
    let critical = sum(&[(n, 4 * 24 + 8)])?.max(if stencil { 0 } else { sum(&[(b, 8)])? });
    let lanes_k = sum(&[(b, lane_k * l)])?;
    let setup =
        lanes_k.checked_add(critical.max(lanes_k)).ok_or_else(over)?.max(if stencil { 0 } else { sum(&[(b, 20)])? });

    // The model, the batches running while one more is set up or steps.
    let concurrent = batches.concurrent as u64;
    let total = batch
        .checked_mul(concurrent.saturating_sub(1))
        .and_then(|v| v.checked_add(batch.max(setup)))
        .and_then(|v| v.checked_add(model))
        .and_then(|v| v.checked_add(PROCESS_BYTES))
        .ok_or_else(over)?;
    Ok(MemoryEstimate { nodes: n, bars: b, model, batch, setup, total })
}

/// Bar-updates of one seed above which `check` and `pipeline` refuse a run unless asked for it
/// (`--allow-long`): 10¹¹, about ten minutes of one core at the stencil's 2–3·10⁸ bar-updates/s.
pub const LONG_RUN_BAR_UPDATES: f64 = 1e11;

/// Δt of `scene` estimated before its lattice is built: the fixed step, or the fraction of the
/// paper's bound `0.6·Lc/Cp`, which is within 10% of the critical step for 0.2 ≤ ν ≤ 0.25
/// (docs/model.md §2).
pub fn dt_estimate(scene: &Scene) -> f64 {
    match scene.time_step {
        TimeStep::Fixed(dt) => dt,
        TimeStep::Fraction(f) => f * scene.paper_time_step_bound(),
    }
}

/// Steps of a run of `scene` at Δt = `dt`: the self-weight stage at most (none without gravity or
/// when it is solved statically), and the shear stage.
pub fn run_steps(scene: &Scene, dt: f64) -> (u64, u64) {
    let sw = &scene.self_weight;
    let settle = if sw.gravity_m_s2 == 0.0 || sw.method == SettleMethod::Static {
        0
    } else {
        (sw.max_duration_s / dt).ceil() as u64
    };
    (settle, (scene.shear.duration_s / dt * (1.0 - 1e-12)).ceil() as u64)
}

/// Samples a run of `scene` records at Δt = `dt` (the self-weight stage counted only if
/// recorded).
pub fn samples(scene: &Scene, dt: f64) -> u64 {
    let (settle, shear) = run_steps(scene, dt);
    let stride = scene.record.interval_s.map_or(1, |iv| ((iv / dt).round() as u64).max(1));
    // Saturating: a Δt so small that the steps saturate is refused by the length check, not wrapped here.
    (shear / stride).saturating_add(2).saturating_add(if scene.record.settling { settle } else { 0 })
}

/// `bytes` in the largest unit that keeps it at least 1 (B, kB, MB, GB, TB; powers of 1000).
pub fn human(bytes: u64) -> String {
    let units = ["B", "kB", "MB", "GB", "TB", "PB", "EB"];
    let mut v = bytes as f64;
    let mut u = 0;
    while v >= 1000.0 && u + 1 < units.len() {
        v /= 1000.0;
        u += 1;
    }
    if u == 0 { format!("{bytes} B") } else { format!("{v:.1} {}", units[u]) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_are_the_closed_forms_and_overflow_is_caught() {
        for dims in [Dims::new(10, 1, 5), Dims::new(200, 50, 20), Dims::new(1, 1, 1), Dims::new(7, 3, 2)] {
            assert_eq!(counts(dims).unwrap(), (dims.node_count() as u64, dims.bar_count() as u64), "{dims:?}");
        }
        let huge = Dims { nx: 1 << 40, ny: 1 << 40, nz: 1 << 40 };
        assert!(counts(huge).is_err());
        let mut scene = Scene::paper();
        scene.dims = Dims { nx: 1 << 30, ny: 1 << 30, nz: 1 << 2 };
        let e = estimate(&scene, Batches::ONE, 1000);
        assert!(e.is_err(), "{e:?}");
    }

    #[test]
    fn a_homogeneous_stencil_holds_no_stiffness_and_ensembles_add_their_batches() {
        let mut scene = Scene::paper();
        scene.dims = Dims::new(200, 50, 20);
        scene.young_cv = 0.0;
        let one = estimate(&scene, Batches::ONE, 0).unwrap();
        scene.young_cv = 0.05;
        let weibull = estimate(&scene, Batches::ONE, 0).unwrap();
        assert_eq!(weibull.batch - one.batch, 4 * one.bars, "f32 factors: 4 bytes per bar");
        let two = estimate(&scene, Batches { lanes: 1, concurrent: 2 }, 0).unwrap();
        assert_eq!(two.total - weibull.total, weibull.batch);
        // One seed, process included: under 60 bytes per bar.
        assert!(weibull.bytes_per_bar() < 60.0, "{weibull:?}");
        assert_eq!(Batches::of_ensemble(16, 2, false), Batches { lanes: 8, concurrent: 2 });
        assert_eq!(Batches::of_ensemble(1, 2, false), Batches { lanes: 1, concurrent: 1 });
        assert_eq!(Batches::of_ensemble(6, 2, false), Batches { lanes: 1, concurrent: 2 });
        assert_eq!(Batches::of_ensemble(100, 2, true), Batches { lanes: 1, concurrent: 2 });
    }
}
