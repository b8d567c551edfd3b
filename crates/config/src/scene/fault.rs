//! `[fault]`, `[absorbing]` and `[[stations]]` checked: the base as one side of a planar fault with
//! its tractions (docs/model.md §15), the faces that let waves leave, and the named stations.

use std::path::Path;

use serde::{Deserialize, Serialize};
use stickslip_solver::fault::{Fault, Nucleation, Overstress, StochasticStress, overburden_share};
use stickslip_solver::geometry::{Lattice, NodeId, NodeKind};
use stickslip_solver::laws::{NodeFriction, RateStateStart};
use stickslip_solver::scene::{Component, ControlChannel, Kinematic, Station};

use super::SceneSections;
use crate::check::{Checker, approx, num};
use crate::friction_map::{Shape, TILE_POINTS, covers, patch_nodes, tile_points, tile_shares};
use crate::input::InputFile;

/// `[fault]`: the base face is one side of a planar fault between identical media, with these
/// initial tractions (docs/model.md §15). Its normal stress is prescribed (no base to lift from),
/// friction acts on the slip, twice the face's displacement; the scene has no gravity.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FaultSection {
    /// Normal traction on the fault, compression positive (Pa).
    pub normal_stress_pa: f64,
    /// Initial shear traction along +x (Pa). Default 0.
    #[serde(default)]
    pub shear_stress_pa: f64,
    /// Initial shear traction along +y (Pa). Default 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub shear_stress_y_pa: f64,
    /// The effective normal stress grows with depth from the surface (y = 0) at this gradient,
    /// `(ρ − ρ_water)·g` (Pa/m), until it reaches the normal stress; above that depth every
    /// traction scales down with it (docs/model.md §15.3). Absent: tractions do not vary with
    /// depth.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overburden_gradient_pa_m: Option<f64>,
    /// Regions with their own tractions, laid over the uniform values (and the grid) in order of
    /// priority.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub patches: Vec<TractionPatchSection>,
    /// Tractions per base node from a CSV file.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid: Option<TractionGridSection>,
    /// A random field on the shear traction, drawn per seed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub stochastic: Option<StochasticSection>,
    /// An overstressed square placed at random per seed: each seed's rupture starts elsewhere.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub nucleation: Option<NucleationSection>,
    /// A smooth overstress that grows over a rise time (SCEC TPV101–104's nucleation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub overstress: Option<OverstressSection>,
    /// The point `[x, y]` of the fault's plane that benchmark files measure along strike and down
    /// dip from (m), e.g. mid-strike at the surface for TPV5; within one face's width of the face
    /// (a half modelled by symmetry measures from beyond its edge). Default `[0, 0]`.
    #[serde(default, skip_serializing_if = "is_origin")]
    pub origin_m: [f64; 2],
}

fn is_origin(v: &[f64; 2]) -> bool {
    *v == [0.0, 0.0]
}

fn is_zero(v: &f64) -> bool {
    *v == 0.0
}

/// `[[fault.patches]]`: a rectangle or ellipse of the base with its own tractions (the ones it
/// names; the others keep what lies below).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct TractionPatchSection {
    /// Name shown by `check`. Default `patch[i]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `"rectangle"` (with `x_m`, `y_m`) or `"ellipse"` (with `centre_m`, `semi_axes_m`).
    pub shape: String,
    /// Rectangle: `[x_min, x_max]` (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_m: Option<[f64; 2]>,
    /// Rectangle: `[y_min, y_max]` (m). Default: the whole width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y_m: Option<[f64; 2]>,
    /// Ellipse: centre `[x, y]` (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre_m: Option<[f64; 2]>,
    /// Ellipse: semi-axes `[a_x, a_y]` (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub semi_axes_m: Option<[f64; 2]>,
    /// Shear traction along +x (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_stress_pa: Option<f64>,
    /// Shear traction along +y (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub shear_stress_y_pa: Option<f64>,
    /// Normal traction (Pa).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub normal_stress_pa: Option<f64>,
    /// Which patch holds where two overlap: the higher. Default 0.
    pub priority: i64,
}

