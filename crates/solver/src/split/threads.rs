//! Ranks as threads of one process, trading halos over channels: the decomposition's logic
//! without MPI (tests, and a check of a split before a cluster run).

use std::sync::mpsc::{Receiver, Sender, channel};

use super::Neighbours;

/// A link to one neighbour: what this rank sends it, what it receives from it.
type Link = (Sender<Vec<f64>>, Receiver<Vec<f64>>);

/// One rank's links to its neighbours.
#[derive(Debug)]
pub struct ThreadRanks {
    down: Option<Link>,
    up: Option<Link>,
}

/// Links for `ranks` ranks in a row, rank 0 first.
pub fn thread_ranks(ranks: usize) -> Vec<ThreadRanks> {
    let mut out: Vec<ThreadRanks> = (0..ranks).map(|_| ThreadRanks { down: None, up: None }).collect();
    for r in 1..ranks {
        let (to_upper, upper_from_lower) = channel();
        let (to_lower, lower_from_upper) = channel();
        out[r - 1].up = Some((to_upper, lower_from_upper));
        out[r].down = Some((to_lower, upper_from_lower));
    }
    out
}

impl Neighbours for ThreadRanks {
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
