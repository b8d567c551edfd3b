//! What a scene builds, without running it: sizes, loads, the critical step over seeds, the
//! effective stiffness of the built block and a fault's tractions against its friction (for
//! `stickslip check`).

use crate::error::SolverError;
use crate::field::Field;
use crate::geometry::Dims;
use crate::model::Model;
use crate::statics::{CriticalStep, EffectiveModuli, Prescribed, critical_step_on, solve_static, uniaxial_moduli};

/// The facts of a built scene.
#[derive(Clone, Debug, PartialEq)]
pub struct Inspection {
    /// Nodes.
    pub nodes: usize,
    /// Bars.
    pub bars: usize,
    /// Contact nodes (the base).
    pub contact_nodes: usize,
    /// Total mass (kg).
    pub mass_kg: f64,
    /// Contact area `nx·Lc × ny·Lc` (m²).
    pub contact_area_m2: f64,
    /// Mean normal stress of the self-weight on the base, `m·g/A` (Pa).
    pub self_weight_stress_pa: f64,
    /// Sliding strength of the whole base under its self-weight, `μs·m·g/A` (Pa).
    pub strength_pa: f64,
    /// Critical step of each seed inspected.
    pub critical: Vec<(u64, CriticalStep)>,
    /// Seconds the first seed's stiffness and critical step took: what a run of the scene spends
    /// on them before its first step, besides building the lattice.
    pub setup_s: f64,
    /// The paper's bound `0.6·Lc/Cp` (Eq. 5, s).
    pub paper_bound_s: f64,
    /// Effective moduli along x and along z (static solves of the lattice of the first seed
    /// inspected, or of a sample block of the same material: see `moduli_of`); empty when a
    /// solve did not converge (`unsolved` says why).
    pub moduli: Vec<EffectiveModuli>,
    /// Why the moduli were not solved, if they were not (a check reads what it can; the run does
    /// not need them).
    pub unsolved: Option<String>,
    /// The block the moduli were solved on: the scene's, or a sample of at most
    /// [`SAMPLE_MODULES`] modules per axis when the scene's is too large ([`Statics::Sample`]).
    pub moduli_of: Dims,
    /// The spring-slider reading of the scene: when stick-slip is expected.
    pub slider: Slider,
}

/// The scene read as a spring-slider (docs/model.md §12): a block of mass `M` pressed with `N`
/// onto the base and loaded through a stiffness `k` — the seated block under its drivers, in
/// series with the plate's springs — against the friction's weakening rate.
#[derive(Clone, Debug, PartialEq)]
pub struct Slider {
    /// Normal force on the base: weight plus normal load (N).
    pub normal_n: f64,
    /// Force the base holds before sliding, μs·N (N).
    pub strength_n: f64,
    /// Force in x at which the loading would tip the block about its leading base edge,
    /// `N·(L/2)/h` with `h` the height the load acts at (N).
    pub tipping_n: f64,
    /// Stiffness of the block under the loaded nodes, base held (static solve, N/m); NaN when not
    /// solved ([`Statics::Sample`], or a solve that did not converge: `block_note` says which).
    pub block_n_m: f64,
    /// Why the block's stiffness was not solved, when it was not.
    pub block_note: Option<String>,
    /// Stiffness of the plate's springs (N/m); infinite without a plate (rigid drivers).
    pub plate_n_m: f64,
    /// The loading stiffness `k`: block and springs in series (N/m).
    pub k_n_m: f64,
    /// Critical stiffness `(μs − μd)·N/Dc` (N/m; `(b − a)·N/L` under rate and state): infinite
    /// when μ drops at once, 0 without weakening.
    pub critical_n_m: f64,
    /// How the law computes the critical stiffness, as printed ([`crate::laws::Law::CRITICAL`]).
    pub critical_formula: &'static str,
    /// Why the law slides steadily without a critical stiffness ([`crate::laws::Law::STEADY`]).
    pub steady_reason: &'static str,
    /// Damping ratio of the slider's swing, `D/(2ω)`, `ω = √(k/M)` (mass-proportional damping
    /// drags the moving block as a whole).
    pub damping_ratio: f64,
    /// Slip speed scale of a dynamic slip, `(μs − μd)·N/k·ω` (m/s).
    pub slip_speed_m_s: f64,
    /// Loading speed u̇f (m/s).
    pub loading_speed_m_s: f64,
    /// The base's resistance while it slides, μd·N (N; μs and μd are the means over the base's
    /// nodes when a friction map gives them their own).
    pub sliding_n: f64,
    /// The fractions of μs·N at which a lattice block lets go of its base, when they depart from
    /// the rigid slider's 1: under rigid driver nodes, whose load lets the trailing base nodes go
    /// first (0.73–0.81 measured, docs/model.md §12); `None` for a plate's springs.
    pub let_go: Option<(f64, f64)>,
}

