//! The rupture as the stochastic part sees it: subfaults of about 1 km resampled from the fault
//! nodes of the deterministic rupture (the Platform's `srf2stoch`), each with its moment, its
//! rupture time and its local rupture speed.
//!
//! The fault plane is `z = 0` with `x` along strike and `y` down dip (`y = 0` the surface), as the
//! lattice's fault scenes lie. The rupture's rectangle is the smallest one holding the tiles of
//! the ruptured nodes (each node stands for a `spacing × spacing` tile); it is cut into
//! `n_x × n_y` cells of `L/n_x × W/n_y` with `n = max(1, round(L/target))`, so cells are as close
//! to the target as the rectangle allows. A cell's moment is `μ·Σ A_i·|D_i|` over its nodes, its
//! rupture time the mean over its ruptured nodes; a cell with no ruptured node has no moment but
//! is counted in N, the number of subfaults, as the Platform counts every cell of the plane.
//!
//! **Local rupture speed.** At each ruptured node the slowness `|∇t_r|` by differences of the
//! rupture times of its neighbours on the node grid (central where both neighbours ruptured,
//! one-sided where one did), and a cell's speed the median over its nodes of `1/|∇t_r|`, kept
//! within [0.2, 1.4]·β (1.4 is the Platform's cap on its rupture speeds). The nodes that broke
//! first, all at the same instant, are left out (an overstressed nucleation patch breaks at once: no
//! front propagated there); a cell with no node left takes the median speed of the others.

use crate::error::SeismoError;

/// One node of the fault, as the deterministic rupture left it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaultNode {
    /// Position along strike (m).
    pub x_m: f64,
    /// Depth (m, ≥ 0).
    pub depth_m: f64,
    /// The fault area it stands for (m²).
    pub area_m2: f64,
    /// Its final slip (m, ≥ 0).
    pub slip_m: f64,
    /// When it ruptured (s); NaN if it never did.
    pub rupture_time_s: f64,
}

/// A subfault of the stochastic part.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Subfault {
    /// Centre along strike (m).
    pub x_m: f64,
    /// Centre depth (m).
    pub depth_m: f64,
    /// Its moment (N·m, > 0).
    pub moment_n_m: f64,
    /// Its rupture time (s).
    pub rupture_time_s: f64,
    /// Its local rupture speed over the S-wave speed.
    pub speed_ratio: f64,
    /// Its cell's index (row-major along strike, then down dip): the key of its random stream.
    pub cell: usize,
}

/// The rupture resampled into subfaults.
#[derive(Clone, Debug, PartialEq)]
pub struct FiniteFault {
    /// The subfaults with a moment.
    pub subfaults: Vec<Subfault>,
    /// N: every cell of the rupture's rectangle.
    pub cells: usize,
    /// Subfault size `dl = √(Δx·Δy)` (m).
    pub size_m: f64,
    /// Total moment (N·m).
    pub moment_n_m: f64,
    /// The ruptured nodes' area (m²).
    pub area_m2: f64,
    /// Depth of the hypocentre: the mean depth of the nodes that broke first (m).
    pub hypocentre_depth_m: f64,
}

/// Smallest and largest rupture speed kept, as fractions of β.
pub const SPEED_RATIO_RANGE: [f64; 2] = [0.2, 1.4];

