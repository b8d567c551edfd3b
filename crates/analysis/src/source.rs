//! The source of a fault scene's run (docs/model.md §15): moment, magnitude, stress drop, slip and
//! slip rates from the fault's own nodes, and every station's distances to the rupture and peak
//! motions.
//!
//! On a fault the slip of each node is known (twice the face's displacement), so the moment is
//! the physical one, `M0 = Σ μ_i·A_i·|D_i|` over the ruptured nodes (those whose slip rate reached
//! `[events] rupture_rate_m_s`), `μ_i` the lattice's shear modulus `C44` at node i's depth (one
//! value in a homogeneous medium, its layer's in a layered one, docs/model.md §18), and
//! `Mw = (2/3)·(log10 M0 − 9.1)` (Hanks & Kanamori 1979, M0 in N·m). The stress drop is the
//! area-weighted mean over the ruptured nodes of the initial minus the final shear traction along the mean slip direction;
//! the Brune (1970) corner frequency of that moment and drop is `f0 = 0.4906·β·(Δσ/M0)^(1/3)`.
//!
//! The block lies on its side (docs/model.md §15): x along strike, y down dip (y = 0 the Earth's
//! surface), z away from the fault. A station at `(x, y, z)` is at depth `y`, at horizontal
//! position `(x, z)`; the rupture's distances are measured to the ruptured nodes `(x_i, y_i, 0)`:
//! R_rup to the nearest, R_JB to the nearest point of their surface projection (the trace segment
//! `z = 0` between the ruptured x's), R_x = z (perpendicular to the trace), epicentral and
//! hypocentral to the hypocentre (the centroid of the first nodes to rupture).

use stickslip_seismo::broadband::HybridRecord;
use stickslip_solver::material::lattice_elastic_constants;
use stickslip_solver::scene::{Component, ControlChannel, Kinematic, Station};
use stickslip_solver::{Model, Recording};

use crate::motions::Motion;

/// The source of one run on a fault.
#[derive(Clone, Debug, PartialEq)]
pub struct Source {
    /// Contact nodes that ruptured (slip rate reached the threshold).
    pub ruptured_nodes: usize,
    /// Their fault area (m²), the mirror image's included ([`stickslip_solver::Scene::fault_copies`]).
    pub area_m2: f64,
    /// Seismic moment `μ·Σ A_i·|D_i|` (N·m), the mirror image's included.
    pub m0_n_m: f64,
    /// Moment magnitude `(2/3)(log10 M0 − 9.1)`.
    pub mw: f64,
    /// Area-weighted mean slip over the ruptured nodes (m).
    pub mean_slip_m: f64,
    /// Largest slip (m).
    pub max_slip_m: f64,
    /// Area-weighted mean stress drop over the ruptured nodes (Pa).
    pub stress_drop_pa: f64,
    /// Largest peak slip rate (m/s).
    pub peak_slip_rate_m_s: f64,
    /// Median over the ruptured nodes of their peak slip rate (m/s).
    pub median_peak_slip_rate_m_s: f64,
    /// Hypocentre: the centroid of the first nodes to rupture (those of the earliest rupture
    /// time), `(x, y)` on the fault (m).
    pub hypocentre_m: [f64; 2],
    /// Time the last ruptured node ruptured (s of the shear stage).
    pub rupture_duration_s: f64,
    /// Extent of the ruptured nodes along x and y (m).
    pub extent_m: [[f64; 2]; 2],
    /// The lattice's shear modulus `C44` (Pa).
    pub shear_modulus_pa: f64,
    /// The lattice's S-wave speed `√(C44/ρ)` (m/s).
    pub s_speed_m_s: f64,
    /// Brune's corner frequency `0.4906·β·(Δσ/M0)^(1/3)` (Hz).
    pub brune_corner_hz: f64,
    /// The corner fitted to the surface stations' displacement spectra
    /// ([`crate::motions::fitted_corner`]), when there are enough of them.
    pub fitted_corner_hz: Option<f64>,
    /// The stochastic part of the broadband records, when the pipeline asks for them.
    pub stochastic: Option<StochasticSource>,
}