/// The fractions of μs·N at which a lattice block under rigid driver nodes lets go of its base
/// (docs/model.md §12: 0.73–0.81 for the 8×1×1 block).
pub const DRIVER_LET_GO: (f64, f64) = (0.73, 0.81);

/// What the spring-slider reading expects, by kind: the verdict without its numbers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regime {
    /// The load tips the block about its leading edge before the base slides.
    Tips,
    /// Stable sliding: μ does not weaken with slip.
    NoWeakening,
    /// Stable sliding: the loading is stiffer than the critical stiffness.
    StiffLoading,
    /// Stable sliding: the swing is damped too much for a slip to outrun the loading.
    Overdamped,
    /// Stable sliding: a lattice block under driver nodes lets go of its base before the drop to
    /// μd·N is large enough for the slip to outrun the loading.
    LetsGoEarly,
    /// Stick-slip or stable sliding: the slip outruns the loading only if the block holds its
    /// base up to a fraction of μs·N inside the range where lattice blocks under drivers let go.
    Marginal,
    /// Stick-slip.
    StickSlip,
    /// Not decided: the block's stiffness under its load was not solved.
    Undetermined,
}

impl Slider {
    /// What the spring-slider reading expects.
    pub fn regime(&self) -> Regime {
        if self.tipping_n < self.strength_n {
            Regime::Tips
        } else if self.critical_n_m == 0.0 {
            Regime::NoWeakening
        } else if self.k_n_m.is_nan() {
            Regime::Undetermined
        } else if self.k_n_m >= self.critical_n_m {
            Regime::StiffLoading
        } else if self.damping_ratio >= 1.0 || self.slip_speed_m_s * self.overshoot() < self.loading_speed_m_s {
            // Underdamped: a slip overshoots and sticks again only if its swing outruns the loading.
            Regime::Overdamped
        } else {
            match (self.let_go, self.holds_until()) {
                (Some((_, hi)), Some(f)) if f > hi => Regime::LetsGoEarly,
                (Some((lo, _)), Some(f)) if f > lo => Regime::Marginal,
                _ => Regime::StickSlip,
            }
        }
    }

    /// The fraction of μs·N the block must hold its base up to for the slip that follows to
    /// outrun the loading: the drop `ΔF` from there to μd·N must swing the block faster than
    /// u̇f, `ΔF/k·ω·e^(−πζ/√(1−ζ²)) = u̇f` (the rigid slider's criterion with the let-go lowered).
    pub fn holds_until(&self) -> Option<f64> {
        let omega = self.slip_speed_m_s * self.k_n_m / (self.strength_n - self.sliding_n);
        let needed = self.loading_speed_m_s * self.k_n_m / (omega * self.overshoot());
        let f = (self.sliding_n + needed) / self.strength_n;
        f.is_finite().then_some(f)
    }

    /// The fraction of its speed a slip's swing overshoots by, `exp(−πζ/√(1 − ζ²))`.
    fn overshoot(&self) -> f64 {
        (-std::f64::consts::PI * self.damping_ratio / (1.0 - self.damping_ratio.powi(2)).max(1e-12).sqrt()).exp()
    }

