//! Friction maps of the base (`[[friction.patches]]`, `[friction.grid]`, and under a rate-and-state
//! law `[friction.rate_state_grid]`): regions with their own μs, μd and Dc (or a, b, L and f₀) —
//! asperities (weak or strong patches where rupture starts) and barriers (strong
//! patches where it stops), after Aki (1979) — built into a per-node [`FrictionMap`] that the
//! Weibull field on μ then multiplies.
//!
//! The grid (a CSV file, one row per base node) replaces the `[friction]` law everywhere; patches
//! are laid over it (or over the law) in order of `priority`. Two patches that share a base node
//! need different priorities: the higher one holds there. A patch must lie on the base and hold
//! at least one base node.

use std::path::Path;

use serde::{Deserialize, Serialize};
use stickslip_solver::geometry::Lattice;
use stickslip_solver::laws::{FrictionLaw, FrictionMap, NodeFriction, Region, RegionKind};

use crate::check::{Checker, approx, num};
use crate::input::InputFile;

/// `[[friction.patches]]`: a region of the base with its own coefficients.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields, default)]
pub struct PatchSection {
    /// Name shown by `check` and in tables. Default `patch[i]`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// `"rectangle"` (with `x_m`, `y_m`) or `"ellipse"` (with `centre_m`, `semi_axes_m`).
    pub shape: String,
    /// Rectangle: `[x_min, x_max]` in metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub x_m: Option<[f64; 2]>,
    /// Rectangle: `[y_min, y_max]` in metres. Default: the whole width.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub y_m: Option<[f64; 2]>,
    /// Ellipse: centre `[x, y]` in metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub centre_m: Option<[f64; 2]>,
    /// Ellipse: semi-axes `[a_x, a_y]` in metres.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub semi_axes_m: Option<[f64; 2]>,
    /// μs of the patch (required under the slip-weakening laws; left out under rate and state).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mu_static: Option<f64>,
    /// μd ≤ μs of the patch. Default: μs (no weakening).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mu_dynamic: Option<f64>,
    /// Dc of the patch (m). Default: the `[friction]` law's.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub slip_weakening_m: Option<f64>,
    /// Which patch holds where two overlap: the higher. Default 0.
    pub priority: i64,
    /// `[friction.patches.rate_state]`: the patch's rate-and-state coefficients (under a
    /// rate-and-state law).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rate_state: Option<crate::laws::RateStatePatch>,
    /// A rectangle's smooth edge (m): over this width outside each side inside the base, its
    /// rate-and-state coefficients blend into what lies below by SCEC TPV101–104's boxcar
    /// ([`boxcar`]). Default: a sharp edge.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub transition_m: Option<f64>,
}

/// SCEC TPV101–104's smooth boxcar at `d` metres outside an interval with a transition of `w`:
/// 1 inside (`d ≤ 0`), `½·[1 + tanh(w/(d − w) + w/d)]` for `0 < d < w`, 0 from `w` on. Every
/// derivative is continuous.
pub fn boxcar(d: f64, w: f64) -> f64 {
    if d <= 0.0 {
        1.0
    } else if d >= w {
        0.0
    } else {
        0.5 * (1.0 + (w / (d - w) + w / d).tanh())
    }
}

/// Each base node's weight of a rectangle patch `x_m × y_m` with a smooth edge `w`:
/// `B(dx; w)·B(dy; w)` ([`boxcar`]), `dx`, `dy` its distances outside the rectangle, for the
/// nodes where it is not 0 (indices into [`Lattice::contact_nodes`]).
fn smooth_weights(lattice: &Lattice, x_m: [f64; 2], y_m: [f64; 2], w: f64) -> Vec<(usize, f64)> {
    let eps = 1e-9 * lattice.lc();
    let outside = |v: f64, [lo, hi]: [f64; 2]| {
        let d = (lo - v).max(v - hi);
        if d <= eps { 0.0 } else { d }
    };
    (0..lattice.contact_count())
        .filter_map(|c| {
            let q = lattice.position(lattice.contact_node(c));
            let weight = boxcar(outside(q[0], x_m), w) * boxcar(outside(q[1], y_m), w);
            (weight > 0.0).then_some((c, weight))
        })
        .collect()
}

