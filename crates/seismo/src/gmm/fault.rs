//! Distances from a site on the free surface to a rectangular planar fault.
//!
//! Frame: x east, y north (km) on the surface, depth z positive down (km). The fault is given by
//! the two end points of its top edge (the strike runs from `top_start` to `top_end`), its dip
//! δ ∈ (0°, 90°] (dipping to the right of the strike, the Aki–Richards convention), the depth of
//! its top edge Z_tor and its down-dip width W. With ŝ the unit strike vector, d̂ = (ŝ_y, −ŝ_x) the
//! horizontal dip direction and L the length, a site at p has the along-strike coordinate
//! u = (p − top_start)·ŝ and the across-strike coordinate w = (p − top_start)·d̂, and
//! ```text
//! R_x  = w                                                    (positive on the hanging wall)
//! R_y0 = max(0, −u, u − L)
//! R_JB = √(e(u; 0, L)² + e(w; 0, W cos δ)²),     e(x; a, b) = x − clamp(x, a, b)
//! R_rup = √(e(u; 0, L)² + e(η; 0, W)² + ζ²),  η = w cos δ − Z_tor sin δ,  ζ = w sin δ + Z_tor cos δ
//! ```
//! (η is the site's coordinate down the dip of the fault plane from its top edge and ζ its distance
//! from the plane: in the orthonormal frame of the plane the closest point of the rectangle is the
//! clamp of the site's coordinates.) Epicentral and hypocentral distances are taken from a point
//! of the fault given by its along-strike and down-dip coordinates.

use crate::error::SeismoError;

use super::{Mechanism, Rupture};

/// A rectangular planar fault.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PlanarFault {
    top_start: [f64; 2],
    strike: [f64; 2],
    length_km: f64,
    dip_deg: f64,
    ztor_km: f64,
    width_km: f64,
}

/// The distances of a site from a fault (km).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Distances {
    /// Closest distance to the fault plane.
    pub r_rup_km: f64,
    /// Closest horizontal distance to the surface projection of the fault.
    pub r_jb_km: f64,
    /// Horizontal distance from the top edge's line, perpendicular to strike, positive on the
    /// hanging wall.
    pub r_x_km: f64,
    /// Horizontal distance off the ends of the fault, parallel to strike (0 beside it).
    pub r_y0_km: f64,
}

impl PlanarFault {
    /// The fault whose top edge runs from `top_start` to `top_end` (x east, y north, km), dipping
    /// `dip_deg` (0 < δ ≤ 90) to the right of that strike, its top at depth `ztor_km` (≥ 0) and
    /// `width_km` (> 0) wide down the dip.
    pub fn new(
        top_start: [f64; 2],
        top_end: [f64; 2],
        dip_deg: f64,
        ztor_km: f64,
        width_km: f64,
    ) -> Result<PlanarFault, SeismoError> {
        for (name, p) in [("top_start", top_start), ("top_end", top_end)] {
            if !(p[0].is_finite() && p[1].is_finite()) {
                return Err(SeismoError::parameter(name, format!("{p:?} km"), "finite coordinates"));
            }
        }
        let (dx, dy) = (top_end[0] - top_start[0], top_end[1] - top_start[1]);
        let length_km = dx.hypot(dy);
        if !(length_km > 0.0) {
            return Err(SeismoError::parameter("top_end", format!("{top_end:?} km"), "a point other than top_start"));
        }
        if !(dip_deg > 0.0 && dip_deg <= 90.0) {
            return Err(SeismoError::parameter("dip_deg", format!("{dip_deg}°"), "0° < dip ≤ 90°"));
        }
        if !(ztor_km >= 0.0 && ztor_km.is_finite()) {
            return Err(SeismoError::parameter("ztor_km", format!("{ztor_km} km"), "a finite Z_tor ≥ 0 km"));
        }
        if !(width_km > 0.0 && width_km.is_finite()) {
            return Err(SeismoError::parameter("width_km", format!("{width_km} km"), "a finite W > 0 km"));
        }
        Ok(PlanarFault { top_start, strike: [dx / length_km, dy / length_km], length_km, dip_deg, ztor_km, width_km })
    }

