//! The fully dynamic cycle: explicit steps of the lattice's antiplane mode inside events
//! (docs/model.md §20.5).
//!
//! **The grid.** The antiplane mode of [`super::antiplane`] with its masses: a corner column (the
//! slab's two corners at x = 0 and x = Lc, moved alike) and a module's centre, linked centre to
//! corner by `c` ([`AntiplaneStencil::link_n_per_m`]). The masses are the lattice's lumped ones
//! summed over the two sides: `ρLc³/2` for a centre, `ρLc³/2` halved once for each outer plane
//! of the y–z block a corner lies on (the fault face, the free surface, the far faces). Its
//! long-wave SH speed is `√(c/(ρ·Lc))`, its highest frequency `ω = 4·√(c/(ρLc³))` (corners and
//! centres in opposition), so the central-difference step is stable below `Lc·√(ρLc/c)/2`.
//! The far face and the bottom absorb: each of their corners carries a dashpot `ρ·c_s` over its
//! share of the face (Lysmer & Kuhlemeyer 1969), taken implicitly. Each link also carries
//! Kelvin–Voigt damping `β·c` times its ends' relative velocity ([`AntiplaneGrid::damping_s`]),
//! against the grid's ringing at its shortest wavelengths that a rupture front excites; with
//! `β = γ·Δt` the step is stable below `Lc·√(ρLc/c)/(2√(1 + 2γ))`.
//!
//! **The fault.** The face corners down to the frictional depth are the fault's nodes (slip
//! `δ = 2u`, the other side the mirror); below they creep with the plate, which over an event's
//! seconds is holding them. A node with mass `m` and area `A` under the grid's force `F`, the
//! traction `τ_s` it had when the event began and friction `τ_f`:
//! `m·(v⁺ − v⁻)/Δt = F + A·(τ_s − τ_f(V⁺, θ))`, `V⁺ = 2v⁺`, which is
//! `σ·f(V⁺, θ) + Z·V⁺ = τ_s + F/A + m·v⁻/(Δt·A)` with `Z = m/(2Δt·A)`: the traction balance
//! the quasi-dynamic step solves, with the step's own impedance. The state follows Kaneko et
//! al. (2008)'s two passes: θ evolved exactly over the step at the old rate, V solved, θ evolved
//! again at the mean of the old and the new rate, V solved again.
//!
//! **The switch.** Between events the quasi-dynamic integration of [`QuasiDynamicFault`] runs;
//! when the fault's largest slip rate exceeds [`FullyDynamicFault::dynamic_above_m_s`] the
//! explicit grid takes over, from rest, carrying the perturbation of the static field the
//! fault had at that moment (superposition: the medium at the switch is in static equilibrium
//! with the fault's traction `τ_s`, quasi-dynamically up to `η·V`, which at 1 mm/s is 5 kPa).
//! When the largest slip rate falls below [`FullyDynamicFault::static_below_m_s`] the
//! quasi-dynamic integration resumes from the fault's slip and state, its traction again the
//! full block's static response `τ0 − K·(δ − V_p·t)`.

use std::time::Instant;

use rayon::prelude::*;

use crate::error::SolverError;
use crate::laws::rate_state::{RateStateNode, balance, evolve};

use super::antiplane::AntiplaneStencil;
use super::quasi_dynamic::{CycleState, CycleStats, Flow, QuasiDynamicFault, Tolerances, YEAR_S};

/// The lattice's antiplane mode as an explicit grid of `ny × nz` modules (y down dip from the
/// free surface, z away from the fault face z = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct AntiplaneGrid {
    /// Modules down dip.
    pub ny: usize,
    /// Modules away from the fault.
    pub nz: usize,
    /// The stencil: the centre-to-corner link and the module side.
    pub stencil: AntiplaneStencil,
    /// Density (kg/m³).
    pub density_kg_m3: f64,
    /// Whether the far face (z = nz) absorbs; otherwise it is free.
    pub absorbing_far: bool,
    /// Whether the bottom (y = ny) absorbs; otherwise it is free.
    pub absorbing_bottom: bool,
    /// Stiffness-proportional (Kelvin–Voigt) damping β (s): each link also carries `β·c` times
    /// its ends' relative velocity. 0: none.
    pub damping_s: f64,
}

