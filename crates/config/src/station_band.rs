//! A fault scene's surface stations as the pipeline checks them: their usable band (docs/model.md
//! §16.2, §17), the refusal of an empty one and the warning for one that holds no ground-motion
//! model's period, and the site a `[set]` of broadband records chooses from.

use crate::check::{Checker, approx, num};

/// The usable periods `(shortest, longest)` (s) of a fault scene's surface stations (docs/model.md
/// §16.2): from `1/f_max` (the lattice's, at most 80% of the record interval's Nyquist), or 0.01 s
/// for broadband records (§17), to `T/(2·1.25)`, `T` the shear stage; `None` for a scene without a
/// fault or surface stations.
pub(crate) fn station_band(scene: &stickslip_solver::Scene, broadband: bool) -> Option<(f64, f64)> {
    use stickslip_analysis::motions::{DEPARTURE, LOW_CORNER_CYCLES};
    let lattice = scene.lattice();
    let surface = scene.stations.iter().any(|s| lattice.position(s.node)[1] == 0.0);
    if !scene.is_fault() || !surface {
        return None;
    }
    let band = scene.usable_band(DEPARTURE).ok()?;
    let nyquist = scene.record.interval_s.map_or(f64::INFINITY, |iv| 0.8 * 0.5 / iv);
    let shortest =
        if broadband { stickslip_analysis::broadband::SHORTEST_PERIOD_S } else { 1.0 / band.f_max_hz.min(nyquist) };
    Some((shortest, scene.shear.duration_s / (LOW_CORNER_CYCLES * 1.25)))
}

/// Refuses a `[set] vs30_m_s` that names no site of the broadband records, and its absence when
/// they stand on several sites.
pub(crate) fn check_set_site(
    ck: &mut Checker,
    vs30: Option<f64>,
    broadband: Option<&stickslip_analysis::broadband::BroadbandSettings>,
) {
    let mut sites: Vec<f64> = broadband.map_or_else(Vec::new, |b| b.sites.iter().map(|s| s.vs30_m_s).collect());
    sites.sort_by(f64::total_cmp);
    sites.dedup();
    let listed = sites.iter().map(|v| num(*v)).collect::<Vec<_>>().join(", ");
    match vs30 {
        Some(v) if broadband.is_none() => ck.push(
            "set.vs30_m_s",
            v,
            "absent: the records of a set stand on a site only when they are broadband records ([broadband] on a fault              scene with surface [[stations]])",
        ),
        Some(v) if !sites.contains(&v) => {
            ck.push("set.vs30_m_s", v, format!("one of the sites the stations are simulated on: {listed} m/s"))
        }
        None if sites.len() > 1 => ck.push(
            "set.vs30_m_s",
            "(absent)",
            format!("the site of the records to choose: the stations stand on {listed} m/s ([broadband] vs30_m_s)"),
        ),
        _ => {}
    }
}

/// Refuses a fault scene whose surface stations' usable band is empty (its shortest period at or
/// above its longest: a soft material or coarse modules put the lattice's f_max below the run's
/// low corner, and the run failed at its first step), naming the field that limits it; warns when
/// the band holds none of the ground-motion models' periods ([`station_band`]).
pub(crate) fn warn_gmm_band(scene: &stickslip_solver::Scene, ck: &mut Checker) {
    use stickslip_analysis::motions::GMM_PERIODS_S;
    let Some((shortest, longest)) = station_band(scene, false) else { return };
    if shortest >= longest {
        let nyquist = scene.record.interval_s.map(|iv| 0.8 * 0.5 / iv);
        let by_sampling = nyquist.is_some_and(|n| 1.0 / n >= shortest * (1.0 - 1e-12));
        let why = format!(
            "the surface stations' usable band is empty: its shortest period, {} s, is not below its longest, {} s \
             (shear.duration_s / 2.5)",
            approx(shortest),
            approx(longest)
        );
        if by_sampling {
            let iv = scene.record.interval_s.unwrap_or(f64::NAN);
            ck.push(
                "record.interval_s",
                iv,
                format!(
                    "{why}, set by the sampling (0.8 of its Nyquist): record.interval_s < {} s, or a longer \
                     shear.duration_s",
                    approx(iv * shortest / longest)
                ),
            );
        } else {
            // f_max grows as √E: the Young's modulus that would put 1/f_max at the longest period.
            ck.push(
                "material.young_pa",
                scene.young_pa,
                format!(
                    "{why}, set by the lattice's f_max = {} Hz (waves of this E, ρ and Lc): material.young_pa > {} Pa \
                     for this block, or smaller modules (block.lc_m), or a longer shear.duration_s",
                    approx(1.0 / shortest),
                    approx(scene.young_pa * (shortest / longest).powi(2))
                ),
            );
        }
        return;
    }
    if !GMM_PERIODS_S.iter().any(|&t| t >= shortest && t <= longest) {
        ck.warn(
            "shear.duration_s",
            scene.shear.duration_s,
            format!(
                "the surface stations' PSA is usable from {} s to {} s, which holds none of the ground-motion \
                 models' periods (0.01–10 s): `stickslip gmm` can compare only PGA and PGV (a longer run or a \
                 finer lattice widens the band)",
                approx(shortest),
                approx(longest)
            ),
        );
    }
}