    /// Length along strike (km).
    pub fn length_km(&self) -> f64 {
        self.length_km
    }

    /// Strike, clockwise from north (degrees, in [0, 360)).
    pub fn strike_deg(&self) -> f64 {
        self.strike[0].atan2(self.strike[1]).to_degrees().rem_euclid(360.0)
    }

    /// Dip (degrees).
    pub fn dip_deg(&self) -> f64 {
        self.dip_deg
    }

    /// Depth of the top edge (km).
    pub fn ztor_km(&self) -> f64 {
        self.ztor_km
    }

    /// Down-dip width (km).
    pub fn width_km(&self) -> f64 {
        self.width_km
    }

    /// Depth of the bottom edge (km).
    pub fn bottom_depth_km(&self) -> f64 {
        self.ztor_km + self.width_km * self.dip_deg.to_radians().sin()
    }

    /// The rupture of this fault for the models, given its magnitude and mechanism (its hypocentral
    /// depth left to CB14's estimate).
    pub fn rupture(&self, mw: f64, mechanism: Mechanism) -> Rupture {
        Rupture {
            mw,
            mechanism,
            dip_deg: self.dip_deg,
            ztor_km: self.ztor_km,
            width_km: self.width_km,
            hypo_depth_km: None,
        }
    }

    fn dip_direction(&self) -> [f64; 2] {
        [self.strike[1], -self.strike[0]]
    }

    /// The point of the fault `along_km` along strike from `top_start` and `down_dip_km` down its
    /// dip from the top edge, as (x, y, depth) in km (no clamping: the coordinates may leave the
    /// rectangle).
    pub fn point(&self, along_km: f64, down_dip_km: f64) -> [f64; 3] {
        let (s, d) = (self.strike, self.dip_direction());
        let (sin, cos) = self.dip_deg.to_radians().sin_cos();
        let h = down_dip_km * cos;
        [
            self.top_start[0] + along_km * s[0] + h * d[0],
            self.top_start[1] + along_km * s[1] + h * d[1],
            self.ztor_km + down_dip_km * sin,
        ]
    }

    /// The surface point at along-strike coordinate `u_km` and across-strike coordinate `w_km`
    /// (its R_x), in km.
    pub fn surface_point(&self, u_km: f64, w_km: f64) -> [f64; 2] {
        let (s, d) = (self.strike, self.dip_direction());
        [self.top_start[0] + u_km * s[0] + w_km * d[0], self.top_start[1] + u_km * s[1] + w_km * d[1]]
    }

    /// The distances of the surface site `site` (x, y in km).
    pub fn distances(&self, site: [f64; 2]) -> Distances {
        let (s, d) = (self.strike, self.dip_direction());
        let p = [site[0] - self.top_start[0], site[1] - self.top_start[1]];
        let u = p[0] * s[0] + p[1] * s[1];
        let w = p[0] * d[0] + p[1] * d[1];
        let (sin, cos) = self.dip_deg.to_radians().sin_cos();
        // A vertical fault: cos 90° is 6e-17, not 0; its surface projection is a segment.
        let cos = if self.dip_deg == 90.0 { 0.0 } else { cos };
        let excess = |x: f64, lo: f64, hi: f64| x - x.clamp(lo, hi);
        let eu = excess(u, 0.0, self.length_km);
        let r_jb = eu.hypot(excess(w, 0.0, self.width_km * cos));
        let eta = w * cos - self.ztor_km * sin;
        let zeta = w * sin + self.ztor_km * cos;
        let r_rup = eu.hypot(excess(eta, 0.0, self.width_km)).hypot(zeta);
        Distances { r_rup_km: r_rup, r_jb_km: r_jb, r_x_km: w, r_y0_km: eu.abs() }
    }
}

/// Horizontal distance (km) from the surface site to the epicentre, the surface point above
/// `hypocentre` (x, y, depth in km, e.g. from [`PlanarFault::point`]).
pub fn epicentral_km(hypocentre: [f64; 3], site: [f64; 2]) -> f64 {
    (site[0] - hypocentre[0]).hypot(site[1] - hypocentre[1])
}

