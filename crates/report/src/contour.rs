//! Contour lines of a field on a regular grid, by marching squares: the segments where the
//! field, linearly interpolated along each cell edge, crosses a level.

/// The segments of the level `level` of `value(i, j)` on the grid `x[i] × y[j]` (values NaN where
/// the field is undefined: cells touching them are left out), as a polyline of pairs separated by
/// NaN points (a break).
pub fn contour(x: &[f64], y: &[f64], value: impl Fn(usize, usize) -> f64, level: f64) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    if x.len() < 2 || y.len() < 2 {
        return out;
    }
    for j in 0..y.len() - 1 {
        for i in 0..x.len() - 1 {
            // Corners counter-clockwise from (i, j).
            let c = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)];
            let v = c.map(|(a, b)| value(a, b));
            if v.iter().any(|v| !v.is_finite()) {
                continue;
            }
            let mut crossings: Vec<(f64, f64)> = Vec::with_capacity(4);
            for e in 0..4 {
                let (a, b) = (e, (e + 1) % 4);
                let (va, vb) = (v[a] - level, v[b] - level);
                if (va < 0.0) != (vb < 0.0) {
                    let t = va / (va - vb);
                    let (pa, pb) = ((x[c[a].0], y[c[a].1]), (x[c[b].0], y[c[b].1]));
                    crossings.push((pa.0 + t * (pb.0 - pa.0), pa.1 + t * (pb.1 - pa.1)));
                }
            }
            // Two crossings: one segment; four (a saddle): pair them by the cell's mean.
            match crossings.len() {
                2 => out.extend([crossings[0], crossings[1], (f64::NAN, f64::NAN)]),
                4 => {
                    let centre_below = v.iter().sum::<f64>() / 4.0 < level;
                    let below0 = v[0] < level;
                    let (p, q) = if centre_below == below0 { ((0, 3), (1, 2)) } else { ((0, 1), (2, 3)) };
                    out.extend([crossings[p.0], crossings[p.1], (f64::NAN, f64::NAN)]);
                    out.extend([crossings[q.0], crossings[q.1], (f64::NAN, f64::NAN)]);
                }
                _ => {}
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contours_of_a_cone_are_circles() {
        // r(x, y) = √(x² + y²): the level 1 contour's points lie on the unit circle to within
        // the interpolation error of a 0.05 grid.
        let g: Vec<f64> = (0..=60).map(|k| -1.5 + 0.05 * k as f64).collect();
        let pts = contour(&g, &g, |i, j| g[i].hypot(g[j]), 1.0);
        let finite: Vec<&(f64, f64)> = pts.iter().filter(|p| p.0.is_finite()).collect();
        assert!(finite.len() > 100);
        for p in finite {
            assert!((p.0.hypot(p.1) - 1.0).abs() < 2e-3, "{p:?}");
        }
        // A NaN corner leaves its cells out.
        assert!(contour(&g, &g, |_, _| f64::NAN, 1.0).is_empty());
    }
}
