//! The medium against closed forms (docs/model.md §18): plane P and S waves in a long column of
//! the lattice lose amplitude as `exp(−π f x/(Q c))` and disperse as
//! `c(f)/c(f_ref) = 1 + ln(f/f_ref)/(πQ)`; a pulse reflects at an interface of two layers by
//! the impedance contrast; a soft layer over a half-space resonates at `Vs/4H` with the
//! amplification of its impedance ratio and Q; the memory variables' work closes the energy
//! ledger; Kelvin–Voigt dashpots lower the stable step as their closed form says. The runs
//! with and without the medium's term use the same lattice, pulse and step, so the lattice's own
//! dispersion divides out of every ratio.

mod common;

use std::f64::consts::PI;

use stickslip_solver::geometry::Face;
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::medium::{Attenuation, Layer, Medium, Profile, QRule};
use stickslip_solver::scene::BoundarySpec;
use stickslip_solver::statics::critical_step_on;
use stickslip_solver::step::{Batch, LaneSetup, Tracking};
use stickslip_solver::{Dims, Model, Scene};

const LC: f64 = 100.0;
const RHO: f64 = 2670.0;
const YOUNG: f64 = 8.01e10;

/// The common column of 100 m modules (`common::column`) in `medium`, absorbing at `absorbing`.
fn column(nz: usize, axis: usize, medium: Medium, absorbing: &[Face]) -> Scene {
    let mut s = common::column(nz, axis);
    if !absorbing.is_empty() {
        s.set_boundary(BoundarySpec::Absorbing(absorbing.to_vec()));
    }
    s.medium = medium;
    s
}

fn speeds() -> (f64, f64) {
    let (c11, _, c44) = lattice_elastic_constants(YOUNG, 0.25);
    ((c11 / RHO).sqrt(), (c44 / RHO).sqrt())
}

fn q_medium(q: f64) -> Medium {
    Medium {
        attenuation: Some(Attenuation { band_hz: [0.05, 5.0], reference_hz: 1.0, q: QRule::Constant(q) }),
        ..Medium::default()
    }
}

/// A lane of `model` at `fraction` of its critical step (the medium's unrelaxed moduli and
/// dashpots included).
fn setup(model: &Model, fraction: f64) -> LaneSetup {
    let k = model.nominal_lane_stiffness();
    let crit = critical_step_on(model, &k, false).unwrap();
    LaneSetup {
        dt_s: fraction * crit.dt_s,
        stiffness: k,
        friction: vec![1.0; model.contact().len()],
        strength: None,
        fault: None,
    }
}

/// Runs `scene` from rest with its bottom plane (z = 0) moved along `axis` by a Gaussian pulse of
/// width `sigma` seconds centred at `4·sigma` for `duration` seconds at `fraction` of the step;
/// the displacement `axis` of the corner nodes at heights `at` (m) every step, and the step. With
/// `stencil`, the bars in the stencil layout, whose kernel adds the medium's terms run by run (as
/// every large scene's does), else listed, with the medium's second pass.
#[allow(clippy::too_many_arguments)]
fn records(
    scene: Scene,
    axis: usize,
    sigma: f64,
    duration: f64,
    at: &[f64],
    fraction: f64,
    stencil: bool,
) -> (Vec<Vec<f64>>, f64) {
    let model = if stencil { Model::with_stencil(scene) } else { Model::new(scene) };
    let lane = setup(&model, fraction);
    let dt = lane.dt_s;
    let mut b = Batch::<1>::new(&model, &[lane]);
    let source = |t: f64| 1e-3 * (-((t - 4.0 * sigma) / sigma).powi(2)).exp();
    let bottom: Vec<usize> = Face::ZMin.nodes(model.lattice()).into_iter().map(|id| model.internal(id)).collect();
    let nodes: Vec<usize> = at
        .iter()
        .map(|&z| model.internal(model.lattice().node_at([0.0, 0.0, z]).expect("a corner node there")))
        .collect();
    let mut out = vec![Vec::new(); at.len()];
    let steps = (duration / dt).round() as usize;
    for n in 0..steps {
        // The newest level after this step is step n + 2 of the schedule.
        b.step();
        for &i in &bottom {
            b.state.u.np1.c[axis][i][0] = source((n + 2) as f64 * dt);
        }
        let v = b.view(0);
        for (o, &i) in out.iter_mut().zip(&nodes) {
            o.push(v.displacement(i)[axis]);
        }
    }
    (out, dt)
}

