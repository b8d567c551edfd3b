//! Contact of the base nodes with the rigid base (docs/model.md §4): unilateral in z, friction in
//! x and y by the scene's friction [`Law`].
//!
//! Per contact node, from its trial position `(x_t, y_t, z_t)` (the step's update without the
//! base) and its position now `(x_n, y_n)`, with `g = m(1 + DΔt/2)/Δt²` the stiffness of the
//! update (a displacement `δ` of the trial costs a force `g·δ`):
//! - **lifted** if `z_t ≥ 0`: the trial stands, no reaction;
//! - otherwise put back on the base, `N = −z_t·g`, and the tangential reaction needed to hold it
//!   still is `R = (x_n − x_t, y_n − y_t)·g`. It **sticks** (stays at `(x_n, y_n)`, reaction `R`)
//!   if `|R| ≤ μ_hold·N`, `μ_hold` being μs if it was sticking (its weakened coefficient, for a
//!   law that does not heal and a node that has slipped) and its kinetic coefficient if it was
//!   sliding; else it **slides** with friction `μ_k·N` along `R` (against the trial motion), to
//!   `(x_t, y_t) + F/g`, and the law advances its state by the distance it moved. A sliding node
//!   whose needed reaction falls within `μ_k·N` would reverse within the step, so it sticks (a law
//!   that heals resets its state; see [`Law::stuck`]).
//!
//! **On a fault** (docs/model.md §15) the face is one side of a planar fault between identical
//! media: there is no base to lift from or land on. The normal force is the prescribed `N_i`
//! (the fault's normal traction times the node's area), the normal trial stands, and the
//! tangential rule is the same as above with that `N`; the law's state advances by twice the
//! distance the node slid (the slip across the fault, the other side moving the opposite way).
//! [`resolve_fault`] is that rule for one node; the lane kernel picks it once for the whole step.
//!
//! The law is asked, never read: its holding and kinetic coefficients, its state after a slide
//! ([`Law`]). The kernel is generic over it and picked once per step ([`FrictionLaws::dispatch`]).
//!
//! [`resolve`] is this rule for one node in plain scalar code; [`apply`] runs it for every contact
//! node and `L` seeds side by side without branches (each lane takes its result by selection, so a
//! lane's arithmetic does not depend on its neighbours), compiled for every instruction set; the
//! two are tested bit for bit against each other.

use stickslip_isa::{Isa, widest};

use crate::field::{Field, Lanes};
use crate::laws::{Law, Trial, WithLaw};
use crate::step::params::Params;
use crate::step::state::{ContactState, SlipLog};

/// Steps a contact node must slide in a row for its slip to count as an onset.
pub const SUSTAINED_SLIP_STEPS: u32 = 10;

/// The base's verdict on one contact node for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Resolved {
    /// Position after the step (m).
    pub position: [f64; 3],
    /// Reaction of the base: friction x, friction y, normal (N).
    pub reaction: [f64; 3],
    /// Whether the node slides.
    pub sliding: bool,
    /// The law's state variable after the step (the slip of the current slide for slip
    /// weakening); after a stick or a lift, what the law keeps of it ([`Law::stuck`]).
    pub state: f64,
}

/// The contact rule for one node under law `W` (see the module doc): `trial` is the position the
/// step would give without the base, `now` the node's `(x, y)` before the step,
/// `g = m(1 + DΔt/2)/Δt²`, `dt` the time step, `sliding` and `state` its state from the last
/// step.
pub fn resolve<W: Law>(
    node: &W::Node,
    (g, dt): (f64, f64),
    trial: [f64; 3],
    now: [f64; 2],
    sliding: bool,
    state: f64,
) -> Resolved {
    if !(trial[2] < 0.0) {
        return Resolved { position: trial, reaction: [0.0; 3], sliding: false, state: W::stuck(node, state, dt) };
    }
    let normal = -trial[2] * g;
    let (rx, ry) = ((now[0] - trial[0]) * g, (now[1] - trial[1]) * g);
    let need = (rx * rx + ry * ry).sqrt();
    let mu_k =
        W::kinetic(node, state, &Trial { need_n: need, normal_n: normal, g_n_m: g, dt_s: dt, slip_per_slide: 1.0 });
    if need <= W::holding(node, sliding, mu_k, state) * normal {
        return Resolved {
            position: [now[0], now[1], 0.0],
            reaction: [rx, ry, normal],
            sliding: false,
            state: W::stuck(node, state, dt),
        };
    }
    let scale = mu_k * normal / need;
    let (fx, fy) = (rx * scale, ry * scale);
    let (x1, y1) = (trial[0] + fx / g, trial[1] + fy / g);
    let (sx, sy) = (x1 - now[0], y1 - now[1]);
    Resolved {
        position: [x1, y1, 0.0],
        reaction: [fx, fy, normal],
        sliding: true,
        state: W::advance(node, state, (sx * sx + sy * sy).sqrt(), dt),
    }
}

