//! The event trace: the interface signals events are measured on, taken from the solver's own
//! steps so that they do not depend on how often the run is recorded (docs/model.md §7).
//!
//! Every integrated step of the shear stage is looked at. A step is **hot** when the raw mean
//! slip rate of the contact nodes is at least [`TracePlan::hot_rate_m_s`] in magnitude; every
//! step within [`TracePlan::margin_s`] of a hot step is kept, so each burst of slip is held at
//! the full rate of the solver with a margin on both sides. Between bursts only one step in
//! every [`TracePlan::quiet_interval_s`] is kept (and, through a quasi-static skip, the skipped
//! motion on the same grid). A detector that smooths over less than the margin and whose
//! thresholds are above the hot rate therefore sees exactly what it would see on every step.
//!
//! With `record.fault` the trace also holds every contact node's slip, slip rate and stresses at
//! the same instants ([`FaultTrace`]): the fault in space and time, at the solver's full rate
//! through every burst. The fault stations' series along x and y are kept at the same instants
//! ([`StationTrace`]), with or without the whole fault; and on a fault (docs/model.md §15) every
//! contact node's rupture time, peak slip rate and final slip and stresses are taken at every
//! step ([`FaultSummary`]), which costs one pass over the contact nodes a step and no memory
//! per step.

use crate::geometry::{Face, NodeId};
use crate::observe::Observed;
use crate::scene::{ControlChannel, Kinematic, TracePlan};
use crate::step::{Interface, NodeContact};

/// The event trace of one run: the shear stage's interface signals at full rate around every
/// burst of slip and sparsely between them, in time order.
#[derive(Clone, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Trace {
    /// Time since the start of the shear stage (s).
    pub time_s: Vec<f64>,
    /// Shear stress τ = −ΣF_x/A (Pa).
    pub shear_stress_pa: Vec<f64>,
    /// Normal stress σ = ΣN/A (Pa).
    pub normal_stress_pa: Vec<f64>,
    /// Mean x-displacement of the contact nodes (m).
    pub mean_slip_m: Vec<f64>,
    /// Mean x-velocity of the contact nodes (m/s).
    pub mean_slip_rate_m_s: Vec<f64>,
    /// Sliding contact nodes.
    pub slipping_nodes: Vec<f64>,
    /// The recorded control acceleration channels, at the same instants.
    pub accelerations: Vec<(ControlChannel, Vec<f64>)>,
    /// Every contact node at the same instants, when the scene records the fault.
    pub fault: Option<FaultTrace>,
    /// The fault stations' series at the same instants, order of `record.fault_stations`.
    pub stations: Vec<StationTrace>,
    /// Every contact node's rupture time, peak slip rate and final slip, on a fault.
    pub summary: Option<FaultSummary>,
}

/// One fault station (a contact node) at the trace's instants: slip, slip rate and shear stress
/// along x and y, and the normal stress. On a fault the slip is across it, twice the face's
/// displacement (docs/model.md §15).
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct StationTrace {
    /// The contact node.
    pub node: NodeId,
    /// The base area it stands for (m²).
    pub area_m2: f64,
    /// Slip since the start of the shear stage along x and y (m).
    pub slip_m: [Vec<f64>; 2],
    /// Slip rate along x and y (m/s).
    pub slip_rate_m_s: [Vec<f64>; 2],
    /// Shear stress `−F/A_i` along x and y (Pa).
    pub shear_stress_pa: [Vec<f64>; 2],
    /// Normal stress `N/A_i` (Pa).
    pub normal_stress_pa: Vec<f64>,
    /// The friction law's state variable (θ in s under rate and state).
    pub state: Vec<f64>,
}

/// Every contact node of a fault over the whole shear stage (docs/model.md §15), canonical
/// contact order, taken at every step.
#[derive(Clone, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct FaultSummary {
    /// The contact nodes.
    pub nodes: Vec<NodeId>,
    /// The fault area each stands for (m²).
    pub area_m2: Vec<f64>,
    /// Time its slip-rate magnitude first reached `rupture_rate_m_s` (s of the shear stage);
    /// NaN if it never did.
    pub rupture_time_s: Vec<f64>,
    /// Largest slip-rate magnitude (m/s).
    pub peak_slip_rate_m_s: Vec<f64>,
    /// Slip at the end along x and y (m).
    pub final_slip_m: Vec<[f64; 2]>,
    /// Shear stress at the start and at the end along x and y (Pa).
    pub shear_stress_pa: Vec<[[f64; 2]; 2]>,
    /// Normal stress (Pa).
    pub normal_stress_pa: Vec<f64>,
    /// The slip-rate threshold of the rupture time (m/s).
    pub rupture_rate_m_s: f64,
}

