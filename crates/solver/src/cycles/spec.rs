//! A cycle run of a scene: what `[cycles]` asks for, and the fault it builds (docs/model.md §20.4).

use crate::error::SolverError;
use crate::geometry::Dims;
use crate::laws::{NodeFriction, RateStateStart, balanced_state};
use crate::model::Model;
use crate::scene::Scene;

use super::antiplane::{AntiplaneStencil, FaultStiffness};
use super::dynamic::{AntiplaneGrid, FullyDynamicFault};
use super::heterogeneity::Heterogeneity;
use super::quasi_dynamic::{QuasiDynamicFault, Tolerances};

/// A cycle run: the plate's loading of a scene's fault over a duration.
#[derive(Clone, Debug, PartialEq)]
pub struct CycleSpec {
    /// How long (s).
    pub duration_s: f64,
    /// The plate rate V_p (m/s).
    pub plate_m_s: f64,
    /// The frictional part of the fault reaches from the free surface down to this depth (m);
    /// below it the fault creeps at the plate rate.
    pub frictional_depth_m: f64,
    /// The direct effect `a` along depth on the background (patches keep their own): points
    /// `(depth m, a)`, linear between them and constant beyond; empty = the background's a.
    pub a_by_depth: Vec<(f64, f64)>,
    /// The step control.
    pub tolerances: Tolerances,
    /// The slip rate above which the fault is in an event (m/s).
    pub event_slip_rate_m_s: f64,
    /// The files' sampling inside events (s).
    pub sample_s: f64,
    /// On-fault stations: their depths (m).
    pub stations_m: Vec<f64>,
    /// The most steps a run may take.
    pub max_steps: u64,
    /// Fully dynamic: the explicit grid inside events; `None`: quasi-dynamic throughout.
    pub dynamic: Option<DynamicSpec>,
    /// Random fields of a, b and L along the fault, one draw per seed; `None`: the scene's
    /// friction as given (one run, whatever the seeds).
    pub heterogeneity: Option<Heterogeneity>,
}

/// The explicit phases of a fully dynamic cycle run (docs/model.md §20.5).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DynamicSpec {
    /// The explicit grid takes over above this largest slip rate (m/s).
    pub above_m_s: f64,
    /// The quasi-dynamic integration resumes below it (m/s).
    pub below_m_s: f64,
    /// The explicit grid's extent down dip and away from the fault (m).
    pub block_m: [f64; 2],
    /// Kelvin–Voigt damping of the grid's links as a fraction γ of the step (`β = γ·Δt`).
    pub damping: f64,
}

impl DynamicSpec {
    /// The default switch to the explicit grid: 5 mm/s, and back below 2 mm/s, the thresholds
    /// of Kaneko, Ampuero & Lapusta (2011)'s spectral-element cycles as Thakur, Huang & Kaneko
    /// (2020)'s code has them.
    pub const ABOVE_M_S: f64 = 5e-3;
    /// The default switch back to the quasi-dynamic integration (m/s).
    pub const BELOW_M_S: f64 = 2e-3;
    /// The explicit step as a fraction of the grid's stability limit (with its damping).
    pub const STEP_FRACTION: f64 = 0.9;
    /// The default damping γ: `β = 0.3·Δt`, against the grid's own ringing at its shortest
    /// wavelengths, which a rupture front excites (at γ = 0.1 the slip rate behind the front still
    /// swings by ±40% every five steps at 100 m, at 0.3 by ±10%; the slip changes by 0.15%). It
    /// attenuates a wave of frequency f by `Q⁻¹ = 2πf·β`: Q ≈ 50 at 1 Hz at 100 m.
    pub const DAMPING: f64 = 0.3;
}

impl CycleSpec {
    /// What a run of `scene` holds at most (bytes): the fault's stiffness (`n²`) and the cosines
    /// it is built from, the explicit grid's displacements, velocities and forces, and the files' rows.
    pub fn memory_bytes(&self, scene: &Scene) -> u64 {
        let lc = scene.lc_m;
        let ny = scene.dims.ny as u64;
        let n = self.frictional_nodes(lc, scene.dims.ny) as u64;
        let stiffness = 8 * n * n + 8 * 3 * n * (ny + 1).max(n);
        let grid = self.dynamic.map_or(0, |d| {
            let (gy, gz) = ((d.block_m[0] / lc).round() as u64, (d.block_m[1] / lc).round() as u64);
            8 * 3 * ((gy + 1) * (gz + 1) + gy * gz)
        });
        // Rows of the files: every max step between events, every sample inside them (BP1: two
        // minutes of events a century; five allowed for), about 110 bytes a station's row.
        let rows = (self.duration_s / self.tolerances.max_step_s) as u64
            + (self.duration_s / (100.0 * super::YEAR_S) * 300.0 / self.sample_s) as u64;
        let files = rows * 110 * (self.stations_m.len() as u64 + 1);
        stiffness + grid + files
    }

    /// The frictional nodes of a block of `ny` modules of `lc_m` down dip: those above the
    /// frictional depth, at most the face's `ny + 1`.
    pub fn frictional_nodes(&self, lc_m: f64, ny: usize) -> usize {
        ((self.frictional_depth_m / lc_m).ceil() as usize).min(ny + 1)
    }

    /// `a` at `depth_m` from [`CycleSpec::a_by_depth`], `None` when it is empty.
    pub fn a_at(&self, depth_m: f64) -> Option<f64> {
        let p = &self.a_by_depth;
        let (first, last) = (p.first()?, p.last()?);
        if depth_m <= first.0 {
            return Some(first.1);
        }
        if depth_m >= last.0 {
            return Some(last.1);
        }
        let i = p.windows(2).position(|w| depth_m >= w[0].0 && depth_m <= w[1].0)?;
        let (d0, a0, d1, a1) = (p[i].0, p[i].1, p[i + 1].0, p[i + 1].1);
        Some(if d1 > d0 { a0 + (a1 - a0) * (depth_m - d0) / (d1 - d0) } else { a1 })
    }
}

