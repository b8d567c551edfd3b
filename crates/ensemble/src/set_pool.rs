//! What the two kinds of record sets share (`crate::set` of events' records,
//! `crate::scenario_set` of a scenario's stations): the candidates on a common period grid, the
//! selection over them (`stickslip_seismo::selection`), and the outcome.

use stickslip_config::SetSettings;
use stickslip_seismo::selection::{Candidate, Selection, select};
use stickslip_store::Folder;
use stickslip_store::tables::set::SetRow;

use crate::error::EnsembleError;

/// What a selection found.
#[derive(Clone, Debug)]
pub struct SetOutcome {
    /// The selection (records, scale factors, mean spectrum, the rule's ratio).
    pub selection: Selection,
    /// The rows of the set table.
    pub rows: Vec<SetRow>,
    /// The prototype period grid (s).
    pub periods: Vec<f64>,
    /// The target on the grid (m/s²).
    pub target: Vec<f64>,
    /// Each chosen record's unscaled PSA on the grid (m/s²).
    pub spectra: Vec<Vec<f64>>,
    /// Candidates considered.
    pub candidates: usize,
    /// What the candidates are, when a bin or a rule left some out (e.g. "stations of ruptures
    /// Mw 6–6.5 at R_rup 10–30 km: 37 of 144").
    pub pool: Option<String>,
}

/// The spectra a set is chosen among, on a common grid, and what each candidate is.
pub(crate) struct Pool<M> {
    /// The period grid (s).
    pub grid: Vec<f64>,
    /// Each candidate: its group, PSA on `grid`, usable periods `(shortest, longest)` (s) and
    /// what it is.
    pub members: Vec<Member<M>>,
}

/// One candidate of a [`Pool`].
pub(crate) struct Member<M> {
    /// Identifier.
    pub id: String,
    /// Group (at most `max_per` of one group).
    pub group: String,
    /// PSA on the pool's grid (m/s²).
    pub psa: Vec<f64>,
    /// Usable periods (s).
    pub usable_s: (f64, f64),
    /// What it is.
    pub meta: M,
}

/// What a selection over a pool chose: the selection, sorted by misfit, and the target on the
/// grid where it is defined.
pub(crate) struct Chosen {
    pub selection: Selection,
    pub periods: Vec<f64>,
    pub target: Vec<f64>,
    pub spectra: Vec<Vec<f64>>,
}

/// Matches `settings` among `pool` (the target where it is defined on the pool's grid), the
/// records ranked by misfit, best first.
pub(crate) fn choose<M>(pool: &Pool<M>, settings: &SetSettings) -> Result<Chosen, EnsembleError> {
    // The target where it is defined (a CSV table may not span the whole grid).
    let on_grid: Vec<(usize, f64)> =
        pool.grid.iter().enumerate().filter_map(|(k, &t)| settings.target.psa(t).ok().map(|v| (k, v))).collect();
    let periods: Vec<f64> = on_grid.iter().map(|&(k, _)| pool.grid[k]).collect();
    let target: Vec<f64> = on_grid.iter().map(|&(_, v)| v).collect();
    let candidates: Vec<Candidate> = pool
        .members
        .iter()
        .map(|m| Candidate {
            id: m.id.clone(),
            group: m.group.clone(),
            psa: on_grid.iter().map(|&(k, _)| m.psa[k]).collect(),
            usable_min: m.usable_s.0,
            usable_max: m.usable_s.1,
        })
        .collect();
    let mut selection = select(&periods, &target, &candidates, &settings.options).map_err(EnsembleError::Set)?;
    // Ranked by misfit, best first: the set table's rank, the files' numbers and the printout.
    selection.records.sort_by(|a, b| a.misfit.total_cmp(&b.misfit).then(a.index.cmp(&b.index)));
    let spectra = selection
        .records
        .iter()
        .map(|c| on_grid.iter().map(|&(k, _)| pool.members[c.index].psa[k]).collect())
        .collect();
    Ok(Chosen { selection, periods, target, spectra })
}

/// Empties `<out>/set/`: a new set replaces the old one whole.
pub(crate) fn clear_set_dir(out: &Folder) -> Result<(), EnsembleError> {
    let dir = out.set_dir();
    if dir.exists() {
        for e in std::fs::read_dir(&dir).map_err(|e| stickslip_store::StoreError::io(&dir, e))?.flatten() {
            let _ = std::fs::remove_file(e.path());
        }
    }
    Ok(())
}