/// The Fourier transform of `u` (step `dt`) at `f`: `Σ u·e^{−iωt}·dt` as (re, im).
fn dft(u: &[f64], dt: f64, f: f64) -> (f64, f64) {
    let w = 2.0 * PI * f;
    u.iter().enumerate().fold((0.0, 0.0), |(re, im), (n, &v)| {
        let t = n as f64 * dt;
        (re + v * (w * t).cos() * dt, im - v * (w * t).sin() * dt)
    })
}

/// The phase `p` (a lag, negative) moved by whole turns to the one nearest `−expected`.
fn unwrap_lag(p: f64, expected: f64) -> f64 {
    p - 2.0 * PI * ((p + expected) / (2.0 * PI)).round()
}

/// `U(b)/U(a)` at `f` as (modulus, phase).
fn ratio(a: &[f64], b: &[f64], dt: f64, f: f64) -> (f64, f64) {
    let (ar, ai) = dft(a, dt, f);
    let (br, bi) = dft(b, dt, f);
    ((br * br + bi * bi).sqrt() / (ar * ar + ai * ai).sqrt(), bi.atan2(br) - ai.atan2(ar))
}

#[test]
fn plane_waves_attenuate_and_disperse_as_a_constant_q_says() {
    let (cp, cs) = speeds();
    let frequencies = [0.3, 1.0, 2.5];
    let mut worst = (0.0f64, 0.0f64);
    for (axis, name, c) in [(2, "P", cp), (0, "S", cs)] {
        // Receivers 5 km and 5 + dx km above a pulse at 1.5 km; the column ends far enough above
        // for nothing to come back before the window closes.
        let (z1, dx) = (5000.0, 30000.0);
        let duration = (z1 + dx + 45000.0) / c;
        let nz = ((c * duration + z1 + dx) / 2.0 / LC).ceil() as usize + 20;
        let run =
            |medium: Medium| records(column(nz, axis, medium, &[]), axis, 0.12, duration, &[z1, z1 + dx], 0.5, true);
        let (elastic, dt) = run(Medium::default());
        for q in [20.0, 50.0, 200.0] {
            let (anelastic, dt_q) = run(q_medium(q));
            for f in frequencies {
                let (ae, pe) = ratio(&elastic[0], &elastic[1], dt, f);
                let (aq, pq) = ratio(&anelastic[0], &anelastic[1], dt_q, f);
                let decay = -(aq / ae).ln() / dx;
                // The closed form with the wave's phase speed in this lattice at f (its own
                // dispersion, from the elastic run: a lag of ω·dx/c).
                let c_lattice = 2.0 * PI * f * dx / -unwrap_lag(pe, 2.0 * PI * f * dx / c);
                let closed = PI * f / (q * c_lattice);
                // The phase lag over dx is ω·dx/c: a faster wave lags less.
                let mut dphase = pq - pe;
                dphase -= (2.0 * PI) * (dphase / (2.0 * PI)).round();
                let speed = 1.0 / (1.0 - dphase * c / (2.0 * PI * f * dx));
                let speed_closed = 1.0 + f.ln() / (PI * q);
                let (ea, ec) = (decay / closed - 1.0, speed - speed_closed);
                println!(
                    "{name} Q {q:>3} at {f:.1} Hz: decay {decay:.4e}/m (closed form {closed:.4e}, {:+.2}%), c/c_ref {speed:.5} (closed form {speed_closed:.5}, {:+.3}%)",
                    100.0 * ea,
                    100.0 * ec
                );
                worst = (worst.0.max(ea.abs()), worst.1.max(ec.abs()));
            }
        }
    }
    println!("worst: decay {:.2}%, phase speed {:.3}%", 100.0 * worst.0, 100.0 * worst.1);
    assert!(worst.0 < 0.05, "amplitude decay off the closed form by {:.2}%", 100.0 * worst.0);
    assert!(worst.1 < 0.005, "phase speed off the closed form by {:.3}%", 100.0 * worst.1);
}