impl FaultSummary {
    /// Seismic moment `M0 = μ·Σ A_i·|D_i|` over the nodes whose slip is at least `min_slip_m`,
    /// with `μ` the shear modulus (N·m), and the area that slipped (m²).
    pub fn moment(&self, shear_modulus_pa: f64, min_slip_m: f64) -> (f64, f64) {
        let mut m0 = 0.0;
        let mut area = 0.0;
        for (d, a) in self.final_slip_m.iter().zip(&self.area_m2) {
            let slip = d[0].hypot(d[1]);
            if slip >= min_slip_m {
                m0 += a * slip;
                area += a;
            }
        }
        (shear_modulus_pa * m0, area)
    }
}

/// Every contact node of the base through the shear stage, at the trace's instants.
#[derive(Clone, Debug, Default, PartialEq, bincode::Encode, bincode::Decode)]
pub struct FaultTrace {
    /// The contact nodes, canonical contact order.
    pub nodes: Vec<NodeId>,
    /// The base area each stands for (m²).
    pub area_m2: Vec<f64>,
    /// Slip of each node: its x-displacement since the start of the shear stage (m).
    pub slip_m: Vec<Vec<f64>>,
    /// Slip rate: x-velocity (m/s).
    pub slip_rate_m_s: Vec<Vec<f64>>,
    /// Shear stress `−F_x/A_i` on the node's area (Pa), positive when the base resists the push.
    pub shear_stress_pa: Vec<Vec<f64>>,
    /// Normal stress `N/A_i` (Pa).
    pub normal_stress_pa: Vec<Vec<f64>>,
}

impl Trace {
    /// Indices of the instants at least `interval_s` apart, from the first (each the first
    /// instant at or past the last kept plus the interval); every instant for `None`.
    pub fn thinned(&self, interval_s: Option<f64>) -> Vec<usize> {
        let Some(iv) = interval_s else { return (0..self.len()).collect() };
        let mut out = Vec::new();
        let mut next = f64::NEG_INFINITY;
        for (i, &t) in self.time_s.iter().enumerate() {
            if t >= next - 1e-9 * iv {
                out.push(i);
                next = t + iv;
            }
        }
        out
    }

    /// Samples held.
    pub fn len(&self) -> usize {
        self.time_s.len()
    }

    /// Whether it holds nothing.
    pub fn is_empty(&self) -> bool {
        self.time_s.is_empty()
    }
}

/// Scalars per sample before the accelerations: step, τ, σ, δ, V, slipping.
const FIXED: usize = 6;

/// Samples of `width` values in a ring, oldest first: the steps that may still become a burst's
/// leading margin. Rows are copied in and out whole.
#[derive(bincode::Encode, bincode::Decode)]
struct Rows {
    width: usize,
    buf: Vec<f64>,
    /// Index of the oldest row.
    head: usize,
    len: usize,
}

impl Rows {
    fn new(width: usize) -> Rows {
        Rows { width, buf: Vec::new(), head: 0, len: 0 }
    }

    fn capacity(&self) -> usize {
        self.buf.len() / self.width
    }

    fn row(&self, k: usize) -> &[f64] {
        let i = (self.head + k) % self.capacity();
        &self.buf[i * self.width..(i + 1) * self.width]
    }

    /// The step index of the oldest row.
    fn front_step(&self) -> Option<u64> {
        (self.len > 0).then(|| self.row(0)[0] as u64)
    }

    fn push(&mut self, sample: &[f64]) {
        if self.len == self.capacity() {
            // Grow, laying the rows out oldest first.
            let mut grown = Vec::with_capacity(2 * self.buf.len().max(self.width));
            for k in 0..self.len {
                grown.extend_from_slice(self.row(k));
            }
            grown.resize(grown.capacity() / self.width * self.width, 0.0);
            self.buf = grown;
            self.head = 0;
        }
        let i = (self.head + self.len) % self.capacity();
        self.buf[i * self.width..(i + 1) * self.width].copy_from_slice(sample);
        self.len += 1;
    }

