//! One SEAS-layout station file per fault station of the scene (docs/model.md §13), under
//! `<out>/fault_stations/seed<seed>/`, at the instants of the `fault` table.

use stickslip_seismo::seas::{StationHeader, StationSeries, station_text};

use crate::error::StoreError;
use crate::files::Stamp;
use crate::io::write_text_atomic;
use crate::layout::Folder;
use crate::spec::SeedView;

/// Writes the station files of a seed that recorded the fault (nothing otherwise).
pub fn write(out: &Folder, view: &SeedView<'_>, stamp: &Stamp<'_>) -> Result<(), StoreError> {
    let (model, seed) = (view.model, view.seed);
    let trace = &view.analysis.run.recording.trace;
    if trace.stations.is_empty() || model.scene().is_fault() {
        return Ok(());
    }
    let keep = trace.thinned(model.scene().record.fault_interval_s);
    let dir = out.fault_stations_dir(seed);
    let problem = format!("stickslip pipeline {} seed {seed} (hash {})", stamp.pipeline, stamp.hash);
    let code = format!("stickslip {}", env!("CARGO_PKG_VERSION"));
    for st in &trace.stations {
        let id = st.node;
        let p = model.lattice().position(id);
        let location = format!(
            "on the base (the fault), x = {} m along strike, y = {} m across; contact node LDEM {}",
            p[0],
            p[1],
            id.ldem()
        );
        let header =
            StationHeader { problem: &problem, code: &code, element_size_m: model.scene().lc_m, location: &location };
        let pick = |v: &[f64]| keep.iter().map(|&k| v[k]).collect::<Vec<f64>>();
        let (t, slip, rate) = (pick(&trace.time_s), pick(&st.slip_m[0]), pick(&st.slip_rate_m_s[0]));
        let (tau, sigma) = (pick(&st.shear_stress_pa[0]), pick(&st.normal_stress_pa));
        let series = StationSeries {
            time_s: &t,
            slip_m: &slip,
            slip_rate_m_s: &rate,
            shear_stress_pa: &tau,
            normal_stress_pa: &sigma,
        };
        write_text_atomic(
            &dir.join(format!("{}.dat", super::fault_station_file(p, None))),
            &station_text(&header, &series),
        )?;
    }
    Ok(())
}