/// The antiplane stencil of the scene's lattice: read from a slab of 1 × 4 × 3 modules of the
/// scene's material and module side, built as the solver builds any block.
pub fn scene_stencil(scene: &Scene) -> Result<AntiplaneStencil, SolverError> {
    let mut slab = Scene::paper();
    slab.dims = Dims::new(1, 4, 3);
    slab.lc_m = scene.lc_m;
    slab.young_pa = scene.young_pa;
    slab.poisson = scene.poisson;
    slab.density_kg_m3 = scene.density_kg_m3;
    slab.young_cv = 0.0;
    slab.boundaries.clear();
    slab.record.interface.clear();
    slab.stations.clear();
    let model = Model::new(slab);
    AntiplaneStencil::from_model(&model, &model.nominal_stiffness())
}

impl QuasiDynamicFault {
    /// The fault of `scene` (a slab one module thick, its base a rate-and-state fault) under
    /// `spec`: the nodes of the slab's side x = 0 from the free surface down to the frictional
    /// depth, each with its friction (`a` from [`CycleSpec::a_by_depth`] on the background), the
    /// fault's tractions, θ₀ balancing the shear traction at the start's slip rate, and
    /// radiation damping `μ/(2c_s)`; the coefficients multiplied by
    /// [`CycleSpec::heterogeneity`]'s fields of `seed` first, when it asks for them.
    pub fn from_scene(scene: &Scene, spec: &CycleSpec, seed: u64) -> Result<Self, SolverError> {
        let Some(fault) = &scene.fault else {
            return Err(SolverError::Unsupported("a cycle run needs a [fault]".into()));
        };
        let Dims { nx, ny, nz } = scene.dims;
        if nx != 1 {
            return Err(SolverError::Unsupported(format!("a cycle run is a slab one module thick (nx = 1), not {nx}")));
        }
        let lc = scene.lc_m;
        let nodes = spec.frictional_nodes(lc, ny);
        let stencil = scene_stencil(scene)?;
        let stiffness = FaultStiffness::antiplane(&stencil, nodes, ny, nz)?;
        let mu = stencil.shear_modulus_pa();
        let eta = mu / (2.0 * scene.s_wave_speed());
        let mut friction = Vec::with_capacity(nodes);
        let (mut normal, mut shear) = (Vec::with_capacity(nodes), Vec::with_capacity(nodes));
        for j in 0..nodes {
            // Contact node of corner (0, j, 0): i fastest over nx + 1 = 2.
            let c = 2 * j;
            let NodeFriction::RateState(mut node) = scene.friction.base(c) else {
                return Err(SolverError::Unsupported("a cycle run needs rate-and-state friction".into()));
            };
            let background = scene.friction.map.as_ref().is_none_or(|m| m.region[c].is_none());
            if background && let Some(a) = spec.a_at(j as f64 * lc) {
                node.a = a;
            }
            friction.push(node);
            normal.push(fault.normal_pa[c]);
            shear.push(fault.shear_pa[c][0]);
        }
        if let Some(h) = &spec.heterogeneity {
            h.apply(&mut friction, lc, seed)?;
        }
        for ((node, &sigma), &tau) in friction.iter_mut().zip(&normal).zip(&shear) {
            // SEAS's start; a balanced one is balanced by the fault's own start().
            if let RateStateStart::SteadyAt(v) = node.start {
                node.start = RateStateStart::State(balanced_state(node, v, tau, sigma, eta));
            }
        }
        Ok(QuasiDynamicFault {
            stiffness,
            friction,
            normal_pa: normal,
            shear0_pa: shear,
            eta_pa_s_m: eta,
            plate_m_s: spec.plate_m_s,
        })
    }
}

impl FullyDynamicFault {
    /// The fault of `scene` under `spec` (which asks for the fully dynamic mode): the
    /// quasi-dynamic fault of [`QuasiDynamicFault::from_scene`] and the explicit grid of the
    /// scene's stencil over [`DynamicSpec::block_m`], its far face and bottom absorbing.
    pub fn from_scene(scene: &Scene, spec: &CycleSpec, seed: u64) -> Result<Self, SolverError> {
        let Some(dynamic) = spec.dynamic else {
            return Err(SolverError::Unsupported(
                "a fully dynamic cycle run needs cycles.mode = \"fully_dynamic\"".into(),
            ));
        };
        let quasi = QuasiDynamicFault::from_scene(scene, spec, seed)?;
        let stencil = scene_stencil(scene)?;
        let lc = scene.lc_m;
        let ny = ((dynamic.block_m[0] / lc).round() as usize).max(quasi.nodes());
        let nz = ((dynamic.block_m[1] / lc).round() as usize).max(4);
        let grid = AntiplaneGrid {
            ny,
            nz,
            stencil,
            density_kg_m3: scene.density_kg_m3,
            absorbing_far: true,
            absorbing_bottom: true,
            damping_s: 0.0,
        };
        let step_s = DynamicSpec::STEP_FRACTION * grid.critical_step_damped_s(dynamic.damping);
        let grid = AntiplaneGrid { damping_s: dynamic.damping * step_s, ..grid };
        Ok(FullyDynamicFault {
            quasi,
            grid,
            dynamic_above_m_s: dynamic.above_m_s,
            static_below_m_s: dynamic.below_m_s,
            step_s,
        })
    }
}
