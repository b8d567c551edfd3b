//! What the figures of several topics share: drawing a sheet into an outcome, the caption texts
//! (seeds, the paper's figure numbers), a seed's series and main shocks, and the control nodes the
//! accelerogram, spectrum and Fourier figures show.

use std::path::Path;

use stickslip_solver::scene::{Component, ControlChannel, Kinematic};
use stickslip_store::schema::SERIES;
use stickslip_store::tables::series::{Trace, read_series_channel};

use super::Outcome;
use crate::charts::{self, Sheet};
use crate::error::ReportError;
use crate::input::ReportInput;

/// At most this many nodes are drawn side by side in the accelerogram, spectrum and Fourier
/// figures; beyond it, a subset spread over the recorded ones, said in the caption.
pub const MAX_NODES: usize = 3;

pub(super) fn seeds_text(seeds: &[u64]) -> String {
    let s: Vec<String> = seeds.iter().map(|s| s.to_string()).collect();
    match s.len() {
        0 => "no seed".into(),
        1 => format!("seed {}", s[0]),
        _ => format!("seeds {}", s.join(", ")),
    }
}

/// " (paper Fig. n)" for the paper's pipelines (`[report] paper_figures`), else nothing.
pub(super) fn paper_fig(d: &ReportInput, n: u32) -> String {
    if d.paper { format!(" (paper Fig. {n})") } else { String::new() }
}

/// Draws `sheet` to `path` and returns the figure's outcome.
pub(super) fn drawn(path: &Path, sheet: &Sheet, title: String, caption: String) -> Result<Outcome, ReportError> {
    let out = charts::draw(path, sheet)?;
    let headings = std::iter::once(&sheet.title)
        .chain(sheet.panels.iter().map(|p| &p.title))
        .filter(|t| !t.is_empty())
        .cloned()
        .collect();
    let dropped = out.panels.iter().flat_map(|p| p.dropped.iter().cloned()).collect();
    Ok(Outcome::Drawn { title, caption, headings, panels: out.panels.into_iter().map(|p| p.name).collect(), dropped })
}

/// (time, values) of a series column for one seed, if recorded.
pub(super) fn series(d: &ReportInput, seed: u64, column: &str) -> Result<Option<Trace>, ReportError> {
    let Some(df) = d.part(&SERIES, seed)? else { return Ok(None) };
    Ok(read_series_channel(&df, column)?)
}

/// A recorded accelerogram channel the figures show.
#[derive(Clone, Debug, PartialEq)]
pub struct NodeChannel {
    /// LDEM number.
    pub ldem: u64,
    /// Component drawn (z if recorded, else the first).
    pub component: Component,
    /// The node's position (m).
    pub at_m: [f64; 3],
}

impl NodeChannel {
    /// "node 36 at (0.2, 0.1, 0.1) m", or in km on a block of kilometres ("node 195789 at (25, 0,
    /// 19) km").
    pub fn name(&self) -> String {
        let km = self.at_m.iter().any(|v| v.abs() >= 1e3);
        let [x, y, z] = self.at_m.map(|v| crate::plot::fmt_tick(&if km { v / 1e3 } else { v }));
        format!("node {} at ({x}, {y}, {z}) {}", self.ldem, if km { "km" } else { "m" })
    }
}

/// The nodes the accelerogram figures show: every control node recording acceleration that the
/// `[accelerograms]` section cuts records of (all of them without one), at most [`MAX_NODES`]
/// spread evenly over them; and how many there were.
pub(super) fn accelerogram_nodes(d: &ReportInput) -> (Vec<NodeChannel>, usize) {
    let control = &d.pipeline.scene.record.control;
    let wanted = |c: &&ControlChannel| {
        d.pipeline.analysis.accelerograms.as_ref().map_or(c.quantity == Kinematic::Acceleration, |a| a.wants(c))
    };
    let mut nodes: Vec<_> = control.iter().filter(wanted).map(|c| c.node).collect();
    nodes.sort();
    nodes.dedup();
    let lattice = d.pipeline.scene.lattice();
    let all: Vec<NodeChannel> = nodes
        .iter()
        .filter_map(|&node| {
            let comps: Vec<Component> =
                control.iter().filter(wanted).filter(|c| c.node == node).map(|c| c.component).collect();
            let component = if comps.contains(&Component::Z) { Component::Z } else { *comps.first()? };
            Some(NodeChannel { ldem: node.ldem(), component, at_m: lattice.position(node) })
        })
        .collect();
    let total = all.len();
    if total <= MAX_NODES {
        return (all, total);
    }
    (spread(total, MAX_NODES).into_iter().map(|i| all[i].clone()).collect(), total)
}