/// Brune's (1970) corner frequency `0.4906·β·(Δσ/M0)^(1/3)` (Hz; β in m/s, Δσ in Pa, M0 in N·m).
pub fn brune_corner_hz(s_speed_m_s: f64, stress_drop_pa: f64, m0_n_m: f64) -> f64 {
    0.4906 * s_speed_m_s * (stress_drop_pa / m0_n_m).cbrt()
}

/// Moment magnitude `(2/3)(log10 M0 − 9.1)` of `m0_n_m` (Hanks & Kanamori 1979).
pub fn moment_magnitude(m0_n_m: f64) -> f64 {
    2.0 / 3.0 * (m0_n_m.log10() - 9.1)
}

/// The source of a run on a fault (`None` on the rigid base, or when nothing ruptured).
pub fn source(rec: &Recording, model: &Model) -> Option<Source> {
    let f = rec.trace.summary.as_ref()?;
    let scene = model.scene();
    let (_, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
    let s_speed = (c44 / scene.density_kg_m3).sqrt();
    let lattice = model.lattice();
    let ruptured: Vec<usize> = (0..f.nodes.len()).filter(|&i| f.rupture_time_s[i].is_finite()).collect();
    if ruptured.is_empty() {
        return None;
    }
    let slip = |i: usize| f.final_slip_m[i][0].hypot(f.final_slip_m[i][1]);
    let area: f64 = ruptured.iter().map(|&i| f.area_m2[i]).sum();
    let potency: f64 = ruptured.iter().map(|&i| f.area_m2[i] * slip(i)).sum();
    // The moment with each node's own rigidity (a layered medium's varies with depth; the
    // homogeneous one keeps c44 · potency), and the potency-weighted S speed.
    let layered = scene.medium.profile.is_some();
    let (m0, vs_sum) = if layered {
        let zones = scene.zones();
        ruptured.iter().fold((0.0, 0.0), |(m, v), &i| {
            let w = f.area_m2[i] * slip(i);
            let zone = &zones[scene.medium.zone_at(scene.depth_of(lattice.position(f.nodes[i])))];
            (m + c44 * zone.young * w, v + zone.vs_m_s * w)
        })
    } else {
        (c44 * potency, s_speed * potency)
    };
    let (c44, s_speed) = if layered && potency > 0.0 { (m0 / potency, vs_sum / potency) } else { (c44, s_speed) };
    // A block that is one half of a fault mirrored across a face (its base nodes there held in
    // y) stands for the whole: the mirror image ruptures alike, so area and moment double; means
    // are the half's.
    let copies = scene.fault_copies();
    let (area_whole, m0) = (copies * area, copies * m0);
    // The mean slip direction, along which the drop is measured.
    let (sx, sy) = ruptured.iter().fold((0.0, 0.0), |(a, b), &i| {
        (a + f.area_m2[i] * f.final_slip_m[i][0], b + f.area_m2[i] * f.final_slip_m[i][1])
    });
    let norm = sx.hypot(sy);
    let (ux, uy) = if norm > 0.0 { (sx / norm, sy / norm) } else { (1.0, 0.0) };
    let drop: f64 = ruptured
        .iter()
        .map(|&i| {
            let [start, end] = f.shear_stress_pa[i];
            f.area_m2[i] * ((start[0] - end[0]) * ux + (start[1] - end[1]) * uy)
        })
        .sum::<f64>()
        / area;
    let mut peaks: Vec<f64> = ruptured.iter().map(|&i| f.peak_slip_rate_m_s[i]).collect();
    peaks.sort_by(f64::total_cmp);
    // The hypocentre: where the first nodes to rupture are. A nucleation patch starts all its
    // nodes on the same step, so the earliest are a tie; their centroid, not the first of them in
    // node order (a corner of the patch).
    let position = |i: usize| lattice.position(f.nodes[i]);
    let t_first = ruptured.iter().map(|&i| f.rupture_time_s[i]).fold(f64::INFINITY, f64::min);
    let first: Vec<usize> = ruptured.iter().copied().filter(|&i| f.rupture_time_s[i] == t_first).collect();
    let h = first.iter().fold([0.0; 2], |[x, y], &i| {
        let p = position(i);
        [x + p[0] / first.len() as f64, y + p[1] / first.len() as f64]
    });
    let range = |axis: usize| {
        ruptured
            .iter()
            .map(|&i| position(i)[axis])
            .fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], v| [lo.min(v), hi.max(v)])
    };
    Some(Source {
        ruptured_nodes: ruptured.len(),
        area_m2: area_whole,
        m0_n_m: m0,
        mw: moment_magnitude(m0),
        mean_slip_m: potency / area,
        max_slip_m: ruptured.iter().map(|&i| slip(i)).fold(0.0, f64::max),
        stress_drop_pa: drop,
        peak_slip_rate_m_s: *peaks.last().expect("some"),
        median_peak_slip_rate_m_s: peaks[peaks.len() / 2],
        hypocentre_m: [h[0], h[1]],
        rupture_duration_s: ruptured.iter().map(|&i| f.rupture_time_s[i]).fold(0.0, f64::max),
        extent_m: [range(0), range(1)],
        shear_modulus_pa: c44,
        s_speed_m_s: s_speed,
        brune_corner_hz: brune_corner_hz(s_speed, drop, m0),
        fitted_corner_hz: None,
        stochastic: None,
    })
}

