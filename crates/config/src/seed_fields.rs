//! What makes a pipeline's seeds differ: its random fields (docs/model.md §3; without one,
//! every seed gives the same run).

use crate::pipeline::PipelineFile;

impl PipelineFile {
    /// The random fields of the file that make its seeds differ, by their fields (empty: every seed
    /// gives the same run).
    pub(crate) fn random_fields(&self) -> Vec<&'static str> {
        let file = self;
        let mut out = Vec::new();
        if file.material.young_cv > 0.0 {
            out.push("material.young_cv");
        }
        if file.friction.mu_cv > 0.0 {
            out.push("friction.mu_cv");
        }
        if file.rupture.as_ref().is_some_and(|r| r.fracture_energy_cv > 0.0) {
            out.push("rupture.fracture_energy_cv");
        }
        if file.fault.as_ref().and_then(|f| f.stochastic.as_ref()).is_some_and(|s| s.std_pa > 0.0) {
            out.push("fault.stochastic.std_pa");
        }
        if file
            .fault
            .as_ref()
            .and_then(|f| f.nucleation.as_ref())
            .is_some_and(|n| n.x_m[0] < n.x_m[1] || n.y_m[0] < n.y_m[1])
        {
            out.push("fault.nucleation");
        }
        if file
            .cycles
            .as_ref()
            .and_then(|c| c.heterogeneity.as_ref())
            .is_some_and(|h| h.log_a_std > 0.0 || h.log_b_std > 0.0 || h.log_dc_std > 0.0)
        {
            out.push("cycles.heterogeneity");
        }
        out
    }
}
