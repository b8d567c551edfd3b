// Scratch probe of BP1-QD (not committed).
use stickslip_solver::cycles::*;
use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let lc: f64 = args.get(1).map(|s| s.parse().unwrap()).unwrap_or(100.0);
    let years: f64 = args.get(2).map(|s| s.parse().unwrap()).unwrap_or(800.0);
    let domain_km: f64 = args.get(3).map(|s| s.parse().unwrap()).unwrap_or(400.0);
    let rtol: f64 = args.get(4).map(|s| s.parse().unwrap()).unwrap_or(1e-7);
    let (rho, cs) = (2670.0, 3464.0);
    let mu = rho * cs * cs;
    let stencil = AntiplaneStencil { link_n_per_m: mu * lc, lc_m: lc };
    let (sigma, a0, amax, b, l, v0, f0, vp): (f64, f64, f64, f64, f64, f64, f64, f64) =
        (50e6, 0.010, 0.025, 0.015, 0.008, 1e-6, 0.6, 1e-9);
    let (h_, hh, wf) = (15e3, 3e3, 40e3);
    let nodes = (wf / lc).round() as usize;
    let nd = (domain_km * 1e3 / lc).round() as usize;
    let t0 = std::time::Instant::now();
    let k = FaultStiffness::antiplane(&stencil, nodes, nd, nd).unwrap();
    eprintln!("K {} nodes, domain {} modules: {:.2} s", nodes, nd, t0.elapsed().as_secs_f64());
    let eta = mu / (2.0 * cs);
    let tau0 = sigma * amax * ((vp / (2.0 * v0)) * ((f0 + b * (v0 / vp).ln()) / amax).exp()).asinh() + eta * vp;
    let mut friction = vec![];
    for j in 0..nodes {
        let z = j as f64 * lc;
        let a = if z < h_ {
            a0
        } else if z < h_ + hh {
            a0 + (amax - a0) * (z - h_) / hh
        } else {
            amax
        };
        let theta0 =
            (l / v0) * ((a / b) * ((2.0 * v0 / vp) * ((tau0 - eta * vp) / (a * sigma)).sinh()).ln() - f0 / b).exp();
        friction.push(RateStateNode {
            a,
            b,
            dc_m: l,
            v0_m_s: v0,
            f0,
            evolution: Evolution::Aging,
            start: RateStateStart::State(theta0),
        });
    }
    let fault = QuasiDynamicFault {
        stiffness: k,
        friction,
        normal_pa: vec![sigma; nodes],
        shear0_pa: vec![tau0; nodes],
        eta_pa_s_m: eta,
        plate_m_s: vp,
    };
    let start = fault.start();
    eprintln!(
        "V0 range {:e} {:e}",
        start.slip_rate_m_s.iter().cloned().fold(f64::INFINITY, f64::min),
        start.slip_rate_m_s.iter().cloned().fold(0.0, f64::max)
    );
    let tol = Tolerances { relative: rtol, slip_m: rtol, log_state: rtol, max_step_s: 0.1 * YEAR_S };
    let mut in_event = false;
    let mut onset = 0.0;
    let mut slip_at_onset = 0.0;
    let mut peak = 0.0f64;
    let j75 = (7500.0 / lc).round() as usize;
    let mut peak75 = 0.0f64;
    let mut slip75 = 0.0;
    let t1 = std::time::Instant::now();
    let (_, stats) = fault
        .run(start, years * YEAR_S, &tol, 100_000_000, |s| {
            let vmax = s.slip_rate_m_s.iter().cloned().fold(0.0, f64::max);
            if !in_event && vmax > 1e-3 {
                in_event = true;
                onset = s.t_s;
                slip_at_onset = s.slip_m[0];
                slip75 = s.slip_m[j75];
                peak = 0.0;
                peak75 = 0.0;
            }
            if in_event {
                peak = peak.max(vmax);
                peak75 = peak75.max(s.slip_rate_m_s[j75]);
                if vmax < 1e-3 {
                    in_event = false;
                    println!(
                        "event at {:9.3} yr: surface slip {:.4} m, at 7.5 km {:.4} m, peak V {:.4} m/s (7.5 km {:.4}), {:.1} s",
                        onset / YEAR_S,
                        s.slip_m[0] - slip_at_onset,
                        s.slip_m[j75] - slip75,
                        peak,
                        peak75,
                        s.t_s - onset
                    );
                }
            }
            Flow::Continue
        })
        .unwrap();
    eprintln!("{:?} in {:.1} s", stats, t1.elapsed().as_secs_f64());
}
