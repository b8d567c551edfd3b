//! Clipping in pixel space: what the charts draw is cut to the plotting area before it reaches
//! plotters, which does not clip (a drawing area's rectangle only positions its elements).
//!
//! Points are first mapped to pixels in f64 (through the axis transform: a log axis is clipped in
//! log space, since its pixels are linear in the logarithm), then cut here; nothing here knows
//! about data coordinates.

/// An axis-aligned rectangle in pixels, closed: `x0 ≤ x ≤ x1`, `y0 ≤ y ≤ y1` (image
/// coordinates, y down).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClipRect {
    /// Left edge.
    pub x0: f64,
    /// Top edge.
    pub y0: f64,
    /// Right edge.
    pub x1: f64,
    /// Bottom edge.
    pub y1: f64,
}

impl ClipRect {
    /// Whether `p` lies inside (edges included).
    pub fn contains(&self, p: (f64, f64)) -> bool {
        p.0 >= self.x0 && p.0 <= self.x1 && p.1 >= self.y0 && p.1 <= self.y1
    }
}

/// The part of the segment `a`–`b` inside `r` (Liang–Barsky), or `None` when it misses `r` or
/// an end is not finite. The returned ends lie on the segment, in the order `a` → `b`.
pub fn clip_segment(a: (f64, f64), b: (f64, f64), r: &ClipRect) -> Option<((f64, f64), (f64, f64))> {
    if ![a.0, a.1, b.0, b.1].iter().all(|v| v.is_finite()) {
        return None;
    }
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    // Each edge as p·t ≤ q: the segment enters where p < 0 and leaves where p > 0.
    for (p, q) in [(-dx, a.0 - r.x0), (dx, r.x1 - a.0), (-dy, a.1 - r.y0), (dy, r.y1 - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None; // parallel to this edge and outside it
            }
        } else {
            let t = q / p;
            if p < 0.0 {
                t0 = t0.max(t);
            } else {
                t1 = t1.min(t);
            }
            if t0 > t1 {
                return None;
            }
        }
    }
    let at = |t: f64| {
        // Clamp against round-off so the ends never fall a hair outside.
        ((a.0 + t * dx).clamp(r.x0, r.x1), (a.1 + t * dy).clamp(r.y0, r.y1))
    };
    Some((if t0 > 0.0 { at(t0) } else { a }, if t1 < 1.0 { at(t1) } else { b }))
}

/// A polyline cut to `r`: broken at every non-finite point and wherever it leaves `r`. Each
/// returned run is a connected polyline of at least two points inside `r`.
pub fn clip_polyline(points: &[(f64, f64)], r: &ClipRect) -> Vec<Vec<(f64, f64)>> {
    let mut runs: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut current: Vec<(f64, f64)> = Vec::new();
    let mut flush = |current: &mut Vec<(f64, f64)>| {
        if current.len() >= 2 {
            runs.push(std::mem::take(current));
        } else {
            current.clear();
        }
    };
    for w in points.windows(2) {
        match clip_segment(w[0], w[1], r) {
            Some((p, q)) => {
                // A new run starts when the segment was cut at its start or follows a gap.
                if current.last() != Some(&p) {
                    flush(&mut current);
                    current.push(p);
                }
                current.push(q);
                if q != w[1] {
                    flush(&mut current); // cut at its end: the line leaves the rectangle
                }
            }
            None => flush(&mut current),
        }
    }
    flush(&mut current);
    runs
}

/// The point of `a`–`b` at abscissa `x`.
fn at_x(x: f64, a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (x, a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
}

/// The point of `a`–`b` at ordinate `y`.
fn at_y(y: f64, a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 + (b.0 - a.0) * (y - a.1) / (b.1 - a.1), y)
}

