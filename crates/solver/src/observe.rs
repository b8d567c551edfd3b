//! What recorders read at one viewed time: a lane of a stepper, or a quasi-static motion.

use crate::scene::{ControlChannel, Kinematic};
use crate::step::{Energy, Interface, LaneView, NodeContact};

/// What a recorder reads at one viewed time: a lane of a stepper, or a quasi-static motion
/// the run skips through.
pub(crate) trait Observed {
    /// Contact node `ci` (order of [`crate::Model::contact`]).
    fn node_contact(&self, ci: usize) -> NodeContact;
    /// Number of contact nodes.
    fn contacts(&self) -> usize;
    /// Interface resultants: the contact nodes summed in their order.
    fn interface(&self) -> Interface {
        Interface::sum((0..self.contacts()).map(|ci| self.node_contact(ci)))
    }
    /// Total driver reaction in x (N).
    fn driver_force(&self) -> f64;
    /// Driver displacement (m).
    fn driver_target(&self) -> f64;
    /// Energy terms.
    fn energy(&self) -> Energy;
    /// Displacement, velocity or acceleration of internal node `node`.
    fn kinematic(&self, node: usize, q: Kinematic) -> [f64; 3];
    /// Control channel `ch` of internal node `node` (on a rank of a split scene, `node` is
    /// [`REMOTE`] when another rank owns it and sends the value).
    fn control(&self, ch: ControlChannel, node: usize) -> f64 {
        self.kinematic(node, ch.quantity)[ch.component.axis()]
    }
}

/// The internal index a rank gives a control node another rank owns ([`Observed::control`]).
pub(crate) const REMOTE: usize = usize::MAX;

impl<const L: usize> Observed for LaneView<'_, '_, L> {
    #[inline(always)]
    fn node_contact(&self, ci: usize) -> NodeContact {
        LaneView::node_contact(self, ci)
    }

    fn contacts(&self) -> usize {
        self.params.model.contact().len()
    }

    fn driver_force(&self) -> f64 {
        LaneView::driver_force(self)
    }

    fn driver_target(&self) -> f64 {
        LaneView::driver_target(self)
    }

    fn energy(&self) -> Energy {
        LaneView::energy(self)
    }

    fn kinematic(&self, node: usize, q: Kinematic) -> [f64; 3] {
        match q {
            Kinematic::Displacement => self.displacement(node),
            Kinematic::Velocity => self.velocity(node),
            Kinematic::Acceleration => self.acceleration(node),
        }
    }
}
