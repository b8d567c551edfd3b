//! A friction map of the base: regions with their own coefficients over the law of the
//! background (patches, a grid), each region a barrier or a weak patch against it.

use super::NodeFriction;

/// A friction map of the base: base coefficients per contact node (canonical contact order,
/// [`crate::geometry::Lattice::contact_nodes`]) and the region each node belongs to; the field
/// factor of each seed multiplies them.
#[derive(Clone, Debug, PartialEq)]
pub struct FrictionMap {
    /// Coefficients of each contact node before the field factor.
    pub nodes: Vec<NodeFriction>,
    /// Region of each contact node: `None` = the background (the `[friction]` law), `Some(i)` =
    /// `regions[i]`.
    pub region: Vec<Option<u16>>,
    /// The regions, in precedence order as written.
    pub regions: Vec<Region>,
}

/// One region of a friction map.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Its name (`patch[i]` or the name given).
    pub name: String,
    /// What it is as seen from the background (from its μs).
    pub kind: RegionKind,
}

/// A region's strength against the background.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RegionKind {
    /// μs above the background's: a barrier.
    Barrier,
    /// μs at most the background's: an asperity where rupture may nucleate.
    Weak,
    /// μs at most the background's and no weakening (the residual coefficient at least the
    /// static one): slip there costs what it gains, as in a velocity-strengthening zone.
    Stable,
}

impl RegionKind {
    /// Name as written in tables and messages.
    pub fn name(self) -> &'static str {
        match self {
            RegionKind::Barrier => "barrier",
            RegionKind::Weak => "weak",
            RegionKind::Stable => "no weakening",
        }
    }
}