/// The grid's displacements and velocities along strike (m, m/s), and the last forces (N).
#[derive(Clone, Debug, PartialEq)]
pub struct GridField {
    /// Corners, `j·(nz + 1) + k`.
    pub corner_u: Vec<f64>,
    /// Corner velocities.
    pub corner_v: Vec<f64>,
    /// Centres, `j·nz + k`.
    pub centre_u: Vec<f64>,
    /// Centre velocities.
    pub centre_v: Vec<f64>,
    /// The elastic force on each corner from the last [`AntiplaneGrid::forces`].
    pub corner_f: Vec<f64>,
    /// The elastic force on each centre.
    pub centre_f: Vec<f64>,
}

impl AntiplaneGrid {
    /// The mass of corner column `(j, k)` (kg).
    pub fn corner_mass(&self, j: usize, k: usize) -> f64 {
        let planes = usize::from(j == 0 || j == self.ny) + usize::from(k == 0 || k == self.nz);
        0.5 * self.module_mass() * 0.5f64.powi(planes as i32)
    }

    /// The mass of a module's centre (kg).
    pub fn centre_mass(&self) -> f64 {
        0.5 * self.module_mass()
    }

    fn module_mass(&self) -> f64 {
        self.density_kg_m3 * self.stencil.lc_m.powi(3)
    }

    /// The long-wave SH speed `√(c/(ρ·Lc))` (m/s).
    pub fn shear_wave_m_s(&self) -> f64 {
        (self.stencil.shear_modulus_pa() / self.density_kg_m3).sqrt()
    }

    /// The central-difference step's stability limit without damping, `2/ω_max = Lc·√(ρLc/c)/2`
    /// (s).
    pub fn critical_step_s(&self) -> f64 {
        0.5 * (self.module_mass() / self.stencil.link_n_per_m).sqrt()
    }

    /// The stability limit with damping `β = γ·Δt`: the highest mode's recurrence
    /// `λ² − (2 − (1 + γ)x²)λ + 1 − γx² = 0`, `x = ω_max·Δt`, keeps `|λ| ≤ 1` while
    /// `x ≤ 2/√(1 + 2γ)`, so `Δt ≤ (2/ω_max)/√(1 + 2γ)`.
    pub fn critical_step_damped_s(&self, gamma: f64) -> f64 {
        self.critical_step_s() / (1.0 + 2.0 * gamma).sqrt()
    }

    /// The fault face's area per node `j` (m²): `Lc` along strike times its length down dip.
    pub fn face_area_m2(&self, j: usize) -> f64 {
        let lc = self.stencil.lc_m;
        lc * if j == 0 || j == self.ny { 0.5 * lc } else { lc }
    }

    /// A field at rest.
    pub fn at_rest(&self) -> GridField {
        let (c, m) = ((self.ny + 1) * (self.nz + 1), self.ny * self.nz);
        GridField {
            corner_u: vec![0.0; c],
            corner_v: vec![0.0; c],
            centre_u: vec![0.0; m],
            centre_v: vec![0.0; m],
            corner_f: vec![0.0; c],
            centre_f: vec![0.0; m],
        }
    }

    /// The dashpot of corner `(j, k)` (N·s/m): `ρ·c_s` over its share of the far face and of
    /// the bottom.
    fn dashpot(&self, j: usize, k: usize) -> f64 {
        let lc = self.stencil.lc_m;
        let z = self.density_kg_m3 * self.shear_wave_m_s() * lc * lc;
        let share = |i: usize, n: usize| if i == 0 || i == n { 0.5 } else { 1.0 };
        let far = if self.absorbing_far && k == self.nz { share(j, self.ny) } else { 0.0 };
        let bottom = if self.absorbing_bottom && j == self.ny { share(k, self.nz) } else { 0.0 };
        z * (far + bottom)
    }

