//! Broadband records of a fault scene's surface stations (docs/model.md §17): the lattice's
//! motion below the crossover joined to a stochastic finite-fault synthesis of the same rupture
//! above it (`stickslip_seismo::broadband`, the Broadband Platform's Graves–Pitarka method), each
//! part taken from its reference site to the station's V_S30, and the station's motion measured on
//! the joined record: PGA, PGV, Arias, D5–95, CAV and RotD50/RotD100 PSA from 0.01 s to the
//! lattice record's long-period limit.
//!
//! - Subfaults: the ruptured fault nodes (final slip, rupture time) resampled into cells of about
//!   `subfault_m`; the rupture's moment magnitude is the source's.
//! - The stochastic part of a station is drawn once (its random streams are named by the station
//!   and the seed) and taken to each of the station's sites: a station simulated on several V_S30
//!   gives one record per site, with the same waves.
//! - Buried stations keep their lattice motion only (the stochastic part is a surface motion: its
//!   spectrum carries the free surface's factor 2).

use stickslip_seismo::broadband::fault::{FaultNode, FiniteFault};
use stickslip_seismo::broadband::stochastic::{Medium, Synthesis, station_key};
use stickslip_seismo::broadband::{Crossover, HybridSite, Stochastic, hybrid};
use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
use stickslip_solver::{Model, Recording};

use crate::motions::motion_of_pair;
use crate::source::{Source, StationBroadband, StationRow, StochasticSource};

/// The shortest period of a broadband record's PSA (s).
pub const SHORTEST_PERIOD_S: f64 = 0.01;

/// One record a station gives: the station, the record's name and its site.
#[derive(Clone, Debug, PartialEq)]
pub struct SiteSpec {
    /// The scene's station.
    pub station: String,
    /// The record's name (the station's own when it has one site).
    pub record: String,
    /// Its V_S30 (m/s).
    pub vs30_m_s: f64,
}

/// What the broadband records are made with.
#[derive(Clone, Debug, PartialEq)]
pub struct BroadbandSettings {
    /// The stochastic part.
    pub stochastic: Stochastic,
    /// The join.
    pub crossover: Crossover,
    /// Every record made, in the order of the scene's stations.
    pub sites: Vec<SiteSpec>,
}

impl BroadbandSettings {
    /// What the broadband records will be, for `stickslip check`: one line each, for a lattice of
    /// S-wave speed `s_speed_m_s` and usable `f_max_hz`.
    pub fn describe(&self, s_speed_m_s: f64, f_max_hz: f64) -> Vec<String> {
        let p = &self.stochastic;
        let g = |v: f64| format!("{}", (v * 1e4).round() / 1e4);
        let mut sites: Vec<f64> = self.sites.iter().map(|s| s.vs30_m_s).collect();
        sites.sort_by(f64::total_cmp);
        sites.dedup();
        let stations = self.sites.iter().map(|s| s.station.as_str()).collect::<std::collections::BTreeSet<_>>().len();
        vec![
            format!(
                "broadband: {} records ({} surface stations × sites V_S30 {} m/s) every {} s, 0.01 s to the lattice \
                 record's long-period end; the lattice below f_m = {} Hz (its usable f_max {} Hz), a stochastic \
                 finite-fault synthesis of the same rupture above",
                self.sites.len(),
                stations,
                sites.iter().map(|v| g(*v)).collect::<Vec<_>>().join(", "),
                g(p.interval_s),
                g(self.crossover.hz),
                g(f_max_hz)
            ),
            format!(
                "    stochastic part (Graves–Pitarka): stress parameter {} MPa × (A0/A)^{}, κ0 {} s, Q(f) = {}·f^{}, \
                 subfaults {} m, corner {}·v_r/(π·dl) with v_r {}, radiation {} (horizontal) {} (vertical), window \
                 ε {} η {} at {} T_gm",
                g(p.stress_parameter_pa / 1e6),
                g(p.stress_area_exponent),
                g(p.kappa_s),
                g(p.q0_for(s_speed_m_s)),
                g(p.q_exponent),
                g(p.subfault_m),
                g(p.corner_constant),
                match p.corner_speed {
                    stickslip_seismo::broadband::CornerSpeed::Platform =>
                        "the Platform's (0.775 ± 0.1 β, slower above 5 km)",
                    stickslip_seismo::broadband::CornerSpeed::Lattice => "the lattice rupture's own",
                },
                g(p.radiation_horizontal),
                g(p.radiation_vertical),
                g(p.window.epsilon),
                g(p.window.eta),
                g(p.window.duration_factor)
            ),
            format!(
                "    sites: BSSA14 site terms from {} m/s (the lattice's rock) and {} m/s (the stochastic part's {} crust) \
                 to each station's V_S30",
                g(s_speed_m_s),
                g(p.crust.vs30_m_s()),
                p.crust.name().replace('_', " ")
            ),
        ]
    }
}