/// The fault rule for one node under law `W` (see the module doc): as [`resolve`], with the
/// prescribed normal force `normal` instead of the base's reaction, the normal trial standing, and
/// the law's state advanced by the slip, twice the distance slid.
pub fn resolve_fault<W: Law>(
    node: &W::Node,
    (g, dt): (f64, f64),
    trial: [f64; 3],
    now: [f64; 2],
    sliding: bool,
    state: f64,
    normal: f64,
) -> Resolved {
    let (rx, ry) = ((now[0] - trial[0]) * g, (now[1] - trial[1]) * g);
    let need = (rx * rx + ry * ry).sqrt();
    let mu_k =
        W::kinetic(node, state, &Trial { need_n: need, normal_n: normal, g_n_m: g, dt_s: dt, slip_per_slide: 2.0 });
    if need <= W::holding(node, sliding, mu_k, state) * normal {
        return Resolved {
            position: [now[0], now[1], trial[2]],
            reaction: [rx, ry, normal],
            sliding: false,
            state: W::stuck(node, state, dt),
        };
    }
    let scale = mu_k * normal / need;
    let (fx, fy) = (rx * scale, ry * scale);
    let (x1, y1) = (trial[0] + fx / g, trial[1] + fy / g);
    let (sx, sy) = (x1 - now[0], y1 - now[1]);
    Resolved {
        position: [x1, y1, trial[2]],
        reaction: [fx, fy, normal],
        sliding: true,
        state: W::advance(node, state, 2.0 * (sx * sx + sy * sy).sqrt(), dt),
    }
}