    /// The elastic forces of the field's displacements, into `corner_f` and `centre_f`, with the
    /// links' damping `β·c·Δv` from the velocities (the step's last, half a step behind): the
    /// forces of `u + β·v`.
    pub fn forces(&self, f: &mut GridField) {
        let (ny, nz, c, beta) = (self.ny, self.nz, self.stencil.link_n_per_m, self.damping_s);
        let w = nz + 1;
        let GridField { corner_u, corner_v, centre_u, centre_v, corner_f, centre_f } = f;
        let (cu, cv, mu, mv) = (&*corner_u, &*corner_v, &*centre_u, &*centre_v);
        // The displacement a link sees: `u + β·v` (β = 0: `u` itself, the same numbers).
        let eff = |u: &[f64], v: &[f64], out: &mut Vec<f64>| {
            out.clear();
            if beta == 0.0 {
                out.extend_from_slice(u);
            } else {
                out.extend(u.iter().zip(v).map(|(u, v)| u + beta * v));
            }
        };
        corner_f.par_chunks_mut(w).enumerate().with_min_len(8).for_each_init(
            || (Vec::new(), Vec::new(), Vec::new()),
            |(own, up, down), (j, row)| {
                eff(&cu[j * w..(j + 1) * w], &cv[j * w..(j + 1) * w], own);
                // The centre rows above and below corner row j (one of them on the block's faces).
                let above = (j > 0).then(|| {
                    eff(&mu[(j - 1) * nz..j * nz], &mv[(j - 1) * nz..j * nz], up);
                    &up[..]
                });
                let below = (j < ny).then(|| {
                    eff(&mu[j * nz..(j + 1) * nz], &mv[j * nz..(j + 1) * nz], down);
                    &down[..]
                });
                let u = &own[..];
                match (above, below) {
                    (Some(a), Some(b)) => {
                        for k in 1..nz {
                            row[k] = c * ((a[k - 1] + a[k]) + (b[k - 1] + b[k]) - 4.0 * u[k]);
                        }
                        row[0] = c * (a[0] + b[0] - 2.0 * u[0]);
                        row[nz] = c * (a[nz - 1] + b[nz - 1] - 2.0 * u[nz]);
                    }
                    (Some(r), None) | (None, Some(r)) => {
                        for k in 1..nz {
                            row[k] = c * (r[k - 1] + r[k] - 2.0 * u[k]);
                        }
                        row[0] = c * (r[0] - u[0]);
                        row[nz] = c * (r[nz - 1] - u[nz]);
                    }
                    (None, None) => row.fill(0.0),
                }
            },
        );
        centre_f.par_chunks_mut(nz).enumerate().with_min_len(8).for_each_init(
            || (Vec::new(), Vec::new(), Vec::new()),
            |(own, top, below), (j, row)| {
                eff(&cu[j * w..(j + 1) * w], &cv[j * w..(j + 1) * w], top);
                eff(&cu[(j + 1) * w..(j + 2) * w], &cv[(j + 1) * w..(j + 2) * w], below);
                eff(&mu[j * nz..(j + 1) * nz], &mv[j * nz..(j + 1) * nz], own);
                let u = &own[..];
                for k in 0..nz {
                    row[k] = c * ((top[k] + top[k + 1]) + (below[k] + below[k + 1]) - 4.0 * u[k]);
                }
            },
        );
    }

    /// The velocity update `v⁺ = a·v⁻ + b·F` of corner `(j, k)` with its dashpot taken
    /// implicitly: `m·(v⁺ − v⁻)/Δt = F − d·(v⁺ + v⁻)/2`.
    fn corner_update(&self, j: usize, k: usize, dt: f64) -> (f64, f64) {
        let m = self.corner_mass(j, k) / dt;
        let d = 0.5 * self.dashpot(j, k);
        ((m - d) / (m + d), 1.0 / (m + d))
    }

    /// One central-difference step of `dt` from the forces of [`AntiplaneGrid::forces`]: every
    /// velocity but the face's (z = 0, which the caller sets), then every displacement.
    pub fn advance(&self, f: &mut GridField, dt: f64) {
        let (nz, w) = (self.nz, self.nz + 1);
        let GridField { corner_u, corner_v, centre_u, centre_v, corner_f, centre_f } = f;
        corner_v.par_chunks_mut(w).zip(corner_u.par_chunks_mut(w)).zip(corner_f.par_chunks(w)).enumerate().for_each(
            |(j, ((v, u), force))| {
                // Along a row only its last corner (the far face) differs from the rest.
                let (a, b) = self.corner_update(j, 1, dt);
                for k in 1..nz {
                    v[k] = a * v[k] + b * force[k];
                }
                let (a, b) = self.corner_update(j, nz, dt);
                v[nz] = a * v[nz] + b * force[nz];
                for k in 0..w {
                    u[k] += dt * v[k];
                }
            },
        );
        let step = dt / self.centre_mass();
        centre_v.par_chunks_mut(nz).zip(centre_u.par_chunks_mut(nz)).zip(centre_f.par_chunks(nz)).for_each(
            |((v, u), force)| {
                for k in 0..nz {
                    v[k] += step * force[k];
                    u[k] += dt * v[k];
                }
            },
        );
    }

