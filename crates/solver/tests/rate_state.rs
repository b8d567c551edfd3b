//! Rate-and-state friction through the step's own contact rule ([`resolve`], which the lane
//! kernel matches bit for bit), against its closed forms (docs/model.md §4).
//!
//! A rigid block of mass `m` pressed on the base with `N`, pulled through a spring `k` from a
//! point moving at `V` and stepped by central differences, with the law deciding its slide. The
//! spring-slider's linear stability boundary is `k_c = (b − a)·N/L·(1 + m·V²/(N·a·L))`
//! (Ruina 1983; Rice & Ruina 1983 with inertia): stiffer, a perturbation of steady sliding dies
//! out; softer, it grows into stick-slip. With a = 0.010, b = 0.015, L = 1 mm, N = 1 N, m = 10 g
//! and V = 1 mm/s, `k_c` = 5 N/m and the inertia correction is 10⁻³.

use stickslip_solver::laws::RateState;
use stickslip_solver::laws::rate_state::{friction, steady_friction};
use stickslip_solver::laws::{Evolution, RateStateNode, RateStateStart};
use stickslip_solver::step::contact::resolve;

const MASS: f64 = 0.01;
const NORMAL: f64 = 1.0;
const LOAD_RATE: f64 = 1e-3;
const DT: f64 = 1e-3;

fn law(evolution: Evolution) -> RateStateNode {
    RateStateNode {
        a: 0.010,
        b: 0.015,
        dc_m: 1e-3,
        v0_m_s: 1e-6,
        f0: 0.6,
        evolution,
        start: RateStateStart::SteadyAt(LOAD_RATE),
    }
}

/// Slides the block for `duration_s` on a spring `k` from steady sliding at the load rate with
/// θ off steady state by `theta_factor`; returns the slip rate of every step.
fn slide(n: &RateStateNode, k: f64, theta_factor: f64, duration_s: f64) -> Vec<f64> {
    let g = MASS / (DT * DT);
    // The spring's stretch at steady sliding holds the steady friction.
    let stretch = steady_friction(n, LOAD_RATE) * NORMAL / k;
    let (mut x_prev, mut x) = (-LOAD_RATE * DT, 0.0);
    let (mut sliding, mut theta) = (true, n.theta0_s(0.0, 0.0) * theta_factor);
    let steps = (duration_s / DT).round() as usize;
    let mut rates = Vec::with_capacity(steps);
    for i in 0..steps {
        let t = i as f64 * DT;
        let spring = k * (LOAD_RATE * t + stretch - x);
        let trial = 2.0 * x - x_prev + spring / g;
        let r = resolve::<RateState>(n, (g, DT), [trial, 0.0, -NORMAL / g], [x, 0.0], sliding, theta);
        (x_prev, x) = (x, r.position[0]);
        (sliding, theta) = (r.sliding, r.state);
        rates.push((x - x_prev) / DT);
    }
    rates
}

/// The swing of ln V (max − min) over `window` steps from `from`.
fn swing(rates: &[f64], from: usize, window: usize) -> f64 {
    let logs = rates[from..from + window].iter().map(|v| v.max(1e-30).ln());
    let (lo, hi) = logs.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| (lo.min(v), hi.max(v)));
    hi - lo
}

#[test]
fn rate_state_steady_sliding_holds_its_rate_and_friction() {
    for evolution in [Evolution::Aging, Evolution::Slip] {
        let n = law(evolution);
        let rates = slide(&n, 50.0, 1.0, 20.0);
        for (i, v) in rates.iter().enumerate().skip(1) {
            assert!((v / LOAD_RATE - 1.0).abs() < 1e-6, "{evolution:?} step {i}: V = {v}");
        }
        // Its friction is the closed form f₀ + (a − b)·ln(V/V₀).
        let closed = n.f0 + (n.a - n.b) * (LOAD_RATE / n.v0_m_s).ln();
        assert!((friction(&n, LOAD_RATE, n.theta0_s(0.0, 0.0)) - closed).abs() < 1e-12);
    }
}

#[test]
fn rate_state_spring_slider_is_stable_above_the_critical_stiffness_and_unstable_below() {
    let n = law(Evolution::Aging);
    let inertia = MASS * LOAD_RATE * LOAD_RATE / (NORMAL * n.a * n.dc_m);
    let k_c = (n.b - n.a) * NORMAL / n.dc_m * (1.0 + inertia);
    assert!((k_c - 5.005).abs() < 1e-9);
    let window = 20_000; // 20 s, several periods of the oscillation near k_c
    let stable = slide(&n, 1.05 * k_c, 1.05, 200.0);
    let (early, late) = (swing(&stable, 1, window), swing(&stable, stable.len() - window, window));
    println!("1.05 k_c: the swing of ln V goes from {early:.3e} to {late:.3e}");
    assert!(late < 0.3 * early, "stable: {early} → {late}");
    let unstable = slide(&n, 0.95 * k_c, 1.05, 200.0);
    let (early, late) = (swing(&unstable, 1, window), swing(&unstable, unstable.len() - window, window));
    println!("0.95 k_c: the swing of ln V goes from {early:.3e} to {late:.3e}");
    assert!(late > 3.0 * early, "unstable: {early} → {late}");
    // Far below k_c the block sticks and slips: its slip rate spans decades.
    let stick_slip = slide(&n, 0.5 * k_c, 1.05, 200.0);
    let late = swing(&stick_slip, stick_slip.len() - window, window);
    println!("0.5 k_c: the swing of ln V is {late:.3e}");
    assert!(late > 3.0, "stick-slip at 0.5 k_c: ln V swings by {late}");
}