/// `[fault.grid]`: tractions per base node from a CSV file with the header
/// `x_m,y_m,shear_stress_pa,shear_stress_y_pa,normal_stress_pa`, one row per base node.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct TractionGridSection {
    /// The CSV file, relative to the pipeline file's folder and inside it (see [`crate::input`]).
    /// Not part of the results hash (the rows are): a grid moved or copied gives the same results.
    pub file: String,
    /// The rows as read (filled in when the pipeline is loaded; part of the results hash).
    #[serde(skip_deserializing, default, skip_serializing_if = "Vec::is_empty")]
    pub rows: Vec<[f64; 5]>,
    /// Whether the file was refused (its refusal is the grid's only one).
    #[serde(skip)]
    pub refused: bool,
}

/// The traction grid's CSV header.
pub const TRACTION_GRID_HEADER: &str = "x_m,y_m,shear_stress_pa,shear_stress_y_pa,normal_stress_pa";

/// The traction grid's columns, in order, for messages.
const TRACTION_GRID_COLUMNS: [&str; 5] = ["x_m", "y_m", "shear_stress_pa", "shear_stress_y_pa", "normal_stress_pa"];

impl TractionGridSection {
    /// Reads the CSV file relative to `base` into `rows` (refusals into `ck`, which never echo the
    /// file's content) and returns the file as read.
    pub fn read(&mut self, base: &Path, ck: &mut Checker) -> Option<InputFile> {
        let per_row = "five finite numbers per row: x_m, y_m, shear_stress_pa, shear_stress_y_pa, normal_stress_pa";
        let read = crate::input::read_grid(
            ck,
            "fault.grid.file",
            &self.file,
            base,
            TRACTION_GRID_HEADER,
            &TRACTION_GRID_COLUMNS,
            per_row,
        );
        self.refused = read.is_none();
        let (input, rows) = read?;
        self.rows = rows;
        Some(input)
    }
}

/// `[fault.stochastic]`: a random field on the initial shear traction along x, drawn per seed,
/// with a von Kármán spectrum.
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct StochasticSection {
    /// Standard deviation over the face (Pa).
    pub std_pa: f64,
    /// Correlation length (m).
    pub correlation_length_m: f64,
    /// Hurst exponent, 0 < H ≤ 1. Default 0.75.
    #[serde(default = "default_hurst")]
    pub hurst: f64,
}

fn default_hurst() -> f64 {
    0.75
}

/// `[fault.nucleation]`: a square of side `size_m` whose shear traction along x is
/// `shear_stress_pa` (above the static strength, so the rupture starts there), its centre drawn
/// per seed uniformly in `x_m × y_m` (laid over the patches, the grid and the random field).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct NucleationSection {
    /// Side of the square (m).
    pub size_m: f64,
    /// Shear traction along x inside it (Pa).
    pub shear_stress_pa: f64,
    /// Range `[min, max]` of the centre along x (m).
    pub x_m: [f64; 2],
    /// Range `[min, max]` of the centre along y, down dip (m).
    pub y_m: [f64; 2],
}

/// `[fault.overstress]`: a shear traction along x added to the initial one,
/// `Δτ₀·F(r)·G(t)` with `F(r) = exp(r²/(r² − R²))` inside the radius R and
/// `G(t) = exp((t − T)²/(t(t − 2T)))` over the rise time T, 1 after (SCEC TPV101–104's
/// nucleation; docs/model.md §15).
#[derive(Clone, Copy, Debug, Serialize, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct OverstressSection {
    /// Centre `[x, y]` (m), on the fault.
    pub centre_m: [f64; 2],
    /// Radius R (m), at least 2·Lc.
    pub radius_m: f64,
    /// Δτ₀, the overstress at the centre once grown (Pa).
    pub shear_stress_pa: f64,
    /// Rise time T (s), ≥ 0 (0: all at once).
    pub rise_time_s: f64,
}

/// `[[stations]]`: named points whose displacement, velocity and acceleration (x, y, z) are
/// recorded at the record interval: one point (`at_m`), or a line of `count` points from
/// `from_m` to `to_m` (named `<name>-<i>`). Each is the nearest corner node.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct StationSection {
    /// Name (a line's points are `<name>-0`, `<name>-1`, …).
    pub name: String,
    /// One point `[x, y, z]` (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub at_m: Option<[f64; 3]>,
    /// A line's first point (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub from_m: Option<[f64; 3]>,
    /// A line's last point (m).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub to_m: Option<[f64; 3]>,
    /// Points on the line, ends included (≥ 2).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub count: Option<i64>,
    /// The station's V_S30 for its broadband records (m/s), one or several; absent: `[broadband]
    /// vs30_m_s`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vs30_m_s: Option<Vs30>,
}