/// Straight-line distance (km) from the surface site to `hypocentre` (x, y, depth in km).
pub fn hypocentral_km(hypocentre: [f64; 3], site: [f64; 2]) -> f64 {
    epicentral_km(hypocentre, site).hypot(hypocentre[2])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn close(a: f64, b: f64, tol: f64) -> bool {
        (a - b).abs() <= tol * (1.0 + b.abs())
    }

    /// R_rup by brute force: the smallest distance over a fine grid of the plane, refined by
    /// golden-section searches (the distance is convex on the rectangle).
    fn brute_r_rup(f: &PlanarFault, site: [f64; 2]) -> f64 {
        let dist = |a: f64, b: f64| {
            let p = f.point(a, b);
            (p[0] - site[0]).hypot(p[1] - site[1]).hypot(p[2])
        };
        let min_over = |g: &dyn Fn(f64) -> f64, lo: f64, hi: f64| {
            let (mut a, mut b) = (lo, hi);
            let r = (5f64.sqrt() - 1.0) / 2.0;
            for _ in 0..200 {
                let (c, d) = (b - r * (b - a), a + r * (b - a));
                if g(c) < g(d) {
                    b = d;
                } else {
                    a = c;
                }
            }
            g(0.5 * (a + b))
        };
        let inner = |a: f64| min_over(&|b| dist(a, b), 0.0, f.width_km());
        min_over(&inner, 0.0, f.length_km())
    }

    #[test]
    fn a_vertical_fault_has_the_closed_forms() {
        // Strike north along the y axis from (0, 0) to (0, 40), top at 2 km, 15 km wide.
        let f = PlanarFault::new([0.0, 0.0], [0.0, 40.0], 90.0, 2.0, 15.0).unwrap();
        assert_eq!(f.strike_deg(), 0.0);
        assert_eq!(f.bottom_depth_km(), 17.0);
        // Beside the fault, 10 km east (the dip side is east, to the right of north).
        let d = f.distances([10.0, 25.0]);
        assert!(close(d.r_jb_km, 10.0, 1e-12) && close(d.r_rup_km, 104f64.sqrt(), 1e-12));
        assert!(close(d.r_x_km, 10.0, 1e-12) && d.r_y0_km == 0.0);
        // West: R_x negative, distances the same.
        let d = f.distances([-10.0, 25.0]);
        assert!(close(d.r_x_km, -10.0, 1e-12) && close(d.r_rup_km, 104f64.sqrt(), 1e-12));
        // Off the north end, 6 km beyond and 8 km east: R_JB = 10, R_y0 = 6.
        let d = f.distances([8.0, 46.0]);
        assert!(close(d.r_jb_km, 10.0, 1e-12) && close(d.r_y0_km, 6.0, 1e-12));
        assert!(close(d.r_rup_km, 104f64.sqrt(), 1e-12));
        // On the trace: R_JB = 0, R_rup = Z_tor.
        let d = f.distances([0.0, 20.0]);
        assert!(d.r_jb_km == 0.0 && close(d.r_rup_km, 2.0, 1e-12));
    }

    #[test]
    fn a_dipping_fault_has_the_closed_forms() {
        // Strike east (90°) from (0, 0) to (30, 0): dips to the south. δ = 30°, Z_tor = 3, W = 20.
        let f = PlanarFault::new([0.0, 0.0], [30.0, 0.0], 30.0, 3.0, 20.0).unwrap();
        assert!(close(f.strike_deg(), 90.0, 1e-12));
        let (sin, cos) = (0.5, 0.75f64.sqrt());
        // Hanging wall above the fault, 5 km south of the trace: R_JB = 0, R_x = 5, and R_rup is
        // the distance to the plane, w sin δ + Z_tor cos δ, as the foot lies inside.
        let d = f.distances([12.0, -5.0]);
        assert!(d.r_jb_km == 0.0 && close(d.r_x_km, 5.0, 1e-12));
        assert!(close(d.r_rup_km, 5.0 * sin + 3.0 * cos, 1e-12), "{d:?}");
        // Footwall, 7 km north: R_x = −7, R_JB = 7, the closest point is the top edge.
        let d = f.distances([12.0, 7.0]);
        assert!(close(d.r_x_km, -7.0, 1e-12) && close(d.r_jb_km, 7.0, 1e-12));
        assert!(close(d.r_rup_km, 58f64.sqrt(), 1e-12));
        // Hanging wall beyond the surface projection (W cos δ = 17.32 km): R_JB = w − W cos δ, and
        // the bottom edge (depth 13 km) is the closest point.
        let w = 25.0;
        let d = f.distances([12.0, -w]);
        assert!(close(d.r_jb_km, w - 20.0 * cos, 1e-12));
        assert!(close(d.r_rup_km, (w - 20.0 * cos).hypot(13.0), 1e-12), "{d:?}");
        // Far off the west end above the hanging wall: R_y0 = 10.
        let d = f.distances([-10.0, -5.0]);
        assert!(close(d.r_y0_km, 10.0, 1e-12) && close(d.r_jb_km, 10.0, 1e-12));
    }

    #[test]
    fn r_rup_agrees_with_a_brute_force_minimum() {
        let f = PlanarFault::new([3.0, -4.0], [-20.0, 31.0], 55.0, 1.5, 14.0).unwrap();
        for site in [[0.0, 0.0], [10.0, 12.0], [-30.0, 5.0], [-25.0, 45.0], [8.0, -20.0], [-6.0, 14.0]] {
            let d = f.distances(site);
            let b = brute_r_rup(&f, site);
            assert!((d.r_rup_km - b).abs() < 1e-6, "{site:?}: {} vs {b}", d.r_rup_km);
            assert!(d.r_jb_km <= d.r_rup_km);
        }
    }

    #[test]
    fn surface_points_and_fault_points_invert_the_coordinates() {
        let f = PlanarFault::new([3.0, -4.0], [-20.0, 31.0], 55.0, 1.5, 14.0).unwrap();
        let p = f.surface_point(7.0, -3.0);
        let d = f.distances(p);
        assert!(close(d.r_x_km, -3.0, 1e-12) && d.r_y0_km == 0.0);
        let p = f.surface_point(f.length_km() + 4.0, 2.0);
        assert!(close(f.distances(p).r_y0_km, 4.0, 1e-12));
        // The hypocentre at mid-length and half the width: depth Z_tor + (W/2) sin δ.
        let h = f.point(0.5 * f.length_km(), 7.0);
        assert!(close(h[2], 1.5 + 7.0 * 55f64.to_radians().sin(), 1e-12));
        let epi = [h[0], h[1]];
        assert_eq!(epicentral_km(h, epi), 0.0);
        assert!(close(hypocentral_km(h, epi), h[2], 1e-12));
        assert!(close(hypocentral_km(h, [epi[0] + 3.0, epi[1] + 4.0]), 5f64.hypot(h[2]), 1e-12));
    }

    #[test]
    fn bad_geometry_is_refused_naming_the_field() {
        let cases = [
            ("top_end", PlanarFault::new([1.0, 1.0], [1.0, 1.0], 90.0, 0.0, 10.0)),
            ("top_start", PlanarFault::new([f64::NAN, 1.0], [1.0, 1.0], 90.0, 0.0, 10.0)),
            ("dip_deg", PlanarFault::new([0.0, 0.0], [1.0, 1.0], 0.0, 0.0, 10.0)),
            ("dip_deg", PlanarFault::new([0.0, 0.0], [1.0, 1.0], 91.0, 0.0, 10.0)),
            ("ztor_km", PlanarFault::new([0.0, 0.0], [1.0, 1.0], 90.0, -0.5, 10.0)),
            ("width_km", PlanarFault::new([0.0, 0.0], [1.0, 1.0], 90.0, 0.0, 0.0)),
        ];
        for (field, r) in cases {
            let e = r.unwrap_err().to_string();
            assert!(e.starts_with(field), "{e}");
        }
    }
}