/// `max` of the indices `0..total` spread evenly over them, the first and the last included (all
/// of them when `total ≤ max`), in increasing order.
pub fn spread(total: usize, max: usize) -> Vec<usize> {
    match (total, max) {
        (t, m) if t <= m => (0..t).collect(),
        (_, 0) => vec![],
        (_, 1) => vec![0],
        (t, m) => (0..m).map(|k| (k * (t - 1) + (m - 1) / 2) / (m - 1)).collect(),
    }
}

/// How the caption says which nodes are drawn.
pub(super) fn nodes_text(nodes: &[NodeChannel], total: usize) -> String {
    let names: Vec<String> = nodes.iter().map(|n| format!("{} ({})", n.name(), n.component.name())).collect();
    let list = names.join("; ");
    if total > nodes.len() {
        format!(
            "{} of the {total} control nodes recording acceleration, spread over them (the figures show at most \
             {MAX_NODES}; every node's records are in the tables): {list}",
            nodes.len()
        )
    } else if nodes.len() > 1 {
        format!("each control node in its own panel: {list}")
    } else {
        format!("control {list}")
    }
}

/// "node 36" or "nodes 36, 12".
pub(super) fn nodes_short(nodes: &[NodeChannel]) -> String {
    let n: Vec<String> = nodes.iter().map(|n| n.ldem.to_string()).collect();
    if n.len() == 1 { format!("node {}", n[0]) } else { format!("nodes {}", n.join(", ")) }
}

/// Main shocks of one seed: (label, start time).
pub(super) fn main_shocks(d: &ReportInput, seed: u64) -> Result<Vec<(String, f64)>, ReportError> {
    let Some(ev) = &d.events else { return Ok(vec![]) };
    Ok((0..ev.len())
        .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
        .map(|i| (ev.kind[i].label(), ev.start_s[i]))
        .collect())
}

/// Main shocks of one seed: (label, start, end).
pub(super) fn main_shocks_with_ends(d: &ReportInput, seed: u64) -> Result<Vec<(String, f64, f64)>, ReportError> {
    let Some(ev) = &d.events else { return Ok(vec![]) };
    Ok((0..ev.len())
        .filter(|&i| ev.seed[i] == seed && ev.kind[i].is_main())
        .map(|i| (ev.kind[i].label(), ev.start_s[i], ev.start_s[i] + ev.duration_s[i]))
        .collect())
}

/// The rank of a main-shock label ("S3" → 3); `None` for any other label.
pub(super) fn rank_of(label: &str) -> Option<u32> {
    label.strip_prefix('S')?.parse().ok()
}

/// The standard error of a least-squares slope `b` from its r² over `n` points.
pub(super) fn slope_se(b: f64, r2: f64, n: f64) -> f64 {
    if n > 2.0 && r2 > 0.0 { b.abs() * ((1.0 / r2 - 1.0) / (n - 2.0)).sqrt() } else { f64::INFINITY }
}

#[cfg(test)]
mod tests {
    use super::spread;

    #[test]
    fn a_subset_of_nodes_spans_the_recorded_ones() {
        assert_eq!(spread(2, 3), vec![0, 1], "all of them when few");
        assert_eq!(spread(12, 3), vec![0, 6, 11]);
        assert_eq!(spread(4, 3), vec![0, 2, 3]);
        assert_eq!(spread(5, 1), vec![0]);
        for total in 1..40 {
            for max in 1..6 {
                let s = spread(total, max);
                assert_eq!(s.len(), total.min(max));
                assert!(s.windows(2).all(|w| w[0] < w[1]), "{total} {max}: {s:?}");
                assert_eq!(s[0], 0);
                if max > 1 {
                    assert_eq!(*s.last().unwrap(), total - 1, "{total} {max}: the last node is shown");
                }
            }
        }
    }
}