/// One V_S30 or several.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum Vs30 {
    /// One site.
    One(f64),
    /// Several sites: one record per station and site.
    Many(Vec<f64>),
}

impl Vs30 {
    pub(crate) fn values(&self) -> Vec<f64> {
        match self {
            Vs30::One(v) => vec![*v],
            Vs30::Many(v) => v.clone(),
        }
    }
}

impl Default for Vs30 {
    fn default() -> Self {
        Vs30::One(760.0)
    }
}

/// The fault of `[fault]` on `lattice`'s base; `None` without one.
pub(super) fn fault(ck: &mut Checker, file: SceneSections<'_>, lattice: &Lattice) -> Option<Fault> {
    let f = file.fault.as_ref()?;
    if file.self_weight.gravity_m_s2 != 0.0 {
        ck.push(
            "self_weight.gravity_m_s2",
            file.self_weight.gravity_m_s2,
            "0 with [fault]: the fault's normal stress is prescribed, and a block on its side has no weight to \
             settle",
        );
    }
    if file.loading_plate.is_some() {
        ck.push(
            "loading_plate",
            "a [loading_plate] with [fault]",
            "no plate on a fault scene: its normal pressure would contradict the fault's prescribed normal stress \
             (load the fault by its tractions)",
        );
    }
    if file.skip_ahead.enabled {
        ck.push("skip_ahead.enabled", true, "false with [fault]: the skip-ahead follows a block on a rigid base");
    }
    ck.positive("fault.normal_stress_pa", f.normal_stress_pa);
    ck.range("fault.shear_stress_pa", f.shear_stress_pa, f64::NEG_INFINITY, true, f64::INFINITY, true);
    ck.range("fault.shear_stress_y_pa", f.shear_stress_y_pa, f64::NEG_INFINITY, true, f64::INFINITY, true);
    let n = lattice.contact_count();
    let mut shear = vec![[f.shear_stress_pa, f.shear_stress_y_pa]; n];
    let mut normal = vec![f.normal_stress_pa; n];
    if let Some(g) = f.grid.as_ref().filter(|g| !g.refused) {
        grid(ck, g, lattice, &mut shear, &mut normal);
    }
    let mut order: Vec<usize> = (0..f.patches.len()).collect();
    order.sort_by_key(|&i| f.patches[i].priority);
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); f.patches.len()];
    let mut shares: Vec<Vec<(usize, f64)>> = vec![Vec::new(); f.patches.len()];
    let shapes: Vec<Shape<'_>> = f
        .patches
        .iter()
        .map(|p| Shape { shape: &p.shape, x_m: p.x_m, y_m: p.y_m, centre_m: p.centre_m, semi_axes_m: p.semi_axes_m })
        .collect();
    for (i, p) in f.patches.iter().enumerate() {
        let field = format!("fault.patches[{i}]");
        members[i] = patch_nodes(ck, &field, &shapes[i], lattice);
        if ck.is_clean() {
            shares[i] = tile_shares(&shapes[i], lattice);
        }
        if p.shear_stress_pa.is_none() && p.shear_stress_y_pa.is_none() && p.normal_stress_pa.is_none() {
            ck.push(
                field.clone(),
                "a patch with no traction",
                "shear_stress_pa, shear_stress_y_pa or normal_stress_pa",
            );
        }
        if let Some(v) = p.shear_stress_pa {
            ck.range(&format!("{field}.shear_stress_pa"), v, f64::NEG_INFINITY, true, f64::INFINITY, true);
        }
        if let Some(v) = p.shear_stress_y_pa {
            ck.range(&format!("{field}.shear_stress_y_pa"), v, f64::NEG_INFINITY, true, f64::INFINITY, true);
        }
        if let Some(v) = p.normal_stress_pa {
            ck.positive(&format!("{field}.normal_stress_pa"), v);
        }
        for j in 0..i {
            let shared = members[i].iter().filter(|c| members[j].binary_search(c).is_ok()).count();
            if shared > 0 && f.patches[i].priority == f.patches[j].priority {
                ck.push(
                    format!("{field}.priority"),
                    p.priority,
                    format!(
                        "a priority other than patches[{j}]'s ({}): the two share {shared} base nodes, and the higher \
                         priority holds there",
                        f.patches[j].priority
                    ),
                );
            }
        }
    }
    // Each node's traction is the average over its tile of the patches laid in order of priority
    // over what lies below (docs/model.md §15.3): a node only one patch reaches blends by the
    // share of its tile the patch covers (exact); one that several reach, from the 16 × 16 points
    // of its tile, each taking the highest-priority patch that covers it and names the component.
    let mut reached = vec![0u32; n];
    for s in &shares {
        for &(c, _) in s {
            reached[c] += 1;
        }
    }
    let values = |p: &TractionPatchSection| [p.shear_stress_pa, p.shear_stress_y_pa, p.normal_stress_pa];
    let below: Vec<[f64; 3]> = (0..n).map(|c| [shear[c][0], shear[c][1], normal[c]]).collect();
    let mut set = |c: usize, k: usize, v: f64| match k {
        0 | 1 => shear[c][k] = v,
        _ => normal[c] = v,
    };
    for &i in &order {
        for &(c, w) in &shares[i] {
            if reached[c] != 1 {
                continue;
            }
            for (k, v) in values(&f.patches[i]).into_iter().enumerate() {
                if let Some(v) = v {
                    set(c, k, if w >= 1.0 { v } else { below[c][k] + w * (v - below[c][k]) });
                }
            }
        }
    }
    for c in (0..n).filter(|&c| reached[c] > 1) {
        let mut sum = [0.0; 3];
        for [x, y] in tile_points(lattice, c) {
            for (k, total) in sum.iter_mut().enumerate() {
                let top = order
                    .iter()
                    .rev()
                    .find_map(|&i| values(&f.patches[i])[k].filter(|_| covers(&shapes[i], x, y, lattice)));
                *total += top.unwrap_or(below[c][k]);
            }
        }
        for (k, total) in sum.into_iter().enumerate() {
            set(c, k, total / TILE_POINTS as f64);
        }
    }
    let depth_scale = match f.overburden_gradient_pa_m {
        Some(g) => overburden(ck, file, g, lattice, &mut shear, &mut normal),
        None => Vec::new(),
    };
    let stochastic = f.stochastic.map(|s| {
        ck.non_negative("fault.stochastic.std_pa", s.std_pa);
        if ck.positive("fault.stochastic.correlation_length_m", s.correlation_length_m)
            && s.correlation_length_m < 2.0 * lattice.lc()
        {
            ck.push(
                "fault.stochastic.correlation_length_m",
                s.correlation_length_m,
                format!(
                    "at least 2·Lc = {} m: a field the lattice cannot resolve is noise",
                    approx(2.0 * lattice.lc())
                ),
            );
        }
        ck.range("fault.stochastic.hurst", s.hurst, 0.0, true, 1.0, false);
        StochasticStress { std_pa: s.std_pa, correlation_length_m: s.correlation_length_m, hurst: s.hurst }
    });
    let e = lattice.extent();
    let nucleation = f.nucleation.map(|n| nucleation(ck, &n, lattice));
    let overstress = f.overstress.map(|o| overstress(ck, &o, lattice));
    // Within a face's width of it: a half modelled by symmetry measures from the whole fault's
    // origin, which may lie beyond its edge (TPV101 from its hypocentre's plane).
    let near = (0..2).all(|a| f.origin_m[a].is_finite() && f.origin_m[a] >= -e[a] && f.origin_m[a] <= 2.0 * e[a]);
    if !near {
        ck.push(
            "fault.origin_m",
            format!("{:?} m", f.origin_m),
            format!(
                "a point in the fault's plane within one face's width of it, −{0} ≤ x ≤ {1} m and −{2} ≤ y ≤ {3} m",
                num(e[0]),
                num(2.0 * e[0]),
                num(e[1]),
                num(2.0 * e[1])
            ),
        );
    }
    let overburden_gradient_pa_m = f.overburden_gradient_pa_m.filter(|_| !depth_scale.is_empty());
    Some(Fault {
        shear_pa: shear,
        normal_pa: normal,
        stochastic,
        nucleation,
        overstress,
        origin_m: f.origin_m,
        depth_scale,
        overburden_gradient_pa_m,
    })
}

