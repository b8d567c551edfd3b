//! Throughput of one step and of the bar kernel alone, for lattices of 10×1×5, 40×20×4 and
//! 100×50×10 modules, one seed and several seeds side by side, on one core. Criterion reports
//! elements/s = bar-updates per second (bars × seeds per step).
//!
//! `cargo bench -p stickslip-lab --bench step`

use std::hint::black_box;

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use stickslip_lab::kernel_scene::{model, settling_batch, setup};
use stickslip_solver::Model;
use stickslip_solver::step::bars::bar_forces;
use stickslip_solver::step::{Batch, Field};

fn stepping<const L: usize>(c: &mut Criterion, m: &Model, name: &str) {
    let mut s = settling_batch::<L>(m);
    let mut g = c.benchmark_group("step");
    g.throughput(Throughput::Elements((m.bar_count() * L) as u64));
    g.bench_function(BenchmarkId::new(format!("{L}_seeds"), name), |b| b.iter(|| s.step()));
    g.finish();
}

/// One seed, each step split over a rayon pool of `threads` (large, slab-cut lattices).
fn stepping_parallel(c: &mut Criterion, m: &Model, name: &str, threads: usize) {
    let mut s = Batch::<1>::new(m, &[setup(m, 1)]);
    s.params.set_damping(0, 400.0);
    s.params.set_body_acceleration(0, [0.0, 0.0, -9.81]);
    s.stepper.set_parallel(true);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
    let mut g = c.benchmark_group("step_parallel");
    g.throughput(Throughput::Elements(m.bar_count() as u64));
    g.bench_function(BenchmarkId::new(format!("{threads}_threads"), name), |b| b.iter(|| pool.install(|| s.step())));
    g.finish();
}

fn kernel<const L: usize>(c: &mut Criterion, m: &Model, name: &str) {
    let k: Vec<[f64; L]> = m.bar_stiffness(1).unwrap().into_iter().map(|v| [v; L]).collect();
    let mut u = Field::<L>::zeros(m.node_count());
    for (i, v) in u.c[0].iter_mut().enumerate() {
        *v = [1e-7 * (i as f64).sin(); L];
    }
    let mut f = Field::<L>::zeros(m.node_count());
    let mut g = c.benchmark_group("bar_forces");
    g.throughput(Throughput::Elements((m.bar_count() * L) as u64));
    g.bench_function(BenchmarkId::new(format!("{L}_seeds"), name), |b| {
        b.iter(|| {
            f.fill_zero();
            bar_forces(m.layout(), &k, black_box(&u), &mut f)
        })
    });
    g.finish();
}

/// Memory bandwidth seen by one core: a triad `a = b + s·c` over arrays of `mb` MB each
/// (3 arrays read or written per element: 24 bytes, plus the write-allocate of `a`).
fn triad(c: &mut Criterion, mb: usize) {
    let n = mb * 1024 * 1024 / 8;
    let (mut a, b, d) = (vec![0.0f64; n], vec![1.0f64; n], vec![2.0f64; n]);
    let mut g = c.benchmark_group("triad");
    g.throughput(Throughput::Bytes((n * 8 * 3) as u64));
    g.bench_function(format!("{mb}MB_arrays"), |bench| {
        bench.iter(|| {
            for i in 0..n {
                a[i] = b[i] + 3.0 * d[i];
            }
            black_box(&a);
        })
    });
    g.finish();
}

fn benches(c: &mut Criterion) {
    triad(c, 8);
    // Three 72 MB arrays: the 215 MB a step of 8 seeds on 100×50×10 touches.
    triad(c, 72);
    triad(c, 256);
    for (nx, ny, nz) in [(10, 1, 5), (40, 20, 4), (100, 50, 10)] {
        let m = model(nx, ny, nz, false);
        let name = format!("{nx}x{ny}x{nz}");
        kernel::<1>(c, &m, &name);
        kernel::<8>(c, &m, &name);
        stepping::<1>(c, &m, &name);
        stepping::<4>(c, &m, &name);
        stepping::<8>(c, &m, &name);
        if m.layout().splits() {
            stepping_parallel(c, &m, &name, 1);
            stepping_parallel(c, &m, &name, 2);
        }
    }
}

criterion_group! {
    name = group;
    config = Criterion::default().sample_size(20).warm_up_time(std::time::Duration::from_millis(500)).measurement_time(std::time::Duration::from_secs(2));
    targets = benches
}
criterion_main!(group);
