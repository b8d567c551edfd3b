//! The rupture front of every event of a seed (docs/model.md §13): the base as a fault (node
//! positions, tributary areas, barrier regions of the friction map), the lattice's wave speeds,
//! and [`stickslip_seismo::front::front`] applied to each event's window.

use stickslip_seismo::events::Catalogue;
use stickslip_seismo::events::EventKind;
use stickslip_seismo::front::{Fault, Front, WaveSpeeds, front, rate_onsets};
use stickslip_solver::dispersion::LatticeMaterial;
use stickslip_solver::geometry::Face;
use stickslip_solver::laws::RegionKind;
use stickslip_solver::{Model, NodeId, Recording};

/// The base of a scene seen as a fault.
#[derive(Clone, Debug, PartialEq)]
pub struct FaultBase {
    /// Contact nodes, canonical contact order.
    pub ids: Vec<NodeId>,
    /// `(x, y)` of each (m).
    pub position_m: Vec<[f64; 2]>,
    /// Tributary area of each (m²).
    pub area_m2: Vec<f64>,
    /// Whether each lies in a barrier region of the friction map.
    pub barrier: Vec<bool>,
    /// Region name of each: `background` or the map's.
    pub region: Vec<String>,
}

impl FaultBase {
    /// The base of `model`.
    pub fn of(model: &Model) -> FaultBase {
        let lattice = model.lattice();
        let ids = lattice.contact_nodes();
        let map = model.scene().friction.map.as_ref();
        let region_of = |c: usize| map.and_then(|m| m.region[c]).map(|r| &map.expect("a map").regions[r as usize]);
        FaultBase {
            position_m: ids.iter().map(|&id| lattice.position(id)).map(|p| [p[0], p[1]]).collect(),
            area_m2: ids.iter().map(|&id| Face::ZMin.tributary_area(lattice, id)).collect(),
            barrier: (0..ids.len()).map(|c| region_of(c).is_some_and(|r| r.kind == RegionKind::Barrier)).collect(),
            region: (0..ids.len())
                .map(|c| region_of(c).map_or_else(|| "background".to_string(), |r| r.name.clone()))
                .collect(),
            ids,
        }
    }

    /// As the front analysis reads it.
    pub fn fault(&self) -> Fault<'_> {
        Fault { position_m: &self.position_m, area_m2: &self.area_m2, barrier: &self.barrier }
    }
}

/// The lattice's long-wave P and S speeds along x at the scene's nominal E (the speeds of the
/// cubic lattice's `C11` and `C44`), with the Rayleigh speed of an isotropic solid of the same
/// two (exact at ν = 0.25, where the lattice is isotropic).
pub fn wave_speeds(model: &Model) -> WaveSpeeds {
    let s = model.scene();
    let (c_p, c_s) = LatticeMaterial::new(s.young_pa, s.poisson, s.density_kg_m3, s.lc_m)
        .map(|m| m.long_wave_speeds_m_s())
        .unwrap_or((f64::NAN, f64::NAN));
    WaveSpeeds::new(c_p, c_s)
}

/// The front of event `event` of kind `kind`, as the tables take it.
#[derive(Clone, Copy, Debug)]
pub struct EventFront<'a> {
    /// Index of the event in the seed's catalogue.
    pub event: u32,
    /// Its kind.
    pub kind: EventKind,
    /// Its front.
    pub front: &'a Front,
}

/// The fronts of one seed's events.
#[derive(Clone, Debug, PartialEq)]
pub struct SeedFronts {
    /// `(event index, front)` of every event in which a node started to slide.
    pub fronts: Vec<(usize, Front)>,
    /// The wave speeds they are classed against.
    pub speeds: WaveSpeeds,
    /// The base they ran over.
    pub base: FaultBase,
    /// What the nodes' rupture times were read on: `slip_rate` (the recorded fault's slip rates
    /// reaching `[events] rupture_rate_m_s`) or `slip_onsets` (sustained slip onsets).
    pub source: &'static str,
}

impl SeedFronts {
    /// The fronts with their events' kinds, as the tables take them.
    pub fn rows<'a>(&'a self, catalogue: &Catalogue) -> Vec<EventFront<'a>> {
        self.fronts
            .iter()
            .map(|(k, f)| EventFront { event: *k as u32, kind: catalogue.events[*k].kind, front: f })
            .collect()
    }
}

/// The front of every event of `catalogue` in its window `[start − smoothing, end]` (an event's
/// start is read on the smoothed rate: its first node may start up to that much earlier). The
/// nodes' rupture times are read on the fault's slip rates when the scene records the fault (the
/// first time each reaches `rupture_rate_m_s`), else on the sustained slip onsets; `None` when it
/// records neither.
pub fn fronts(
    rec: &Recording,
    catalogue: &Catalogue,
    model: &Model,
    smoothing_s: f64,
    rupture_rate_m_s: f64,
) -> Option<SeedFronts> {
    let base = FaultBase::of(model);
    let index: std::collections::HashMap<NodeId, usize> = base.ids.iter().enumerate().map(|(i, &id)| (id, i)).collect();
    let (onsets, source): (Vec<(f64, usize)>, _) = match &rec.trace.fault {
        Some(f) => {
            // The trace's node order is the model's contact order; the base's is canonical.
            let mut rates: Vec<&[f64]> = vec![&[]; base.ids.len()];
            for (id, r) in f.nodes.iter().zip(&f.slip_rate_m_s) {
                rates[index[id]] = r;
            }
            (rate_onsets(&rec.trace.time_s, &rates, rupture_rate_m_s), "slip_rate")
        }
        None if model.scene().record.slip_onsets => {
            (rec.onsets.iter().filter_map(|&(t, id)| index.get(&id).map(|&i| (t, i))).collect(), "slip_onsets")
        }
        None => return None,
    };
    let fault = base.fault();
    let fronts = catalogue
        .events
        .iter()
        .enumerate()
        .filter_map(|(k, e)| front(&onsets, &fault, e.burst.start_s - smoothing_s, e.burst.end_s).map(|f| (k, f)))
        .collect();
    Some(SeedFronts { fronts, speeds: wave_speeds(model), source, base })
}