    /// Drops the oldest row, appending it to `to` when given.
    fn pop_front(&mut self, to: Option<&mut Vec<f64>>) {
        if let Some(to) = to {
            to.extend_from_slice(self.row(0));
        }
        self.head = (self.head + 1) % self.capacity();
        self.len -= 1;
    }

    /// Appends every row to `to`, oldest first, and empties the ring.
    fn drain_into(&mut self, to: &mut Vec<f64>) {
        while self.len > 0 {
            self.pop_front(Some(to));
        }
    }
}

/// Builds a [`Trace`] step by step.
#[derive(bincode::Encode, bincode::Decode)]
pub(crate) struct Tracer {
    hot_rate: f64,
    margin: u64,
    quiet: u64,
    origin: u64,
    area: f64,
    nodes: Vec<(ControlChannel, usize)>,
    /// Contact nodes recorded (all or none) and their x-displacement at the first step.
    fault: Option<(usize, Vec<f64>)>,
    /// The fault stations' contact indices and their slip at the first step.
    stations: Vec<(usize, [f64; 2])>,
    /// The fault summary being built (on a fault).
    summary: Option<SummaryBuilder>,
    /// Whether a step has been looked at.
    observed: bool,
    /// The contact nodes of the step being looked at (reused).
    contacts: Vec<NodeContact>,
    width: usize,
    /// The last `margin` steps not yet kept.
    pending: Rows,
    kept: Vec<f64>,
    keep_until: Option<u64>,
    scratch: Vec<f64>,
}

impl Tracer {
    /// A tracer for a shear stage starting at step `origin`, time step `dt`.
    pub(crate) fn new(
        plan: &TracePlan,
        model: &crate::model::Model,
        origin: u64,
        dt: f64,
        accelerations: &[ControlChannel],
    ) -> Tracer {
        let nodes: Vec<(ControlChannel, usize)> = accelerations
            .iter()
            .filter(|c| c.quantity == Kinematic::Acceleration)
            .map(|&c| (c, model.held(c.node).unwrap_or(crate::observe::REMOTE)))
            .collect();
        let fault = model.scene().record.fault.then(|| (model.contact().len(), Vec::new()));
        let lattice = model.lattice();
        let stations: Vec<(usize, [f64; 2])> = model
            .scene()
            .record
            .fault_stations
            .iter()
            .map(|&id| {
                (lattice.contact_nodes().iter().position(|&c| c == id).expect("a station is a contact node"), [0.0; 2])
            })
            .collect();
        let summary =
            model.scene().is_fault().then(|| SummaryBuilder::new(model.contact().len(), plan.rupture_rate_m_s));
        let width = FIXED + nodes.len() + fault.as_ref().map_or(0, |(n, _)| 4 * n) + STATION_WIDTH * stations.len();
        Tracer {
            hot_rate: plan.hot_rate_m_s,
            margin: (plan.margin_s / dt).ceil().max(1.0) as u64,
            quiet: (plan.quiet_interval_s / dt).round().max(1.0) as u64,
            origin,
            area: model.lattice().contact_area(),
            nodes,
            fault,
            stations,
            summary,
            observed: false,
            contacts: Vec::new(),
            width,
            pending: Rows::new(width),
            kept: Vec::new(),
            keep_until: None,
            scratch: Vec::with_capacity(width),
        }
    }

    /// Whether a skipped (quasi-static) step `step` lies on the quiet grid.
    pub(crate) fn on_grid(&self, step: u64) -> bool {
        (step - self.origin).is_multiple_of(self.quiet)
    }