/// What the lane kernel reads and writes, the law's coefficients aside.
pub(crate) struct ContactArrays<'a, const L: usize> {
    pub mass: &'a [f64],
    pub nodes: &'a [u32],
    pub cf: &'a Lanes<L>,
    pub dt: &'a Lanes<L>,
    /// Trial positions (overwritten with the result).
    pub trial: [&'a mut Vec<Lanes<L>>; 3],
    /// Positions before the step, x and y.
    pub now: [&'a Vec<Lanes<L>>; 2],
    pub sliding: &'a mut [[bool; L]],
    /// The law's state variable of each node.
    pub state: &'a mut [Lanes<L>],
    pub reaction: &'a mut [Vec<Lanes<L>>; 3],
    /// The prescribed normal force of each node when the base is a fault.
    pub fault_normal: Option<&'a [Lanes<L>]>,
}

impl<const L: usize> WithLaw<L> for (Isa, &mut ContactArrays<'_, L>) {
    type Out = ();

    fn run<W: Law>(self, law: &[W::Lanes<L>]) {
        let (isa, arrays) = self;
        if arrays.fault_normal.is_some() {
            fault_dispatch(isa, arrays, law, W::default());
        } else {
            contact_dispatch(isa, arrays, law, W::default());
        }
    }
}

/// Applies the contact rule to every contact node and lane: `trial` holds the trial positions
/// (the result is written over them), `now` the positions before the step; updates the contact
/// state and, when asked, the slip log (`step` is the step being taken).
pub(crate) fn apply<const L: usize>(
    p: &Params<'_, L>,
    trial: &mut Field<L>,
    now: &Field<L>,
    contact: &mut ContactState<L>,
    log: Option<(&mut SlipLog<L>, bool, bool, u64)>,
) {
    let model = p.model;
    let [tx, ty, tz] = &mut trial.c;
    let mut c = ContactArrays {
        mass: model.mass(),
        nodes: model.contact(),
        cf: &p.coefficients().cf,
        dt: p.dts(),
        trial: [tx, ty, tz],
        now: [&now.c[0], &now.c[1]],
        sliding: &mut contact.sliding,
        state: &mut contact.state,
        reaction: &mut contact.reaction,
        fault_normal: p.fault.as_ref().map(|f| f.normal_n.as_slice()),
    };
    p.friction.dispatch((Isa::current(), &mut c));
    let Some((log, track_slid, track_onsets, step)) = log else { return };
    if track_slid {
        for (any, now) in log.slid.iter_mut().zip(&contact.sliding) {
            for l in 0..L {
                any[l] |= now[l];
            }
        }
    }
    if track_onsets {
        for ci in 0..contact.sliding.len() {
            for l in 0..L {
                let run = &mut log.run[ci][l];
                if contact.sliding[ci][l] {
                    *run += 1;
                    if *run == SUSTAINED_SLIP_STEPS {
                        log.onsets[l].push((step + 1 - u64::from(SUSTAINED_SLIP_STEPS), ci as u32));
                    }
                } else {
                    *run = 0;
                }
            }
        }
    }
}

widest! {
    /// The contact update of every contact node in instruction set `isa`, under law `W`.
    fn contact_dispatch<const L: usize, W: Law>(c: &mut ContactArrays<'_, L>, law: &[W::Lanes<L>], kind: W) => contact
}

/// [`resolve`] for every contact node, `L` lanes at once without branches.
#[inline(always)]
fn contact<const L: usize, W: Law>(c: &mut ContactArrays<'_, L>, law: &[W::Lanes<L>], _: W) {
    for (ci, &node) in c.nodes.iter().enumerate() {
        let p = node as usize;
        let m = c.mass[p];
        let (xt, yt, zt) = (c.trial[0][p], c.trial[1][p], c.trial[2][p]);
        let (xn, yn) = (c.now[0][p], c.now[1][p]);
        let (slipping, state) = (c.sliding[ci], c.state[ci]);
        let coefficients = law[ci];
        let (mut ox, mut oy, mut oz) = ([0.0; L], [0.0; L], [0.0; L]);
        let (mut rxo, mut ryo, mut no) = ([0.0; L], [0.0; L], [0.0; L]);
        let (mut slip_o, mut state_o) = ([false; L], [0.0; L]);
        for l in 0..L {
            let g = m / c.cf[l];
            let touching = zt[l] < 0.0;
            let normal = -zt[l] * g;
            let (rx, ry) = ((xn[l] - xt[l]) * g, (yn[l] - yt[l]) * g);
            let need = (rx * rx + ry * ry).sqrt();
            let node = W::lane(&coefficients, l);
            let mu_k = W::kinetic(
                &node,
                state[l],
                &Trial { need_n: need, normal_n: normal, g_n_m: g, dt_s: c.dt[l], slip_per_slide: 1.0 },
            );
            let limit = W::holding(&node, slipping[l], mu_k, state[l]) * normal;
            let stick = need <= limit;
            // Sliding: friction μ_k·N against the trial motion (unused when sticking).
            let scale = mu_k * normal / need;
            let (fx, fy) = (rx * scale, ry * scale);
            let (x1, y1) = (xt[l] + fx / g, yt[l] + fy / g);
            let (sx, sy) = (x1 - xn[l], y1 - yn[l]);
            let slides = touching && !stick;
            ox[l] = if !touching {
                xt[l]
            } else if stick {
                xn[l]
            } else {
                x1
            };
            oy[l] = if !touching {
                yt[l]
            } else if stick {
                yn[l]
            } else {
                y1
            };
            oz[l] = if touching { 0.0 } else { zt[l] };
            rxo[l] = if !touching {
                0.0
            } else if stick {
                rx
            } else {
                fx
            };
            ryo[l] = if !touching {
                0.0
            } else if stick {
                ry
            } else {
                fy
            };
            no[l] = if touching { normal } else { 0.0 };
            slip_o[l] = slides;
            state_o[l] = if slides {
                W::advance(&node, state[l], (sx * sx + sy * sy).sqrt(), c.dt[l])
            } else {
                W::stuck(&node, state[l], c.dt[l])
            };
        }
        (c.trial[0][p], c.trial[1][p], c.trial[2][p]) = (ox, oy, oz);
        (c.reaction[0][ci], c.reaction[1][ci], c.reaction[2][ci]) = (rxo, ryo, no);
        (c.sliding[ci], c.state[ci]) = (slip_o, state_o);
    }
}

widest! {
    /// The fault update of every contact node in instruction set `isa`, under law `W`.
    fn fault_dispatch<const L: usize, W: Law>(c: &mut ContactArrays<'_, L>, law: &[W::Lanes<L>], kind: W) => fault
}

/// [`resolve_fault`] for every contact node, `L` lanes at once without branches.
#[inline(always)]
fn fault<const L: usize, W: Law>(c: &mut ContactArrays<'_, L>, law: &[W::Lanes<L>], _: W) {
    let normals = c.fault_normal.expect("the fault kernel runs with the fault's normal forces");
    for (ci, &node) in c.nodes.iter().enumerate() {
        let p = node as usize;
        let m = c.mass[p];
        let (xt, yt) = (c.trial[0][p], c.trial[1][p]);
        let (xn, yn) = (c.now[0][p], c.now[1][p]);
        let (slipping, state, normal) = (c.sliding[ci], c.state[ci], normals[ci]);
        let coefficients = law[ci];
        let (mut ox, mut oy) = ([0.0; L], [0.0; L]);
        let (mut rxo, mut ryo) = ([0.0; L], [0.0; L]);
        let (mut slip_o, mut state_o) = ([false; L], [0.0; L]);
        for l in 0..L {
            let g = m / c.cf[l];
            let (rx, ry) = ((xn[l] - xt[l]) * g, (yn[l] - yt[l]) * g);
            let need = (rx * rx + ry * ry).sqrt();
            let node = W::lane(&coefficients, l);
            let mu_k = W::kinetic(
                &node,
                state[l],
                &Trial { need_n: need, normal_n: normal[l], g_n_m: g, dt_s: c.dt[l], slip_per_slide: 2.0 },
            );
            let stick = need <= W::holding(&node, slipping[l], mu_k, state[l]) * normal[l];
            let scale = mu_k * normal[l] / need;
            let (fx, fy) = (rx * scale, ry * scale);
            let (x1, y1) = (xt[l] + fx / g, yt[l] + fy / g);
            let (sx, sy) = (x1 - xn[l], y1 - yn[l]);
            ox[l] = if stick { xn[l] } else { x1 };
            oy[l] = if stick { yn[l] } else { y1 };
            rxo[l] = if stick { rx } else { fx };
            ryo[l] = if stick { ry } else { fy };
            slip_o[l] = !stick;
            state_o[l] = if stick {
                W::stuck(&node, state[l], c.dt[l])
            } else {
                W::advance(&node, state[l], 2.0 * (sx * sx + sy * sy).sqrt(), c.dt[l])
            };
        }
        (c.trial[0][p], c.trial[1][p]) = (ox, oy);
        (c.reaction[0][ci], c.reaction[1][ci], c.reaction[2][ci]) = (rxo, ryo, normal);
        (c.sliding[ci], c.state[ci]) = (slip_o, state_o);
    }
}

#[cfg(test)]
mod tests {
    use rand::{RngExt, SeedableRng};

    use super::*;
    use crate::laws::{
        Coulomb, Evolution, Exponential, ExponentialNode, ExponentialWeakening, FrictionLaw, NodeFriction, RateState,
        RateStateNode, RateStateStart, SlipWeakening, StaticDynamic, Weakening, WeakeningNode,
    };

    /// A law the kernels are tested under: its coefficients with a friction map's own Dc (the
    /// law's times `dc_scale`) and healing or not, and its node out of a [`NodeFriction`].
    trait Tested: Law {
        /// Whether a node in contact can stick (a rate-and-state node slides at the rate its step
        /// balances).
        const STICKS: bool = true;
        fn node(n: NodeFriction, dc_scale: f64, heals: bool) -> Self::Node;
    }

    impl Tested for RateState {
        const STICKS: bool = false;
        fn node(n: NodeFriction, dc_scale: f64, _: bool) -> RateStateNode {
            let NodeFriction::RateState(n) = n else { panic!("{n:?}") };
            RateStateNode { dc_m: n.dc_m * dc_scale, ..n }
        }
    }

    /// Rate-and-state friction whose state, drawn from the cases' slip paths (0–4 µs), spans
    /// both sides of steady state at the cases' slip rates.
    fn rate_state(evolution: Evolution) -> FrictionLaw {
        let start = RateStateStart::State(1e-6);
        RateStateNode { a: 0.01, b: 0.015, dc_m: 3e-6, v0_m_s: 1e-6, f0: 0.6, evolution, start }.into()
    }

    impl Tested for Weakening {
        fn node(n: NodeFriction, dc_scale: f64, heals: bool) -> WeakeningNode {
            let NodeFriction::Weakening(n) = n else { panic!("{n:?}") };
            let dc = n.weakening_distance_m() * dc_scale;
            WeakeningNode::new(Weakening::static_coefficient(&n), Weakening::residual_coefficient(&n), dc)
                .with_healing(heals)
        }
    }

    impl Tested for Exponential {
        fn node(n: NodeFriction, dc_scale: f64, heals: bool) -> ExponentialNode {
            let NodeFriction::Exponential(n) = n else { panic!("{n:?}") };
            let dc = Exponential::coefficients(&n)[2].value * dc_scale;
            Exponential::with_healing(
                &ExponentialNode::new(Exponential::static_coefficient(&n), Exponential::residual_coefficient(&n), dc),
                heals,
            )
        }
    }

    /// Random contact states of `nodes` nodes and `L` lanes: trial positions below and above the
    /// base, nodes that were sliding with some slip path, coefficients varying per node and lane.
    struct Case<W: Law, const L: usize> {
        mass: Vec<f64>,
        cf: Lanes<L>,
        dt: Lanes<L>,
        law: Vec<[W::Node; L]>,
        trial: [Vec<Lanes<L>>; 3],
        now: [Vec<Lanes<L>>; 2],
        sliding: Vec<[bool; L]>,
        path: Vec<Lanes<L>>,
    }

    fn case<W: Tested, const L: usize>(law: &FrictionLaw, seed: u64, nodes: usize) -> Case<W, L> {
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed);
        let mut lanes = |lo: f64, hi: f64| -> Lanes<L> { std::array::from_fn(|_| rng.random_range(lo..hi)) };
        let mass: Vec<f64> = (0..nodes).map(|_| lanes(1.0, 3.0)[0]).collect();
        let cf = lanes(1e-11, 1e-10);
        let dt = cf.map(f64::sqrt);
        // The law's coefficients times a random-field factor per node and lane; a friction map may
        // give nodes their own Dc: half the nodes keep the law's.
        let law = (0..nodes)
            .map(|i| {
                let (factor, dc) = (lanes(0.3, 5.0), lanes(0.5, 2.0));
                // A third of the nodes keep their slip when they stick (no healing).
                std::array::from_fn(|l| W::node(law.node(factor[l]), if i % 2 == 0 { 1.0 } else { dc[l] }, i % 3 != 0))
            })
            .collect();
        // Tangential trials a few µm from where the node is, vertical ones ±1 µm about the base:
        // some nodes lift, some stick, some slide.
        let trial = [
            (0..nodes).map(|_| lanes(-2e-6, 2e-6)).collect(),
            (0..nodes).map(|_| lanes(-2e-6, 2e-6)).collect(),
            (0..nodes).map(|_| lanes(-1e-6, 0.5e-6)).collect(),
        ];
        let now = [(0..nodes).map(|_| lanes(-1e-6, 1e-6)).collect(), (0..nodes).map(|_| lanes(-1e-6, 1e-6)).collect()];
        let sliding = (0..nodes).map(|_| lanes(0.0, 1.0).map(|v| v < 0.5)).collect();
        let path = (0..nodes).map(|_| lanes(0.0, 4e-6)).collect();
        Case { mass, cf, dt, law, trial, now, sliding, path }
    }

    /// The lane kernel in build `isa` against [`resolve`] on every node and lane, bit for bit.
    fn agree<W: Tested, const L: usize>(law: FrictionLaw, isa: Isa, seed: u64) {
        let c = case::<W, L>(&law, seed, 40);
        let nodes: Vec<u32> = (0..c.mass.len() as u32).collect();
        let mut trial = c.trial.clone();
        let mut sliding = c.sliding.clone();
        let mut path = c.path.clone();
        let mut reaction = [vec![[0.0; L]; nodes.len()], vec![[0.0; L]; nodes.len()], vec![[0.0; L]; nodes.len()]];
        let coefficients: Vec<_> = c.law.iter().map(|n| W::lanes(*n)).collect();
        {
            let [tx, ty, tz] = &mut trial;
            let mut arrays = ContactArrays {
                mass: &c.mass,
                nodes: &nodes,
                cf: &c.cf,
                dt: &c.dt,
                trial: [tx, ty, tz],
                now: [&c.now[0], &c.now[1]],
                sliding: &mut sliding,
                state: &mut path,
                reaction: &mut reaction,
                fault_normal: None,
            };
            contact_dispatch(isa, &mut arrays, &coefficients, W::default());
        }
        let mut outcomes = [0usize; 3];
        for i in 0..nodes.len() {
            for l in 0..L {
                let g = c.mass[i] / c.cf[l];
                let t = [c.trial[0][i][l], c.trial[1][i][l], c.trial[2][i][l]];
                let now = [c.now[0][i][l], c.now[1][i][l]];
                let want = resolve::<W>(&c.law[i][l], (g, c.dt[l]), t, now, c.sliding[i][l], c.path[i][l]);
                let got = Resolved {
                    position: [trial[0][i][l], trial[1][i][l], trial[2][i][l]],
                    reaction: [reaction[0][i][l], reaction[1][i][l], reaction[2][i][l]],
                    sliding: sliding[i][l],
                    state: path[i][l],
                };
                let bits = |r: &Resolved| {
                    (r.position.map(f64::to_bits), r.reaction.map(f64::to_bits), r.sliding, r.state.to_bits())
                };
                assert_eq!(bits(&got), bits(&want), "{law:?}, {isa:?}, node {i}, lane {l}: {got:?} vs {want:?}");
                outcomes[if want.reaction[2] == 0.0 {
                    0
                } else if want.sliding {
                    2
                } else {
                    1
                }] += 1;
            }
        }
        let exercised = outcomes[0] > 0 && outcomes[2] > 0 && (outcomes[1] > 0 || !W::STICKS);
        assert!(exercised, "every outcome (lift, stick, slide) is exercised: {outcomes:?}");
    }

    /// The fault kernel in build `isa` against [`resolve_fault`], bit for bit, with normal forces
    /// of each node and lane.
    fn agree_fault<W: Tested, const L: usize>(law: FrictionLaw, isa: Isa, seed: u64) {
        let c = case::<W, L>(&law, seed, 40);
        let nodes: Vec<u32> = (0..c.mass.len() as u32).collect();
        let mut rng = rand::rngs::ChaCha8Rng::seed_from_u64(seed + 100);
        // Normal forces comparable to the tangential trials' reactions (g·µm), so that nodes both
        // stick and slide.
        let normal: Vec<Lanes<L>> = (0..nodes.len())
            .map(|i| std::array::from_fn(|l| c.mass[i] / c.cf[l] * rng.random_range(0.2e-6..3e-6)))
            .collect();
        let mut trial = c.trial.clone();
        let mut sliding = c.sliding.clone();
        let mut path = c.path.clone();
        let mut reaction = [vec![[0.0; L]; nodes.len()], vec![[0.0; L]; nodes.len()], vec![[0.0; L]; nodes.len()]];
        let coefficients: Vec<_> = c.law.iter().map(|n| W::lanes(*n)).collect();
        {
            let [tx, ty, tz] = &mut trial;
            let mut arrays = ContactArrays {
                mass: &c.mass,
                nodes: &nodes,
                cf: &c.cf,
                dt: &c.dt,
                trial: [tx, ty, tz],
                now: [&c.now[0], &c.now[1]],
                sliding: &mut sliding,
                state: &mut path,
                reaction: &mut reaction,
                fault_normal: Some(&normal),
            };
            fault_dispatch(isa, &mut arrays, &coefficients, W::default());
        }
        let mut outcomes = [0usize; 2];
        for i in 0..nodes.len() {
            for l in 0..L {
                let g = c.mass[i] / c.cf[l];
                let t = [c.trial[0][i][l], c.trial[1][i][l], c.trial[2][i][l]];
                let now = [c.now[0][i][l], c.now[1][i][l]];
                let want =
                    resolve_fault::<W>(&c.law[i][l], (g, c.dt[l]), t, now, c.sliding[i][l], c.path[i][l], normal[i][l]);
                let got = Resolved {
                    position: [trial[0][i][l], trial[1][i][l], trial[2][i][l]],
                    reaction: [reaction[0][i][l], reaction[1][i][l], reaction[2][i][l]],
                    sliding: sliding[i][l],
                    state: path[i][l],
                };
                let bits = |r: &Resolved| {
                    (r.position.map(f64::to_bits), r.reaction.map(f64::to_bits), r.sliding, r.state.to_bits())
                };
                assert_eq!(bits(&got), bits(&want), "{law:?}, {isa:?}, node {i}, lane {l}: {got:?} vs {want:?}");
                // The normal trial stands: no base on a fault.
                assert_eq!(got.position[2].to_bits(), t[2].to_bits());
                outcomes[usize::from(want.sliding)] += 1;
            }
        }
        assert!(
            outcomes[1] > 0 && (outcomes[0] > 0 || !W::STICKS),
            "both outcomes (stick, slide) are exercised: {outcomes:?}"
        );
    }

    #[test]
    fn fault_kernel_agrees_with_the_scalar_rule_bit_for_bit_in_every_build() {
        for isa in Isa::available() {
            for seed in 0..4 {
                let sd = StaticDynamic { mu_static: 1.0, mu_dynamic: 0.8 }.into();
                let sw = SlipWeakening { mu_static: 1.0, mu_dynamic: 0.8, dc_m: 3e-6 }.into();
                for law in [sd, sw] {
                    agree_fault::<Weakening, 1>(law, isa, seed);
                    agree_fault::<Weakening, 4>(law, isa, seed);
                    agree_fault::<Weakening, 8>(law, isa, seed);
                }
                let exponential = ExponentialWeakening { mu_static: 1.0, mu_dynamic: 0.8, dc_m: 3e-6 }.into();
                agree_fault::<Exponential, 1>(exponential, isa, seed);
                agree_fault::<Exponential, 4>(exponential, isa, seed);
                agree_fault::<Exponential, 8>(exponential, isa, seed);
                for evolution in [Evolution::Aging, Evolution::Slip] {
                    agree_fault::<RateState, 1>(rate_state(evolution), isa, seed);
                    agree_fault::<RateState, 4>(rate_state(evolution), isa, seed);
                }
            }
        }
    }

    #[test]
    fn a_sliding_fault_node_weakens_with_twice_its_displacement() {
        // A node sliding 1 µm in a step has slipped 2 µm across the fault: with Dc = 4 µm the
        // slip-weakening state is 2 µm, halfway from μs to μd.
        let law = SlipWeakening { mu_static: 0.6, mu_dynamic: 0.4, dc_m: 4e-6 };
        let NodeFriction::Weakening(node) = FrictionLaw::from(law).node(1.0) else { unreachable!() };
        let g = 1.0e6;
        let normal = 1.0;
        // A trial 10 µm away: the friction (0.6 N at most) moves it back 0.6 µm, to 9.4 µm.
        let r = resolve_fault::<Weakening>(&node, (g, 1e-3), [10e-6, 0.0, 3e-7], [0.0, 0.0], false, 0.0, normal);
        assert!(r.sliding);
        assert!((r.position[0] - 9.4e-6).abs() < 1e-15);
        assert!((r.state - 2.0 * 9.4e-6).abs() < 1e-18);
        assert_eq!(r.position[2], 3e-7);
        assert_eq!(r.reaction[2], normal);
    }

    #[test]
    fn lane_kernel_agrees_with_the_scalar_law_bit_for_bit_in_every_build() {
        for isa in Isa::available() {
            for seed in 0..4 {
                let plain = Coulomb { mu: 1.0 }.into();
                let sd = StaticDynamic { mu_static: 1.0, mu_dynamic: 0.8 }.into();
                let sw = SlipWeakening { mu_static: 1.0, mu_dynamic: 0.8, dc_m: 3e-6 }.into();
                let exponential = ExponentialWeakening { mu_static: 1.0, mu_dynamic: 0.8, dc_m: 3e-6 }.into();
                agree::<Exponential, 1>(exponential, isa, seed);
                agree::<Exponential, 4>(exponential, isa, seed);
                agree::<Exponential, 8>(exponential, isa, seed);
                for evolution in [Evolution::Aging, Evolution::Slip] {
                    agree::<RateState, 1>(rate_state(evolution), isa, seed);
                    agree::<RateState, 4>(rate_state(evolution), isa, seed);
                }
                for law in [plain, sd, sw] {
                    agree::<Weakening, 1>(law, isa, seed);
                    agree::<Weakening, 4>(law, isa, seed);
                    agree::<Weakening, 8>(law, isa, seed);
                }
            }
        }
    }
}
