//! Rupture fronts on a fault with a strong asperity (`pipelines/fault-asperity.toml`,
//! docs/model.md §13): where ruptures start, how fast they spread, and the fault's own records.

use std::ops::ControlFlow;

use stickslip_config::Pipeline;
use stickslip_ensemble::fronts::{FaultBase, fronts};
use stickslip_ensemble::seed::catalogue;
use stickslip_solver::{Model, RunOptions, run_seed};
use stickslip_support::repo_path;

#[test]
fn ruptures_start_in_the_asperity_and_run_slower_than_p_waves() {
    let p = Pipeline::load(&repo_path("pipelines/fault-asperity.toml")).unwrap();
    let model = Model::new(p.scene.clone());
    let base = FaultBase::of(&model);
    let share = base.region.iter().filter(|r| *r == "asperity").count() as f64 / base.region.len() as f64;
    let (mut mains, mut in_asperity, mut speeds, mut c_s) = (0, 0, Vec::new(), f64::NAN);
    for &seed in &p.seeds[..4] {
        let out = run_seed(&model, seed, RunOptions::default(), &mut |_| ControlFlow::Continue(())).unwrap();
        let cat = catalogue(&out.recording, &model, &p.events);
        let f = fronts(&out.recording, &cat, &model, p.events.smoothing_s, p.events.rupture_rate_m_s).unwrap();
        assert_eq!(f.source, "slip_rate");
        c_s = f.speeds.s_m_s;
        // The fault's series are the trace's instants, one per node.
        let fault = out.recording.trace.fault.as_ref().unwrap();
        assert_eq!(fault.nodes.len(), base.ids.len());
        assert!(fault.slip_rate_m_s.iter().all(|r| r.len() == out.recording.trace.len()));
        for (k, front) in &f.fronts {
            if !cat.events[*k].kind.is_main() {
                continue;
            }
            mains += 1;
            in_asperity += usize::from(base.region[front.hypocentre.0] == "asperity");
            let v = front.speed_m_s();
            assert!(v > 0.0 && v < f.speeds.p_m_s, "seed {seed}: a front at {v} m/s, P {}", f.speeds.p_m_s);
            speeds.push(v);
        }
    }
    // The asperity holds 17% of the base's nodes. Measured: 12 of 15 main shocks (4 seeds) start
    // in it, the others at the leading edge (25 of 30 over the file's 8 seeds). At least 60% (9 of
    // 15) has a chance below 1e-4 if hypocentres fell anywhere on the base with equal chance.
    println!("{in_asperity} of {mains} main shocks start in the asperity (its share of the base {share:.2})");
    assert!(mains >= 12, "{mains} main shocks in 4 seeds");
    assert!(in_asperity as f64 >= 0.6 * mains as f64, "{in_asperity} of {mains} in the asperity");
    speeds.sort_by(f64::total_cmp);
    let median = speeds[speeds.len() / 2];
    // Measured: a median of 0.3 c_s; the fronts are sub-Rayleigh but far from standing.
    println!("median rupture speed {median:.0} m/s = {:.2} c_s", median / c_s);
    assert!(median > 0.05 * c_s && median < c_s, "median rupture speed {median} m/s, c_s {c_s} m/s");
}
