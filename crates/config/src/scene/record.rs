//! `[record]` checked into the record plan: sampling, channels and fault stations.

use stickslip_solver::TracePlan;
use stickslip_solver::geometry::{Lattice, NodeId, NodeSet};
use stickslip_solver::scene::{Component, ControlChannel, InterfaceQuantity, Kinematic, RecordPlan};

use super::RecordSection;
use super::block::resolve_nodes;
use crate::check::{Checker, approx};

/// The fewest samples the shear stage may give at `record.interval_s` (and the fault table at
/// `record.fault_interval_s`): fewer make empty records and flat figures, not results.
pub const MIN_SAMPLES: f64 = 10.0;

/// Checks `record.interval_s` and `record.fault_interval_s` against the shear stage of
/// `duration_s`: at least [`MIN_SAMPLES`] samples over it.
pub(super) fn check_interval(ck: &mut Checker, r: &RecordSection, duration_s: f64) {
    let longest = duration_s / MIN_SAMPLES;
    for (field, iv) in [("record.interval_s", r.interval_s), ("record.fault_interval_s", r.fault_interval_s)] {
        let Some(iv) = iv else { continue };
        if ck.positive(field, iv) && duration_s > 0.0 && duration_s.is_finite() && iv > longest {
            ck.push(
                field,
                iv,
                format!(
                    "0 < {} ≤ shear.duration_s/{MIN_SAMPLES} = {} s (at least {MIN_SAMPLES} samples over the shear \
                     stage; fewer give empty records and flat figures)",
                    field.rsplit('.').next().unwrap_or(field),
                    approx(longest)
                ),
            );
        }
    }
}

/// The interface quantities of `record.interface`.
pub(super) fn interface(ck: &mut Checker, r: &RecordSection) -> Vec<InterfaceQuantity> {
    let mut interface: Vec<InterfaceQuantity> = ck.named_list("record.interface", &r.interface);
    interface.dedup();
    interface
}

/// The record plan of `[record]` with its checked `interface` and `control` channels; the fault
/// stations and the fault table's interval are checked here.
pub(super) fn plan(
    ck: &mut Checker,
    r: &RecordSection,
    interface: Vec<InterfaceQuantity>,
    control: Vec<ControlChannel>,
    lattice: &Lattice,
) -> RecordPlan {
    RecordPlan {
        interval_s: r.interval_s,
        // Set by the pipeline when it processes accelerograms.
        resampled: false,
        interface,
        energy: r.energy,
        settling: r.settling,
        slip_onsets: r.slip_onsets,
        fault: r.fault,
        fault_stations: fault_stations(ck, &r.fault_stations_m, lattice),
        fault_interval_s: r.fault_interval_s.filter(|&v| v > 0.0 && v.is_finite()),
        control,
        trace: TracePlan::default(),
    }
}

/// The control channels of `[[record.control]]`, sorted and unique.
pub(super) fn control_channels(ck: &mut Checker, r: &RecordSection, lattice: &Lattice) -> Vec<ControlChannel> {
    let mut control = Vec::new();
    for (i, c) in r.control.iter().enumerate() {
        let field = format!("record.control[{i}].");
        if c.nodes.is_empty() && c.at_m.is_empty() && c.set.is_none() {
            ck.push(
                format!("{field}nodes"),
                "[]",
                "at least one node (nodes = [LDEM numbers], at_m = [[x, y, z]] or set = \"top_line\" | \"top\" | \"surface\")",
            );
        }
        if c.quantities.is_empty() {
            ck.push(
                format!("{field}quantities"),
                "[]",
                "at least one of \"displacement\", \"velocity\", \"acceleration\"",
            );
        }
        if c.components.is_empty() {
            ck.push(format!("{field}components"), "[]", "at least one of \"x\", \"y\", \"z\"");
        }
        let quantities: Vec<Kinematic> = ck.named_list(&format!("{field}quantities"), &c.quantities);
        let components: Vec<Component> = ck.named_list(&format!("{field}components"), &c.components);
        let names = (format!("{field}nodes"), format!("{field}at_m"));
        let mut nodes = resolve_nodes(ck, lattice, (&names.0, &names.1), &c.nodes, &c.at_m);
        if let Some(set) = &c.set
            && let Some(set) = ck.named::<NodeSet>(&format!("{field}set"), set)
        {
            nodes.extend(set.nodes(lattice));
        }
        for node in nodes {
            for &quantity in &quantities {
                for &component in &components {
                    control.push(ControlChannel { node, quantity, component });
                }
            }
        }
    }
    control.sort();
    control.dedup();
    control
}

/// The contact node nearest to each fault station, every station outside the base (or on a node
/// already taken by another) refused.
fn fault_stations(ck: &mut Checker, at_m: &[[f64; 2]], lattice: &Lattice) -> Vec<NodeId> {
    let e = lattice.extent();
    let lc = lattice.lc();
    let mut out: Vec<(usize, NodeId)> = Vec::new();
    for (i, p) in at_m.iter().enumerate() {
        let field = format!("record.fault_stations_m[{i}]");
        let inside = (0..2).all(|a| p[a].is_finite() && p[a] >= -1e-9 * e[a] && p[a] <= e[a] * (1.0 + 1e-9));
        if !inside {
            ck.push(
                field,
                format!("{p:?} m"),
                format!("a point of the base, 0 ≤ x ≤ {} m and 0 ≤ y ≤ {} m", approx(e[0]), approx(e[1])),
            );
            continue;
        }
        let snap = |v: f64| (v / lc).round() * lc;
        let Some(id) = lattice.node_at([snap(p[0]), snap(p[1]), 0.0]) else {
            ck.push(field, format!("{p:?} m"), "a point of the base");
            continue;
        };
        if let Some(&(j, _)) = out.iter().find(|&&(_, o)| o == id) {
            let q = lattice.position(id);
            ck.push(
                field,
                format!("{p:?} m"),
                format!("a station on its own node: station {j} is already at the nearest node ({}, {}) m", q[0], q[1]),
            );
            continue;
        }
        out.push((i, id));
    }
    out.into_iter().map(|(_, id)| id).collect()
}
