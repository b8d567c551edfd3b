//! Ranks as MPI processes (the `mpi` feature: rsmpi over Open MPI or MPICH): each step's halo
//! layers go to the neighbours with non-blocking sends, posted with the receives, then waited on.
//! MPI is called from the thread that steps only.

use mpi::topology::SimpleCommunicator;
use mpi::traits::{Communicator, Destination, Root, Source};

use stickslip_solver::split::Neighbours;

/// Message tags: a layer sent up, a layer sent down.
const UP: i32 = 1;
const DOWN: i32 = 2;
/// A rank's numbers gathered to rank 0.
const GATHER: i32 = 3;

/// One rank's neighbours in a communicator whose ranks are the partition's, bottom up.
pub struct MpiRanks<'c> {
    world: &'c SimpleCommunicator,
}

impl<'c> MpiRanks<'c> {
    /// The neighbours of this process in `world`.
    pub fn new(world: &'c SimpleCommunicator) -> Self {
        MpiRanks { world }
    }
}

impl Neighbours for MpiRanks<'_> {
    fn rank(&self) -> usize {
        self.world.rank() as usize
    }

    fn size(&self) -> usize {
        self.world.size() as usize
    }

    fn gather(&mut self, mine: &[f64]) -> Vec<Vec<f64>> {
        if self.world.rank() == 0 {
            let mut all = vec![mine.to_vec()];
            for r in 1..self.world.size() {
                all.push(self.world.process_at_rank(r).receive_vec_with_tag::<f64>(GATHER).0);
            }
            all
        } else {
            self.world.process_at_rank(0).send_with_tag(mine, GATHER);
            Vec::new()
        }
    }

    fn broadcast(&mut self, data: &mut [f64]) {
        self.world.process_at_rank(0).broadcast_into(data);
    }

    fn swap(&mut self, send_down: &[f64], send_up: &[f64], from_below: &mut [f64], from_above: &mut [f64]) {
        let (rank, size) = (self.world.rank(), self.world.size());
        mpi::request::scope(|scope| {
            let mut pending = Vec::with_capacity(4);
            if rank > 0 {
                let below = self.world.process_at_rank(rank - 1);
                pending.push(below.immediate_receive_into_with_tag(scope, from_below, UP));
                pending.push(below.immediate_send_with_tag(scope, send_down, DOWN));
            }
            if rank + 1 < size {
                let above = self.world.process_at_rank(rank + 1);
                pending.push(above.immediate_receive_into_with_tag(scope, from_above, DOWN));
                pending.push(above.immediate_send_with_tag(scope, send_up, UP));
            }
            for request in pending {
                request.wait();
            }
        });
    }
}
