//! Named sets of nodes: the faces of the block and the control-node sets.

use crate::geometry::lattice::{Lattice, NodeId, NodeKind};

/// A face of the block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// x = 0.
    XMin,
    /// x = nx·Lc.
    XMax,
    /// y = 0.
    YMin,
    /// y = ny·Lc.
    YMax,
    /// z = 0 (the base).
    ZMin,
    /// z = nz·Lc (the top).
    ZMax,
}

impl Face {
    /// Every face.
    pub const ALL: [Face; 6] = [Face::XMin, Face::XMax, Face::YMin, Face::YMax, Face::ZMin, Face::ZMax];

    /// Name as written in pipeline files.
    pub fn name(self) -> &'static str {
        match self {
            Face::XMin => "x_min",
            Face::XMax => "x_max",
            Face::YMin => "y_min",
            Face::YMax => "y_max",
            Face::ZMin => "z_min",
            Face::ZMax => "z_max",
        }
    }

    /// The axis normal to the face and whether it is the face at the far end of that axis.
    pub fn axis(self) -> (usize, bool) {
        match self {
            Face::XMin => (0, false),
            Face::XMax => (0, true),
            Face::YMin => (1, false),
            Face::YMax => (1, true),
            Face::ZMin => (2, false),
            Face::ZMax => (2, true),
        }
    }

    /// The nodes on the face (corner nodes only: centre nodes lie inside), canonical order.
    pub fn nodes(self, lattice: &Lattice) -> Vec<NodeId> {
        let (axis, at_max) = self.axis();
        let target = if at_max { 2 * lattice.dims().along(axis) } else { 0 };
        (0..lattice.node_count() as u32).map(NodeId).filter(|&id| lattice.half_units(id)[axis] == target).collect()
    }

    /// The share of the face's area that node `id` of the face stands for (m²): `Lc²`, halved
    /// for each edge of the face the node lies on; the shares of a face's nodes add up to its
    /// area.
    pub fn tributary_area(self, lattice: &Lattice, id: NodeId) -> f64 {
        let (axis, _) = self.axis();
        let h = lattice.half_units(id);
        let lc = lattice.lc();
        (0..3)
            .filter(|&a| a != axis)
            .map(|a| if h[a] == 0 || h[a] == 2 * lattice.dims().along(a) { 0.5 * lc } else { lc })
            .product()
    }
}

/// Named sets of control nodes (corner nodes only).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NodeSet {
    /// The line of top-face nodes at y = 0 (along x).
    TopLine,
    /// Every node of the top face.
    Top,
    /// Every corner node on the outer surface.
    Surface,
}

impl NodeSet {
    /// Every set.
    pub const ALL: [NodeSet; 3] = [NodeSet::TopLine, NodeSet::Top, NodeSet::Surface];

    /// Name as written in pipeline files.
    pub fn name(self) -> &'static str {
        match self {
            NodeSet::TopLine => "top_line",
            NodeSet::Top => "top",
            NodeSet::Surface => "surface",
        }
    }

    /// The nodes of the set in `lattice`, canonical order.
    pub fn nodes(self, lattice: &Lattice) -> Vec<NodeId> {
        let top = 2 * lattice.dims().nz;
        (0..lattice.node_count() as u32)
            .map(NodeId)
            .filter(|&id| {
                let h = lattice.half_units(id);
                let corner = matches!(lattice.kind(id), NodeKind::Corner(_));
                corner
                    && match self {
                        NodeSet::TopLine => h[2] == top && h[1] == 0,
                        NodeSet::Top => h[2] == top,
                        NodeSet::Surface => lattice.on_surface(id),
                    }
            })
            .collect()
    }
}
