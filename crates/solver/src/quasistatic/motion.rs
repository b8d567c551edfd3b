//! The quasi-static motion of one contact configuration (every base node sticking or lifted):
//! `u(t) = u_p + d(t)·g − D·ḋ·h` from three static solves, and how a recorder sees it.

use nalgebra::{Matrix3, Vector3};

use crate::error::SolverError;
use crate::field::Field;
use crate::model::Model;
use crate::observe::Observed;
use crate::quasistatic::{CG_MAX_ITERATIONS, CG_TOLERANCE};
use crate::scene::Kinematic;
use crate::statics::{Prescribed, StaticSolution, solve_static_from};
use crate::step::{Energy, NodeContact, Params, State};

/// What a base node does during a quasi-static motion.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Contact {
    /// Sticks: held where it is.
    Held,
    /// Off the base.
    Lifted,
}

/// The quasi-static motion of one contact configuration: `u = Σ cₖ·basisₖ` with
/// `c = (1, d, −D·ḋ)`.
pub(crate) struct Motion {
    /// Which contact configuration (states, held positions, driver bases) it belongs to.
    pub(crate) key: Vec<u64>,
    /// `u_p`, `g`, `h`.
    pub(crate) basis: [Field<1>; 3],
    /// Reactions of each basis solution.
    pub(crate) reaction: [Field<1>; 3],
    /// `basisᵢᵀ·K·basisⱼ`.
    pub(crate) gram_k: Matrix3<f64>,
    /// `basisᵢᵀ·M·basisⱼ`.
    pub(crate) gram_m: Matrix3<f64>,
    /// `Σ m·b·basisₖ` (body force times each basis).
    pub(crate) body: Vector3<f64>,
    /// Per contact node.
    pub(crate) state: Vec<Contact>,
    /// Solver iterations of the three solves.
    pub(crate) iterations: usize,
}

impl Motion {
    pub(crate) fn u(&self, c: &Vector3<f64>, i: usize, comp: usize) -> f64 {
        c[0] * self.basis[0].c[comp][i][0] + c[1] * self.basis[1].c[comp][i][0] + c[2] * self.basis[2].c[comp][i][0]
    }

    pub(crate) fn r(&self, c: &Vector3<f64>, i: usize, comp: usize) -> f64 {
        c[0] * self.reaction[0].c[comp][i][0]
            + c[1] * self.reaction[1].c[comp][i][0]
            + c[2] * self.reaction[2].c[comp][i][0]
    }

    /// Reaction `[x, y, normal]` of contact node `ci` (zero when lifted).
    pub(crate) fn contact_reaction(&self, model: &Model, c: &Vector3<f64>, ci: usize) -> [f64; 3] {
        if self.state[ci] == Contact::Lifted {
            return [0.0; 3];
        }
        let p = model.contact()[ci] as usize;
        [0, 1, 2].map(|k| self.r(c, p, k))
    }
}

/// The contact configuration of lane `l` and its key (states, held positions, driver bases,
/// body force, damping); `None` if a base node slid since the last look (`slid`).
pub(crate) fn configuration<const L: usize>(
    params: &Params<'_, L>,
    state: &State<L>,
    l: usize,
    slid: &[bool],
) -> Option<(Vec<u64>, Vec<Contact>)> {
    let model = params.model;
    let mut key = Vec::with_capacity(3 * model.contact().len() + 8);
    let mut contacts = Vec::with_capacity(model.contact().len());
    for (ci, &node) in model.contact().iter().enumerate() {
        let r = state.contact_reaction(ci, l);
        if r[2] <= 0.0 {
            key.push(0);
            contacts.push(Contact::Lifted);
        } else if slid[ci] || state.contact.sliding[ci][l] {
            return None;
        } else {
            let u = state.displacement(node as usize, l);
            key.extend([1, u[0].to_bits(), u[1].to_bits()]);
            contacts.push(Contact::Held);
        }
    }
    key.extend((0..model.drivers().len()).map(|d| state.loading.base[d][l].to_bits()));
    key.extend(params.body_acceleration(l).map(f64::to_bits));
    key.push(params.damping(l).to_bits());
    Some((key, contacts))
}

