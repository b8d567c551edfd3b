//! Fields over the nodes, `L` seeds side by side: `c[axis][node][lane]`.

/// One `f64` per lane.
pub type Lanes<const L: usize> = [f64; L];

/// A vector field over the nodes, structure of arrays: `c[axis][node][lane]`.
#[derive(Clone, Debug, PartialEq, bincode::Encode, bincode::Decode)]
pub struct Field<const L: usize> {
    /// Components x, y, z.
    pub c: [Vec<Lanes<L>>; 3],
}

impl<const L: usize> Field<L> {
    /// A zero field over `n` nodes.
    pub fn zeros(n: usize) -> Self {
        Field { c: [vec![[0.0; L]; n], vec![[0.0; L]; n], vec![[0.0; L]; n]] }
    }

    /// Number of nodes.
    pub fn len(&self) -> usize {
        self.c[0].len()
    }

    /// Whether the field has no nodes.
    pub fn is_empty(&self) -> bool {
        self.c[0].is_empty()
    }

    /// Sets every value to zero.
    pub fn fill_zero(&mut self) {
        for comp in &mut self.c {
            comp.fill([0.0; L]);
        }
    }

    /// Value of lane `l` at `node`.
    pub fn get(&self, node: usize, l: usize) -> [f64; 3] {
        [self.c[0][node][l], self.c[1][node][l], self.c[2][node][l]]
    }

    /// Sets every value of lane `l` from `value(node, axis)`.
    pub fn set_lane(&mut self, l: usize, value: impl Fn(usize, usize) -> f64) {
        for (axis, comp) in self.c.iter_mut().enumerate() {
            for (i, v) in comp.iter_mut().enumerate() {
                v[l] = value(i, axis);
            }
        }
    }

    /// Multiplies every value of lane `l` by `factor`.
    pub fn scale_lane(&mut self, l: usize, factor: f64) {
        for comp in &mut self.c {
            for v in comp.iter_mut() {
                v[l] *= factor;
            }
        }
    }
}
