//! Where labels go: one rule for every text a chart places (legends, reference-line labels,
//! marker labels, panel names).
//!
//! A chart first draws its data and marks every pixel it covered in an [`Occupancy`] grid (lines
//! with their width and a small clearance, bands, points, markers, reference lines). A label is
//! then a box of the size its text has in the chart's font (plotters' font metrics), offered at
//! a list of candidate positions in order of preference; [`choose`] takes the candidate that
//! lies inside the allowed region, overlaps no label already placed, and covers the fewest data
//! pixels, the earlier one on a tie. The chart decides what happens when the best candidate
//! still covers data (a legend or a reference label moves outside the axes, see
//! `charts`), and a label that would overlap another is not drawn at all: labels never
//! overprint each other.

/// A box in image pixels, half-open: `x0 ≤ x < x1`, `y0 ≤ y < y1` (y down).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelBox {
    /// Left edge.
    pub x0: i32,
    /// Top edge.
    pub y0: i32,
    /// One past the right edge.
    pub x1: i32,
    /// One past the bottom edge.
    pub y1: i32,
}

impl PixelBox {
    /// The box of size `(w, h)` with its top-left corner at `(x, y)`.
    pub fn at(x: i32, y: i32, (w, h): (i32, i32)) -> Self {
        PixelBox { x0: x, y0: y, x1: x + w, y1: y + h }
    }

    /// Width.
    pub fn width(&self) -> i32 {
        self.x1 - self.x0
    }

    /// Height.
    pub fn height(&self) -> i32 {
        self.y1 - self.y0
    }

    /// Whether the two boxes share a pixel.
    pub fn intersects(&self, o: &PixelBox) -> bool {
        self.x0 < o.x1 && o.x0 < self.x1 && self.y0 < o.y1 && o.y0 < self.y1
    }

    /// Whether `o` lies wholly inside this box.
    pub fn holds(&self, o: &PixelBox) -> bool {
        o.x0 >= self.x0 && o.x1 <= self.x1 && o.y0 >= self.y0 && o.y1 <= self.y1
    }

    /// Whether the pixel `p` lies inside.
    pub fn contains(&self, p: (i32, i32)) -> bool {
        p.0 >= self.x0 && p.0 < self.x1 && p.1 >= self.y0 && p.1 < self.y1
    }

    /// The box grown by `d` pixels on every side (shrunk when `d < 0`).
    pub fn grown(&self, d: i32) -> PixelBox {
        PixelBox { x0: self.x0 - d, y0: self.y0 - d, x1: self.x1 + d, y1: self.y1 + d }
    }
}

/// Which pixels of an image hold drawn data.
#[derive(Clone, Debug)]
pub struct Occupancy {
    w: i32,
    h: i32,
    cells: Vec<bool>,
}

impl Occupancy {
    /// An empty grid of `w × h` pixels.
    pub fn new(w: u32, h: u32) -> Self {
        Occupancy { w: w as i32, h: h as i32, cells: vec![false; w as usize * h as usize] }
    }

    /// Marks the pixels of `b` (the part inside the image).
    pub fn mark_box(&mut self, b: PixelBox) {
        let (x0, x1) = (b.x0.max(0), b.x1.min(self.w));
        let (y0, y1) = (b.y0.max(0), b.y1.min(self.h));
        for y in y0..y1 {
            let row = (y * self.w) as usize;
            self.cells[row + x0 as usize..row + x1.max(x0) as usize].fill(true);
        }
    }

    /// Marks the segment `a`–`b` (pixel coordinates) drawn `half` pixels to each side.
    pub fn mark_segment(&mut self, a: (f64, f64), b: (f64, f64), half: i32) {
        let steps = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0) as usize;
        for k in 0..=steps {
            let t = k as f64 / steps as f64;
            let (x, y) = ((a.0 + t * (b.0 - a.0)).round() as i32, (a.1 + t * (b.1 - a.1)).round() as i32);
            self.mark_box(PixelBox { x0: x - half, y0: y - half, x1: x + half + 1, y1: y + half + 1 });
        }
    }

    /// Whether the pixel `p` holds data.
    pub fn is_marked(&self, p: (i32, i32)) -> bool {
        p.0 >= 0 && p.0 < self.w && p.1 >= 0 && p.1 < self.h && self.cells[(p.1 * self.w + p.0) as usize]
    }

    /// The data pixels inside `b`.
    pub fn count(&self, b: &PixelBox) -> u32 {
        let (x0, x1) = (b.x0.max(0), b.x1.min(self.w));
        let (y0, y1) = (b.y0.max(0), b.y1.min(self.h));
        if x1 <= x0 {
            return 0;
        }
        (y0..y1)
            .map(|y| {
                let row = (y * self.w) as usize;
                self.cells[row + x0 as usize..row + x1 as usize].iter().filter(|c| **c).count() as u32
            })
            .sum()
    }
}

/// The placement rule: of `candidates` (in order of preference), those inside `within` that
/// overlap none of the `placed` label boxes compete; the one covering the fewest data pixels
/// wins, the earlier on a tie. Returns its index and the data pixels it covers, or `None` when
/// no candidate is allowed.
pub fn choose(
    candidates: &[PixelBox],
    within: &PixelBox,
    data: &Occupancy,
    placed: &[PixelBox],
) -> Option<(usize, u32)> {
    let mut best: Option<(usize, u32)> = None;
    for (i, c) in candidates.iter().enumerate() {
        if !within.holds(c) || placed.iter().any(|p| p.intersects(c)) {
            continue;
        }
        let n = data.count(c);
        if best.is_none_or(|(_, m)| n < m) {
            best = Some((i, n));
            if n == 0 {
                break; // nothing beats an empty spot, and earlier ones are preferred
            }
        }
    }
    best
}