    /// The field's kinetic and elastic energy (J).
    pub fn energy(&self, f: &GridField) -> f64 {
        let (ny, nz, c) = (self.ny, self.nz, self.stencil.link_n_per_m);
        let w = nz + 1;
        let mut e = 0.0;
        for j in 0..=ny {
            for k in 0..=nz {
                e += 0.5 * self.corner_mass(j, k) * f.corner_v[j * w + k].powi(2);
            }
        }
        for j in 0..ny {
            for k in 0..nz {
                let um = f.centre_u[j * nz + k];
                e += 0.5 * self.centre_mass() * f.centre_v[j * nz + k].powi(2);
                for (a, b) in [(j, k), (j, k + 1), (j + 1, k), (j + 1, k + 1)] {
                    e += 0.5 * c * (f.corner_u[a * w + b] - um).powi(2);
                }
            }
        }
        e
    }
}

/// A fault node in the explicit phase.
#[derive(Clone, Copy, Debug)]
struct FaceNode {
    theta: f64,
    /// Slip rate (m/s), signed.
    v: f64,
    /// Friction traction (Pa), signed.
    tau: f64,
}

/// The step of a fault node: the slip rate and state from the grid's force `force` on it, its
/// velocity `v_old`, the static traction `tau_s`, normal stress `sigma`, mass `m` and area `a`.
fn face_step(
    node: &RateStateNode,
    s: FaceNode,
    force: f64,
    v_old: f64,
    (tau_s, sigma, m, a): (f64, f64, f64, f64),
    dt: f64,
) -> FaceNode {
    let need = tau_s + force / a + m * v_old / (dt * a);
    let z = m / (2.0 * dt * a);
    let solve = |theta: f64| balance(node, theta, need.abs(), sigma, z).copysign(need);
    let old = s.v.abs();
    let v1 = solve(evolve(node, s.theta, old, dt));
    let theta = evolve(node, s.theta, 0.5 * (old + v1.abs()), dt);
    let v = solve(theta);
    // The balance's own friction, `need − Z·V` (`need` itself when V underflows to 0).
    let tau = need - z * v;
    FaceNode { theta, v, tau }
}

/// A fault under rate-and-state friction loaded by the plate, fully dynamic: quasi-dynamic
/// between events, the lattice's explicit antiplane grid inside them.
#[derive(Clone, Debug)]
pub struct FullyDynamicFault {
    /// The fault and its quasi-static stiffness (the phases between events).
    pub quasi: QuasiDynamicFault,
    /// The explicit grid of the events.
    pub grid: AntiplaneGrid,
    /// The explicit grid takes over when the largest slip rate exceeds this (m/s).
    pub dynamic_above_m_s: f64,
    /// The quasi-dynamic integration resumes when the largest slip rate falls below this (m/s).
    pub static_below_m_s: f64,
    /// The explicit step (s).
    pub step_s: f64,
}

impl FullyDynamicFault {
    /// Integrates from `state` to `until_s` as [`QuasiDynamicFault::run`] does, switching to the
    /// explicit grid inside events; `observe` sees every accepted step of both.
    pub fn run(
        &self,
        mut state: CycleState,
        until_s: f64,
        tol: &Tolerances,
        max_steps: u64,
        mut observe: impl FnMut(&CycleState) -> Flow,
    ) -> Result<(CycleState, CycleStats), SolverError> {
        let mut stats = CycleStats { min_step_s: f64::INFINITY, ..CycleStats::default() };
        let vmax = |s: &CycleState| s.slip_rate_m_s.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        let mut first = true;
        loop {
            let (t_start, mut stopped) = (state.t_s, false);
            let clock = Instant::now();
            let budget = max_steps.saturating_sub(stats.accepted + stats.rejected + stats.dynamic_steps).max(1);
            let (next, phase) = self.quasi.run(state, until_s, tol, budget, |s| {
                // The first look of a phase (the state the last one handed over) never switches.
                let handed_over = s.t_s == t_start && !first;
                if observe(s) == Flow::Stop {
                    stopped = true;
                    return Flow::Stop;
                }
                if !handed_over && vmax(s) > self.dynamic_above_m_s { Flow::Stop } else { Flow::Continue }
            })?;
            first = false;
            stats.quasi_wall_s += clock.elapsed().as_secs_f64();
            stats.accepted += phase.accepted;
            stats.rejected += phase.rejected;
            if phase.accepted > 0 {
                stats.min_step_s = stats.min_step_s.min(phase.min_step_s);
                stats.max_step_s = stats.max_step_s.max(phase.max_step_s);
            }
            state = next;
            if stopped || state.t_s >= until_s {
                return Ok((state, stats));
            }
            let clock = Instant::now();
            let (next, flow) = self.event(state, until_s, max_steps, &mut stats, &mut observe)?;
            stats.dynamic_wall_s += clock.elapsed().as_secs_f64();
            stats.handover_jump_pa = stats.handover_jump_pa.max(self.handover_jump(&next));
            state = next;
            if flow == Flow::Stop || state.t_s >= until_s {
                return Ok((state, stats));
            }
        }
    }

