//! Acoustic emission: bar breaks close in space and time grouped into events, with a magnitude
//! from their energy (docs/model.md §11.5).
//!
//! Two breaks are **linked** when they are at most `link_time_s` apart in time and at most
//! `link_distance_m` apart in space; an acoustic-emission event is a class of breaks connected by
//! links (single linkage, so a crack that runs through the block at a finite speed is one event
//! however long it grows). Its time is that of its first break, its **hypocentre** the first
//! break's position, its **centroid** the energy-weighted mean position, its energy `E` the sum of
//! its breaks' energies.
//!
//! **Magnitude convention.** `M = (log10 E − 4.8)/1.5`, `E` in joules: the Gutenberg–Richter
//! energy–magnitude relation `log10 E = 1.5·M + 4.8` (`11.8` with `E` in erg) applied to the
//! energy the breaks released. It puts laboratory acoustic emission on the scale of earthquakes
//! (a millijoule is M ≈ −5.2); the energy is the fracture energy of the broken bars, not the energy
//! radiated as waves, which the model does not separate from damping.

/// How breaks are linked.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClusterParams {
    /// Largest distance between two linked breaks (m).
    pub link_distance_m: f64,
    /// Largest time between two linked breaks (s).
    pub link_time_s: f64,
}

/// One bar break.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Break {
    /// When (s).
    pub time_s: f64,
    /// Where (m).
    pub position: [f64; 3],
    /// Energy it released (J).
    pub energy_j: f64,
}

/// An acoustic-emission event.
#[derive(Clone, Debug, PartialEq)]
pub struct Cluster {
    /// Time of the first break (s).
    pub start_s: f64,
    /// Time of the last break (s).
    pub end_s: f64,
    /// Indices of its breaks in the input, in time order.
    pub breaks: Vec<usize>,
    /// Position of the first break (m).
    pub hypocentre: [f64; 3],
    /// Energy-weighted mean position (m).
    pub centroid: [f64; 3],
    /// Sum of the breaks' energies (J).
    pub energy_j: f64,
    /// `(log10 E − 4.8)/1.5`.
    pub magnitude: f64,
}

/// The magnitude of an energy `e_j` in joules: `(log10 E − 4.8)/1.5` (Gutenberg–Richter).
pub fn energy_magnitude(e_j: f64) -> f64 {
    (e_j.log10() - 4.8) / 1.5
}