    /// What the spring-slider reading expects, in words: the [`Regime`], its numbers and what would
    /// change it, in physical quantities.
    pub fn verdict(&self) -> String {
        match self.regime() {
            Regime::Tips => format!(
                "the block tips before it slides: the load tips it about its leading edge at {:.4e} N, below the \
                 base's strength μs·N = {:.4e} N (load it lower, e.g. through springs on the trailing face, or lower \
                 μs)",
                self.tipping_n, self.strength_n
            ),
            Regime::NoWeakening => format!("stable sliding expected: {}", self.steady_reason),
            Regime::StiffLoading => format!(
                "stable sliding expected: the loading stiffness k = {:.4e} N/m is above the critical stiffness \
                 {} = {:.4e} N/m (softer loading, a larger drop or a shorter weakening distance make it unstable)",
                self.k_n_m, self.critical_formula, self.critical_n_m
            ),
            Regime::Overdamped => format!(
                "stable sliding expected despite k < k_c: the damping ratio of the block's swing D/(2ω) = {} lets a slip \
                 overshoot by only {:.2e} m/s, less than the loading speed {:.2e} m/s, so the block never stops again \
                 (lower the shear stage's damping or the loading speed)",
                three(self.damping_ratio),
                self.slip_speed_m_s * self.overshoot(),
                self.loading_speed_m_s
            ),
            Regime::LetsGoEarly | Regime::Marginal => {
                let (lo, hi) = self.let_go.unwrap_or((1.0, 1.0));
                let f = self.holds_until().unwrap_or(f64::NAN);
                let head = if self.regime() == Regime::LetsGoEarly {
                    "stable sliding expected"
                } else {
                    "stick-slip or stable sliding (marginal)"
                };
                format!(
                    "{head}: the rigid slider would stick and slip (k = {:.4e} N/m below k_c, swing damping ratio {:.3}), \
                     but its slip outruns the loading only if the block holds its base up to {f:.2}·μs·N, and a \
                     lattice block under driver nodes lets its base go from the driven edge at {lo:.2}–{hi:.2}·μs·N, \
                     where the drop to μd·N = {:.4e} N is {}; a plate on springs loads the base more evenly",
                    self.k_n_m,
                    self.damping_ratio,
                    self.sliding_n,
                    if f > hi { "too small: it slides with its loading" } else { "about what stick-slip needs" }
                )
            }
            Regime::Undetermined => format!(
                "not assessed: the reading needs the block's stiffness under its load, a static solve of the whole \
                 lattice, {} (the critical stiffness {} = {:.4e} N/m)",
                self.block_note.as_deref().unwrap_or("left out for a block this large"),
                self.critical_formula,
                self.critical_n_m
            ),
            Regime::StickSlip => format!(
                "stick-slip expected: k = {:.4e} N/m below k_c = {}, swing damping ratio {}",
                self.k_n_m,
                if self.critical_n_m.is_finite() {
                    format!("{:.4e} N/m", self.critical_n_m)
                } else {
                    "∞ (μ drops at once)".into()
                },
                three(self.damping_ratio)
            ),
        }
    }
}

/// `v` with three decimals, or with an exponent once it is 10⁶ or more in size.
fn three(v: f64) -> String {
    if v.abs() < 1e6 { format!("{v:.3}") } else { format!("{v:.3e}") }
}

impl Inspection {
    /// Smallest and largest critical step over the seeds inspected (s).
    pub fn critical_range_s(&self) -> (f64, f64) {
        self.critical
            .iter()
            .map(|(_, c)| c.dt_s)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)))
    }
}

/// Modules per axis of the sample block of [`Statics::Sample`].
pub const SAMPLE_MODULES: usize = 16;

/// Lattices with more bars than this get [`Statics::Sample`] by default: a static solve costs
/// thousands of steps' worth of bar passes (the condition number grows with the block).
pub const FULL_STATICS_MAX_BARS: usize = 500_000;

/// The largest bars × longest side (in modules) solved whole by default: a conjugate-gradient
/// solve takes iterations in proportion to the longest side, each a pass over the bars, so a
/// long thin block (9999×1×2 modules, 320 000 bars: 64 s of `check`) is read on a sample block.
pub const FULL_STATICS_MAX_WORK: f64 = 1e8;

/// Which static solves [`inspect`] makes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Statics {
    /// The effective moduli and the block's stiffness under its load, on the whole lattice.
    Full,
    /// The effective moduli on a sample block of the same material, seed and Lc, at most
    /// [`SAMPLE_MODULES`] modules per axis; the block's stiffness is not solved.
    Sample,
}

impl Statics {
    /// [`Statics::Full`] up to [`FULL_STATICS_MAX_BARS`] bars and [`FULL_STATICS_MAX_WORK`],
    /// [`Statics::Sample`] above.
    pub fn for_model(model: &Model) -> Statics {
        let d = model.scene().dims;
        let longest = d.nx.max(d.ny).max(d.nz) as f64;
        let work = model.bar_count() as f64 * longest;
        if model.bar_count() <= FULL_STATICS_MAX_BARS && work <= FULL_STATICS_MAX_WORK {
            Statics::Full
        } else {
            Statics::Sample
        }
    }
}