/// Solves the three basis motions of configuration `contacts` of lane `l`, starting from the
/// previous motion where there is one (a configuration differs from the last by a node or two).
pub(crate) fn build_motion<const L: usize>(
    params: &Params<'_, L>,
    state: &State<L>,
    l: usize,
    stiffness: &[f64],
    (key, contacts): (Vec<u64>, Vec<Contact>),
    previous: Option<&Motion>,
) -> Result<Motion, SolverError> {
    let model = params.model;
    let n = model.node_count();
    let mass = model.mass();
    // Held components at their place (`now`) or at zero, the driver at its base (`now`) or at
    // `driver`.
    let constraints = |now: bool, driver: f64| {
        let mut p = model.boundaries().held(|i, a| if now { state.displacement(i, l)[a] } else { 0.0 });
        for (ci, &node) in model.contact().iter().enumerate() {
            let u = state.displacement(node as usize, l);
            let axes = match contacts[ci] {
                Contact::Held => 0..3,
                Contact::Lifted => 0..0,
            };
            p.extend(axes.map(|axis| Prescribed {
                node: node as usize,
                axis,
                value: if now && axis < 2 { u[axis] } else { 0.0 },
            }));
        }
        for (d, &node) in model.drivers().iter().enumerate() {
            let value = if now { state.loading.base[d][l] } else { driver };
            p.push(Prescribed { node: node as usize, axis: 0, value });
        }
        p
    };
    let b = params.body_acceleration(l);
    let mut gravity = Field::<1>::zeros(n);
    for i in 0..n {
        for c in 0..3 {
            gravity.c[c][i][0] = mass[i] * b[c];
        }
    }
    let solve = |loads: &Field<1>, prescribed: &[Prescribed], initial: Option<&Field<1>>| {
        solve_static_from(model, stiffness, loads, prescribed, initial, CG_TOLERANCE, CG_MAX_ITERATIONS)
    };
    // `g` and `h` depend on which nodes are held only, not on where: reuse them when only
    // positions changed (after a slip).
    let same_pattern = previous.filter(|m| m.state == contacts);
    let mut iterations = 0;
    let (g, h) = match same_pattern {
        Some(m) => (
            StaticSolution {
                u: m.basis[1].clone(),
                reactions: m.reaction[1].clone(),
                iterations: 0,
                relative_residual: 0.0,
            },
            Some(StaticSolution {
                u: m.basis[2].clone(),
                reactions: m.reaction[2].clone(),
                iterations: 0,
                relative_residual: 0.0,
            }),
        ),
        None => (solve(&Field::<1>::zeros(n), &constraints(false, 1.0), previous.map(|m| &m.basis[1]))?, None),
    };
    // The actual displacement is close to u_p + d·g.
    let d_now = state.loading.target[l];
    let mut guess = Field::<1>::zeros(n);
    for c in 0..3 {
        for i in 0..n {
            guess.c[c][i][0] = state.displacement(i, l)[c] - d_now * g.u.c[c][i][0];
        }
    }
    let up = solve(&gravity, &constraints(true, 0.0), Some(&guess))?;
    let zero = Field::<1>::zeros(n);
    let mut mg = Field::<1>::zeros(n);
    for i in 0..n {
        for c in 0..3 {
            mg.c[c][i][0] = mass[i] * g.u.c[c][i][0];
        }
    }
    let h = match h {
        Some(h) => h,
        None => solve(&mg, &constraints(false, 0.0), previous.map(|m| &m.basis[2]))?,
    };
    iterations += g.iterations + up.iterations + h.iterations;
    let loads = [gravity, zero, mg];
    let basis = [up.u, g.u, h.u];
    let reaction = [up.reactions, g.reactions, h.reactions];
    let dot = |a: &Field<1>, b: &Field<1>, w: Option<&[f64]>| -> f64 {
        let mut s = 0.0;
        for c in 0..3 {
            for i in 0..n {
                s += w.map_or(1.0, |w| w[i]) * a.c[c][i][0] * b.c[c][i][0];
            }
        }
        s
    };
    let mut gram_k = Matrix3::zeros();
    let mut gram_m = Matrix3::zeros();
    let mut body = Vector3::zeros();
    for j in 0..3 {
        // K·basisⱼ = reactionⱼ + loadsⱼ.
        let mut kb = reaction[j].clone();
        for c in 0..3 {
            for i in 0..n {
                kb.c[c][i][0] += loads[j].c[c][i][0];
            }
        }
        for i in 0..3 {
            gram_k[(i, j)] = dot(&basis[i], &kb, None);
            gram_m[(i, j)] = dot(&basis[i], &basis[j], Some(mass));
        }
        body[j] = dot(&loads[0], &basis[j], None);
    }
    let gram_k = 0.5 * (gram_k + gram_k.transpose());
    Ok(Motion { key, basis, reaction, gram_k, gram_m, body, state: contacts, iterations })
}

