//! Stations of a planar vertical strike-slip scenario placed like the recordings of a real
//! earthquake: each recording's longitude and latitude projected onto the scenario's fault trace
//! (a great circle from its southern to its northern end on a sphere of radius 6371 km: distance
//! along strike from the southern end, and perpendicular distance), then placed on the modelled
//! side of the fault (the scene models one side by symmetry) so that its distance to the trace —
//! its R_rup, for a surface station and a vertical plane that reaches the surface — is the
//! recording's own R_rup:
//!
//! - beside the fault (0 ≤ along ≤ L): at its along-strike position, R_rup away from the plane;
//! - past an end: in its own direction from that end, R_rup away from it (the offset beyond the
//!   end and the perpendicular distance both scaled by R_rup/d, d its distance to the end).
//!
//! In the block, x is along strike from `x0` (the southern end), z away from the fault, y = 0
//! the surface.

/// Earth's radius of the projection (km).
pub const EARTH_RADIUS_KM: f64 = 6371.0;

/// A point on the Earth: latitude and longitude (degrees).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LatLon {
    /// Latitude (degrees north).
    pub lat: f64,
    /// Longitude (degrees east).
    pub lon: f64,
}

fn radians(p: LatLon) -> (f64, f64) {
    (p.lat.to_radians(), p.lon.to_radians())
}

/// Great-circle distance (km).
pub fn distance_km(a: LatLon, b: LatLon) -> f64 {
    let ((p1, l1), (p2, l2)) = (radians(a), radians(b));
    let h = ((p2 - p1) / 2.0).sin().powi(2) + p1.cos() * p2.cos() * ((l2 - l1) / 2.0).sin().powi(2);
    2.0 * EARTH_RADIUS_KM * h.sqrt().asin()
}

/// Initial bearing from `a` to `b` (radians clockwise from north).
pub fn bearing(a: LatLon, b: LatLon) -> f64 {
    let ((p1, l1), (p2, l2)) = (radians(a), radians(b));
    let y = (l2 - l1).sin() * p2.cos();
    let x = p1.cos() * p2.sin() - p1.sin() * p2.cos() * (l2 - l1).cos();
    y.atan2(x)
}

/// A fault trace from its southern end to its northern end.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Trace {
    /// The southern end (x = 0 along strike).
    pub start: LatLon,
    /// The northern end.
    pub end: LatLon,
}

impl Trace {
    /// Its length (km).
    pub fn length_km(&self) -> f64 {
        distance_km(self.start, self.end)
    }

    /// Its strike (degrees clockwise from north, 0–360).
    pub fn strike_deg(&self) -> f64 {
        bearing(self.start, self.end).to_degrees().rem_euclid(360.0)
    }

    /// A point's distance along the trace's great circle from the start (km; negative behind it)
    /// and its signed perpendicular distance (km; positive to the right of the strike).
    pub fn project(&self, p: LatLon) -> [f64; 2] {
        let d = distance_km(self.start, p) / EARTH_RADIUS_KM;
        let dtheta = bearing(self.start, p) - bearing(self.start, self.end);
        let cross = (d.sin() * dtheta.sin()).asin();
        let along = (d.cos() / cross.cos()).clamp(-1.0, 1.0).acos();
        let along = if dtheta.cos() < 0.0 { -along } else { along };
        [along * EARTH_RADIUS_KM, cross * EARTH_RADIUS_KM]
    }
}

/// A station placed in the block.
#[derive(Clone, Debug, PartialEq)]
pub struct Placement {
    /// Along strike and perpendicular, from the projection (km).
    pub projected_km: [f64; 2],
    /// Distance to the trace segment (km).
    pub trace_distance_km: f64,
    /// Where it goes: along strike from the southern end, and away from the fault (km, ≥ 0).
    pub at_km: [f64; 2],
}

/// Places a station projected at `[along, perpendicular]` (km) beside a fault of length
/// `length_km` at distance `r_rup_km` from it (see the module's rules).
pub fn place(projected_km: [f64; 2], length_km: f64, r_rup_km: f64) -> Placement {
    let [a, p] = projected_km;
    let end = if a < 0.0 {
        Some(0.0)
    } else if a > length_km {
        Some(length_km)
    } else {
        None
    };
    let (trace_distance_km, at_km) = match end {
        None => (p.abs(), [a, r_rup_km]),
        Some(e) => {
            let d = (a - e).hypot(p);
            let s = if d > 0.0 { r_rup_km / d } else { 0.0 };
            (d, [e + (a - e) * s, p.abs() * s])
        }
    };
    Placement { projected_km, trace_distance_km, at_km }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_meridian_trace_projects_points_along_and_across_it() {
        // A trace due north along 116°W; 1° of latitude is 111.19 km on the 6371 km sphere.
        let t = Trace { start: LatLon { lat: 34.0, lon: -116.0 }, end: LatLon { lat: 35.0, lon: -116.0 } };
        assert!((t.length_km() - 111.195).abs() < 0.01);
        assert!(t.strike_deg().abs() < 1e-9 || (t.strike_deg() - 360.0).abs() < 1e-9);
        let [a, p] = t.project(LatLon { lat: 34.5, lon: -116.0 });
        assert!((a - 55.597).abs() < 0.01 && p.abs() < 1e-9);
        // East of the trace is to the right of a northward strike.
        let [a, p] = t.project(LatLon { lat: 34.0, lon: -115.9 });
        assert!(a.abs() < 0.01 && (p - 9.215).abs() < 0.01, "{a} {p}");
        let [a, _] = t.project(LatLon { lat: 33.9, lon: -116.0 });
        assert!((a + 11.12).abs() < 0.01, "{a}");
    }

    #[test]
    fn stations_keep_their_rupture_distance_and_their_side_of_the_ends() {
        // Beside the fault: along strike as projected, R_rup away from it (either side).
        let s = place([30.0, -12.0], 70.0, 10.0);
        assert_eq!((s.at_km, s.trace_distance_km), ([30.0, 10.0], 12.0));
        // 30 km past the northern end and 40 km aside (d = 50 km) with R_rup 45 km: scaled by 0.9.
        let s = place([100.0, 40.0], 70.0, 45.0);
        assert!((s.at_km[0] - 97.0).abs() < 1e-12 && (s.at_km[1] - 36.0).abs() < 1e-12);
        assert_eq!(s.trace_distance_km, 50.0);
        // Behind the southern end.
        let s = place([-3.0, -4.0], 70.0, 10.0);
        assert!((s.at_km[0] + 6.0).abs() < 1e-12 && (s.at_km[1] - 8.0).abs() < 1e-12);
        for p in [place([-3.0, -4.0], 70.0, 10.0), place([100.0, 40.0], 70.0, 45.0)] {
            let e = if p.at_km[0] < 0.0 { 0.0 } else { 70.0 };
            let r = (p.at_km[0] - e).hypot(p.at_km[1]);
            assert!((r - if e == 0.0 { 10.0 } else { 45.0 }).abs() < 1e-12);
        }
    }
}
