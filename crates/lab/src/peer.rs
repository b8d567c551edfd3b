//! Side-by-side throughput with a peer code (LAMMPS): writes the lattice as a LAMMPS data file and
//! input script, and times our stepper on the same lattice, time step and step count.
//!
//! Both sides: homogeneous lattice (CV = 0), no contact forces, mass-proportional damping
//! D = 400/s, Δt = 0.5 of our critical step, small initial displacements. `stickslip-bench peer
//! NX NY NZ STEPS OUT_DIR` runs it; `crates/lab/lammps/compare.sh` runs both codes and prints
//! the ratios.

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use stickslip_config::PipelineFile;
use stickslip_solver::Model;
use stickslip_solver::geometry::BarFamily;
use stickslip_solver::statics::critical_step;
use stickslip_solver::step::{LaneSetup, Params, State, Stepper};

use crate::LabError;

/// What the timing of our side found.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PeerTiming {
    /// Bars of the lattice.
    pub bars: usize,
    /// Time step (s).
    pub dt_s: f64,
    /// Bar-updates per second with one seed.
    pub one_seed: f64,
    /// Bar-updates per second with eight seeds side by side.
    pub eight_seeds: f64,
}

/// Writes `out/lattice.data` and `out/in.lattice` for the `nx × ny × nz` lattice and times
/// `steps` steps of ours on it.
pub fn peer(nx: i64, ny: i64, nz: i64, steps: usize, out: &Path) -> Result<PeerTiming, LabError> {
    std::fs::create_dir_all(out).map_err(|e| LabError::Setup(format!("{}: {e}", out.display())))?;
    let mut f = PipelineFile::default();
    (f.block.nx, f.block.ny, f.block.nz) = (nx, ny, nz);
    f.material.young_cv = 0.0;
    f.shear.driver_at_m = vec![[0.0, 0.0, 0.1]];
    let model = Model::new(f.scene()?);
    let k = model.nominal_stiffness();
    let dt =
        0.5 * critical_step(&model, &model.nominal_lane_stiffness()).map_err(|e| LabError::Setup(e.to_string()))?.dt_s;
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
    let canonical = model.canonical_bars();
    let mut ends = vec![[0usize; 2]; model.bar_count()];
    model.layout().visit(|b, i, j, _| ends[b] = [i, j]);
    for (b, e) in ends.iter().enumerate() {
        let bar = &lattice.bar(canonical[b] as usize);
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
    let write = |name: &str, text: &str| {
        std::fs::write(out.join(name), text).map_err(|e| LabError::Setup(format!("{}: {e}", out.join(name).display())))
    };
    write("lattice.data", &data)?;
    let scale: String = masses.iter().enumerate().map(|(i, m)| format!(" scale {} {m:.12e}", i + 1)).collect();
    let input = format!(
        "# stickslip lattice {nx}x{ny}x{nz}: {} atoms, {} bonds\nunits si\natom_style bond\nboundary s s s\n\
         bond_style harmonic\nread_data lattice.data\npair_style none\nneighbor 0.0 bin\n\
         neigh_modify delay 0 every 1000000000 check no\nfix 1 all nve\nfix 2 all viscous {damping}{scale}\n\
         timestep {dt:.12e}\nthermo 0\nrun {steps}\n",
        model.node_count(),
        model.bar_count()
    );
    write("in.lattice", &input)?;
    let lane = || LaneSetup {
        dt_s: dt,
        stiffness: model.nominal_lane_stiffness(),
        friction: vec![1.0; model.contact().len()],
        strength: None,
        fault: None,
    };
    Ok(PeerTiming {
        bars: model.bar_count(),
        dt_s: dt,
        one_seed: time::<1>(&model, std::array::from_fn(|_| lane()), damping, steps),
        eight_seeds: time::<8>(&model, std::array::from_fn(|_| lane()), damping, steps),
    })
}

/// Bar-updates per second of `L` seeds side by side over `steps` steps, after a warm-up.
fn time<const L: usize>(model: &Model, lanes: [LaneSetup; L], damping: f64, steps: usize) -> f64 {
    let mut p = Params::<L>::new(model, &lanes);
    let mut s = State::<L>::at_rest(model.node_count(), model.contact().len(), model.drivers().len());
    let mut stepper = Stepper::<L>::new(model);
    let lattice = model.lattice();
    for l in 0..L {
        p.set_damping(l, damping);
        s.u.np1.set_lane(l, |i, axis| {
            let x = lattice.position(model.canonical(i))[0];
            if axis == 0 { 1e-9 * (x * 7.0).sin() } else { 0.0 }
        });
    }
    for _ in 0..steps / 10 + 2 {
        stepper.step(&p, &mut s); // warm-up: first touch of the arrays, caches
    }
    let t = Instant::now();
    for _ in 0..steps {
        stepper.step(&p, &mut s);
    }
    (L * steps * model.bar_count()) as f64 / t.elapsed().as_secs_f64()
}