/// A polygon cut to `r` (Sutherland–Hodgman against the four edges). Any simple polygon works,
/// convex or not; a concave one may come back with zero-width bridges along the edges, which
/// fill nothing. Vertices must be finite (split the polygon at non-finite points first).
pub fn clip_polygon(poly: &[(f64, f64)], r: &ClipRect) -> Vec<(f64, f64)> {
    type Inside = fn(&ClipRect, (f64, f64)) -> bool;
    type Cross = fn(&ClipRect, (f64, f64), (f64, f64)) -> (f64, f64);
    let edges: [(Inside, Cross); 4] = [
        (|r, p| p.0 >= r.x0, |r, a, b| at_x(r.x0, a, b)),
        (|r, p| p.0 <= r.x1, |r, a, b| at_x(r.x1, a, b)),
        (|r, p| p.1 >= r.y0, |r, a, b| at_y(r.y0, a, b)),
        (|r, p| p.1 <= r.y1, |r, a, b| at_y(r.y1, a, b)),
    ];
    let mut out: Vec<(f64, f64)> = poly.to_vec();
    for (inside, cross) in edges {
        let input = std::mem::take(&mut out);
        let Some(&last) = input.last() else { break };
        let mut prev = last;
        for &p in &input {
            match (inside(r, p), inside(r, prev)) {
                (true, true) => out.push(p),
                (true, false) => {
                    out.push(cross(r, prev, p));
                    out.push(p);
                }
                (false, true) => out.push(cross(r, prev, p)),
                (false, false) => {}
            }
            prev = p;
        }
    }
    out.iter().map(|&(x, y)| (x.clamp(r.x0, r.x1), y.clamp(r.y0, r.y1))).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const R: ClipRect = ClipRect { x0: 0.0, y0: 0.0, x1: 10.0, y1: 10.0 };

    fn close(a: (f64, f64), b: (f64, f64)) -> bool {
        (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12
    }

    #[test]
    fn a_segment_inside_is_kept_whole() {
        assert_eq!(clip_segment((1.0, 2.0), (3.0, 4.0), &R), Some(((1.0, 2.0), (3.0, 4.0))));
        // On the edges counts as inside.
        assert_eq!(clip_segment((0.0, 0.0), (10.0, 0.0), &R), Some(((0.0, 0.0), (10.0, 0.0))));
    }

    #[test]
    fn a_segment_crossing_is_cut_at_the_edges() {
        let (p, q) = clip_segment((-5.0, 5.0), (15.0, 5.0), &R).unwrap();
        assert!(close(p, (0.0, 5.0)) && close(q, (10.0, 5.0)), "{p:?} {q:?}");
        // A vertical spike from inside to far above: cut at the top edge.
        let (p, q) = clip_segment((5.0, 8.0), (5.0, -1e9), &R).unwrap();
        assert!(close(p, (5.0, 8.0)) && close(q, (5.0, 0.0)), "{p:?} {q:?}");
        // A diagonal through a corner region.
        let (p, q) = clip_segment((-2.0, 4.0), (4.0, -2.0), &R).unwrap();
        assert!(close(p, (0.0, 2.0)) && close(q, (2.0, 0.0)), "{p:?} {q:?}");
    }

    #[test]
    fn a_segment_outside_or_not_finite_is_dropped() {
        assert_eq!(clip_segment((-5.0, -5.0), (-1.0, 20.0), &R), None, "left of the rectangle");
        assert_eq!(clip_segment((-1.0, 12.0), (12.0, 30.0), &R), None, "passes the corner outside");
        assert_eq!(clip_segment((11.0, 1.0), (11.0, 9.0), &R), None, "parallel to an edge, outside");
        assert_eq!(clip_segment((1.0, 1.0), (f64::NAN, 2.0), &R), None);
        assert_eq!(clip_segment((1.0, 1.0), (f64::INFINITY, 2.0), &R), None);
    }

    #[test]
    fn a_polyline_breaks_at_gaps_and_at_exits() {
        let pts =
            [(1.0, 1.0), (2.0, 2.0), (f64::NAN, 3.0), (4.0, 4.0), (5.0, 5.0), (5.0, 50.0), (6.0, 5.0), (7.0, 6.0)];
        let runs = clip_polyline(&pts, &R);
        assert_eq!(runs.len(), 3, "{runs:?}");
        assert_eq!(runs[0], vec![(1.0, 1.0), (2.0, 2.0)]);
        assert_eq!(runs[1][..2], [(4.0, 4.0), (5.0, 5.0)]);
        assert!(close(*runs[1].last().unwrap(), (5.0, 10.0)));
        assert!(close(runs[2][0], (5.0 + 40.0 / 45.0, 10.0)), "{:?}", runs[2]);
        assert_eq!(runs[2][1..], [(6.0, 5.0), (7.0, 6.0)]);
        for run in &runs {
            assert!(run.iter().all(|&p| R.contains(p)));
        }
    }

    #[test]
    fn a_polygon_is_cut_to_the_rectangle() {
        // A square overhanging the top-right corner keeps only its inside quarter.
        let poly = clip_polygon(&[(5.0, 5.0), (15.0, 5.0), (15.0, -5.0), (5.0, -5.0)], &R);
        assert!(poly.iter().all(|&p| R.contains(p)), "{poly:?}");
        let area = poly.iter().zip(poly.iter().cycle().skip(1)).map(|(a, b)| a.0 * b.1 - b.0 * a.1).sum::<f64>() / 2.0;
        assert!((area.abs() - 25.0).abs() < 1e-9, "area {area}");
        assert!(clip_polygon(&[(20.0, 20.0), (30.0, 20.0), (30.0, 30.0)], &R).is_empty(), "outside");
    }
}