/// `fault.overburden_gradient_pa_m` checked and applied: each node's tractions scaled by its
/// share at its depth (the mean over its tile of `min(1, g·d/σn)`, depth `d = y`), returned per
/// node for the seed's parts. The surface must be the free face y_min.
fn overburden(
    ck: &mut Checker,
    file: SceneSections<'_>,
    gradient: f64,
    lattice: &Lattice,
    shear: &mut [[f64; 2]],
    normal: &mut [f64],
) -> Vec<f64> {
    let field = "fault.overburden_gradient_pa_m";
    if !ck.range(field, gradient, 0.0, true, f64::INFINITY, true) {
        return Vec::new();
    }
    let absorbs_surface = file.absorbing.as_ref().is_some_and(|a| a.faces.iter().any(|f| f == "y_min"));
    let holds_surface = file.boundary.iter().any(|b| b.face == "y_min");
    let surface = file.medium.as_ref().and_then(|m| m.surface.as_deref());
    let not_free = if absorbs_surface {
        Some("an absorbing y_min".to_string())
    } else if holds_surface {
        Some("a y_min held by a [[boundary]] (a mirror plane is not the surface)".to_string())
    } else {
        surface.filter(|s| *s != "y_min").map(|s| format!("medium.surface = {s:?}"))
    };
    if let Some(not_free) = not_free {
        ck.push(
            field,
            num(gradient),
            format!("a scene whose Earth's surface is the free face y_min (depth is y on the fault), not {not_free}"),
        );
        return Vec::new();
    }
    let (half, width) = (0.5 * lattice.lc(), lattice.extent()[1]);
    (0..normal.len())
        .map(|c| {
            let y = lattice.position(lattice.contact_node(c))[1];
            let share = overburden_share(gradient, normal[c], (y - half).max(0.0), (y + half).min(width));
            normal[c] *= share;
            shear[c] = shear[c].map(|t| t * share);
            share
        })
        .collect()
}

