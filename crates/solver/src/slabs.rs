//! Whether a lattice is a stencil, and where its z-slabs start (see [`crate::stencil`]'s doc): the
//! step's threads and the ranks of a split scene ([`crate::split`]) both cut the layers by this
//! rule.

/// Elastic lattices with at least this many bars run as a stencil ([`crate::stencil::StencilLayout`]):
/// their bars' ends follow from the runs, and each run is one vector loop. Smaller ones list
/// their bars, and so does each rank of one split ([`crate::split::Partition`]).
pub const STENCIL_MIN_BARS: usize = 100_000;

/// Most slabs of a lattice (the parallelism of one step), not counting a top layer alone.
pub const MAX_SLABS: usize = 16;

/// The layers where the slabs of a lattice of `layers` layers start, and its layer count at the
/// end: at most [`MAX_SLABS`] slabs of at least two layers, and the top layer alone when the
/// count is odd.
pub fn bounds(layers: usize) -> Vec<usize> {
    let top_alone = layers % 2 == 1 && layers >= 5;
    let below = if top_alone { layers - 1 } else { layers };
    let count = (below / 2).clamp(1, MAX_SLABS);
    let mut slabs: Vec<usize> = (0..=count).map(|s| s * below / count).collect();
    if top_alone {
        slabs.push(layers);
    }
    slabs
}