/// A layer of `thickness` (m; infinite for the half-space) with the lattice's Vp at ν = 0.25.
fn layer(thickness_m: f64, vs: f64, rho: f64, qs: f64) -> Layer {
    Layer { thickness_m, vp_m_s: vs * 3f64.sqrt(), vs_m_s: vs, density_kg_m3: rho, qp: qs, qs }
}

/// The scene's rock below a layer `top` of the column, its surface the top face.
fn layered(top: Layer, q: bool) -> Medium {
    let (_, cs) = speeds();
    Medium {
        profile: Some(Profile { layers: vec![top, layer(f64::INFINITY, cs, RHO, 1e4)], surface: Face::ZMax }),
        attenuation: q.then_some(Attenuation { band_hz: [0.02, 2.0], reference_hz: 1.0, q: QRule::Profile }),
        ..Medium::default()
    }
}

#[test]
fn a_pulse_reflects_at_an_interface_by_the_impedance_contrast() {
    // 20 km of soft rock (Vs 2000 m/s, ρ 2400) over the scene's rock, the pulse sent up from the
    // bottom of 20 km of rock; a receiver 10 km up sees the incident pulse and, 20 km of travel
    // later, its reflection. The displacement's reflection coefficient from rock (1) to the
    // layer (2) is (Z₁ − Z₂)/(Z₁ + Z₂), the (Z₂ − Z₁)/(Z₂ + Z₁) with its sign for
    // stress.
    let (cp, cs) = speeds();
    let (vs2, rho2) = (2000.0, 2400.0);
    for (axis, name, c1, c2) in [(2, "P", cp, vs2 * cp / cs), (0, "S", cs, vs2)] {
        let sigma = 0.3;
        let duration = 4.0 * sigma + 33000.0 / c1;
        let scene = column(400, axis, layered(layer(20000.0, vs2, rho2, 1e4), false), &[]);
        let (rec, dt) = records(scene, axis, sigma, duration, &[10000.0], 0.5, false);
        let split = ((4.0 * sigma + 20000.0 / c1) / dt) as usize;
        let peak = |u: &[f64]| u.iter().cloned().fold(0.0f64, |m, v| if v.abs() > m.abs() { v } else { m });
        let (incident, reflected) = (peak(&rec[0][..split]), peak(&rec[0][split..]));
        let (z1, z2) = (RHO * c1, rho2 * c2);
        let closed = (z1 - z2) / (z1 + z2);
        let got = reflected / incident;
        println!(
            "{name}: reflected/incident {got:.4}, closed form {closed:.4} ({:+.2}%)",
            100.0 * (got / closed - 1.0)
        );
        assert!((got / closed - 1.0).abs() < 0.05, "{name}: {got} vs {closed}");
    }
}