/// `below`'s coefficients moved a share `w` of the way to `patch`'s: a, b, L and f₀ of two
/// rate-and-state nodes (the rest is the patch's); `None` under other laws.
fn blend(below: &NodeFriction, patch: &NodeFriction, w: f64) -> Option<NodeFriction> {
    let (NodeFriction::RateState(lo), NodeFriction::RateState(hi)) = (below, patch) else { return None };
    let mix = |a: f64, b: f64| if w >= 1.0 { b } else { a + w * (b - a) };
    Some(NodeFriction::RateState(stickslip_solver::laws::RateStateNode {
        a: mix(lo.a, hi.a),
        b: mix(lo.b, hi.b),
        dc_m: mix(lo.dc_m, hi.dc_m),
        f0: mix(lo.f0, hi.f0),
        ..*hi
    }))
}

/// `[friction.grid]`: coefficients per base node from a CSV file with the header
/// `x_m,y_m,mu_static,mu_dynamic,slip_weakening_m` and one row per base node (any order).
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct GridSection {
    /// The CSV file, relative to the pipeline file's folder and inside it (see [`crate::input`]).
    /// Not part of the results hash (the rows are): a grid moved or copied gives the same results.
    pub file: String,
    /// The rows as read (filled in when the pipeline is loaded; part of the results hash, so a
    /// changed file changes the hash).
    #[serde(skip_deserializing, default, skip_serializing_if = "Vec::is_empty")]
    pub rows: Vec<[f64; 5]>,
    /// Whether the file was refused (its refusal is the grid's only one).
    #[serde(skip)]
    pub refused: bool,
}

/// The grid's CSV header.
pub const GRID_HEADER: &str = "x_m,y_m,mu_static,mu_dynamic,slip_weakening_m";

/// The grid's columns, in order, for messages.
const GRID_COLUMNS: [&str; 5] = ["x_m", "y_m", "mu_static", "mu_dynamic", "slip_weakening_m"];

impl GridSection {
    /// Reads the CSV file relative to `base` into `rows` (refusals into `ck`, which never echo the
    /// file's content) and returns the file as read.
    pub fn read(&mut self, base: &Path, ck: &mut Checker) -> Option<InputFile> {
        let per_row = "five finite numbers per row, x_m, y_m, μs, μd, Dc";
        let read =
            crate::input::read_grid(ck, "friction.grid.file", &self.file, base, GRID_HEADER, &GRID_COLUMNS, per_row);
        self.refused = read.is_none();
        let (input, rows) = read?;
        self.rows = rows;
        Some(input)
    }
}

/// `[friction.rate_state_grid]`: rate-and-state coefficients per base node from a CSV file with
/// the header `x_m,y_m,a,b,dc_m,f0` and one row per base node (any order), under a rate-and-state
/// law.
#[derive(Clone, Debug, Serialize, Deserialize, PartialEq, Default)]
#[serde(deny_unknown_fields)]
pub struct RateStateGridSection {
    /// The CSV file, as [`GridSection::file`].
    pub file: String,
    /// The rows as read (filled in when the pipeline is loaded; part of the results hash).
    #[serde(skip_deserializing, default, skip_serializing_if = "Vec::is_empty")]
    pub rows: Vec<[f64; 6]>,
    /// Whether the file was refused.
    #[serde(skip)]
    pub refused: bool,
}

/// The rate-and-state grid's CSV header.
pub const RATE_STATE_GRID_HEADER: &str = "x_m,y_m,a,b,dc_m,f0";

impl RateStateGridSection {
    /// Reads the CSV file relative to `base` into `rows`, as [`GridSection::read`].
    pub fn read(&mut self, base: &Path, ck: &mut Checker) -> Option<InputFile> {
        let per_row = "six finite numbers per row, x_m, y_m, a, b, L (dc_m), f₀";
        let columns = ["x_m", "y_m", "a", "b", "dc_m", "f0"];
        let field = "friction.rate_state_grid.file";
        let read = crate::input::read_grid(ck, field, &self.file, base, RATE_STATE_GRID_HEADER, &columns, per_row);
        self.refused = read.is_none();
        let (input, rows) = read?;
        self.rows = rows;
        Some(input)
    }
}

