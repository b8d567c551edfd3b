//! Absorbing faces (docs/model.md §15): Lysmer–Kuhlemeyer dashpots on the nodes of chosen faces,
//! so that waves leave the block instead of reflecting. Each node of an absorbing face carries a
//! dashpot `c_n = ρ·Cp·A_i` along the face's normal and `c_t = ρ·Cs·A_i` along each tangent, with
//! `A_i` the node's share of the face ([`Face::tributary_area`]) and `Cp = √(C11/ρ)`,
//! `Cs = √(C44/ρ)` the long-wave speeds of this lattice at the mean Young's modulus (a node on an
//! edge of two absorbing faces carries both). Exact for plane P and S waves at normal incidence in
//! a continuum (Lysmer & Kuhlemeyer 1969), partial at other angles.
//!
//! The dashpot force is `−c·v` with the centred velocity `v = (uₙ₊₁ − uₙ₋₁)/2Δt` of the step's
//! own update, like the mass-proportional damping: for a node component of mass `m`, the update
//! with damping `D` and a dashpot `c` is the one with damping `D + c/m`, so the trial `u_t` the
//! step computed with `D` becomes `uₙ₋₁ + (u_t − uₙ₋₁)·(1 + a)/(1 + a + b)` with `a = DΔt/2`,
//! `b = cΔt/2m`. A centred viscous term leaves the stability bound of central differences at
//! `ωΔt ≤ 2` whatever the damping (the characteristic polynomial
//! `(1 + ξωΔt)λ² − (2 − ω²Δt²)λ + (1 − ξωΔt)` has both roots in the unit disc exactly when
//! `ωΔt ≤ 2`), so the dashpots do not change the critical step (a test shows it). What they take
//! out of the block, `c·v·(uₙ₊₁ − uₙ₋₁)` per step, is the ledger's `absorbed` term. The
//! skip-ahead's quasi-static motion has no velocity and does not include them.

use super::{Boundary, Phase, Step, Work};
use crate::geometry::NodeId;
use crate::material::lattice_elastic_constants;
use crate::scene::Scene;

/// The dashpots of the scene's absorbing faces (none without one).
#[derive(Clone, Debug, Default)]
pub struct Absorbing {
    /// Internal node and its dashpot coefficient along x, y and z (N·s/m), by internal node.
    pub dashpots: Vec<(u32, [f64; 3])>,
}

/// The impedances `ρ·Cp` and `ρ·Cs` of the scene's lattice at its mean modulus (Pa·s/m).
pub fn impedances(scene: &Scene) -> (f64, f64) {
    let (c11, _, c44) = lattice_elastic_constants(scene.young_pa, scene.poisson);
    let rho = scene.density_kg_m3;
    ((c11 * rho).sqrt(), (c44 * rho).sqrt())
}

impl Absorbing {
    /// The dashpots of `scene`'s absorbing faces.
    pub(crate) fn new(scene: &Scene, internal: &dyn Fn(NodeId) -> Option<u32>) -> Absorbing {
        if scene.absorbing().is_empty() {
            return Absorbing::default();
        }
        let lattice = scene.lattice();
        let (zp, zs) = impedances(scene);
        // In a layered medium each dashpot takes the impedance of the layer at its node's depth
        // (both impedances scale as √(E·ρ) at one Poisson ratio).
        let medium = &scene.medium;
        let zones = medium.zones(scene.young_pa, scene.density_kg_m3, scene.poisson);
        let extent = lattice.extent();
        let mut dashpots: Vec<(u32, [f64; 3])> = Vec::new();
        for &face in scene.absorbing() {
            let (axis, _) = face.axis();
            for id in face.nodes(&lattice) {
                let zone = &zones[medium.zone_at(medium.depth(lattice.position(id), extent))];
                let local = (zone.young * zone.density).sqrt();
                let area = face.tributary_area(&lattice, id) * local;
                let mut c = [zs * area; 3];
                c[axis] = zp * area;
                if let Some(i) = internal(id) {
                    dashpots.push((i, c));
                }
            }
        }
        // One entry per node: a node on an edge of two absorbing faces carries both dashpots.
        dashpots.sort_by_key(|&(node, _)| node);
        let mut merged: Vec<(u32, [f64; 3])> = Vec::with_capacity(dashpots.len());
        for (node, c) in dashpots {
            match merged.last_mut() {
                Some((last, sum)) if *last == node => (0..3).for_each(|k| sum[k] += c[k]),
                _ => merged.push((node, c)),
            }
        }
        Absorbing { dashpots: merged }
    }

    /// Whether the scene has any.
    pub fn is_empty(&self) -> bool {
        self.dashpots.is_empty()
    }
}

impl Boundary for Absorbing {
    fn phase(&self) -> Phase {
        Phase::Dashpot
    }

    /// Each dashpot component turns the trial into the update with damping `D + c/m` (see the
    /// module doc); forces of the other boundaries must already be in the trial.
    fn apply<const L: usize>(&self, s: &mut Step<'_, L>) {
        for &(node, c) in &self.dashpots {
            let i = node as usize;
            let m = s.mass[i];
            for l in 0..L {
                let a = 0.5 * s.damping[l] * s.dt[l];
                for k in 0..3 {
                    let b = 0.5 * c[k] * s.dt[l] / m;
                    let old = s.before.c[k][i][l];
                    let t = &mut s.trial.c[k][i][l];
                    *t = old + (*t - old) * ((1.0 + a) / (1.0 + a + b));
                }
            }
        }
    }

    /// `c·v·(uₙ₊₁ − uₙ₋₁)/2 = c·(uₙ₊₁ − uₙ₋₁)²/4Δt` per component: what left the block.
    fn work<const L: usize>(&self, w: &mut Work<'_, L>) {
        for &(node, c) in &self.dashpots {
            let i = node as usize;
            let part = w.layer(i);
            for l in 0..L {
                let mut sum = 0.0;
                for k in 0..3 {
                    let d = w.new.c[k][i][l] - w.old.c[k][i][l];
                    sum += c[k] * d * d;
                }
                w.parts[part][l].absorbed += sum / (4.0 * w.dt[l]);
            }
        }
    }

    /// A centred dashpot leaves `ωΔt ≤ 2` as it is (see the module doc): nothing to add.
    fn stiffening(&self, _: &[f64]) -> f64 {
        0.0
    }

    fn skip_ahead(&self) -> Result<(), &'static str> {
        if self.dashpots.is_empty() {
            Ok(())
        } else {
            Err("the skip-ahead's quasi-static motion has no velocity for the absorbing faces' dashpots")
        }
    }
}