/// The acoustic-emission events of `breaks` (any order), in the order of their first break.
pub fn clusters(breaks: &[Break], p: &ClusterParams) -> Vec<Cluster> {
    let n = breaks.len();
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| breaks[a].time_s.total_cmp(&breaks[b].time_s).then(a.cmp(&b)));
    // Union-find over positions in `order`.
    let mut parent: Vec<usize> = (0..n).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    // Each break is compared with the earlier breaks within the link time in its cell and the 26
    // around it: cells of the link distance's side, so that two breaks within it are at most one
    // cell apart along each axis. A burst of breaks costs their neighbours, not their square
    // (all of a block's bars breaking at once took minutes as a scan of every pair in time).
    let d2 = p.link_distance_m * p.link_distance_m;
    // A side a little over the distance: two breaks exactly the distance apart stay within one
    // cell of each other whatever the rounding of v/side (the distance test below decides).
    let side =
        if p.link_distance_m > 0.0 && p.link_distance_m.is_finite() { p.link_distance_m * (1.0 + 1e-9) } else { 1.0 };
    let cell = |q: &[f64; 3]| q.map(|v| (v / side).floor() as i64);
    let mut recent: std::collections::HashMap<[i64; 3], std::collections::VecDeque<usize>> =
        std::collections::HashMap::new();
    for b in 0..n {
        let bb = &breaks[order[b]];
        let [cx, cy, cz] = cell(&bb.position);
        for dx in -1..=1 {
            for dy in -1..=1 {
                for dz in -1..=1 {
                    let key = [cx.saturating_add(dx), cy.saturating_add(dy), cz.saturating_add(dz)];
                    let Some(earlier) = recent.get_mut(&key) else { continue };
                    while earlier.front().is_some_and(|&a| bb.time_s - breaks[order[a]].time_s > p.link_time_s) {
                        earlier.pop_front();
                    }
                    for &a in earlier.iter() {
                        let ba = &breaks[order[a]];
                        let dist2: f64 = (0..3).map(|c| (bb.position[c] - ba.position[c]).powi(2)).sum();
                        if dist2 <= d2 {
                            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
                            if ra != rb {
                                // The earlier break's class absorbs the later one's: roots stay
                                // first breaks.
                                parent[ra.max(rb)] = ra.min(rb);
                            }
                        }
                    }
                }
            }
        }
        recent.entry([cx, cy, cz]).or_default().push_back(b);
    }
    let mut members: Vec<Vec<usize>> = vec![Vec::new(); n];
    for a in 0..n {
        let r = root(&mut parent, a);
        members[r].push(a);
    }
    members
        .into_iter()
        .filter(|m| !m.is_empty())
        .map(|m| {
            let idx: Vec<usize> = m.iter().map(|&a| order[a]).collect();
            let energy: f64 = idx.iter().map(|&i| breaks[i].energy_j).sum();
            let mut centroid = [0.0; 3];
            for &i in &idx {
                for c in 0..3 {
                    centroid[c] += breaks[i].energy_j * breaks[i].position[c];
                }
            }
            let centroid = centroid.map(|v| if energy > 0.0 { v / energy } else { f64::NAN });
            let first = &breaks[idx[0]];
            Cluster {
                start_s: first.time_s,
                end_s: breaks[*idx.last().expect("a class has a member")].time_s,
                hypocentre: first.position,
                centroid,
                energy_j: energy,
                magnitude: energy_magnitude(energy),
                breaks: idx,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Single linkage by every pair in time, the definition the cells must give.
    fn classes_by_pairs(breaks: &[Break], p: &ClusterParams) -> Vec<Vec<usize>> {
        let n = breaks.len();
        let mut class: Vec<usize> = (0..n).collect();
        let linked = |a: &Break, b: &Break| {
            (a.time_s - b.time_s).abs() <= p.link_time_s
                && (0..3).map(|c| (a.position[c] - b.position[c]).powi(2)).sum::<f64>() <= p.link_distance_m.powi(2)
        };
        loop {
            let mut changed = false;
            for a in 0..n {
                for b in 0..n {
                    if linked(&breaks[a], &breaks[b]) && class[b] < class[a] {
                        class[a] = class[b];
                        changed = true;
                    }
                }
            }
            if !changed {
                break;
            }
        }
        let mut out: Vec<Vec<usize>> = (0..n).map(|r| (0..n).filter(|&i| class[i] == r).collect()).collect();
        out.retain(|m| !m.is_empty());
        out.sort();
        out
    }

    #[test]
    fn the_cells_link_exactly_the_pairs_within_both_limits() {
        // 400 breaks of a small random cloud, bursts of equal times included, on link distances
        // smaller and larger than the cloud's spacing.
        let mut state = 0x9e37_79b9_7f4a_7c15_u64;
        let mut u = || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        let breaks: Vec<Break> = (0..400)
            .map(|_| Break {
                time_s: (u() * 40.0).floor() * 0.05,
                position: [u() * 10.0 - 5.0, u() * 10.0, u() * 3.0],
                energy_j: 1.0,
            })
            .collect();
        for (d, t) in [(0.5, 0.05), (1.0, 0.2), (2.5, 0.0), (0.0, 1.0)] {
            let p = ClusterParams { link_distance_m: d, link_time_s: t };
            let mut got: Vec<Vec<usize>> = clusters(&breaks, &p)
                .into_iter()
                .map(|c| {
                    let mut b = c.breaks;
                    b.sort();
                    b
                })
                .collect();
            got.sort();
            assert_eq!(got, classes_by_pairs(&breaks, &p), "link distance {d}, time {t}");
        }
    }

    fn b(t: f64, x: f64, e: f64) -> Break {
        Break { time_s: t, position: [x, 0.0, 0.0], energy_j: e }
    }

    #[test]
    fn breaks_close_in_space_and_time_form_one_event() {
        let p = ClusterParams { link_distance_m: 0.15, link_time_s: 1e-4 };
        let breaks = vec![
            b(0.0, 0.0, 1.0),
            b(5e-5, 0.1, 1.0),    // linked to the first
            b(1.4e-4, 0.2, 2.0),  // linked to the second (chain), not to the first
            b(1.5e-4, 0.9, 1.0),  // in time, too far: its own event
            b(1.0, 0.0, 4.0),     // much later: its own event
            b(1.00005, 0.5, 1.0), // in time with the last, too far
        ];
        let c = clusters(&breaks, &p);
        assert_eq!(c.len(), 4);
        assert_eq!(c[0].breaks, vec![0, 1, 2]);
        assert_eq!((c[0].start_s, c[0].end_s), (0.0, 1.4e-4));
        assert!((c[0].energy_j - 4.0).abs() < 1e-15);
        assert!((c[0].centroid[0] - (0.1 + 0.4) / 4.0).abs() < 1e-15);
        assert_eq!(c[1].breaks, vec![3]);
        assert_eq!(c[2].breaks, vec![4]);
        assert_eq!(c[3].breaks, vec![5]);
        // The input order does not matter.
        let mut shuffled = breaks.clone();
        shuffled.reverse();
        let d = clusters(&shuffled, &p);
        assert_eq!(d.iter().map(|c| c.breaks.len()).collect::<Vec<_>>(), vec![3, 1, 1, 1]);
        assert_eq!(d[0].energy_j, c[0].energy_j);
    }

    #[test]
    fn the_magnitude_follows_gutenberg_richter() {
        // log10 E = 1.5 M + 4.8: M = 0 is 63 kJ, each unit 10^1.5 more energy.
        assert!((energy_magnitude(10f64.powf(4.8)) - 0.0).abs() < 1e-12);
        assert!((energy_magnitude(10f64.powf(6.3)) - 1.0).abs() < 1e-12);
        assert!((energy_magnitude(1e-3) - (-7.8 / 1.5)).abs() < 1e-12);
    }
}