impl FiniteFault {
    /// Subfaults of about `target_m` from `nodes` (on a grid of `spacing_m`) in a medium of shear
    /// modulus `shear_modulus_pa` and S-wave speed `s_speed_m_s`; `None` when no node ruptured
    /// with slip.
    pub fn from_nodes(
        nodes: &[FaultNode],
        spacing_m: f64,
        target_m: f64,
        shear_modulus_pa: f64,
        s_speed_m_s: f64,
    ) -> Result<Option<FiniteFault>, SeismoError> {
        if !(spacing_m > 0.0 && target_m > 0.0 && shear_modulus_pa > 0.0 && s_speed_m_s > 0.0) {
            return Err(SeismoError::parameter(
                "spacing_m, target_m, shear_modulus_pa, s_speed_m_s",
                format!("{spacing_m}, {target_m}, {shear_modulus_pa}, {s_speed_m_s}"),
                "all > 0",
            ));
        }
        let ruptured: Vec<&FaultNode> =
            nodes.iter().filter(|n| n.rupture_time_s.is_finite() && n.slip_m > 0.0 && n.area_m2 > 0.0).collect();
        if ruptured.is_empty() {
            return Ok(None);
        }
        let half = 0.5 * spacing_m;
        let span = |f: &dyn Fn(&FaultNode) -> f64| {
            ruptured.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |[lo, hi], n| [lo.min(f(n)), hi.max(f(n))])
        };
        let [x0, x1] = span(&|n| n.x_m);
        let [y0, y1] = span(&|n| n.depth_m);
        let (x0, x1, y0, y1) = (x0 - half, x1 + half, (y0 - half).max(0.0), y1 + half);
        let count = |l: f64| ((l / target_m).round() as usize).max(1);
        let (nx, ny) = (count(x1 - x0), count(y1 - y0));
        let (dx, dy) = ((x1 - x0) / nx as f64, (y1 - y0) / ny as f64);
        let cell_of = |n: &FaultNode| {
            let i = (((n.x_m - x0) / dx).floor() as isize).clamp(0, nx as isize - 1) as usize;
            let j = (((n.depth_m - y0) / dy).floor() as isize).clamp(0, ny as isize - 1) as usize;
            (i, j)
        };
        let cells = nx * ny;
        let mut moment = vec![0.0; cells];
        let mut time_sum = vec![0.0; cells];
        let mut members: Vec<Vec<usize>> = vec![Vec::new(); cells];
        for (k, n) in ruptured.iter().enumerate() {
            let (i, j) = cell_of(n);
            let c = j * nx + i;
            moment[c] += shear_modulus_pa * n.area_m2 * n.slip_m;
            time_sum[c] += n.rupture_time_s;
            members[c].push(k);
        }
        // Local rupture speed: the slowness at each node from its grid neighbours' rupture times,
        // the nodes that broke at the first instant left out.
        let first = ruptured.iter().map(|n| n.rupture_time_s).fold(f64::INFINITY, f64::min);
        let grid_index = |v: f64, origin: f64| ((v - origin) / spacing_m).round() as i64;
        let (gx0, gy0) = (x0 + half, y0.min(ruptured.iter().map(|n| n.depth_m).fold(f64::INFINITY, f64::min)));
        let times: std::collections::HashMap<(i64, i64), f64> = ruptured
            .iter()
            .filter(|n| n.rupture_time_s > first)
            .map(|n| ((grid_index(n.x_m, gx0), grid_index(n.depth_m, gy0)), n.rupture_time_s))
            .collect();
        let derivative = |at: (i64, i64), step: (i64, i64)| -> Option<f64> {
            let t0 = times.get(&at)?;
            let ahead = times.get(&(at.0 + step.0, at.1 + step.1));
            let behind = times.get(&(at.0 - step.0, at.1 - step.1));
            match (behind, ahead) {
                (Some(b), Some(a)) => Some((a - b) / (2.0 * spacing_m)),
                (None, Some(a)) => Some((a - t0) / spacing_m),
                (Some(b), None) => Some((t0 - b) / spacing_m),
                (None, None) => None,
            }
        };
        let mut node_speeds: Vec<Vec<f64>> = vec![Vec::new(); cells];
        for n in &ruptured {
            let at = (grid_index(n.x_m, gx0), grid_index(n.depth_m, gy0));
            let (Some(gx), Some(gy)) = (derivative(at, (1, 0)), derivative(at, (0, 1))) else { continue };
            let (i, j) = cell_of(n);
            let slowness = gx.hypot(gy);
            let ratio = if slowness > 0.0 { 1.0 / (slowness * s_speed_m_s) } else { f64::INFINITY };
            node_speeds[j * nx + i].push(ratio.clamp(SPEED_RATIO_RANGE[0], SPEED_RATIO_RANGE[1]));
        }
        let speed: Vec<Option<f64>> = node_speeds
            .iter_mut()
            .map(|v| {
                v.sort_by(f64::total_cmp);
                (!v.is_empty()).then(|| {
                    if v.len() % 2 == 1 { v[v.len() / 2] } else { 0.5 * (v[v.len() / 2 - 1] + v[v.len() / 2]) }
                })
            })
            .collect();
        let mut known: Vec<f64> = speed.iter().flatten().copied().collect();
        known.sort_by(f64::total_cmp);
        let fallback = if known.is_empty() { 0.8 } else { known[known.len() / 2] };
        let subfaults = (0..cells)
            .filter(|&c| moment[c] > 0.0)
            .map(|c| {
                let (i, j) = (c % nx, c / nx);
                Subfault {
                    x_m: x0 + (i as f64 + 0.5) * dx,
                    depth_m: y0 + (j as f64 + 0.5) * dy,
                    moment_n_m: moment[c],
                    rupture_time_s: time_sum[c] / members[c].len() as f64,
                    speed_ratio: speed[c].unwrap_or(fallback),
                    cell: c,
                }
            })
            .collect();
        let hypo: Vec<f64> = ruptured.iter().filter(|n| n.rupture_time_s == first).map(|n| n.depth_m).collect();
        Ok(Some(FiniteFault {
            hypocentre_depth_m: hypo.iter().sum::<f64>() / hypo.len() as f64,
            subfaults,
            cells,
            size_m: (dx * dy).sqrt(),
            moment_n_m: moment.iter().sum(),
            area_m2: ruptured.iter().map(|n| n.area_m2).sum(),
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 20 × 8 km fault of 500 m nodes, rupture spreading from (5 km, 4 km) at `v` m/s, slip
    /// `slip(x, y)`.
    fn nodes(v: f64, slip: impl Fn(f64, f64) -> f64) -> Vec<FaultNode> {
        let mut out = Vec::new();
        for i in 0..40 {
            for j in 0..16 {
                let (x, y) = (250.0 + 500.0 * i as f64, 250.0 + 500.0 * j as f64);
                let r = (x - 5000.0).hypot(y - 4000.0);
                out.push(FaultNode { x_m: x, depth_m: y, area_m2: 0.25e6, slip_m: slip(x, y), rupture_time_s: r / v });
            }
        }
        out
    }

    #[test]
    fn cells_of_one_kilometre_hold_the_moment_and_the_local_speed() {
        let (mu, beta) = (3.2e10, 3464.0);
        let f = FiniteFault::from_nodes(&nodes(2800.0, |_, _| 1.0), 500.0, 1000.0, mu, beta).unwrap().unwrap();
        assert_eq!(f.cells, 20 * 8);
        assert_eq!(f.subfaults.len(), 160);
        assert!((f.size_m - 1000.0).abs() < 1e-9);
        assert!((f.moment_n_m - mu * 160e6).abs() < 1e-6 * f.moment_n_m);
        // Away from the hypocentre the front is nearly plane over a cell: speed 2800 m/s.
        let far =
            f.subfaults.iter().find(|s| (s.x_m - 17500.0).abs() < 1.0 && (s.depth_m - 4500.0).abs() < 1.0).unwrap();
        assert!((far.speed_ratio * beta / 2800.0 - 1.0).abs() < 0.02, "{}", far.speed_ratio * beta);
        // Rupture time: the mean of its four nodes.
        let t: f64 = [(17250.0, 4250.0), (17750.0, 4250.0), (17250.0, 4750.0), (17750.0, 4750.0)]
            .iter()
            .map(|(x, y)| (x - 5000.0f64).hypot(y - 4000.0) / 2800.0)
            .sum::<f64>()
            / 4.0;
        assert!((far.rupture_time_s - t).abs() < 1e-12);
    }

    #[test]
    fn the_rectangle_is_that_of_the_ruptured_nodes_and_empty_cells_count() {
        // Slip only on x < 10 km, and within that a hole: every cell counts, the hole has none.
        let slip = |x: f64, y: f64| {
            if x < 10_000.0 && !(x > 4000.0 && x < 6000.0 && y > 2000.0 && y < 4000.0) { 2.0 } else { 0.0 }
        };
        let f = FiniteFault::from_nodes(&nodes(3000.0, slip), 500.0, 1000.0, 3e10, 3464.0).unwrap().unwrap();
        assert_eq!(f.cells, 10 * 8);
        assert_eq!(f.subfaults.len(), 80 - 4);
        // A fault that never ruptured has no subfaults.
        let none = nodes(3000.0, |_, _| 0.0);
        assert!(FiniteFault::from_nodes(&none, 500.0, 1000.0, 3e10, 3464.0).unwrap().is_none());
        // Speeds are bounded.
        assert!(f.subfaults.iter().all(|s| (0.2..=1.4).contains(&s.speed_ratio)));
    }

    #[test]
    fn a_patch_that_breaks_at_once_takes_the_median_speed() {
        // A 3 × 3 km patch at the hypocentre ruptures at t = 0 (an overstressed nucleation), the
        // rest spreads from it at 2800 m/s: the patch's nodes are left out, its cells measure the
        // front around it or take the median.
        let mut n = nodes(2800.0, |_, _| 1.0);
        for p in n.iter_mut() {
            if (p.x_m - 5000.0).abs() < 1500.0 && (p.depth_m - 4000.0).abs() < 1500.0 {
                p.rupture_time_s = 0.0;
            }
        }
        let f = FiniteFault::from_nodes(&n, 500.0, 1000.0, 3e10, 3464.0).unwrap().unwrap();
        let centre =
            f.subfaults.iter().find(|s| (s.x_m - 4500.0).abs() < 1.0 && (s.depth_m - 3500.0).abs() < 1.0).unwrap();
        let mut ratios: Vec<f64> = f.subfaults.iter().map(|s| s.speed_ratio).collect();
        ratios.sort_by(f64::total_cmp);
        assert!(centre.speed_ratio < 1.4, "{}", centre.speed_ratio);
        assert!((centre.speed_ratio * 3464.0 / 2800.0 - 1.0).abs() < 0.1, "{}", centre.speed_ratio * 3464.0);
    }
}