    /// Looks at step `step` (shear stage) as `s` shows it.
    pub(crate) fn observe(&mut self, s: &impl Observed, step: u64) {
        // With the fault recorded, each contact node is read once: for its own columns and the sums.
        let mut contacts = std::mem::take(&mut self.contacts);
        contacts.clear();
        let face = if self.fault.is_some() || self.summary.is_some() {
            contacts.extend((0..s.contacts()).map(|ci| s.node_contact(ci)));
            Interface::sum(contacts.iter().copied())
        } else {
            s.interface()
        };
        let first = !self.observed;
        self.observed = true;
        if let Some(summary) = self.summary.as_mut() {
            summary.observe(&contacts, step - self.origin);
        }
        let hot = face.mean_slip_rate.abs() >= self.hot_rate;
        let mut sample = std::mem::take(&mut self.scratch);
        sample.clear();
        sample.extend([
            step as f64,
            -face.friction_x / self.area,
            face.normal / self.area,
            face.mean_slip,
            face.mean_slip_rate,
            face.slipping as f64,
        ]);
        sample.extend(self.nodes.iter().map(|&(c, node)| s.control(c, node)));
        if let Some((_, origin)) = self.fault.as_mut() {
            if origin.is_empty() {
                origin.extend(contacts.iter().map(|c| c.slip));
            }
            for (c, u0) in contacts.iter().zip(origin.iter()) {
                sample.extend([c.slip - u0, c.slip_rate, c.friction_x, c.normal]);
            }
        }
        for (ci, origin) in self.stations.iter_mut() {
            let c = if contacts.is_empty() { s.node_contact(*ci) } else { contacts[*ci] };
            if first {
                *origin = [c.slip, c.slip_y];
            }
            sample.extend([
                c.slip - origin[0],
                c.slip_y - origin[1],
                c.slip_rate,
                c.slip_rate_y,
                c.friction_x,
                c.friction_y,
                c.normal,
                c.state,
            ]);
        }
        self.contacts = contacts;
        // Samples older than the margin leave the pending queue: kept if on the quiet grid.
        while let Some(front) = self.pending.front_step()
            && front + self.margin < step
        {
            let keep = self.on_grid(front);
            self.pending.pop_front(keep.then_some(&mut self.kept));
        }
        if hot {
            self.pending.drain_into(&mut self.kept);
            self.kept.extend_from_slice(&sample);
            self.keep_until = Some(step + self.margin);
        } else if self.keep_until.is_some_and(|u| step <= u) {
            self.kept.extend_from_slice(&sample);
        } else {
            self.pending.push(&sample);
        }
        self.scratch = sample;
    }

    /// The trace, times from step indices with time step `dt`; `model` names the fault's nodes.
    pub(crate) fn finish(mut self, dt: f64, model: &crate::model::Model) -> Trace {
        self.pending.drain_into(&mut self.kept);
        // One pass over the rows fills every column.
        let n = self.kept.len() / self.width;
        let mut columns: Vec<Vec<f64>> = (0..self.width).map(|_| Vec::with_capacity(n)).collect();
        for row in self.kept.chunks_exact(self.width) {
            for (c, &v) in columns.iter_mut().zip(row) {
                c.push(v);
            }
        }
        let mut column = |k: usize| std::mem::take(&mut columns[k]);
        let origin = self.origin as f64;
        let lattice = model.lattice();
        let first_station = FIXED + self.nodes.len() + self.fault.as_ref().map_or(0, |(n, _)| 4 * n);
        let contact_ids = lattice.contact_nodes();
        let stations = self
            .stations
            .iter()
            .enumerate()
            .map(|(k, &(ci, _))| {
                let node = contact_ids[ci];
                let area = Face::ZMin.tributary_area(lattice, node);
                let at = first_station + STATION_WIDTH * k;
                let stress = |v: Vec<f64>, sign: f64| v.into_iter().map(|f| sign * f / area).collect::<Vec<f64>>();
                StationTrace {
                    node,
                    area_m2: area,
                    slip_m: [column(at), column(at + 1)],
                    slip_rate_m_s: [column(at + 2), column(at + 3)],
                    shear_stress_pa: [stress(column(at + 4), -1.0), stress(column(at + 5), -1.0)],
                    normal_stress_pa: stress(column(at + 6), 1.0),
                    state: column(at + 7),
                }
            })
            .collect();
        let summary = self.summary.take().map(|b| b.finish(model, dt));
        Trace {
            time_s: column(0).into_iter().map(|s| (s - origin) * dt).collect(),
            shear_stress_pa: column(1),
            normal_stress_pa: column(2),
            mean_slip_m: column(3),
            mean_slip_rate_m_s: column(4),
            slipping_nodes: column(5),
            accelerations: self.nodes.iter().enumerate().map(|(k, &(c, _))| (c, column(FIXED + k))).collect(),
            fault: self.fault.as_ref().map(|&(count, _)| {
                let first = FIXED + self.nodes.len();
                let lattice = model.lattice();
                let nodes: Vec<NodeId> = model.contact().iter().map(|&i| model.canonical(i as usize)).collect();
                let area: Vec<f64> = nodes.iter().map(|&id| Face::ZMin.tributary_area(lattice, id)).collect();
                let mut series = |k: usize, f: &dyn Fn(f64, f64) -> f64| -> Vec<Vec<f64>> {
                    (0..count)
                        .map(|ci| {
                            let mut c = column(first + 4 * ci + k);
                            c.iter_mut().for_each(|v| *v = f(*v, area[ci]));
                            c
                        })
                        .collect()
                };
                FaultTrace {
                    slip_m: series(0, &|v, _| v),
                    slip_rate_m_s: series(1, &|v, _| v),
                    shear_stress_pa: series(2, &|v, a| -v / a),
                    normal_stress_pa: series(3, &|v, a| v / a),
                    nodes,
                    area_m2: area,
                }
            }),
            stations,
            summary,
        }
    }
}