/// Inspects `model` for `seeds` (at least one): the critical step of each, the moduli of the
/// first (on the whole lattice or a sample block, as `statics` says) and the spring-slider
/// reading.
pub fn inspect(model: &Model, seeds: &[u64], statics: Statics) -> Result<Inspection, SolverError> {
    assert!(!seeds.is_empty(), "inspect at least one seed");
    let scene = model.scene();
    let lattice = model.lattice();
    let mut critical = Vec::with_capacity(seeds.len());
    let mut setup_s = f64::NAN;
    for &seed in seeds {
        // `check` runs alone: the pool is its.
        let start = std::time::Instant::now();
        critical.push((seed, critical_step_on(model, &model.lane_stiffness_on(seed, true)?, true)?));
        if setup_s.is_nan() {
            setup_s = start.elapsed().as_secs_f64();
        }
    }
    // The per-bar stiffness only for the static solves on the whole block.
    let k = if statics == Statics::Full { model.bar_stiffness(seeds[0])? } else { Vec::new() };
    let (moduli, moduli_of) = match statics {
        Statics::Full => ([0, 2].map(|axis| uniaxial_moduli(model, &k, axis)), scene.dims),
        Statics::Sample => {
            let d = scene.dims;
            let dims = Dims::new(d.nx.min(SAMPLE_MODULES), d.ny.min(SAMPLE_MODULES), d.nz.min(SAMPLE_MODULES));
            let sample = Model::new(scene.sample(dims));
            let ks = sample.bar_stiffness(seeds[0])?;
            ([0, 2].map(|axis| uniaxial_moduli(&sample, &ks, axis)), dims)
        }
    };
    // A solve that does not converge leaves the moduli out; the check goes on (the run does not
    // need them).
    let (moduli, unsolved) = match moduli {
        [Ok(x), Ok(z)] => (vec![x, z], None),
        [Err(e), _] | [_, Err(e)] => (Vec::new(), Some(e.to_string())),
    };
    let weight = model.total_mass() * scene.self_weight.gravity_m_s2;
    let area = lattice.contact_area();
    let slider = slider(model, (statics == Statics::Full).then_some(&k[..]), weight)?;
    Ok(Inspection {
        nodes: model.node_count(),
        bars: model.bar_count(),
        contact_nodes: model.contact().len(),
        mass_kg: model.total_mass(),
        contact_area_m2: area,
        self_weight_stress_pa: weight / area,
        strength_pa: slider.strength_n / slider.normal_n * weight / area,
        critical,
        setup_s,
        paper_bound_s: scene.paper_time_step_bound(),
        moduli,
        unsolved,
        moduli_of,
        slider,
    })
}

/// Untimed steps before [`probe_step_time`] times any: the three time levels of the state and the
/// forces are freshly allocated, zero pages the kernel maps at their first write, and each of the
/// first three steps writes one level for the first time (on a 50 M-bar lattice these steps took
/// 0.24–0.25 s against 0.15 s for the ones after; timing them put `check`'s estimate 1.6–3× above
/// the run).
pub const PROBE_WARM_UP_STEPS: u32 = 3;

/// Seconds per step of one seed of `model` at Δt = `dt` with the scene's tracking (energy terms,
/// slip onsets), on the current rayon pool (each step split over it with `parallel`): steps timed
/// from rest under the shear stage's damping, after [`PROBE_WARM_UP_STEPS`] untimed steps, until
/// `budget_s` has passed (at least 3 steps, at most 200).
pub fn probe_step_time(model: &Model, seed: u64, dt: f64, parallel: bool, budget_s: f64) -> Result<f64, SolverError> {
    use crate::step::{Batch, LaneSetup, Tracking};
    let scene = model.scene();
    let setup = LaneSetup {
        dt_s: dt,
        stiffness: model.lane_stiffness(seed)?,
        friction: model.friction_factors(seed)?,
        strength: model.bar_strength(seed)?,
        fault: model.fault_loads(seed)?,
    };
    let mut batch = Batch::<1>::new(model, &[setup]);
    batch.params.set_damping(0, scene.shear.damping_per_s);
    batch.params.set_body_acceleration(0, [0.0, 0.0, -scene.self_weight.gravity_m_s2]);
    batch.stepper.set_parallel(parallel && model.layout().splits());
    batch.stepper.set_tracking(Tracking { energy: scene.record.energy, onsets: scene.record.slip_onsets, slid: false });
    for _ in 0..PROBE_WARM_UP_STEPS {
        batch.step();
    }
    let start = std::time::Instant::now();
    let mut steps = 0u32;
    while steps < 200 && (steps < 3 || start.elapsed().as_secs_f64() < budget_s) {
        batch.step();
        steps += 1;
    }
    Ok(start.elapsed().as_secs_f64() / f64::from(steps))
}

