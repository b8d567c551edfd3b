//! The rupture kernel against the elastic one while nothing has cracked (docs/model.md §11): the
//! same lattice, seeds and loading, stepped by a stepper built from a scene without `[rupture]`
//! (the elastic kernel) and from the same scene with it (Gf = 100 J/m², Kr = 3), on the paper
//! lattice (10×1×5) and on 100×50×10, one seed and eight side by side.
//!
//! The two steppers are timed **alternately in the same process** — `ROUNDS` rounds of
//! (elastic, rupture), each a block of steps of about 0.1 s — and the median of each is kept: on a
//! shared machine only ratios measured this way mean something. Bar-updates per second
//! (bars × seeds per step). Pin it to one core:
//!
//! `taskset -c 1 cargo bench -p stickslip-lab --bench rupture`

use std::hint::black_box;
use std::time::Instant;

use stickslip_lab::kernel_scene::{model, settling_batch};
use stickslip_solver::step::{Batch, Kernel};

const ROUNDS: usize = 9;

fn time<const L: usize>(s: &mut Batch<'_, L>, steps: usize) -> f64 {
    let t = Instant::now();
    for _ in 0..steps {
        s.step();
    }
    black_box(&s.state);
    t.elapsed().as_secs_f64()
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn compare<const L: usize>(dims: (i64, i64, i64)) {
    let (elastic_m, rupture_m) = (model(dims.0, dims.1, dims.2, false), model(dims.0, dims.1, dims.2, true));
    let (mut elastic, mut rupture) = (settling_batch::<L>(&elastic_m), settling_batch::<L>(&rupture_m));
    assert_eq!(elastic.stepper.kernel(), Kernel::Elastic);
    assert_eq!(rupture.stepper.kernel(), Kernel::Rupture);
    // Steps per block: about 0.1 s of the elastic kernel.
    let probe = time(&mut elastic, 5) / 5.0;
    let steps = ((0.1 / probe) as usize).max(5);
    let (mut te, mut tr) = (Vec::new(), Vec::new());
    for _ in 0..ROUNDS {
        te.push(time(&mut elastic, steps));
        tr.push(time(&mut rupture, steps));
    }
    let state = rupture.state.rupture.as_ref().unwrap();
    for l in 0..L {
        assert_eq!(
            state.damaged(rupture.params.k.per_bar(), l),
            0,
            "a bar cracked: the comparison is not the intact one"
        );
    }
    let updates = (elastic_m.bar_count() * L * steps) as f64;
    let (e, r) = (updates / median(te), updates / median(tr));
    println!(
        "{}x{}x{} {L} seed(s): elastic {e:.3e}, rupture {r:.3e} bar-updates/s; rupture/elastic time {:.3}",
        dims.0,
        dims.1,
        dims.2,
        e / r
    );
}

fn main() {
    // `cargo bench` passes `--bench`; `cargo test --benches` runs nothing here.
    if !std::env::args().any(|a| a == "--bench") {
        return;
    }
    println!("medians of {ROUNDS} alternating rounds, one process");
    compare::<1>((10, 1, 5));
    compare::<8>((10, 1, 5));
    compare::<1>((100, 50, 10));
    compare::<8>((100, 50, 10));
}