/// The rows of a grid of either kind: each base node's position and its coefficients as a
/// patch's keys.
pub(crate) struct GridRows<'a> {
    /// `friction.grid.file` or `friction.rate_state_grid.file`.
    pub field: &'static str,
    /// The file as given.
    pub file: &'a str,
    /// `(x, y, keys)` per row.
    pub rows: Vec<(f64, f64, crate::laws::RegionKeys)>,
}

impl GridSection {
    /// Its rows as a patch's keys.
    pub(crate) fn rows(&self) -> GridRows<'_> {
        let rows = self
            .rows
            .iter()
            .map(|r| {
                let keys = crate::laws::RegionKeys {
                    mu_static: Some(r[2]),
                    mu_dynamic: Some(r[3]),
                    slip_weakening_m: Some(r[4]),
                    rate_state: None,
                };
                (r[0], r[1], keys)
            })
            .collect();
        GridRows { field: "friction.grid.file", file: &self.file, rows }
    }
}

impl RateStateGridSection {
    /// Its rows as a patch's keys.
    pub(crate) fn rows(&self) -> GridRows<'_> {
        let rows = self
            .rows
            .iter()
            .map(|r| {
                let rate_state =
                    crate::laws::RateStatePatch { a: Some(r[2]), b: Some(r[3]), dc_m: Some(r[4]), f0: Some(r[5]) };
                let keys = crate::laws::RegionKeys {
                    mu_static: None,
                    mu_dynamic: None,
                    slip_weakening_m: None,
                    rate_state: Some(rate_state),
                };
                (r[0], r[1], keys)
            })
            .collect();
        GridRows { field: "friction.rate_state_grid.file", file: &self.file, rows }
    }
}

fn describe_base(lattice: &Lattice) -> String {
    let e = lattice.extent();
    format!("inside the base, 0 ≤ x ≤ {} m and 0 ≤ y ≤ {} m", approx(e[0]), approx(e[1]))
}

/// Coefficients of one region under the background `law`'s law, checked; `field` is its
/// section's name.
fn coefficients(ck: &mut Checker, field: &str, keys: crate::laws::RegionKeys, law: &FrictionLaw) -> NodeFriction {
    (crate::laws::of(law).region)(ck, field, &keys, law)
}

/// The shape of a patch of the base (friction patches, fault traction patches).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Shape<'a> {
    /// `"rectangle"` or `"ellipse"`.
    pub shape: &'a str,
    /// Rectangle: `[x_min, x_max]` (m).
    pub x_m: Option<[f64; 2]>,
    /// Rectangle: `[y_min, y_max]` (m); the whole width when absent.
    pub y_m: Option<[f64; 2]>,
    /// Ellipse: centre (m).
    pub centre_m: Option<[f64; 2]>,
    /// Ellipse: semi-axes (m).
    pub semi_axes_m: Option<[f64; 2]>,
}

impl PatchSection {
    fn shape(&self) -> Shape<'_> {
        Shape {
            shape: &self.shape,
            x_m: self.x_m,
            y_m: self.y_m,
            centre_m: self.centre_m,
            semi_axes_m: self.semi_axes_m,
        }
    }
}

/// Whether the base point `(x, y)` lies in the patch (boundary included, to a part in 10⁹ of Lc).
fn contains(p: &Shape<'_>, x: f64, y: f64, width: f64, eps: f64) -> bool {
    match p.shape {
        "rectangle" => {
            let [x0, x1] = p.x_m.unwrap_or([0.0, 0.0]);
            let [y0, y1] = p.y_m.unwrap_or([0.0, width]);
            x >= x0 - eps && x <= x1 + eps && y >= y0 - eps && y <= y1 + eps
        }
        _ => {
            let [cx, cy] = p.centre_m.unwrap_or([0.0, 0.0]);
            let [a, b] = p.semi_axes_m.unwrap_or([1.0, 1.0]);
            let (dx, dy) = ((x - cx) / a, (y - cy) / b);
            dx * dx + dy * dy <= 1.0 + eps / a.min(b)
        }
    }
}