    /// The largest difference between the friction of `state` (an explicit phase's end) and
    /// the full block's static traction for its slip, `τ0 − K·(δ − V_p·t) − η·V` (Pa).
    fn handover_jump(&self, state: &CycleState) -> f64 {
        let q = &self.quasi;
        let behind: Vec<f64> = state.slip_m.iter().map(|d| d - q.plate_m_s * state.t_s).collect();
        (0..q.nodes())
            .map(|j| {
                let static_pa = q.shear0_pa[j] + q.stiffness.traction_change_at(j, &behind);
                (static_pa - q.eta_pa_s_m * state.slip_rate_m_s[j] - state.shear_pa[j]).abs()
            })
            .fold(0.0, f64::max)
    }

    /// One explicit phase from `state` until the largest slip rate falls below
    /// [`FullyDynamicFault::static_below_m_s`] (or `until_s`, or the observer stops it).
    fn event(
        &self,
        mut state: CycleState,
        until_s: f64,
        max_steps: u64,
        stats: &mut CycleStats,
        observe: &mut impl FnMut(&CycleState) -> Flow,
    ) -> Result<(CycleState, Flow), SolverError> {
        let q = &self.quasi;
        let (g, dt, n) = (&self.grid, self.step_s, q.nodes());
        let eta = q.eta_pa_s_m;
        // The static traction at the switch: the friction plus the radiation damping it carried.
        let tau_s: Vec<f64> = (0..n).map(|j| state.shear_pa[j] + eta * state.slip_rate_m_s[j]).collect();
        let slip0 = state.slip_m.clone();
        let props: Vec<(f64, f64, f64, f64)> =
            (0..n).map(|j| (tau_s[j], q.normal_pa[j], g.corner_mass(j, 0), g.face_area_m2(j))).collect();
        let mut nodes: Vec<FaceNode> = (0..n)
            .map(|j| FaceNode { theta: state.log_state[j].exp(), v: state.slip_rate_m_s[j], tau: state.shear_pa[j] })
            .collect();
        let mut field = g.at_rest();
        let w = g.nz + 1;
        for (j, node) in nodes.iter().enumerate() {
            field.corner_v[j * w] = 0.5 * node.v;
        }
        stats.dynamic_phases += 1;
        let t0 = state.t_s;
        let mut step = 0u64;
        loop {
            if stats.accepted + stats.rejected + stats.dynamic_steps >= max_steps {
                return Err(SolverError::Numerical(format!(
                    "the cycle run reached {max_steps} steps at t = {:.6e} s ({:.3} years), inside an event",
                    state.t_s,
                    state.t_s / YEAR_S
                )));
            }
            g.forces(&mut field);
            let (cf, cv) = (&field.corner_f, &field.corner_v);
            nodes.par_iter_mut().enumerate().with_min_len(64).for_each(|(j, s)| {
                *s = face_step(&q.friction[j], *s, cf[j * w], cv[j * w], props[j], dt);
            });
            for (j, s) in nodes.iter().enumerate() {
                field.corner_v[j * w] = 0.5 * s.v;
            }
            // Below the frictional part the face creeps with the plate: held over the event.
            for j in n..=g.ny {
                field.corner_v[j * w] = 0.0;
            }
            g.advance(&mut field, dt);
            step += 1;
            stats.dynamic_steps += 1;
            let t = t0 + step as f64 * dt;
            if !nodes.iter().all(|s| s.v.is_finite() && s.theta.is_finite()) {
                return Err(SolverError::Numerical(format!(
                    "the explicit phase of the cycle run became non-finite at t = {t:.6e} s ({:.3} years)",
                    t / YEAR_S
                )));
            }
            state.t_s = t;
            for (j, s) in nodes.iter().enumerate() {
                state.slip_m[j] = slip0[j] + 2.0 * field.corner_u[j * w];
                state.slip_rate_m_s[j] = s.v;
                state.log_state[j] = s.theta.ln();
                state.shear_pa[j] = s.tau;
            }
            stats.dynamic_time_s += dt;
            if observe(&state) == Flow::Stop {
                return Ok((state, Flow::Stop));
            }
            let vmax = nodes.iter().fold(0.0f64, |a, s| a.max(s.v.abs()));
            if vmax < self.static_below_m_s || t >= until_s {
                return Ok((state, Flow::Continue));
            }
        }
    }
}