/// `[fault.overstress]` checked: its centre on the fault, a radius the lattice resolves, a finite
/// overstress and rise time.
fn overstress(ck: &mut Checker, o: &OverstressSection, lattice: &Lattice) -> Overstress {
    let field = "fault.overstress";
    let e = lattice.extent();
    let [x, y] = o.centre_m;
    if !(x.is_finite() && y.is_finite() && (0.0..=e[0]).contains(&x) && (0.0..=e[1]).contains(&y)) {
        ck.push(
            format!("{field}.centre_m"),
            format!("[{}, {}]", num(x), num(y)),
            format!("a point of the fault, 0 ≤ x ≤ {} m and 0 ≤ y ≤ {} m", num(e[0]), num(e[1])),
        );
    }
    if ck.positive(&format!("{field}.radius_m"), o.radius_m) && o.radius_m < 2.0 * lattice.lc() {
        ck.push(
            format!("{field}.radius_m"),
            num(o.radius_m),
            format!("at least 2·Lc = {} m: a bump the lattice cannot resolve is one node", approx(2.0 * lattice.lc())),
        );
    }
    ck.range(&format!("{field}.shear_stress_pa"), o.shear_stress_pa, f64::NEG_INFINITY, true, f64::INFINITY, true);
    if o.shear_stress_pa == 0.0 {
        ck.push(format!("{field}.shear_stress_pa"), 0, "an overstress other than 0 (leave the section out)");
    }
    ck.range(&format!("{field}.rise_time_s"), o.rise_time_s, 0.0, false, f64::INFINITY, true);
    Overstress { centre_m: o.centre_m, radius_m: o.radius_m, overstress_pa: o.shear_stress_pa, rise_s: o.rise_time_s }
}

/// Refuses a rate-and-state start balanced against the initial traction
/// (`friction.rate_state.balanced_slip_rate_m_s`) without a fault, or on a fault with a node
/// whose shear traction is not positive (it cannot slide forward at any state).
pub(super) fn refuse_unbalanced_start(
    ck: &mut Checker,
    fault: Option<&Fault>,
    friction: &stickslip_solver::scene::Friction,
) {
    let NodeFriction::RateState(node) = friction.law.node(1.0) else { return };
    let RateStateStart::Balanced(v) = node.start else { return };
    let field = "friction.rate_state.balanced_slip_rate_m_s";
    match fault {
        None => ck.push(
            field,
            num(v),
            "a [fault] section: the start is balanced against a fault's initial shear and normal tractions \
             (on a rigid base use initial_slip_rate_m_s or initial_state_s)",
        ),
        Some(f) => {
            if let Some(c) = f.shear_pa.iter().position(|s| s[0].hypot(s[1]) <= 0.0) {
                ck.push(
                    "fault.shear_stress_pa",
                    format!("0 on base node {c}"),
                    format!("a shear traction > 0 on every node with {field}: a node slides at Vᵢ only under shear"),
                );
            }
        }
    }
}

