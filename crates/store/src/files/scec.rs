//! A fault scene's files in the layout of the SCEC/USGS dynamic-rupture benchmarks
//! ([`stickslip_seismo::scec`], docs/model.md §15), under `<out>/scec/seed<seed>/`: one file per
//! fault station (`faultst<±strike>dp<depth>.dat`, named from its position against
//! `[fault] origin_m`), one per station off the fault (`<name>.dat`), and the rupture times of
//! every fault node (`cplot.dat`).
//!
//! The block lies on its side (x along strike, y down dip, z away from the fault; its side is the
//! benchmarks' far side), so the benchmark's horizontal, vertical (down) and normal components are
//! x, y and z.

use std::time::{SystemTime, UNIX_EPOCH};

use stickslip_seismo::scec::{Header, OffFault, OnFault, cplot_text, off_fault_text, on_fault_text};
use stickslip_solver::laws::NodeFriction;
use stickslip_solver::scene::{Component, Kinematic};

use crate::error::StoreError;
use crate::files::Stamp;
use crate::io::write_text_atomic;
use crate::layout::Folder;
use crate::spec::SeedView;

/// Writes the benchmark files of a seed on a fault (nothing on the rigid base).
pub fn write(out: &Folder, view: &SeedView<'_>, stamp: &Stamp<'_>) -> Result<(), StoreError> {
    let (model, seed) = (view.model, view.seed);
    let Some(fault) = &model.scene().fault else { return Ok(()) };
    let rec = &view.analysis.run.recording;
    let trace = &rec.trace;
    let dir = out.root().join("scec").join(format!("seed{seed}"));
    let problem =
        format!("{} (stickslip pipeline {}, seed {seed}, hash {})", stamp.pipeline, stamp.pipeline, stamp.hash);
    let code = format!("stickslip {}", env!("CARGO_PKG_VERSION"));
    let date = today();
    let lc = model.scene().lc_m;
    let [x0, y0] = fault.origin_m;
    let lattice = model.lattice();
    let keep = trace.thinned(model.scene().record.fault_interval_s);
    let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
    let t = pick(&trace.time_s);
    let rate_state = matches!(model.scene().friction.law.background, NodeFriction::RateState(_));
    for st in &trace.stations {
        let p = lattice.position(st.node);
        let (strike, depth) = (p[0] - x0, p[1] - y0);
        let location = format!(
            "on fault, {} km along strike, {} km depth (node LDEM {})",
            strike / 1e3,
            depth / 1e3,
            st.node.ldem()
        );
        let header = Header { problem: &problem, code: &code, date: &date, element_size_m: lc, location: &location };
        let (sh, sv) = (pick(&st.slip_m[0]), pick(&st.slip_m[1]));
        let (rh, rv) = (pick(&st.slip_rate_m_s[0]), pick(&st.slip_rate_m_s[1]));
        let (th, tv) = (pick(&st.shear_stress_pa[0]), pick(&st.shear_stress_pa[1]));
        let (normal, state) = (pick(&st.normal_stress_pa), pick(&st.state));
        let rate_state = rate_state.then_some([&normal[..], &state[..]]);
        let series = OnFault {
            time_s: &t,
            slip_m: [&sh, &sv],
            slip_rate_m_s: [&rh, &rv],
            shear_stress_pa: [&th, &tv],
            rate_state,
        };
        write_text_atomic(
            &dir.join(format!("{}.dat", super::fault_station_file(p, Some(fault.origin_m)))),
            &on_fault_text(&header, &series),
        )?;
    }
    let shear = rec.sampling.shear_start;
    let times = &rec.time_s[shear.min(rec.time_s.len())..];
    for st in &model.scene().stations {
        let p = lattice.position(st.node);
        let location = format!(
            "{} km off fault, {} km along strike, {} km depth (node LDEM {})",
            p[2] / 1e3,
            (p[0] - x0) / 1e3,
            (p[1] - y0) / 1e3,
            st.node.ldem()
        );
        let header = Header { problem: &problem, code: &code, date: &date, element_size_m: lc, location: &location };
        let series = |q: Kinematic, c: Component| -> &[f64] {
            rec.control
                .iter()
                .find(|(ch, _)| ch.node == st.node && ch.quantity == q && ch.component == c)
                .map_or(&[][..], |(_, v)| &v[shear.min(v.len())..])
        };
        let d = Component::ALL.map(|c| series(Kinematic::Displacement, c));
        let v = Component::ALL.map(|c| series(Kinematic::Velocity, c));
        if d.iter().chain(&v).any(|s| s.len() != times.len()) {
            continue;
        }
        let s = OffFault { time_s: times, displacement_m: d, velocity_m_s: v };
        write_text_atomic(&dir.join(format!("{}.dat", st.name)), &off_fault_text(&header, &s))?;
    }
    if let Some(summary) = &trace.summary {
        let nodes: Vec<([f64; 2], f64)> = summary
            .nodes
            .iter()
            .zip(&summary.rupture_time_s)
            .map(|(&id, &t)| {
                let p = lattice.position(id);
                ([p[0] - x0, p[1] - y0], t)
            })
            .collect();
        let header =
            Header { problem: &problem, code: &code, date: &date, element_size_m: lc, location: "every fault node" };
        write_text_atomic(&dir.join("cplot.dat"), &cplot_text(&header, &nodes))?;
    }
    Ok(())
}

/// Today's date in UTC as `YYYY/MM/DD` (the civil calendar from the days since 1970, Hinnant's
/// algorithm).
fn today() -> String {
    let days = SystemTime::now().duration_since(UNIX_EPOCH).map_or(0, |d| d.as_secs() / 86_400) as i64;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!("{y:04}/{m:02}/{d:02}")
}