/// The stochastic part of a seed's rupture, as a summary.
#[derive(Clone, Debug, PartialEq)]
pub struct StochasticSource {
    /// Stress parameter after its area scaling (Pa).
    pub stress_parameter_pa: f64,
    /// Subfaults with a moment, and N, the cells of the rupture's rectangle.
    pub subfaults: usize,
    /// N.
    pub cells: usize,
    /// Subfault size (m).
    pub subfault_m: f64,
    /// Frankel's C.
    pub frankel: f64,
    /// CPU seconds of the stochastic synthesis and the joins (the subfaults included).
    pub synthesis_cpu_s: f64,
    /// CPU seconds of the broadband records' processing and measures (RotD, intensity).
    pub motions_cpu_s: f64,
}

/// A station's broadband record and its motion.
#[derive(Clone, Debug, PartialEq)]
pub struct StationBroadband {
    /// The site's V_S30 (m/s).
    pub vs30_m_s: f64,
    /// The record (x, y, z; each part and their sum).
    pub record: HybridRecord,
    /// The motion of the joined horizontal pair, or why it has none.
    pub motion: Result<Motion, String>,
}

/// One station of a fault scene: where it is against the rupture and its peak motions.
#[derive(Clone, Debug, PartialEq)]
pub struct StationRow {
    /// The station.
    pub station: Station,
    /// Its position `(x, y, z)` (m): along strike, depth, distance from the fault.
    pub position_m: [f64; 3],
    /// Epicentral distance: horizontal, to the hypocentre's surface point (m).
    pub epicentral_m: f64,
    /// Hypocentral distance (m).
    pub hypocentral_m: f64,
    /// Rupture distance R_rup: to the nearest ruptured node (m).
    pub r_rup_m: f64,
    /// Joyner–Boore distance R_JB: horizontal, to the rupture's surface projection (m).
    pub r_jb_m: f64,
    /// R_x: horizontal distance perpendicular to the trace (m).
    pub r_x_m: f64,
    /// Ry0: horizontal distance along strike beyond the rupture's ends (0 alongside it) (m).
    pub r_y0_m: f64,
    /// Azimuth from the epicentre, from the strike direction (+x) toward the station side (+z),
    /// degrees in [0, 180].
    pub azimuth_deg: f64,
    /// Peak horizontal acceleration, `max |(a_x, a_z)|` (m/s²).
    pub pga_m_s2: f64,
    /// Peak horizontal velocity (m/s).
    pub pgv_m_s: f64,
    /// Peak horizontal displacement (m).
    pub pgd_m: f64,
    /// Peak vertical acceleration `max |a_y|` (m/s²).
    pub pga_vertical_m_s2: f64,
    /// Its processed horizontal motion as RotD50/RotD100 ([`crate::motions`]), or why it has none:
    /// the lattice's record.
    pub motion: Result<Motion, String>,
    /// Its broadband record at its site ([`crate::broadband`]), when the pipeline asks for them.
    pub broadband: Option<StationBroadband>,
    /// The V_S30 of the layered medium's profile when the station stands on its surface (m/s).
    pub site_vs30_m_s: Option<f64>,
}