/// On a fault, two fault stations (`record.fault_stations_m`, on different nodes) whose
/// benchmark file names coincide — `faultst<strike>dp<depth>` counts hectometres from
/// `[fault] origin_m` — would write one file over the other: the second is refused.
pub(super) fn refuse_shared_station_names(
    ck: &mut Checker,
    at_m: &[[f64; 2]],
    nodes: &[NodeId],
    fault: Option<&Fault>,
    lattice: &Lattice,
) {
    // With a station refused (outside, or on a taken node) the record has said what is wrong.
    let Some(f) = fault.filter(|_| nodes.len() == at_m.len()) else { return };
    let mut names: Vec<String> = Vec::new();
    for (i, (&node, p)) in nodes.iter().zip(at_m).enumerate() {
        let q = lattice.position(node);
        let name = stickslip_seismo::scec::fault_station_name(q[0] - f.origin_m[0], q[1] - f.origin_m[1]);
        if let Some(j) = names.iter().position(|n| *n == name) {
            ck.push(
                format!("record.fault_stations_m[{i}]"),
                format!("[{}, {}] m", num(p[0]), num(p[1])),
                format!(
                    "a station whose benchmark file differs from station {j}'s ({name}.dat): the names count \
                     hectometres from [fault] origin_m, so fault stations lie at least 100 m apart"
                ),
            );
        }
        names.push(name);
    }
}

/// One station point of `[[stations]]` before it is placed on a node.
struct StationPoint {
    /// The station's name (`<name>-<k>` for a line's points).
    name: String,
    /// Its position (m).
    at: [f64; 3],
    /// The field a refusal names.
    field: String,
    /// Index of its `[[stations]]` entry.
    index: usize,
    /// The position as a refusal shows it.
    shown: String,
}

/// `[fault.nucleation]` checked: a square of at least 2·Lc whose centre's range keeps it on the
/// fault, with a positive traction (whether it exceeds the strength where it lands is the
/// friction map's business: `check` prints the nucleation).
fn nucleation(ck: &mut Checker, n: &NucleationSection, lattice: &Lattice) -> Nucleation {
    let e = lattice.extent();
    let lc = lattice.lc();
    if ck.positive("fault.nucleation.size_m", n.size_m) && n.size_m < 2.0 * lc {
        ck.push(
            "fault.nucleation.size_m",
            num(n.size_m),
            format!(
                "at least 2·Lc = {} m: a square the lattice cannot resolve does not start a rupture",
                approx(2.0 * lc)
            ),
        );
    }
    ck.positive("fault.nucleation.shear_stress_pa", n.shear_stress_pa);
    let half = 0.5 * n.size_m.max(0.0);
    for (a, (field, r)) in [("fault.nucleation.x_m", n.x_m), ("fault.nucleation.y_m", n.y_m)].into_iter().enumerate() {
        let (lo, hi) = (half, e[a] - half);
        let ok = r.iter().all(|v| v.is_finite()) && r[0] <= r[1] && r[0] >= lo - 1e-9 * lc && r[1] <= hi + 1e-9 * lc;
        if !ok {
            ck.push(
                field,
                format!("[{}, {}] m", num(r[0]), num(r[1])),
                format!(
                    "min ≤ max within [{}, {}] m, so that the square (side {} m) stays on the fault",
                    approx(lo),
                    approx(hi),
                    approx(n.size_m)
                ),
            );
        }
    }
    Nucleation { size_m: n.size_m, shear_pa: n.shear_stress_pa, x_m: n.x_m, y_m: n.y_m }
}