/// The share of each base node's tile (its Lc × Lc tributary area, clipped to the face) that the
/// patch `p` covers, for every node it covers at all (indices into [`Lattice::contact_nodes`]):
/// exact for a rectangle, from 16 × 16 points of the tile for an ellipse. A traction laid over a
/// node in proportion to its share is the patch's traction integrated over the node's area, so a
/// 3 km square covers 3 km at any spacing (by node membership it would cover 3 km + Lc when its
/// sides fall on nodes).
pub(crate) fn tile_shares(p: &Shape<'_>, lattice: &Lattice) -> Vec<(usize, f64)> {
    let e = lattice.extent();
    let overlap = |lo: f64, hi: f64, a: f64, b: f64| (hi.min(b) - lo.max(a)).max(0.0);
    (0..lattice.contact_count())
        .filter_map(|c| {
            let [[x0, x1], [y0, y1]] = tile(lattice, c);
            let area = (x1 - x0) * (y1 - y0);
            let share = match p.shape {
                "rectangle" => {
                    let [a0, a1] = p.x_m.unwrap_or([0.0, 0.0]);
                    let [b0, b1] = p.y_m.unwrap_or([0.0, e[1]]);
                    overlap(x0, x1, a0, a1) * overlap(y0, y1, b0, b1) / area
                }
                _ => {
                    // Only tiles that reach the ellipse's bounding box are sampled.
                    let [cx, cy] = p.centre_m.unwrap_or([0.0, 0.0]);
                    let [a, b] = p.semi_axes_m.unwrap_or([1.0, 1.0]);
                    if overlap(x0, x1, cx - a, cx + a) * overlap(y0, y1, cy - b, cy + b) == 0.0 {
                        return None;
                    }
                    let inside = tile_points(lattice, c).filter(|&[x, y]| covers(p, x, y, lattice)).count();
                    inside as f64 / TILE_POINTS as f64
                }
            };
            (share > 0.0 && area > 0.0).then_some((c, share.min(1.0)))
        })
        .collect()
}

/// Base node `c`'s tile, `[[x0, x1], [y0, y1]]` (m): its Lc × Lc tributary area clipped to the
/// face (`c` indexes [`Lattice::contact_nodes`]).
pub(crate) fn tile(lattice: &Lattice, c: usize) -> [[f64; 2]; 2] {
    let (e, h) = (lattice.extent(), 0.5 * lattice.lc());
    let q = lattice.position(lattice.contact_node(c));
    [[(q[0] - h).max(0.0), (q[0] + h).min(e[0])], [(q[1] - h).max(0.0), (q[1] + h).min(e[1])]]
}

/// How many points of a tile [`tile_points`] gives (16 × 16).
pub(crate) const TILE_POINTS: usize = 256;

/// The 16 × 16 cell midpoints of base node `c`'s tile (its Lc × Lc tributary area clipped to the
/// face; `c` indexes [`Lattice::contact_nodes`]). A side through the tile's centre or along its
/// edge splits them exactly.
pub(crate) fn tile_points(lattice: &Lattice, c: usize) -> impl Iterator<Item = [f64; 2]> {
    let [[x0, x1], [y0, y1]] = tile(lattice, c);
    (0..TILE_POINTS).map(move |k| {
        [x0 + (x1 - x0) * ((k % 16) as f64 + 0.5) / 16.0, y0 + (y1 - y0) * ((k / 16) as f64 + 0.5) / 16.0]
    })
}

/// Whether the base point `(x, y)` lies in the patch `p` (no tolerance).
pub(crate) fn covers(p: &Shape<'_>, x: f64, y: f64, lattice: &Lattice) -> bool {
    contains(p, x, y, lattice.extent()[1], 0.0)
}