#[test]
fn a_soft_layer_over_rock_resonates_at_vs_over_4h_with_its_closed_form_amplification() {
    // 1 km of Vs 1000 m/s, ρ 2000 kg/m³, Qs 20 over the scene's rock (Qs 10 000); an S pulse sent
    // up through 55 km of rock. The surface motion over that of the rock alone (twice the
    // incident wave) is the layer's transfer function |1/(cos k*H + i α* sin k*H)|, with
    // k* = ω/Vs* and α* = ρ₁Vs₁*/(ρ₂Vs₂) from the complex speed of the fitted Q.
    let (_, cs) = speeds();
    let (h, vs, rho, q) = (1000.0, 1000.0, 2000.0, 20.0);
    let nz = 560;
    let top = nz as f64 * LC;
    // Until just before the wave the surface sends down comes back from the bottom.
    let duration = 4.0 * 0.2 + top / cs + 2.0 * (top - h) / cs - 2.0;
    let run = |medium: Medium| records(column(nz, 0, medium, &[]), 0, 0.2, duration, &[top], 0.5, false);
    let (soil, dt) = run(layered(layer(h, vs, rho, q), true));
    let (rock, dt_rock) = run(Medium::default());
    let relaxation = stickslip_solver::medium::Relaxation::fit(q, [0.02, 2.0], 1.0);
    let closed = |f: f64| {
        use nalgebra::Complex;
        let vs_c = Complex::new(vs, 0.0) * relaxation.modulus(f).sqrt();
        let k = Complex::new(2.0 * PI * f, 0.0) / vs_c;
        let alpha = vs_c * rho / (RHO * cs);
        let d = (k * h).cos() + Complex::new(0.0, 1.0) * alpha * (k * h).sin();
        1.0 / d.norm()
    };
    let measured = |f: f64| {
        let (a, b) = (dft(&soil[0], dt, f), dft(&rock[0], dt_rock, f));
        ((a.0 * a.0 + a.1 * a.1) / (b.0 * b.0 + b.1 * b.1)).sqrt()
    };
    let grid: Vec<f64> = (0..=400).map(|i| 0.15 + 0.2 * i as f64 / 400.0).collect();
    let argmax = |g: &dyn Fn(f64) -> f64| grid.iter().cloned().max_by(|a, b| g(*a).total_cmp(&g(*b))).unwrap();
    let (f_meas, f_closed) = (argmax(&measured), argmax(&closed));
    let f0 = vs / (4.0 * h);
    println!(
        "resonance: measured {f_meas:.4} Hz, closed form {f_closed:.4} Hz, Vs/4H {f0:.4} Hz; amplification measured {:.3}, closed form {:.3}",
        measured(f_meas),
        closed(f_closed)
    );
    assert!((f_meas / f0 - 1.0).abs() < 0.05, "resonance at {f_meas} Hz, Vs/4H = {f0}");
    assert!((f_meas / f_closed - 1.0).abs() < 0.05, "resonance at {f_meas} Hz, closed form {f_closed}");
    assert!(
        (measured(f_meas) / closed(f_closed) - 1.0).abs() < 0.05,
        "amplification {} vs {}",
        measured(f_meas),
        closed(f_closed)
    );
}

#[test]
fn the_memory_variables_and_dashpots_close_the_energy_ledger() {
    // A P pulse in a column with Q = 20 and Kelvin–Voigt damping: what the kinetic and strain
    // energy lose is what the medium took, step by step, to round-off.
    let (cp, _) = speeds();
    let mut medium = q_medium(20.0);
    medium.kelvin_voigt_s = 1e-3;
    // Listed bars (the medium's second pass) and the stencil (its terms in the kernel).
    for model in [Model::new(column(60, 2, medium.clone(), &[])), Model::with_stencil(column(60, 2, medium, &[]))] {
        let lane = setup(&model, 0.5);
        let dt = lane.dt_s;
        let mut b = Batch::<1>::new(&model, &[lane]);
        b.stepper.set_tracking(Tracking { energy: true, ..Tracking::default() });
        let pulse = move |z: f64, t: f64| 1e-3 * (-((z - 20.0 * LC - cp * t) / (4.0 * LC)).powi(2)).exp();
        b.initialize(0, |p| ([0.0, 0.0, pulse(p[2], -dt)], [0.0, 0.0, pulse(p[2], 0.0)]));
        b.step();
        let start = b.view(0).energy();
        let total0 = start.kinetic + start.elastic;
        let mut worst: f64 = 0.0;
        for _ in 0..(60.0 * LC / cp / dt) as usize {
            b.step();
            let e = b.view(0).energy();
            worst = worst.max((e.residual() - start.residual()).abs() / total0);
        }
        let e = b.view(0).energy();
        println!("the medium took {:.4} of the pulse, worst ledger drift {worst:.2e}", e.anelastic / total0);
        assert!(e.anelastic > 0.01 * total0, "the medium should have taken some: {}", e.anelastic / total0);
        assert!(worst < 1e-9, "the ledger drifts by {worst:e} of the pulse's energy");
    }
}