/// The grid's tractions laid on `shear` and `normal`, every row checked.
fn grid(ck: &mut Checker, g: &TractionGridSection, lattice: &Lattice, shear: &mut [[f64; 2]], normal: &mut [f64]) {
    let field = "fault.grid.file";
    let n = shear.len();
    if g.rows.len() != n {
        ck.push(
            field,
            format!("{:?} with {} rows", g.file, g.rows.len()),
            format!(
                "one row per base node: {n} rows for this block ({} × {} corner nodes every Lc = {} m)",
                lattice.dims().nx + 1,
                lattice.dims().ny + 1,
                approx(lattice.lc())
            ),
        );
        return;
    }
    let mut seen = vec![false; n];
    for (i, row) in g.rows.iter().enumerate() {
        let c = lattice.node_at([row[0], row[1], 0.0]).map(|id| id.index()).filter(|&c| c < n);
        let Some(c) = c else {
            let e = lattice.extent();
            ck.push(
                field,
                format!("row {}: x = {} m, y = {} m", i + 1, num(row[0]), num(row[1])),
                format!(
                    "a base node, 0 ≤ x ≤ {} m and 0 ≤ y ≤ {} m, on the lattice (every {} m)",
                    approx(e[0]),
                    approx(e[1]),
                    approx(lattice.lc())
                ),
            );
            continue;
        };
        if std::mem::replace(&mut seen[c], true) {
            ck.push(
                field,
                format!("row {}: x = {} m, y = {} m", i + 1, num(row[0]), num(row[1])),
                "each base node once",
            );
        }
        if !(row[4] > 0.0) {
            ck.push(field, format!("row {}: normal_stress_pa = {}", i + 1, num(row[4])), "a positive normal stress");
        }
        shear[c] = [row[2], row[3]];
        normal[c] = row[4];
    }
}

/// The stations of `[[stations]]` (sorted by node) and the control channels that record them:
/// displacement, velocity and acceleration, x, y and z. A point outside the block, a name used
/// twice and two stations on one node (a spacing finer than the lattice) are refused.
pub(super) fn stations(
    ck: &mut Checker,
    file: SceneSections<'_>,
    lattice: &Lattice,
) -> (Vec<Station>, Vec<ControlChannel>) {
    let e = lattice.extent();
    let lc = lattice.lc();
    let inside = |p: [f64; 3]| (0..3).all(|a| p[a].is_finite() && p[a] >= -1e-9 * lc && p[a] <= e[a] + 1e-9 * lc);
    let block_text = || {
        format!(
            "a point of the block, 0 ≤ x ≤ {} m, 0 ≤ y ≤ {} m, 0 ≤ z ≤ {} m",
            approx(e[0]),
            approx(e[1]),
            approx(e[2])
        )
    };
    let mut out: Vec<StationPoint> = Vec::new();
    for (i, s) in file.stations.iter().enumerate() {
        let field = format!("stations[{i}]");
        let valid_name = !s.name.is_empty() && s.name.chars().all(|c| c.is_ascii_alphanumeric() || "-_.".contains(c));
        if !valid_name {
            ck.push(format!("{field}.name"), format!("{:?}", s.name), "a name of letters, digits, '-', '_' or '.'");
        }
        match (s.at_m, s.from_m, s.to_m, s.count) {
            (Some(p), None, None, None) => out.push(StationPoint {
                name: s.name.clone(),
                at: p,
                field: format!("{field}.at_m"),
                index: i,
                shown: format!("{p:?}"),
            }),
            (None, Some(a), Some(b), Some(count)) => {
                let Some(count) =
                    ck.count(&format!("{field}.count"), count, 2, 100_000, " (points on the line, ends included)")
                else {
                    continue;
                };
                // Both ends in the block put every point of the line in it (the block is convex);
                // a point on a node already taken says the line has too many points.
                let mut ends_inside = true;
                for (key, end) in [("from_m", a), ("to_m", b)] {
                    if !inside(end) {
                        ends_inside = false;
                        ck.push(format!("{field}.{key}"), format!("{end:?} m"), block_text());
                    }
                }
                if !ends_inside {
                    continue;
                }
                for k in 0..count {
                    let t = k as f64 / (count - 1) as f64;
                    let p = [0, 1, 2].map(|a_| a[a_] + t * (b[a_] - a[a_]));
                    let shown = format!("[{}, {}, {}]", approx(p[0]), approx(p[1]), approx(p[2]));
                    out.push(StationPoint {
                        name: format!("{}-{k}", s.name),
                        at: p,
                        field: format!("{field}.count"),
                        index: i,
                        shown,
                    });
                }
            }
            _ => ck.push(
                field,
                "neither a point nor a line",
                "at_m = [x, y, z], or from_m, to_m and count for a line of stations",
            ),
        }
    }
    let mut stations: Vec<Station> = Vec::new();
    for StationPoint { name, at: p, field, index: i, shown } in out {
        if !inside(p) {
            ck.push(field, format!("{shown} m"), block_text());
            continue;
        }
        // The nearest corner node.
        let snap = |v: f64| (v / lc).round() * lc;
        let Some(node) = lattice.node_at([snap(p[0]), snap(p[1]), snap(p[2])]) else { continue };
        debug_assert!(matches!(lattice.kind(node), NodeKind::Corner(_)));
        if let Some(other) = stations.iter().find(|s| s.node == node) {
            let q = lattice.position(node);
            ck.push(
                field,
                format!("{name} at {shown} m"),
                format!(
                    "a station on its own node: {} is already at the nearest node ({}, {}, {}) m (stations closer than \
                     the lattice spacing Lc = {} m are one)",
                    other.name,
                    approx(q[0]),
                    approx(q[1]),
                    approx(q[2]),
                    approx(lc)
                ),
            );
            continue;
        }
        if stations.iter().any(|s| s.name == name) {
            ck.push(
                format!("stations[{i}].name"),
                format!("{name:?}"),
                "a name no other station has (a line's points are named <name>-0, <name>-1, …)",
            );
            continue;
        }
        stations.push(Station { name, node });
    }
    stations.sort_by_key(|s| s.node);
    let mut control = Vec::new();
    for s in &stations {
        for quantity in Kinematic::ALL {
            for component in Component::ALL {
                control.push(ControlChannel { node: s.node, quantity, component });
            }
        }
    }
    (stations, control)
}