/// The base nodes (indices into [`Lattice::contact_nodes`]) a patch `p` named `field` holds,
/// its shape checked: a rectangle or an ellipse on the base that holds at least one base node.
pub(crate) fn patch_nodes(ck: &mut Checker, field: &str, p: &Shape<'_>, lattice: &Lattice) -> Vec<usize> {
    let contact = lattice.contact_nodes();
    let e = lattice.extent();
    let eps = 1e-9 * lattice.lc();
    let inside = |lo: f64, hi: f64, max: f64| lo >= -eps && hi <= max + eps && lo < hi;
    match p.shape {
        "rectangle" => match p.x_m {
            None => ck.push(format!("{field}.x_m"), "(missing)", "[x_min, x_max] in metres for a rectangle"),
            Some([x0, x1]) => {
                let [y0, y1] = p.y_m.unwrap_or([0.0, e[1]]);
                if !inside(x0, x1, e[0]) || !inside(y0, y1, e[1]) {
                    ck.push(
                        field,
                        format!("x_m = [{}, {}], y_m = [{}, {}]", num(x0), num(x1), num(y0), num(y1)),
                        format!("a rectangle {} (min < max)", describe_base(lattice)),
                    );
                }
            }
        },
        "ellipse" => match (p.centre_m, p.semi_axes_m) {
            (Some([cx, cy]), Some([a, b])) => {
                if !(a > 0.0 && b > 0.0 && inside(cx - a, cx + a, e[0]) && inside(cy - b, cy + b, e[1])) {
                    ck.push(
                        field,
                        format!("centre_m = [{}, {}], semi_axes_m = [{}, {}]", num(cx), num(cy), num(a), num(b)),
                        format!("an ellipse with positive semi-axes {}", describe_base(lattice)),
                    );
                }
            }
            _ => ck.push(
                field,
                "an ellipse without centre_m or semi_axes_m",
                "centre_m = [x, y] and semi_axes_m = [a_x, a_y] in metres",
            ),
        },
        other => ck.push(format!("{field}.shape"), format!("{other:?}"), "\"rectangle\" or \"ellipse\""),
    }
    let held: Vec<usize> = contact
        .iter()
        .enumerate()
        .filter(|(_, id)| {
            let q = lattice.position(**id);
            contains(p, q[0], q[1], e[1], eps)
        })
        .map(|(c, _)| c)
        .collect();
    if held.is_empty() && ck.is_clean() {
        ck.push(
            field,
            "a patch holding no base node",
            format!("a patch that holds at least one base node (they lie every Lc = {} m)", approx(lattice.lc())),
        );
    }
    held
}

