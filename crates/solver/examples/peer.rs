//! Side-by-side throughput with a peer code (LAMMPS): writes the lattice as a LAMMPS data file
//! and input script, and times our stepper on the same lattice, time step and step count.
//!
//! `cargo run --release -p stickslip-solver --example peer -- NX NY NZ STEPS OUT_DIR`
//! prints `ours_1 <bar-updates/s>` (one seed) and `ours_8 <bar-updates/s>` (8 seeds side by
//! side), and writes OUT_DIR/lattice.data and OUT_DIR/in.lattice for `lmp -in in.lattice`.
//! Both sides: homogeneous lattice (CV = 0), no contact forces, mass-proportional damping
//! D = 400/s, Δt = 0.5 of our critical step, small initial displacements.

use std::fmt::Write as _;
use std::time::Instant;

use stickslip_solver::critical::critical_time_step;
use stickslip_solver::lattice::BarFamily;
use stickslip_solver::stepper::{LaneSetup, Stepper};
use stickslip_solver::{Model, Scene, SceneFile};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let (nx, ny, nz): (i64, i64, i64) = (a[1].parse().unwrap(), a[2].parse().unwrap(), a[3].parse().unwrap());
    let steps: usize = a[4].parse().unwrap();
    let out = std::path::Path::new(&a[5]);
    std::fs::create_dir_all(out).unwrap();
    let mut f = SceneFile::default();
    (f.block.nx, f.block.ny, f.block.nz) = (nx, ny, nz);
    f.material.young_cv = 0.0;
    f.shear.driver_at_m = vec![[0.0, 0.0, 0.1]];
    let model = Model::new(Scene::try_from(f).unwrap());
    let k = model.nominal_stiffness().to_vec();
    let dt = 0.5 * critical_time_step(&model, &k).unwrap().dt_s;
    let damping = 400.0;

    // LAMMPS: bond types by (stiffness, rest length), atom types by mass.
    let lattice = model.lattice();
    let mut masses: Vec<f64> = Vec::new();
    let mut atoms = String::new();
    for i in 0..model.node_count() {
        let m = model.mass()[i];
        let t = match masses.iter().position(|x| (x - m).abs() < 1e-12 * m) {
            Some(t) => t + 1,
            None => {
                masses.push(m);
                masses.len()
            }
        };
        let p = lattice.position(model.canonical(i));
        // Tiny offsets so the initial state is not an equilibrium.
        let d = 1e-9 * (p[0] * 7.0).sin();
        let _ = writeln!(atoms, "{} 1 {} {:.12e} {:.12e} {:.12e}", i + 1, t, p[0] + d, p[1], p[2]);
    }
    let mut types: Vec<(f64, f64)> = Vec::new();
    let mut bonds = String::new();
    for (b, e) in model.ends().iter().enumerate() {
        let bar = &lattice.bars()[model.bar_canonical()[b] as usize];
        let kk = k[b] * if bar.family == BarFamily::Diagonal { 3.0 } else { 1.0 };
        let r0 = bar.length_factor() * lattice.lc();
        let t = match types.iter().position(|&(x, r)| (x - kk).abs() < 1e-9 * kk && (r - r0).abs() < 1e-12) {
            Some(t) => t + 1,
            None => {
                types.push((kk, r0));
                types.len()
            }
        };
        let _ = writeln!(bonds, "{} {} {} {}", b + 1, t, e[0] + 1, e[1] + 1);
    }
    let ext = lattice.extent();
    let mut data = format!(
        "LAMMPS data file: stickslip lattice {nx}x{ny}x{nz}\n\n{} atoms\n{} bonds\n{} atom types\n{} bond types\n\n\
         -0.01 {} xlo xhi\n-0.01 {} ylo yhi\n-0.01 {} zlo zhi\n\nMasses\n\n",
        model.node_count(),
        model.bar_count(),
        masses.len(),
        types.len(),
        ext[0] + 0.01,
        ext[1] + 0.01,
        ext[2] + 0.01
    );
    for (i, m) in masses.iter().enumerate() {
        let _ = writeln!(data, "{} {m:.12e}", i + 1);
    }
    data += "\nBond Coeffs # harmonic: K = EA/(2L), r0 = L\n\n";
    for (i, (kk, r0)) in types.iter().enumerate() {
        let _ = writeln!(data, "{} {:.12e} {r0:.12e}", i + 1, kk / 2.0);
    }
    data += "\nAtoms # bond\n\n";
    data += &atoms;
    data += "\nBonds\n\n";
    data += &bonds;
    std::fs::write(out.join("lattice.data"), data).unwrap();
    let scale: String = masses.iter().enumerate().map(|(i, m)| format!(" scale {} {m:.12e}", i + 1)).collect();
    let input = format!(
        "# stickslip lattice {nx}x{ny}x{nz}: {} atoms, {} bonds\nunits si\natom_style bond\nboundary s s s\n\
         bond_style harmonic\nread_data lattice.data\npair_style none\nneighbor 0.0 bin\n\
         neigh_modify delay 0 every 1000000000 check no\nfix 1 all nve\nfix 2 all viscous {damping}{scale}\n\
         timestep {dt:.12e}\nthermo 0\nrun {steps}\n",
        model.node_count(),
        model.bar_count()
    );
    std::fs::write(out.join("in.lattice"), input).unwrap();

    // Ours, one seed then eight side by side.
    let lane = || LaneSetup { dt_s: dt, stiffness: k.clone(), friction: vec![1.0; model.contact().len()] };
    let one = {
        let mut s = Stepper::<1>::new(&model, &[lane()]);
        s.set_damping(0, damping);
        s.initialize(0, |p| ([0.0; 3], [1e-9 * (p[0] * 7.0).sin(), 0.0, 0.0]));
        for _ in 0..steps / 10 + 2 {
            s.step(); // warm-up: first touch of the arrays, caches
        }
        let t = Instant::now();
        for _ in 0..steps {
            s.step();
        }
        (steps * model.bar_count()) as f64 / t.elapsed().as_secs_f64()
    };
    let eight = {
        let mut s = Stepper::<8>::new(&model, &std::array::from_fn(|_| lane()));
        for l in 0..8 {
            s.set_damping(l, damping);
            s.initialize(l, |p| ([0.0; 3], [1e-9 * (p[0] * 7.0).sin(), 0.0, 0.0]));
        }
        for _ in 0..steps / 10 + 2 {
            s.step(); // warm-up: first touch of the arrays, caches
        }
        let t = Instant::now();
        for _ in 0..steps {
            s.step();
        }
        (8 * steps * model.bar_count()) as f64 / t.elapsed().as_secs_f64()
    };
    println!("bars {}", model.bar_count());
    println!("dt {dt:e}");
    println!("ours_1 {one:e}");
    println!("ours_8 {eight:e}");
}