#[test]
fn kelvin_voigt_dashpots_lower_the_stable_step_as_the_closed_form_says() {
    // With β = Δt_c (ξ = 1) the stable step is (√2 − 1)·Δt_c: 2% below it every mode stays
    // bounded, 5% above it the highest grows.
    // A free block: constraints would lower the highest frequency below the free lattice's.
    let free = |medium: Medium| {
        let mut s = column(20, 2, medium, &[]);
        s.boundaries.clear();
        Model::new(s)
    };
    let plain = free(Medium::default());
    let k = plain.nominal_lane_stiffness();
    let dt_c = critical_step_on(&plain, &k, false).unwrap().dt_s;
    let model = free(Medium { kelvin_voigt_s: dt_c, ..Medium::default() });
    let dt_kv = critical_step_on(&model, &k, false).unwrap().dt_s;
    println!("critical step {dt_c:.4e} s, with β = Δt_c {dt_kv:.4e} s ({:.4} of it)", dt_kv / dt_c);
    assert!((dt_kv / dt_c - (2f64.sqrt() - 1.0)).abs() < 1e-12);
    let grows = |fraction: f64| {
        let lane = LaneSetup {
            dt_s: fraction * dt_kv,
            stiffness: k.clone(),
            friction: vec![1.0; model.contact().len()],
            strength: None,
            fault: None,
        };
        let mut b = Batch::<1>::new(&model, &[lane]);
        // Every mode excited: a scramble of about 1 µm on z.
        b.initialize(0, |p| {
            let s = 1e-6 * ((p[0] * 7.31 + p[1] * 3.17 + p[2] * 17.93) / LC).sin();
            ([0.0, 0.0, -s], [0.0, 0.0, s])
        });
        for _ in 0..3000 {
            b.step();
        }
        let v = b.view(0);
        (0..model.node_count()).map(|i| v.displacement(i)[2].abs()).fold(0.0, f64::max) > 1e-3
    };
    assert!(!grows(0.98), "98% of the damped step should be stable");
    assert!(grows(1.05), "105% of the damped step should be unstable");
}

#[test]
fn the_medium_gives_the_same_bits_on_one_and_two_threads() {
    let mut medium = q_medium(30.0);
    medium.kelvin_voigt_s = 2e-4;
    medium.profile = layered(layer(1500.0, 2000.0, 2300.0, 30.0), false).profile;
    let mut scene = column(40, 0, medium, &[]);
    scene.dims = Dims::new(8, 6, 40);
    scene.boundaries.clear();
    let model = Model::with_stencil(scene);
    assert!(model.layout().splits(), "the test needs slabs");
    let run = |parallel: bool| {
        let lane = setup(&model, 0.5);
        let mut b = Batch::<1>::new(&model, &[lane]);
        b.stepper.set_parallel(parallel);
        b.initialize(0, |p| {
            let u = 1e-3 * (-((p[2] - 2000.0) / 400.0f64).powi(2)).exp();
            ([u, 0.5 * u, 0.0], [u, 0.5 * u, 0.0])
        });
        for _ in 0..200 {
            b.step();
        }
        let v = b.view(0);
        (0..model.node_count()).flat_map(|i| v.displacement(i)).map(f64::to_bits).collect::<Vec<u64>>()
    };
    let serial = run(false);
    let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
    let parallel = pool.install(|| run(true));
    assert!(serial.iter().any(|&b| b != 0));
    assert_eq!(serial, parallel);
}