/// The friction map of `patches` and `grid` on `lattice`'s base, over the background `law`;
/// `None` when there is neither.
pub(crate) fn build(
    ck: &mut Checker,
    lattice: &Lattice,
    law: &FrictionLaw,
    patches: &[PatchSection],
    grid: Option<GridRows<'_>>,
) -> Option<FrictionMap> {
    if patches.is_empty() && grid.is_none() {
        return None;
    }
    let contact = lattice.contact_nodes();
    let mut nodes = vec![law.node(1.0); contact.len()];
    let mut region: Vec<Option<u16>> = vec![None; contact.len()];
    let mut regions: Vec<Region> = Vec::new();
    let background = law.node(1.0).static_coefficient();
    let kind = |c: &NodeFriction| {
        if c.static_coefficient() > background {
            RegionKind::Barrier
        } else if c.residual_coefficient() >= c.static_coefficient() {
            RegionKind::Stable
        } else {
            RegionKind::Weak
        }
    };
    if let Some(g) = grid {
        let field = g.field;
        if g.rows.len() != contact.len() {
            ck.push(
                field,
                format!("{:?} with {} rows", g.file, g.rows.len()),
                format!(
                    "one row per base node: {} rows for this block ({} × {} corner nodes every Lc = {} m)",
                    contact.len(),
                    lattice.dims().nx + 1,
                    lattice.dims().ny + 1,
                    approx(lattice.lc())
                ),
            );
        } else {
            let mut seen = vec![false; contact.len()];
            for (i, (x, y, keys)) in g.rows.into_iter().enumerate() {
                let c = lattice.node_at([x, y, 0.0]).map(|id| id.index()).filter(|&c| c < contact.len());
                let Some(c) = c else {
                    ck.push(
                        field,
                        format!("row {}: x = {} m, y = {} m", i + 1, num(x), num(y)),
                        describe_base(lattice),
                    );
                    continue;
                };
                if std::mem::replace(&mut seen[c], true) {
                    ck.push(field, format!("row {}: x = {} m, y = {} m", i + 1, num(x), num(y)), "each base node once");
                }
                let co = coefficients(ck, &format!("{field} row {}", i + 1), keys, law);
                nodes[c] = co;
                region[c] = Some(0);
            }
            regions.push(Region { name: "grid".into(), kind: RegionKind::Weak });
        }
    }
    // Patch i is region `first + i` (after the grid's, when there is one).
    let first = regions.len();
    // Each patch's base nodes and coefficients, and the weights of a smooth edge's nodes.
    let mut members: Vec<(Vec<usize>, NodeFriction)> = Vec::new();
    let mut smooth: Vec<Option<Vec<(usize, f64)>>> = Vec::new();
    for (i, p) in patches.iter().enumerate() {
        let field = format!("friction.patches[{i}]");
        let mut held = patch_nodes(ck, &field, &p.shape(), lattice);
        smooth.push(p.transition_m.and_then(|w| {
            let key = format!("{field}.transition_m");
            if !ck.positive(&key, w) {
                return None;
            }
            if !matches!(law.node(1.0), NodeFriction::RateState(_)) || p.shape != "rectangle" {
                ck.push(
                    key,
                    num(w),
                    "left out except on a rectangle under a rate-and-state law (it blends a, b, L and f₀)",
                );
                return None;
            }
            if w < 2.0 * lattice.lc() {
                ck.push(
                    key,
                    num(w),
                    format!("at least 2·Lc = {} m, or left out (a sharp edge)", approx(2.0 * lattice.lc())),
                );
                return None;
            }
            let weights = smooth_weights(lattice, p.x_m?, p.y_m.unwrap_or([0.0, lattice.extent()[1]]), w);
            held = weights.iter().map(|&(c, _)| c).collect();
            Some(weights)
        }));
        let keys = crate::laws::RegionKeys {
            mu_static: p.mu_static,
            mu_dynamic: p.mu_dynamic,
            slip_weakening_m: p.slip_weakening_m,
            rate_state: p.rate_state,
        };
        let co = coefficients(ck, &field, keys, law);
        let name = p.name.clone().unwrap_or_else(|| format!("patch[{i}]"));
        regions.push(Region { name, kind: kind(&co) });
        members.push((held, co));
    }
    // Overlaps need a precedence.
    let mut held_by_i = vec![false; contact.len()];
    for i in 0..patches.len() {
        // A mask of patch i's nodes, so each overlap is counted in one pass (not one search per node).
        held_by_i.iter_mut().for_each(|h| *h = false);
        for &c in &members[i].0 {
            held_by_i[c] = true;
        }
        for j in i + 1..patches.len() {
            let shared = members[j].0.iter().filter(|&&c| held_by_i[c]).count();
            if shared > 0 && patches[i].priority == patches[j].priority {
                ck.push(
                    format!("friction.patches[{j}].priority"),
                    patches[j].priority,
                    format!(
                        "a priority other than patches[{i}]'s ({}): the two share {shared} base nodes, and the higher \
                         priority holds there",
                        patches[i].priority
                    ),
                );
            }
        }
    }
    let mut order: Vec<usize> = (0..patches.len()).collect();
    order.sort_by_key(|&i| patches[i].priority);
    for i in order {
        let (held, co) = &members[i];
        match &smooth[i] {
            None => {
                for &c in held {
                    nodes[c] = *co;
                    region[c] = Some((first + i) as u16);
                }
            }
            Some(weights) => {
                for &(c, w) in weights {
                    nodes[c] = blend(&nodes[c], co, w).unwrap_or(*co);
                    if w >= 0.5 {
                        region[c] = Some((first + i) as u16);
                    }
                }
            }
        }
    }
    Some(FrictionMap { nodes, region, regions })
}

#[cfg(test)]
mod tests {
    use stickslip_solver::Dims;

    use super::*;