impl StationRow {
    /// The motion engineers get from this station: the broadband record's when there is one, else
    /// the lattice's.
    pub fn record_motion(&self) -> &Result<Motion, String> {
        self.broadband.as_ref().map_or(&self.motion, |b| &b.motion)
    }
}

/// The stations of a fault scene against the rupture of `src` (the fault summary's ruptured
/// nodes), with their peak motions over the shear stage and their processed RotD motions.
pub fn stations(rec: &Recording, model: &Model, src: &Source) -> Vec<StationRow> {
    let resolved_hz = model.scene().usable_band(crate::motions::DEPARTURE).map_or(f64::INFINITY, |b| b.f_max_hz);
    let Some(f) = rec.trace.summary.as_ref() else { return Vec::new() };
    let lattice = model.lattice();
    let ruptured: Vec<[f64; 3]> =
        (0..f.nodes.len()).filter(|&i| f.rupture_time_s[i].is_finite()).map(|i| lattice.position(f.nodes[i])).collect();
    let [x_lo, x_hi] = src.extent_m[0];
    let h = src.hypocentre_m;
    let shear = rec.sampling.shear_start;
    model
        .scene()
        .stations
        .iter()
        .map(|st| {
            let p = lattice.position(st.node);
            let r_rup = ruptured
                .iter()
                .map(|q| ((p[0] - q[0]).powi(2) + (p[1] - q[1]).powi(2) + p[2] * p[2]).sqrt())
                .fold(f64::INFINITY, f64::min);
            let along = if p[0] < x_lo {
                x_lo - p[0]
            } else if p[0] > x_hi {
                p[0] - x_hi
            } else {
                0.0
            };
            let series = |quantity: Kinematic, component: Component| -> &[f64] {
                rec.control(ControlChannel { node: st.node, quantity, component })
                    .map_or(&[][..], |v| &v[shear.min(v.len())..])
            };
            let horizontal = |q: Kinematic| -> f64 {
                let (x, z) = (series(q, Component::X), series(q, Component::Z));
                x.iter().zip(z).map(|(a, b)| a.hypot(*b)).fold(0.0, f64::max)
            };
            let dx = p[0] - h[0];
            StationRow {
                station: st.clone(),
                position_m: p,
                epicentral_m: dx.hypot(p[2]),
                hypocentral_m: (dx * dx + (p[1] - h[1]).powi(2) + p[2] * p[2]).sqrt(),
                r_rup_m: r_rup,
                r_jb_m: along.hypot(p[2]),
                r_x_m: p[2],
                r_y0_m: along,
                azimuth_deg: p[2].atan2(dx).to_degrees(),
                pga_m_s2: horizontal(Kinematic::Acceleration),
                pgv_m_s: horizontal(Kinematic::Velocity),
                pgd_m: horizontal(Kinematic::Displacement),
                pga_vertical_m_s2: series(Kinematic::Acceleration, Component::Y)
                    .iter()
                    .fold(0.0, |m, v| m.max(v.abs())),
                motion: crate::motions::motion(rec, st.node, resolved_hz),
                broadband: None,
                site_vs30_m_s: model.scene().site_vs30_m_s().filter(|_| model.scene().depth_of(p) == 0.0),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brune_corner_of_an_m6_at_10_mpa() {
        // Brune (1970) in its usual units: f0 = 4.906e6·β[km/s]·(Δσ[bar]/M0[dyne·cm])^(1/3).
        // Mw 6 (Hanks–Kanamori, 9.1): M0 = 10^18.1 N·m = 10^25.1 dyne·cm; 10 MPa = 100 bar.
        // 4.906e6 · 3.5 · 10^((2 − 25.1)/3) = 0.3426 Hz (0.356 Hz with the 9.05 constant).
        let m0 = 10f64.powf(1.5 * 6.0 + 9.1);
        let f0 = brune_corner_hz(3500.0, 10e6, m0);
        let cgs = 4.906e6 * 3.5 * 10f64.powf((2.0 - 25.1) / 3.0);
        assert!((f0 - cgs).abs() < 1e-4 * cgs, "{f0} against {cgs}");
        assert!((f0 - 0.3426).abs() < 5e-4, "{f0}");
        assert!((moment_magnitude(m0) - 6.0).abs() < 1e-12);
    }
}