/// The fewest nodes across a rate-and-state fault's process zone `Λ₀` accepted: below it the
/// lattice does not resolve the rupture front (Day et al. 2005's criterion for slip weakening;
/// Lapusta & Liu 2009 ask 3–5 for rate and state).
pub const LEAST_ZONE_NODES: f64 = 3.0;

/// Refuses a fault under a rate-and-state law whose node spacing `Lc` does not resolve the law's
/// process zone `Λ₀ = (9π/32)·μ·L/(b·σn)` at the fault's largest normal stress
/// ([`LEAST_ZONE_NODES`] nodes), naming both sizes and the nucleation size `h*`.
pub(super) fn refuse_unresolved_rate_state(
    ck: &mut Checker,
    fault: Option<&Fault>,
    friction: &stickslip_solver::scene::Friction,
    material: &super::MaterialSection,
    lc_m: f64,
) {
    let Some(fault) = fault else { return };
    if !crate::laws::of(&friction.law).zone_refused {
        return;
    }
    let (_, _, c44) = stickslip_solver::material::lattice_elastic_constants(material.young_pa, material.poisson);
    let sigma = fault.normal_pa.iter().copied().fold(0.0, f64::max);
    // The smallest process zone over the base: the law's, or a patch's or grid row's.
    let background = [friction.law.node(1.0)];
    let nodes = friction.map.as_ref().map_or(&background[..], |m| &m.nodes[..]);
    let smallest =
        nodes.iter().filter_map(|n| n.cohesive_zone_m(c44, sigma).map(|z| (*n, z))).min_by(|a, b| a.1.total_cmp(&b.1));
    let Some((node, zone)) = smallest else { return };
    if zone < LEAST_ZONE_NODES * lc_m {
        let nucleation = node
            .nucleation_m(c44, sigma)
            .map(|h| format!(", nucleation size h* = {} m", approx(h)))
            .unwrap_or_default();
        ck.push(
            "block.lc_m",
            num(lc_m),
            format!(
                "at most Λ₀/{LEAST_ZONE_NODES} = {} m under rate-and-state friction: the process zone \
                 Λ₀ = (9π/32)·μ·L/(b·σn) = {} m at σn = {} Pa{nucleation}, the smallest over the base's \
                 nodes (a longer friction.rate_state.dc_m, in patches and grid rows too, or smaller modules \
                 resolve it)",
                approx(zone / LEAST_ZONE_NODES),
                approx(zone),
                approx(sigma)
            ),
        );
    }
}
