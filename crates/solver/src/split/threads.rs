//! Ranks as threads of one process, trading halos over channels: the decomposition's logic
//! without MPI (tests, and a check of a split before a cluster run).

use std::sync::mpsc::{Receiver, Sender, channel};

use super::Neighbours;

/// A link to one neighbour: what this rank sends it, what it receives from it.
type Link = (Sender<Vec<f64>>, Receiver<Vec<f64>>);

/// One rank's links to its neighbours and to rank 0.
#[derive(Debug)]
pub struct ThreadRanks {
    rank: usize,
    size: usize,
    down: Option<Link>,
    up: Option<Link>,
    /// Rank 0: a link to every other rank (index `r − 1`); the others: their link to rank 0.
    root: Vec<Link>,
}

/// Links for `ranks` ranks in a row, rank 0 first.
pub fn thread_ranks(ranks: usize) -> Vec<ThreadRanks> {
    let mut out: Vec<ThreadRanks> =
        (0..ranks).map(|rank| ThreadRanks { rank, size: ranks, down: None, up: None, root: Vec::new() }).collect();
    for r in 1..ranks {
        let (to_upper, upper_from_lower) = channel();
        let (to_lower, lower_from_upper) = channel();
        out[r - 1].up = Some((to_upper, lower_from_upper));
        out[r].down = Some((to_lower, upper_from_lower));
        let (to_root, root_from) = channel();
        let (from_root_tx, from_root) = channel();
        out[0].root.push((from_root_tx, root_from));
        out[r].root.push((to_root, from_root));
    }
    out
}

impl Neighbours for ThreadRanks {
    fn rank(&self) -> usize {
        self.rank
    }

    fn size(&self) -> usize {
        self.size
    }

    fn gather(&mut self, mine: &[f64]) -> Vec<Vec<f64>> {
        if self.rank == 0 {
            let mut all = vec![mine.to_vec()];
            all.extend(self.root.iter().map(|(_, rx)| rx.recv().expect("every rank is running")));
            all
        } else {
            self.root[0].0.send(mine.to_vec()).expect("rank 0 is running");
            Vec::new()
        }
    }

    fn broadcast(&mut self, data: &mut [f64]) {
        if self.rank == 0 {
            for (tx, _) in &self.root {
                tx.send(data.to_vec()).expect("every rank is running");
            }
        } else {
            data.copy_from_slice(&self.root[0].1.recv().expect("rank 0 is running"));
        }
    }

    fn swap(&mut self, send_down: &[f64], send_up: &[f64], from_below: &mut [f64], from_above: &mut [f64]) {
        // Channels are unbounded: send both, then wait for both.
        if let Some((tx, _)) = &self.down {
            tx.send(send_down.to_vec()).expect("the rank below is running");
        }
        if let Some((tx, _)) = &self.up {
            tx.send(send_up.to_vec()).expect("the rank above is running");
        }
        if let Some((_, rx)) = &self.down {
            from_below.copy_from_slice(&rx.recv().expect("the rank below is running"));
        }
        if let Some((_, rx)) = &self.up {
            from_above.copy_from_slice(&rx.recv().expect("the rank above is running"));
        }
    }
}
