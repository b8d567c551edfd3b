//! Where the z-slabs of a stencil lattice start (see [`crate::stencil`]'s doc): the step's
//! threads and the ranks of a split scene ([`crate::split`]) both cut the layers by this rule.

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
