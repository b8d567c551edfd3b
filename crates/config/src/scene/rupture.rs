//! `[rupture]` checked into the bilinear softening law of the bars that crack.

use stickslip_solver::geometry::Face;
use stickslip_solver::rupture::{Rupture, kr_from_failure_factor, max_failure_factor};

use super::{DEFAULT_KR, MaterialSection, RuptureSection};
use crate::check::Checker;

/// The bilinear law of `[rupture]`, every refused value recorded in `ck`.
pub(super) fn rupture(ck: &mut Checker, r: &RuptureSection, m: &MaterialSection, lc_m: f64) -> Rupture {
    ck.positive("rupture.fracture_energy_j_m2", r.fracture_energy_j_m2);
    let lattice_ok = m.poisson > 0.0 && m.poisson < 0.5 && lc_m > 0.0 && lc_m.is_finite();
    let kr = match (r.kr, r.failure_factor_per_sqrt_m) {
        (Some(_), Some(_)) => {
            ck.push(
                "rupture",
                "both kr and failure_factor_per_sqrt_m",
                "one of rupture.kr or rupture.failure_factor_per_sqrt_m (with a failure factor, Kr follows from the energy)",
            );
            DEFAULT_KR
        }
        (Some(kr), None) => {
            ck.range("rupture.kr", kr, 1.0, true, f64::INFINITY, true);
            kr
        }
        (None, Some(rf)) => {
            if ck.positive("rupture.failure_factor_per_sqrt_m", rf) && lattice_ok {
                let kr = kr_from_failure_factor(rf, m.poisson, lc_m);
                if !(kr > 1.0) {
                    ck.push(
                        "rupture.failure_factor_per_sqrt_m",
                        rf,
                        format!(
                            "0 < failure_factor_per_sqrt_m < {:.6} for this lattice (it gives Kr = 2(1 − ν²)/((2 + 4δ)·α·Lc·Rf²) \
                             = {kr:.4}; the softening branch needs Kr > 1)",
                            max_failure_factor(m.poisson, lc_m)
                        ),
                    );
                }
                kr
            } else {
                DEFAULT_KR
            }
        }
        (None, None) => DEFAULT_KR,
    };
    ck.range("rupture.fracture_energy_cv", r.fracture_energy_cv, 0.0, false, 1.0, false);
    let stream = match (r.fracture_energy_stream, r.fracture_energy_cv > 0.0) {
        (None, true) => {
            ck.push(
                "rupture.fracture_energy_stream",
                "(missing)",
                format!(
                    "a random stream ≥ 2 for the Weibull field on Gf (fracture_energy_cv = {}); streams 0 and 1 draw the \
                     fields on E and μ",
                    r.fracture_energy_cv
                ),
            );
            None
        }
        (Some(s), true) => {
            if s < 2 {
                ck.push(
                    "rupture.fracture_energy_stream",
                    s,
                    "an integer ≥ 2 (streams 0 and 1 draw the fields on E and μ; the Gf field needs its own)",
                );
            }
            u64::try_from(s).ok()
        }
        (Some(s), false) => {
            ck.push("rupture.fracture_energy_stream", s, "only with rupture.fracture_energy_cv > 0 (no field to draw)");
            None
        }
        (None, false) => None,
    };
    if ck.range("rupture.young_correlation", r.young_correlation, -1.0, false, 1.0, false)
        && r.young_correlation != 0.0
        && !(m.young_cv > 0.0 && r.fracture_energy_cv > 0.0)
    {
        ck.push(
            "rupture.young_correlation",
            r.young_correlation,
            "0 unless material.young_cv and rupture.fracture_energy_cv are both > 0 (a correlation needs two fields)",
        );
    }
    if let Some(d) = r.ae_link_distance_m {
        ck.positive("rupture.ae_link_distance_m", d);
    }
    if let Some(t) = r.ae_link_time_s {
        ck.non_negative("rupture.ae_link_time_s", t);
    }
    let mut elastic_zones = Vec::new();
    for (i, z) in r.elastic_zones.iter().enumerate() {
        let face = ck.named::<Face>(&format!("rupture.elastic_zones[{i}].face"), &z.face);
        if ck.positive(&format!("rupture.elastic_zones[{i}].depth_m"), z.depth_m)
            && let Some(face) = face
        {
            elastic_zones.push((face, z.depth_m));
        }
    }
    Rupture {
        fracture_energy_j_m2: r.fracture_energy_j_m2,
        kr,
        failure_factor_per_sqrt_m: r.failure_factor_per_sqrt_m,
        fracture_energy_cv: r.fracture_energy_cv,
        fracture_energy_stream: stream,
        young_correlation: r.young_correlation,
        elastic_zones,
    }
}