/// Smallest `x > 0` with `a·x² + b·x + c = 0`, if any.
pub(crate) fn first_positive_root(a: f64, b: f64, c: f64) -> Option<f64> {
    let scale = a.abs().max(b.abs()).max(c.abs());
    if scale == 0.0 {
        return None;
    }
    let roots: Vec<f64> = if a.abs() <= 1e-14 * scale {
        if b == 0.0 { vec![] } else { vec![-c / b] }
    } else {
        let disc = b * b - 4.0 * a * c;
        if disc < 0.0 {
            vec![]
        } else {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            if q == 0.0 { vec![0.0] } else { vec![q / a, c / q] }
        }
    };
    roots.into_iter().filter(|&x| x > 0.0 && x.is_finite()).min_by(f64::total_cmp)
}

/// The quasi-static motion at one step, as a recorder sees it.
pub(crate) struct MotionView<'a> {
    pub(crate) model: &'a Model,
    pub(crate) motion: &'a Motion,
    /// Coefficients at the step before, the step, the step after.
    pub(crate) c: [Vector3<f64>; 3],
    pub(crate) dt: f64,
    pub(crate) acc: Energy,
    pub(crate) kinetic: f64,
    pub(crate) elastic: f64,
}

impl Observed for MotionView<'_> {
    fn contacts(&self) -> usize {
        self.model.contact().len()
    }

    fn node_contact(&self, ci: usize) -> NodeContact {
        let m = self.motion;
        let [cm, c, cp] = &self.c;
        let p = self.model.contact()[ci] as usize;
        let r = m.contact_reaction(self.model, c, ci);
        let rate = |axis: usize| (m.u(cp, p, axis) - m.u(cm, p, axis)) * 0.5 / self.dt;
        NodeContact {
            friction_x: r[0],
            friction_y: r[1],
            normal: r[2],
            slip: m.u(c, p, 0),
            slip_y: m.u(c, p, 1),
            slip_rate: rate(0),
            slip_rate_y: rate(1),
            slipping: false,
            lifted: m.state[ci] == Contact::Lifted,
            // The skip-ahead refuses laws with a state that evolves (and faults).
            state: 0.0,
        }
    }

    fn driver_force(&self) -> f64 {
        self.model.drivers().iter().map(|&d| self.motion.r(&self.c[1], d as usize, 0)).sum()
    }

    fn driver_target(&self) -> f64 {
        self.c[2][1]
    }

    fn energy(&self) -> Energy {
        Energy { kinetic: self.kinetic, elastic: self.elastic, ..self.acc }
    }

    fn kinematic(&self, node: usize, q: Kinematic) -> [f64; 3] {
        let m = self.motion;
        let [cm, c, cp] = &self.c;
        [0, 1, 2].map(|k| match q {
            Kinematic::Displacement => m.u(c, node, k),
            Kinematic::Velocity => (m.u(cp, node, k) - m.u(cm, node, k)) * 0.5 / self.dt,
            Kinematic::Acceleration => {
                (m.u(cp, node, k) - 2.0 * m.u(c, node, k) + m.u(cm, node, k)) / (self.dt * self.dt)
            }
        })
    }
}

#[cfg(test)]
mod tests {
    use super::first_positive_root;

    #[test]
    fn roots() {
        // (x − 2)(x − 3)
        assert_eq!(first_positive_root(1.0, -5.0, 6.0), Some(2.0));
        // (x + 1)(x − 4)
        assert_eq!(first_positive_root(1.0, -3.0, -4.0), Some(4.0));
        // linear 2x − 1
        assert_eq!(first_positive_root(0.0, 2.0, -1.0), Some(0.5));
        assert_eq!(first_positive_root(1.0, 0.0, 1.0), None);
        assert_eq!(first_positive_root(0.0, 1.0, 1.0), None);
    }
}