    fn rectangle(x: [f64; 2], y: [f64; 2]) -> Shape<'static> {
        Shape { shape: "rectangle", x_m: Some(x), y_m: Some(y), centre_m: None, semi_axes_m: None }
    }

    /// The area a patch loads: Σ share × the node's tile (clipped to the face).
    fn loaded_area(p: &Shape<'_>, lattice: &Lattice) -> f64 {
        tile_shares(p, lattice)
            .into_iter()
            .map(|(c, w)| {
                let [[x0, x1], [y0, y1]] = tile(lattice, c);
                w * (x1 - x0) * (y1 - y0)
            })
            .sum()
    }

    #[test]
    fn a_patch_loads_its_own_area_at_any_spacing() {
        // TPV5's 3 × 3 km square, its sides on rows of nodes at 100 m and 500 m, between rows at
        // 200 m along x: it loads 9 km² in every case (by whole nodes: 9.61, 9.6 and 12.25 km²).
        for lc in [100.0, 200.0, 500.0] {
            let lattice = Lattice::new(Dims::new((40_000.0 / lc) as usize, (20_000.0 / lc) as usize, 2), lc);
            let square = rectangle([18_500.0, 21_500.0], [6_000.0, 9_000.0]);
            let area = loaded_area(&square, &lattice);
            assert!((area - 9e6).abs() < 1e-6 * 9e6, "Lc {lc}: {area} m²");
            // A side on a row of nodes gives it half, a corner a quarter.
            let shares = tile_shares(&square, &lattice);
            let least = shares.iter().map(|s| s.1).fold(1.0, f64::min);
            assert!(least == 0.25 || (lc == 200.0 && least == 0.5), "Lc {lc}: least share {least}");
        }
        // At the face's edge the tile is clipped: a patch over the whole face loads the face.
        let lattice = Lattice::new(Dims::new(10, 4, 2), 0.5);
        let all = rectangle([0.0, 5.0], [0.0, 2.0]);
        assert!((loaded_area(&all, &lattice) - 10.0).abs() < 1e-12);
        assert!(tile_shares(&all, &lattice).iter().all(|s| s.1 == 1.0));
        // An ellipse from 16 × 16 points per tile: its area within a percent.
        let lattice = Lattice::new(Dims::new(40, 40, 2), 100.0);
        let ellipse = Shape {
            shape: "ellipse",
            x_m: None,
            y_m: None,
            centre_m: Some([2_000.0, 2_000.0]),
            semi_axes_m: Some([1_230.0, 770.0]),
        };
        let area = loaded_area(&ellipse, &lattice);
        let exact = std::f64::consts::PI * 1_230.0 * 770.0;
        assert!((area / exact - 1.0).abs() < 0.01, "{area} against {exact}");
    }

    #[test]
    fn a_smooth_edge_blends_a_as_tpv101_defines_it() {
        // TPV101's a = 0.008 + 0.008·[1 − B(x)·B(y)] with w = 3 km: 0.008 inside, 0.016 from 3 km
        // outside on, and halfway (B(w/2) = ½(1 + tanh(−2 + 2)) = ½) 1.5 km outside: 0.012, or
        // 0.016 − 0.008/4 = 0.014 1.5 km outside both sides at a corner. The side on the face's
        // edge (y = 0) is not tapered: the patch continues beyond it.
        use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
        let lattice = Lattice::new(Dims::new(100, 50, 2), 100.0);
        let background = RateStateNode {
            a: 0.016,
            b: 0.012,
            dc_m: 0.02,
            v0_m_s: 1e-6,
            f0: 0.6,
            evolution: Evolution::Aging,
            start: RateStateStart::Balanced(1e-12),
        };
        let law: FrictionLaw = background.into();
        let patch = PatchSection {
            shape: "rectangle".into(),
            x_m: Some([3_000.0, 7_000.0]),
            y_m: Some([0.0, 1_000.0]),
            rate_state: Some(crate::laws::RateStatePatch { a: Some(0.008), ..Default::default() }),
            transition_m: Some(3_000.0),
            ..PatchSection::default()
        };
        let mut ck = Checker::default();
        let map = build(&mut ck, &lattice, &law, &[patch], None).expect("a map");
        assert!(ck.is_clean());
        let a_at = |x: f64, y: f64| {
            let id = lattice.node_at([x, y, 0.0]).expect("a base node");
            let NodeFriction::RateState(n) = map.nodes[id.index()] else { panic!() };
            n.a
        };
        for (x, y, want) in [
            (5_000.0, 0.0, 0.008),
            (5_000.0, 1_000.0, 0.008),
            (1_500.0, 500.0, 0.012),
            (8_500.0, 0.0, 0.012),
            (5_000.0, 2_500.0, 0.012),
            (8_500.0, 2_500.0, 0.014),
            (10_000.0, 0.0, 0.016),
            (5_000.0, 4_000.0, 0.016),
        ] {
            assert!((a_at(x, y) - want).abs() < 1e-15, "a({x}, {y}) = {} not {want}", a_at(x, y));
        }
        assert_eq!(boxcar(-1.0, 3.0), 1.0);
        assert_eq!(boxcar(3.0, 3.0), 0.0);
    }
}