/// The lattice's three components of the station at `node` over the shear stage, the time of
/// their first sample and their interval.
fn lattice_components(rec: &Recording, node: stickslip_solver::geometry::NodeId) -> Option<([&[f64]; 3], f64, f64)> {
    let span = rec.uniform_shear()?;
    let t = &rec.time_s[span.clone()];
    if t.len() < 8 {
        return None;
    }
    let series = |component| {
        rec.control(ControlChannel { node, quantity: Kinematic::Acceleration, component }).map(|v| &v[span.clone()])
    };
    let dt = (t[t.len() - 1] - t[0]) / (t.len() - 1) as f64;
    Some(([series(Component::X)?, series(Component::Y)?, series(Component::Z)?], t[0], dt))
}

/// The broadband records of `rows` (the scene's stations against the rupture of `src`) for seed
/// `seed`: each surface station becomes one row per site of `settings` (named as the site says),
/// with its broadband record; buried stations stay as they are. `None` with the rows unchanged
/// when the fault has no ruptured node with slip.
pub fn records(
    rows: Vec<StationRow>,
    rec: &Recording,
    model: &Model,
    src: &Source,
    settings: &BroadbandSettings,
    seed: u64,
) -> (Vec<StationRow>, Option<StochasticSource>) {
    let started = crate::thread_cpu_s();
    let Some(f) = rec.trace.summary.as_ref() else { return (rows, None) };
    let lattice = model.lattice();
    let nodes: Vec<FaultNode> = (0..f.nodes.len())
        .map(|i| {
            let p = lattice.position(f.nodes[i]);
            FaultNode {
                x_m: p[0],
                depth_m: p[1],
                area_m2: f.area_m2[i],
                slip_m: f.final_slip_m[i][0].hypot(f.final_slip_m[i][1]),
                rupture_time_s: f.rupture_time_s[i],
            }
        })
        .collect();
    let p = &settings.stochastic;
    let fault = match FiniteFault::from_nodes(
        &nodes,
        model.scene().lc_m,
        p.subfault_m,
        src.shear_modulus_pa,
        src.s_speed_m_s,
    ) {
        Ok(Some(fault)) => fault,
        _ => return (rows, None),
    };
    let medium = Medium { s_speed_m_s: src.s_speed_m_s, density_kg_m3: model.scene().density_kg_m3 };
    let synthesis = Synthesis::new(&fault, src.mw, medium, p, seed);
    let mut out = Vec::with_capacity(rows.len());
    let mut synthesis_cpu_s = crate::thread_cpu_s() - started;
    let mut motions_cpu_s = 0.0;
    for row in rows {
        let specs: Vec<&SiteSpec> = settings.sites.iter().filter(|s| s.station == row.station.name).collect();
        let surface = row.position_m[1] == 0.0;
        let lattice_record = lattice_components(rec, row.station.node);
        let (Some((det, t0, det_dt)), true, false) = (lattice_record, surface, specs.is_empty()) else {
            out.push(row);
            continue;
        };
        let dt = p.interval_s;
        let duration = t0 + (det[0].len() - 1) as f64 * det_dt;
        let len = (duration / dt).floor() as usize + 1;
        let started = crate::thread_cpu_s();
        let stochastic = synthesis.record(row.position_m, len, seed, station_key(&row.station.name));
        synthesis_cpu_s += crate::thread_cpu_s() - started;
        for spec in specs {
            let site = HybridSite {
                vs30_m_s: spec.vs30_m_s,
                deterministic_vref_m_s: model.scene().site_vs30_m_s().unwrap_or(src.s_speed_m_s),
                stochastic_vref_m_s: p.crust.vs30_m_s(),
            };
            let started = crate::thread_cpu_s();
            let record = hybrid(det, det_dt, t0, &stochastic, dt, settings.crossover, site);
            let joined = crate::thread_cpu_s();
            synthesis_cpu_s += joined - started;
            let [x, _, z] = &record.components;
            let motion = motion_of_pair(&x.broadband, &z.broadband, dt, f64::INFINITY, Some(SHORTEST_PERIOD_S));
            motions_cpu_s += crate::thread_cpu_s() - joined;
            let mut r = row.clone();
            r.station.name = spec.record.clone();
            r.broadband = Some(StationBroadband { vs30_m_s: spec.vs30_m_s, record, motion });
            out.push(r);
        }
    }
    let summary = StochasticSource {
        stress_parameter_pa: synthesis.stress_parameter_pa(),
        subfaults: fault.subfaults.len(),
        cells: fault.cells,
        subfault_m: fault.size_m,
        frankel: synthesis.frankel(),
        synthesis_cpu_s,
        motions_cpu_s,
    };
    (out, Some(summary))
}