/// Candidate boxes of `size` around a point (a marker): above it, then beside it, then below,
/// `gap` pixels away from the point's `reach` (the marker's half-size).
pub fn around_point(p: (i32, i32), reach: i32, gap: i32, size: (i32, i32)) -> Vec<PixelBox> {
    let (w, h) = size;
    let d = reach + gap;
    let (x, y) = p;
    [
        (x - w / 2, y - d - h),         // above
        (x + d / 2, y - d - h),         // above right
        (x - w - d / 2, y - d - h),     // above left
        (x + d, y - h / 2),             // right
        (x - d - w, y - h / 2),         // left
        (x - w / 2, y + d),             // below
        (x + d / 2, y + d),             // below right
        (x - w - d / 2, y + d),         // below left
        (x - w / 2, y - d - 2 * h - 2), // further above
    ]
    .into_iter()
    .map(|(x, y)| PixelBox::at(x, y, size))
    .collect()
}

/// Candidate boxes of `size` just above and just below a horizontal line at pixel row `y`,
/// spanning `x0..x1`: at the left end, the right end, then at quarters.
pub fn along_hline(y: i32, x0: i32, x1: i32, gap: i32, size: (i32, i32)) -> Vec<PixelBox> {
    let (w, h) = size;
    let span = (x1 - x0 - w).max(0);
    let xs = [x0 + gap, x0 + span - gap, x0 + span / 4, x0 + span / 2, x0 + 3 * span / 4];
    let mut out = Vec::with_capacity(2 * xs.len());
    for x in xs {
        out.push(PixelBox::at(x, y - gap - h, size));
        out.push(PixelBox::at(x, y + gap + 1, size));
    }
    out
}

/// Candidate boxes of `size` inside `area`, `inset` pixels from its edges: the four corners
/// (upper right first), the middles of the edges, then a scan of the whole area in steps of
/// `step` pixels.
pub fn in_area(area: &PixelBox, inset: i32, step: i32, size: (i32, i32)) -> Vec<PixelBox> {
    let (w, h) = size;
    let (l, r) = (area.x0 + inset, area.x1 - inset - w);
    let (t, b) = (area.y0 + inset, area.y1 - inset - h);
    if r < l || b < t {
        return vec![];
    }
    let (cx, cy) = ((l + r) / 2, (t + b) / 2);
    let mut out: Vec<PixelBox> = [(r, t), (l, t), (r, b), (l, b), (cx, t), (cx, b), (r, cy), (l, cy)]
        .iter()
        .map(|&(x, y)| PixelBox::at(x, y, size))
        .collect();
    let step = step.max(1);
    let mut y = t;
    while y <= b {
        let mut x = l;
        while x <= r {
            out.push(PixelBox::at(x, y, size));
            x += step;
        }
        y += step;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_box_on_no_data_wins_and_ties_go_to_the_preferred() {
        let mut data = Occupancy::new(100, 100);
        data.mark_box(PixelBox::at(0, 0, (50, 100))); // the left half is full
        let within = PixelBox::at(0, 0, (100, 100));
        let left = PixelBox::at(10, 10, (20, 10));
        let right = PixelBox::at(60, 10, (20, 10));
        let right_low = PixelBox::at(60, 60, (20, 10));
        assert_eq!(choose(&[left, right, right_low], &within, &data, &[]), Some((1, 0)));
        // With the right spot taken by a label, the other free one.
        assert_eq!(choose(&[left, right, right_low], &within, &data, &[right]), Some((2, 0)));
        // No free spot: the least covered one, and how much it covers.
        let half = PixelBox::at(40, 10, (20, 10));
        assert_eq!(choose(&[left, half], &within, &data, &[]), Some((1, 100)));
    }

    #[test]
    fn no_candidate_outside_the_region_or_on_a_label() {
        let data = Occupancy::new(100, 100);
        let within = PixelBox::at(10, 10, (80, 80));
        let outside = PixelBox::at(85, 10, (20, 10));
        let label = PixelBox::at(20, 20, (30, 10));
        let on_label = PixelBox::at(40, 25, (20, 10));
        assert_eq!(choose(&[outside, on_label], &within, &data, &[label]), None);
    }

    #[test]
    fn segments_mark_their_width() {
        let mut data = Occupancy::new(50, 50);
        data.mark_segment((10.0, 10.0), (40.0, 10.0), 1);
        assert!(data.is_marked((25, 9)) && data.is_marked((25, 11)) && !data.is_marked((25, 12)));
        assert_eq!(data.count(&PixelBox::at(10, 9, (31, 3))), 93);
        // Off-image parts are ignored, not wrapped.
        data.mark_segment((-10.0, 45.0), (60.0, 45.0), 0);
        assert_eq!(data.count(&PixelBox::at(0, 45, (50, 1))), 50);
    }

    #[test]
    fn candidates_have_the_size_asked_and_start_where_preferred() {
        let area = PixelBox::at(100, 50, (400, 300));
        let c = in_area(&area, 6, 20, (80, 30));
        assert!(c.iter().all(|b| area.holds(b) && b.width() == 80 && b.height() == 30));
        assert_eq!(c[0], PixelBox::at(500 - 6 - 80, 56, (80, 30)), "upper right first");
        let a = around_point((200, 200), 5, 3, (20, 10));
        assert_eq!(a[0], PixelBox::at(190, 182, (20, 10)), "above first");
        assert!(a.iter().all(|b| !b.contains((200, 200))));
        let h = along_hline(100, 0, 300, 4, (50, 12));
        assert!(h.iter().all(|b| b.y1 <= 96 || b.y0 >= 105), "never on the line");
    }
}