/// Values per station and instant: slip x, y, slip rate x, y, friction x, y, normal force.
const STATION_WIDTH: usize = 8;

/// Builds a [`FaultSummary`] from every step of the shear stage.
#[derive(bincode::Encode, bincode::Decode)]
struct SummaryBuilder {
    threshold: f64,
    rupture_step: Vec<Option<u64>>,
    peak: Vec<f64>,
    origin: Vec<[f64; 2]>,
    first: Vec<[f64; 2]>,
    last: Vec<NodeContact>,
}

impl SummaryBuilder {
    fn new(contacts: usize, threshold: f64) -> SummaryBuilder {
        SummaryBuilder {
            threshold,
            rupture_step: vec![None; contacts],
            peak: vec![0.0; contacts],
            origin: Vec::new(),
            first: Vec::new(),
            last: Vec::new(),
        }
    }

    /// Takes in the contact nodes at shear-stage step `j`.
    fn observe(&mut self, contacts: &[NodeContact], j: u64) {
        if self.origin.is_empty() {
            self.origin = contacts.iter().map(|c| [c.slip, c.slip_y]).collect();
            self.first = contacts.iter().map(|c| [c.friction_x, c.friction_y]).collect();
        }
        for (ci, c) in contacts.iter().enumerate() {
            let rate = c.slip_rate.hypot(c.slip_rate_y);
            if rate > self.peak[ci] {
                self.peak[ci] = rate;
            }
            if self.rupture_step[ci].is_none() && rate >= self.threshold {
                self.rupture_step[ci] = Some(j);
            }
        }
        self.last.clear();
        self.last.extend_from_slice(contacts);
    }

    fn finish(self, model: &crate::model::Model, dt: f64) -> FaultSummary {
        let lattice = model.lattice();
        let nodes = lattice.contact_nodes();
        let area_m2: Vec<f64> = nodes.iter().map(|&id| Face::ZMin.tributary_area(lattice, id)).collect();
        let n = nodes.len();
        let last = |ci: usize| self.last.get(ci).copied();
        FaultSummary {
            rupture_time_s: self.rupture_step.iter().map(|s| s.map_or(f64::NAN, |j| j as f64 * dt)).collect(),
            peak_slip_rate_m_s: self.peak,
            final_slip_m: (0..n)
                .map(|ci| match (last(ci), self.origin.get(ci)) {
                    (Some(c), Some(o)) => [c.slip - o[0], c.slip_y - o[1]],
                    _ => [0.0; 2],
                })
                .collect(),
            shear_stress_pa: (0..n)
                .map(|ci| {
                    let a = area_m2[ci];
                    let start = self.first.get(ci).map_or([0.0; 2], |f| [-f[0] / a, -f[1] / a]);
                    let end = last(ci).map_or([0.0; 2], |c| [-c.friction_x / a, -c.friction_y / a]);
                    [start, end]
                })
                .collect(),
            normal_stress_pa: (0..n).map(|ci| last(ci).map_or(0.0, |c| c.normal / area_m2[ci])).collect(),
            nodes,
            area_m2,
            rupture_rate_m_s: self.threshold,
        }
    }
}