/// The spring-slider reading of `model` for `seed` without the critical step ([`inspect`] gives
/// it with the rest): the block's stiffness under its load solved only with [`Statics::Full`].
pub fn spring_slider(model: &Model, seed: u64, statics: Statics) -> Result<Slider, SolverError> {
    let weight = model.total_mass() * model.scene().self_weight.gravity_m_s2;
    match statics {
        Statics::Full => slider(model, Some(&model.bar_stiffness(seed)?), weight),
        Statics::Sample => slider(model, None, weight),
    }
}

/// The spring-slider reading of `model` with bar stiffness `k` under `weight`; without `k` the
/// block's stiffness is not solved (NaN).
fn slider(model: &Model, k: Option<&[f64]>, weight: f64) -> Result<Slider, SolverError> {
    let scene = model.scene();
    let lattice = model.lattice();
    let normal = weight + scene.normal_load().map_or(0.0, |n| n.total());
    // The loaded nodes: the drivers and the plate's nodes.
    let loaded: Vec<usize> =
        model.drivers().iter().map(|&d| d as usize).chain(model.plate().iter().map(|&(i, _)| i as usize)).collect();
    // The base's coefficients: the law's, or their means over a friction map's nodes.
    let contacts = model.contact().len().max(1);
    let nodes: Vec<_> = (0..contacts).map(|c| scene.friction.base(c)).collect();
    let mean = |f: &dyn Fn(&crate::laws::NodeFriction) -> f64| nodes.iter().map(f).sum::<f64>() / nodes.len() as f64;
    let (mu_s, mu_d) = (mean(&|n| n.static_coefficient()), mean(&|n| n.residual_coefficient()));
    let strength = mu_s * normal;
    let e = lattice.extent();
    let h = if loaded.is_empty() {
        e[2]
    } else {
        loaded.iter().map(|&i| lattice.position(model.canonical(i))[2]).sum::<f64>() / loaded.len() as f64
    };
    let tipping = if h > 0.0 { normal * 0.5 * e[0] / h } else { f64::INFINITY };
    // Block stiffness: base held, loaded nodes moved together by δ in x; k = ΣR/δ.
    let mut block_note = None;
    let block = if loaded.is_empty() {
        f64::INFINITY
    } else if let Some(k) = k {
        let delta = 1e-6;
        let mut prescribed = Vec::new();
        for &c in model.contact() {
            prescribed.extend((0..3).map(|axis| Prescribed { node: c as usize, axis, value: 0.0 }));
        }
        prescribed.extend(loaded.iter().map(|&i| Prescribed { node: i, axis: 0, value: delta }));
        match solve_static(model, k, &Field::zeros(model.node_count()), &prescribed, 1e-8, 20_000) {
            Ok(sol) => loaded.iter().map(|&i| sol.reactions.c[0][i][0]).sum::<f64>() / delta,
            Err(e) => {
                block_note = Some(format!("which did not converge here ({e})"));
                f64::NAN
            }
        }
    } else {
        f64::NAN
    };
    let plate = scene.plate().map_or(f64::INFINITY, |p| p.stiffness());
    let k_load = 1.0 / (1.0 / block + 1.0 / plate);
    // Each node's critical stiffness at its share of the normal force, summed (infinite when
    // any node drops at once).
    let critical = nodes.iter().map(|n| n.critical_stiffness(normal / contacts as f64)).sum::<f64>();
    let omega = (k_load / model.total_mass()).sqrt();
    Ok(Slider {
        normal_n: normal,
        strength_n: strength,
        tipping_n: tipping,
        block_n_m: block,
        block_note,
        plate_n_m: plate,
        k_n_m: k_load,
        critical_n_m: critical,
        critical_formula: nodes[0].critical_formula(),
        steady_reason: nodes[0].steady_reason(),
        damping_ratio: scene.shear.damping_per_s / (2.0 * omega),
        slip_speed_m_s: (mu_s - mu_d) * normal / k_load * omega,
        loading_speed_m_s: scene.shear.velocity_m_s,
        sliding_n: mu_d * normal,
        let_go: (!model.drivers().is_empty() && model.plate().is_empty()).then_some(DRIVER_LET_GO),
    })
}

/// What `check` says of a fault before running it (docs/model.md §15): its tractions against the
/// strength of its nodes, where rupture can start, and whether the lattice resolves its cohesive
/// zone.
#[derive(Clone, Debug, PartialEq)]
pub struct FaultReading {
    /// Range of the normal traction over the fault (Pa).
    pub normal_pa: (f64, f64),
    /// Range of the initial shear traction's magnitude (Pa).
    pub shear_pa: (f64, f64),
    /// Nodes whose initial shear traction exceeds their static strength `μs·σn` (they slide from
    /// the first step: the nucleation), and their area (m²).
    pub overstressed: (usize, f64),
    /// Nodes that can slip: those whose traction exceeds their dynamic strength `μd·σn`.
    pub can_slip: usize,
    /// Median over the nodes that can slip and are not overstressed of the strength excess
    /// `S = (τs − τ0)/(τ0 − τd)` (Das & Aki 1977).
    pub median_s: Option<f64>,
    /// Smallest static cohesive-zone width over the nodes that can slip,
    /// `Λ0 = (9π/32)·μ·Dc/(τs − τd)` (Day et al. 2005), `μ` the lattice's shear modulus (m); `None`
    /// when no such node weakens over a distance.
    pub cohesive_zone_m: Option<f64>,
    /// Smallest nucleation size over the fault's nodes (a rate-and-state law's `h*`, m); `None`
    /// when the law has none.
    pub nucleation_m: Option<f64>,
}

impl FaultReading {
    /// Reads the fault of `model` (its tractions before any random field) against its friction.
    pub fn of(model: &Model) -> Option<FaultReading> {
        let scene = model.scene();
        let fault = scene.fault.as_ref()?;
        let (_, _, c44) = crate::material::lattice_elastic_constants(scene.young_pa, scene.poisson);
        let lattice = model.lattice();
        let area: Vec<f64> =
            lattice.contact_nodes().iter().map(|&id| crate::geometry::Face::ZMin.tributary_area(lattice, id)).collect();
        let range = |v: &mut dyn Iterator<Item = f64>| {
            v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| (a.min(x), b.max(x)))
        };
        let mut overstressed = (0, 0.0);
        let mut can_slip = 0;
        let mut s_values = Vec::new();
        let mut zone: Option<f64> = None;
        let mut nucleation: Option<f64> = None;
        for c in 0..fault.normal_pa.len() {
            let friction = scene.friction.base(c);
            let (sn, tau) = (fault.normal_pa[c], fault.shear_pa[c][0].hypot(fault.shear_pa[c][1]));
            if let Some(h) = friction.nucleation_m(c44, sn) {
                nucleation = Some(nucleation.map_or(h, |n: f64| n.min(h)));
            }
            let (ts, td) = (friction.static_coefficient() * sn, friction.residual_coefficient() * sn);
            if tau > ts {
                overstressed.0 += 1;
                overstressed.1 += area[c];
            }
            if tau > td {
                can_slip += 1;
                if tau <= ts {
                    s_values.push((ts - tau) / (tau - td));
                }
                if let Some(l) = friction.cohesive_zone_m(c44, sn) {
                    zone = Some(zone.map_or(l, |z: f64| z.min(l)));
                }
            }
        }
        s_values.sort_by(f64::total_cmp);
        Some(FaultReading {
            normal_pa: range(&mut fault.normal_pa.iter().copied()),
            shear_pa: range(&mut fault.shear_pa.iter().map(|s| s[0].hypot(s[1]))),
            overstressed,
            can_slip,
            median_s: s_values.get(s_values.len() / 2).copied(),
            cohesive_zone_m: zone,
            nucleation_m: nucleation,
        })
    }
}
