//! One damped linear oscillator driven by an input read as straight lines between samples: the
//! exact step (Nigam & Jennings 1969), the exact largest |u| inside a step, and the free
//! vibration after the input ends.
//!
//! The oscillator `ü + 2ξωu̇ + ω²u = −a(t)` (u relative displacement, a ground acceleration, ω
//! = 2π/T, ω_d = ω√(1−ξ²), λ = −ξω + iω_d) is advanced over steps of `h` seconds in which the
//! input is linear, `a(τ) = a₀ + sτ`, `s = (a₁ − a₀)/h`. Inside a step the response is, exactly,
//!
//! ```text
//! u(τ) = L(τ) + y(τ),   L(τ) = −a(τ)/ω² + 2ξs/ω³   (particular solution, linear in τ),
//! y(τ) = Re(z·e^{λτ}),  z = y₀ − i(ẏ₀ + ξωy₀)/ω_d,  y₀ = u₀ − L(0),  ẏ₀ = u̇₀ + s/ω²,
//! ```
//!
//! so `u̇(τ) = −s/ω² + Re(λz·e^{λτ})` and `ü(τ) = Re(λ²z·e^{λτ})` (L is linear). The step itself
//! is `[u, u̇]₁ = A·[u, u̇]₀ + B·[a₀, a₁]` with the Nigam–Jennings matrices, taken from the
//! transition matrix `exp(M·h)` of the augmented system `[u, u̇, a, ȧ]` (nalgebra's Padé
//! exponential) when ωh < 1, and from the decomposition above in closed form otherwise (where
//! it has no cancellation).
//!
//! **Largest |u| inside a step.** An interior extremum of u is a zero of u̇. Cheap bounds come
//! first: `max(|L(0)|, |L(h)|) + |z|`; no zero of u̇ when it has one sign at both ends and
//! stays away from zero by more than `(h²/8)·ω³|z|`; and `max(|u₀|, |u₁|) + (h²/8)·(max|ü_end|
//! + (h²/8)·ω⁴|z|)` (ü is a damped harmonic of amplitude ω²|z|). Otherwise the zeros of u̇ are
//! found: between two consecutive zeros of ü — which fall every π/ω_d at
//! `ω_dτ + arg(λ²z) ≡ π/2 (mod π)` — u̇ is monotone, so it has at most one zero there,
//! bracketed by the signs of u̇ at the ends of the piece (when ω_d·h < π there is at most one
//! such zero of ü, told by the signs of ü at the step's ends). Each zero is found by Newton's
//! method kept inside its bracket (bisection when it leaves it), stopped once the step is below
//! 1e-7/ω, where |u| is read: u is stationary there, so that is ½|ü|·(1e-7/ω)² ≈ 1e-14 relative
//! from the extremum. Pieces whose bound `max|L| + |z|·e^{−ξωτ}` cannot beat the running peak
//! are skipped, and the walk stops once the bound for the rest of the step cannot. Where
//! ω·τ < 1, u and u̇ are evaluated as `u₀ + u̇₀τ + Re(z·E₂)`, `u̇₀ + Re(λz·E₁)` with
//! `E₁ = e^{λτ} − 1`, `E₂ = e^{λτ} − 1 − λτ` (by their series for |λτ| < ½), which avoids the
//! cancellation between L and y of a long-period oscillator under a rough input; elsewhere as
//! `L + y`.
//!
//! **Free vibration.** After the input ends the oscillator swings freely from `(u₀, u̇₀)`; the
//! velocity `e^{−ξωt}[u̇₀ cos ω_dt − (ξωu̇₀ + ω²u₀)/ω_d · sin ω_dt]` first vanishes at
//! `tan ω_dt = u̇₀ω_d/(ξωu̇₀ + ω²u₀)`, and every later extremum is smaller by `e^{−ξωπ/ω_d}`, so
//! the largest |u| is |u₀| or the first extremum.

use std::f64::consts::{FRAC_PI_2, PI};

use nalgebra::Matrix4;
use rustfft::num_complex::Complex;

/// A damped linear oscillator and its exact step for an input linear inside steps of `h`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Oscillator {
    omega: f64,
    xi: f64,
    wd: f64,
    h: f64,
    /// Nigam–Jennings coefficients `[a11, a12, a21, a22, bu0, bu1, bv0, bv1]`.
    nj: [f64; 8],
    lambda: Complex<f64>,
    lambda2: Complex<f64>,
    /// 1/ω², 2ξ/ω³, 1/h, 1/ω_d (multiplications are cheaper than divisions in the bounds).
    inv_w2: f64,
    k_slope: f64,
    inv_h: f64,
    inv_wd: f64,
    /// `(cos, sin)` of `ω_d·h` when it is below π (see [`Oscillator::turn`]).
    turn: Option<(f64, f64)>,
}

impl Oscillator {
    /// The oscillator of period `period` (s, > 0) and damping `damping` (fraction of critical,
    /// 0 ≤ ξ < 1) stepped every `h` seconds (> 0). Parameters are not checked here (the plans
    /// check them).
    pub fn new(period: f64, damping: f64, h: f64) -> Self {
        let omega = 2.0 * PI / period;
        let xi = damping;
        let wd = omega * (1.0 - xi * xi).sqrt();
        let lambda = Complex::new(-xi * omega, wd);
        Oscillator {
            omega,
            xi,
            wd,
            h,
            nj: transition(omega, xi, h),
            lambda,
            lambda2: lambda * lambda,
            inv_w2: 1.0 / (omega * omega),
            k_slope: 2.0 * xi / (omega * omega * omega),
            inv_h: 1.0 / h,
            inv_wd: 1.0 / wd,
            turn: (wd * h < PI).then(|| {
                let (s, c) = (wd * h).sin_cos();
                (c, s)
            }),
        }
    }

    /// Circular frequency ω (rad/s).
    pub fn omega(&self) -> f64 {
        self.omega
    }

    /// Damping ratio ξ.
    pub fn damping(&self) -> f64 {
        self.xi
    }

    /// Step length h (s).
    pub fn h(&self) -> f64 {
        self.h
    }

    /// Nigam–Jennings coefficients `[a11, a12, a21, a22, bu0, bu1, bv0, bv1]`:
    /// `u₁ = a11·u₀ + a12·u̇₀ + bu0·a₀ + bu1·a₁`, `u̇₁ = a21·u₀ + a22·u̇₀ + bv0·a₀ + bv1·a₁`.
    pub fn coefficients(&self) -> [f64; 8] {
        self.nj
    }

    /// `(u, u̇)` one step after `(u, v)` (length unit of the record, per second) with the input
    /// going linearly from `a0` to `a1` (record units, e.g. m/s²).
    pub fn step(&self, u: f64, v: f64, a0: f64, a1: f64) -> (f64, f64) {
        let c = &self.nj;
        (c[0] * u + c[1] * v + c[4] * a0 + c[5] * a1, c[2] * u + c[3] * v + c[6] * a0 + c[7] * a1)
    }

    /// `max(floor, |u(τ)|)` over the extrema of u strictly inside the step that starts at
    /// `(u0, v0)` with the input going linearly from `a0` to `a1` (the values at the step's ends
    /// are not looked at: the caller counts them). Exact to rounding.
    pub fn step_peak(&self, u0: f64, v0: f64, a0: f64, a1: f64, floor: f64) -> f64 {
        let (omega, xi, wd, h) = (self.omega, self.xi, self.wd, self.h);
        let w2 = omega * omega;
        let s = (a1 - a0) * self.inv_h;
        let p1 = -s * self.inv_w2;
        let l0 = -a0 * self.inv_w2 + self.k_slope * s;
        let y0 = u0 - l0;
        let z = Complex::new(y0, -(v0 - p1 + xi * omega * y0) * self.inv_wd);
        let zn = z.norm_sqr().sqrt();
        let lh = (l0 + p1 * h).abs();
        if !(zn > 0.0) || lh.max(l0.abs()) + zn <= floor {
            return floor;
        }
        // No zero of u̇ inside: it has one sign at both ends and |d²u̇/dτ²| ≤ ω³|z| keeps it
        // within (h²/8)·ω³|z| of the chord.
        let (u1, v1) = self.step(u0, v0, a0, a1);
        let hh = h * h / 8.0;
        if v0 * v1 > 0.0 && v0.abs().min(v1.abs()) > hh * w2 * omega * zn {
            return floor;
        }
        // An interior extremum is within h/2 of an end, where |u| is at most max|u_end|, and
        // |ü| ≤ max|ü_end| + (h²/8)·ω⁴|z| in between (ü is a damped harmonic of amplitude ω²|z|).
        let acc = |u: f64, v: f64, a: f64| (-a - 2.0 * xi * omega * v - w2 * u).abs();
        if u0.abs().max(u1.abs()) + hh * (acc(u0, v0, a0).max(acc(u1, v1, a1)) + hh * w2 * w2 * zn) <= floor {
            return floor;
        }
        // The cubic Hermite interpolant of (u0, u̇0, u1, u̇1) is within ω⁴|z|·h⁴/384 of u inside
        // the step (the fourth derivative of u is Re(λ⁴z·e^{λτ}) with |λ| = ω, and the
        // interpolant's error is at most its largest value times τ²(h−τ)²/24): when the
        // interpolant's largest |value| plus that stays below the floor, with a margin for the
        // roundings of both, no extremum inside can reach it and the solve below would return the
        // floor. Much tighter than the bound above for periods of a few steps.
        let reach = hermite_peak(u0, v0 * h, u1, v1 * h) + w2 * w2 * zn * h.powi(4) / 384.0;
        let rounding = 1e-12 * (u0.abs() + u1.abs() + (v0 * h).abs() + (v1 * h).abs() + l0.abs() + lh + zn);
        if reach * (1.0 + 1e-9) + rounding <= floor {
            return floor;
        }
        let st = InStep { u0, v0, l0, p1, omega, z, lz: self.lambda * z, l2z: self.lambda2 * z, lambda: self.lambda };
        // Zeros of ü = Re(λ²z·e^{λτ}) = e^{−ξωτ}|λ²z|·cos(ω_dτ + ψ): every π/ω_d.
        let half = PI / wd;
        let first_zero = || {
            let psi = st.l2z.im.atan2(st.l2z.re);
            let t = (FRAC_PI_2 - psi).rem_euclid(PI) / wd;
            if t > 0.0 { t } else { half }
        };
        if wd * h < PI {
            // At most one zero of ü inside, so u̇ is monotone or has one interior extremum.
            let signed_acc = |u: f64, v: f64, a: f64| -a - 2.0 * xi * omega * v - w2 * u;
            if v0 * v1 < 0.0 {
                return floor.max(st.extremum(0.0, h, v0, v1));
            }
            if signed_acc(u0, v0, a0) * signed_acc(u1, v1, a1) < 0.0 {
                // u̇ turns once inside: two zeros if it crosses zero there.
                let tz = first_zero();
                if tz < h {
                    let vz = st.eval(tz).1;
                    if vz * v0 < 0.0 {
                        return floor.max(st.extremum(0.0, tz, v0, vz)).max(st.extremum(tz, h, vz, v1));
                    }
                }
            }
            return floor;
        }
        let mut next = first_zero();
        let (mut a, mut va, mut best) = (0.0, v0, floor);
        loop {
            let env = zn * (-xi * omega * a).exp();
            let la = (l0 + p1 * a).abs();
            if la.max(lh) + env <= best {
                break;
            }
            let last = next >= h;
            let b = if last { h } else { next };
            let vb = if last { v1 } else { st.eval(b).1 };
            if va * vb < 0.0 {
                if la.max((l0 + p1 * b).abs()) + env > best {
                    best = best.max(st.extremum(a, b, va, vb));
                }
            } else if vb == 0.0 && !last {
                best = best.max(st.eval(b).0.abs());
            }
            if last {
                break;
            }
            (a, va) = (b, vb);
            next += half;
        }
        best
    }

    /// `(L(0), L(h), z)` of the step that starts at `(u0, v0)` with the input going linearly
    /// from `a0` to `a1` (z as `[re, im]`): `|u(τ)| ≤ max(|L(0)|, |L(h)|) + |z|` and
    /// `|ü(τ)| ≤ ω²|z|` inside it; all three are linear in `(u0, v0, a0, a1)`.
    pub(crate) fn envelope(&self, u0: f64, v0: f64, a0: f64, a1: f64) -> (f64, f64, [f64; 2]) {
        let s = (a1 - a0) * self.inv_h;
        let p1 = -s * self.inv_w2;
        let l0 = -a0 * self.inv_w2 + self.k_slope * s;
        let y0 = u0 - l0;
        (l0, l0 + p1 * self.h, [y0, -(v0 - p1 + self.xi * self.omega * y0) * self.inv_wd])
    }

    /// `e^{λt}` as `[re, im]`: the homogeneous part `y(t) = Re(z·e^{λt})` of a step (see
    /// [`Oscillator::envelope`]) `t` seconds into it.
    pub(crate) fn phase(&self, t: f64) -> [f64; 2] {
        let e = (self.lambda * t).exp();
        [e.re, e.im]
    }

    /// `(cos, sin)` of the phase `ω_d·h` the damped harmonic turns through in one step, if less
    /// than π (then `|y|` has an interior maximum in the step only where `Im(z·e^{iω_dτ})`
    /// changes sign, see `rotd`).
    pub(crate) fn turn(&self) -> Option<(f64, f64)> {
        self.turn
    }

    /// Largest |u| of the free vibration from `(u0, v0)` (see [`free_vibration_peak`]).
    pub fn free_peak(&self, u0: f64, v0: f64) -> f64 {
        free_vibration_peak(u0, v0, self.omega, self.xi)
    }
}

/// Largest |H(s)| over `0 ≤ s ≤ 1` of the cubic with `H(0) = u0`, `H'(0) = d0`, `H(1) = u1`,
/// `H'(1) = d1` (derivatives in units of the interval): its ends and the zeros of the quadratic
/// `H'` inside, found by the stable form of the roots.
fn hermite_peak(u0: f64, d0: f64, u1: f64, d1: f64) -> f64 {
    let a = 2.0 * u0 + d0 - 2.0 * u1 + d1;
    let b = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1;
    let c = d0;
    let at = |s: f64| ((a * s + b) * s + c) * s + u0;
    let mut peak = u0.abs().max(u1.abs());
    // H'(s) = 3a·s² + 2b·s + c.
    let (qa, qb, qc) = (3.0 * a, 2.0 * b, c);
    let mut look = |s: f64| {
        if s > 0.0 && s < 1.0 {
            peak = peak.max(at(s).abs());
        }
    };
    if qa == 0.0 {
        if qb != 0.0 {
            look(-qc / qb);
        }
    } else {
        let disc = qb * qb - 4.0 * qa * qc;
        if disc >= 0.0 {
            let q = -0.5 * (qb + qb.signum() * disc.sqrt());
            look(q / qa);
            if q != 0.0 {
                look(qc / q);
            }
        }
    }
    peak
}

/// The response inside one step, in the forms of the module documentation.
struct InStep {
    u0: f64,
    v0: f64,
    l0: f64,
    p1: f64,
    omega: f64,
    z: Complex<f64>,
    lz: Complex<f64>,
    l2z: Complex<f64>,
    lambda: Complex<f64>,
}

impl InStep {
    /// `(u, u̇, ü)` at `t` seconds into the step.
    fn eval(&self, t: f64) -> (f64, f64, f64) {
        let w = self.lambda * t;
        let (e, e1, e2) = exp_parts(w);
        let acc = (self.l2z * e).re;
        if self.omega * t < 1.0 {
            (self.u0 + self.v0 * t + (self.z * e2).re, self.v0 + (self.lz * e1).re, acc)
        } else {
            (self.l0 + self.p1 * t + (self.z * e).re, self.p1 + (self.lz * e).re, acc)
        }
    }

    /// |u| at the zero of u̇ in `(a, b)`, where u̇ is monotone and goes from `va` to `vb` (of
    /// opposite signs): Newton's method kept inside the bracket, bisection when it leaves it.
    /// It stops once the next Newton step is below 1e-7/ω, and returns |u| where it stands:
    /// u is stationary at the zero, so that is within ½|ü|·(1e-7/ω)² (≈ 1e-14 relative) of
    /// the extremum.
    fn extremum(&self, a: f64, b: f64, va: f64, vb: f64) -> f64 {
        let (mut lo, mut hi) = (a, b);
        let mut t = a + (b - a) * (va / (va - vb));
        let tol = 1e-7 / self.omega;
        for _ in 0..200 {
            let (u, v, acc) = self.eval(t);
            if v == 0.0 {
                return u.abs();
            }
            if (v > 0.0) == (va > 0.0) {
                lo = t;
            } else {
                hi = t;
            }
            let next = t - v / acc;
            if next > lo && next < hi {
                if (next - t).abs() <= tol {
                    return u.abs();
                }
                t = next;
            } else {
                t = 0.5 * (lo + hi);
            }
            if hi - lo <= tol {
                break;
            }
        }
        self.eval(t).0.abs()
    }
}

/// `1/k` for the series of [`exp_parts`].
const INVERSES: [f64; 19] = {
    let mut a = [0.0; 19];
    let mut k = 1;
    while k < 19 {
        a[k] = 1.0 / k as f64;
        k += 1;
    }
    a
};

/// `(e^w, e^w − 1, e^w − 1 − w)`, the last two without cancellation for small |w|.
fn exp_parts(w: Complex<f64>) -> (Complex<f64>, Complex<f64>, Complex<f64>) {
    let one = Complex::new(1.0, 0.0);
    if w.norm_sqr() < 0.25 {
        // e^w − 1 − w = (w²/2)·(1 + (w/3)·(1 + (w/4)·(1 + …))), to w¹⁸/18! (< 1e-20 relative).
        let mut s = one;
        for k in (3..=18).rev() {
            s = one + s * (w * INVERSES[k]);
        }
        let e2 = w * w * 0.5 * s;
        let e1 = w + e2;
        (one + e1, e1, e2)
    } else {
        let e = w.exp();
        (e, e - one, e - one - w)
    }
}

/// Nigam–Jennings coefficients `[a11, a12, a21, a22, bu0, bu1, bv0, bv1]` over `h` (see the
/// module documentation for the two ways they are computed).
fn transition(omega: f64, xi: f64, h: f64) -> [f64; 8] {
    if omega * h < 1.0 {
        // z = [u, v, a, s] with s = ȧ constant: u̇ = v, v̇ = −ω²u − 2ξωv − a, ȧ = s, ṡ = 0.
        #[rustfmt::skip]
        let m = Matrix4::new(
            0.0, 1.0, 0.0, 0.0,
            -omega * omega, -2.0 * xi * omega, -1.0, 0.0,
            0.0, 0.0, 0.0, 1.0,
            0.0, 0.0, 0.0, 0.0,
        ) * h;
        let e = m.exp();
        // z(h) = E·[u, v, a0, (a1 − a0)/h]: the a0 weight is E[.,2] − E[.,3]/h, a1's E[.,3]/h.
        return [
            e[(0, 0)],
            e[(0, 1)],
            e[(1, 0)],
            e[(1, 1)],
            e[(0, 2)] - e[(0, 3)] / h,
            e[(0, 3)] / h,
            e[(1, 2)] - e[(1, 3)] / h,
            e[(1, 3)] / h,
        ];
    }
    // Homogeneous part: u(h) = e^{−ξωh}[u₀ cos + (u̇₀ + ξωu₀)/ω_d · sin], and its derivative.
    let wd = omega * (1.0 - xi * xi).sqrt();
    let (sn, cs) = (wd * h).sin_cos();
    let e = (-xi * omega * h).exp();
    let a11 = e * (cs + xi * omega / wd * sn);
    let a12 = e * sn / wd;
    let a21 = -e * omega * omega / wd * sn;
    let a22 = e * (cs - xi * omega / wd * sn);
    // Forced part from rest: u(h) = L(h) − [A·(L(0), L̇)]₀ with L(τ) = −(a₀ + sτ)/ω² + 2ξs/ω³,
    // L̇ = −s/ω²; linear in (a₀, a₁), so each weight is the response to a unit a₀ or a₁.
    let forced = |a0: f64, a1: f64| {
        let s = (a1 - a0) / h;
        let w2 = omega * omega;
        let (l0, lh, ld) = ((-a0 + 2.0 * xi * s / omega) / w2, (-a1 + 2.0 * xi * s / omega) / w2, -s / w2);
        (lh - a11 * l0 - a12 * ld, ld - a21 * l0 - a22 * ld)
    };
    let (bu0, bv0) = forced(1.0, 0.0);
    let (bu1, bv1) = forced(0.0, 1.0);
    [a11, a12, a21, a22, bu0, bu1, bv0, bv1]
}

/// Largest |u| of the damped free vibration of circular frequency `omega` (rad/s) and damping
/// `xi` that starts from `(u0, v0)`: |u0| or the first extremum (later extrema are smaller by
/// `exp(−ξωπ/ω_d)` each).
pub fn free_vibration_peak(u0: f64, v0: f64, omega: f64, xi: f64) -> f64 {
    let wd = omega * (1.0 - xi * xi).sqrt();
    // v(t) = e^{−ξωt}[v0·cos ω_d t − (ξω v0 + ω² u0)/ω_d · sin ω_d t] vanishes where
    // tan ω_d t = v0·ω_d / (ξω v0 + ω² u0).
    let mut theta = (v0 * wd).atan2(xi * omega * v0 + omega * omega * u0);
    if theta <= 0.0 {
        theta += PI;
    }
    let t = theta / wd;
    let u1 = (-xi * omega * t).exp() * (u0 * (wd * t).cos() + (v0 + xi * omega * u0) / wd * (wd * t).sin());
    u0.abs().max(u1.abs())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn free_vibration_peak_matches_a_scan() {
        for (u0, v0, xi) in [(1.0, 0.0, 0.05), (0.0, 1.0, 0.05), (-0.3, 2.0, 0.1), (0.5, -3.0, 0.02), (0.0, 0.0, 0.05)]
        {
            let omega = 7.0;
            let wd = omega * (1.0f64 - xi * xi).sqrt();
            let mut best = 0.0f64;
            for i in 0..200_000 {
                let t = i as f64 * 1e-5;
                let u = (-xi * omega * t).exp() * (u0 * (wd * t).cos() + (v0 + xi * omega * u0) / wd * (wd * t).sin());
                best = best.max(u.abs());
            }
            let exact = free_vibration_peak(u0, v0, omega, xi);
            assert!((exact - best).abs() <= 1e-6 * best.max(1e-12), "{u0} {v0}: {exact} vs scan {best}");
        }
    }

    #[test]
    fn the_two_ways_to_the_coefficients_agree_where_both_are_accurate() {
        for xi in [0.0, 0.05, 0.3, 0.9] {
            for wh in [0.3, 0.6, 0.99, 1.01, 1.5, 2.5] {
                let (omega, h) = (wh / 0.01, 0.01);
                // Padé (the branch below ωh = 1) against the closed form above it.
                let pade = {
                    #[rustfmt::skip]
                    let m = Matrix4::new(
                        0.0, 1.0, 0.0, 0.0,
                        -omega * omega, -2.0 * xi * omega, -1.0, 0.0,
                        0.0, 0.0, 0.0, 1.0,
                        0.0, 0.0, 0.0, 0.0,
                    ) * h;
                    let e = m.exp();
                    [
                        e[(0, 0)],
                        e[(0, 1)],
                        e[(1, 0)],
                        e[(1, 1)],
                        e[(0, 2)] - e[(0, 3)] / h,
                        e[(0, 3)] / h,
                        e[(1, 2)] - e[(1, 3)] / h,
                        e[(1, 3)] / h,
                    ]
                };
                let got = transition(omega, xi, h);
                // Scale of each coefficient: 1, h, ω, 1 for A; h², h² for B·u; h, h for B·u̇.
                let scale = [1.0, h, omega, 1.0, h * h, h * h, h, h];
                for k in 0..8 {
                    assert!(
                        (got[k] - pade[k]).abs() <= 1e-13 * scale[k],
                        "ξ {xi}, ωh {wh}, coefficient {k}: {} vs {}",
                        got[k],
                        pade[k]
                    );
                }
            }
        }
    }

    /// Dense scan of the exact in-step response (the recurrence sub-stepped 20 000 times).
    fn scan(o: &Oscillator, u0: f64, v0: f64, a0: f64, a1: f64) -> f64 {
        let m = 20_000;
        let fine = Oscillator::new(2.0 * PI / o.omega, o.xi, o.h / m as f64);
        let (mut u, mut v, mut best) = (u0, v0, 0.0f64);
        for k in 0..m {
            let s0 = a0 + (a1 - a0) * k as f64 / m as f64;
            let s1 = a0 + (a1 - a0) * (k + 1) as f64 / m as f64;
            (u, v) = fine.step(u, v, s0, s1);
            best = best.max(u.abs());
        }
        best
    }

    #[test]
    fn hermite_peak_matches_a_dense_scan() {
        // Cubics with no, one and two extrema inside, a quadratic (leading coefficient zero)
        // and a straight line.
        for (u0, d0, u1, d1) in [
            (0.0, 1.0, 0.0, -1.0),
            (1.0, -3.0, -0.5, 2.0),
            (0.2, 0.1, 0.9, 0.3),
            (-1.0, 4.0, 1.0, 4.0),
            (0.0, 2.0, 1.0, 0.0),
            (1.0, 1.0, 2.0, 1.0),
            (0.3, -0.1, 0.3, 0.1),
        ] {
            let a = 2.0 * u0 + d0 - 2.0 * u1 + d1;
            let b = -3.0 * u0 - 2.0 * d0 + 3.0 * u1 - d1;
            let dense = (0..=100_000)
                .map(|i| i as f64 / 100_000.0)
                .map(|s| (((a * s + b) * s + d0) * s + u0).abs())
                .fold(0.0, f64::max);
            let peak = hermite_peak(u0, d0, u1, d1);
            assert!(peak >= dense * (1.0 - 1e-12) && peak <= dense * (1.0 + 1e-9), "{peak} vs {dense}");
        }
    }

    #[test]
    fn step_peak_matches_a_dense_scan() {
        // Periods from far below to far above the step, states and inputs of every sign.
        let h = 0.01;
        for (t, xi) in [(2.0, 0.05), (0.05, 0.05), (0.02, 0.0), (0.013, 0.1), (0.004, 0.02), (0.0031, 0.7)] {
            let o = Oscillator::new(t, xi, h);
            for (u0, v0, a0, a1) in
                [(0.01, 0.3, 1.0, -2.0), (-1e-4, 0.02, 3.0, 3.5), (0.0, 0.0, 0.0, 9.0), (2e-3, -0.5, -1.0, 1.0)]
            {
                let (u1, _) = o.step(u0, v0, a0, a1);
                let exact = o.step_peak(u0, v0, a0, a1, u0.abs().max(u1.abs()));
                let dense = scan(&o, u0, v0, a0, a1).max(u0.abs());
                // The scan's sampling error, (ω·h/20000)²/8 of the peak at most, and its rounding
                // over 20 000 sub-steps.
                let tol = ((o.omega * h / 20_000.0).powi(2) / 8.0 + 1e-11) * dense + 1e-18;
                println!("T {t}, ξ {xi}: step peak/scan − 1 = {:.1e}", exact / dense - 1.0);
                assert!(exact >= dense - tol && exact <= dense + tol, "T {t}, ξ {xi}: {exact} vs scan {dense}");
            }
        }
    }

    #[test]
    fn a_velocity_that_dips_across_zero_inside_a_step_gives_both_extrema() {
        // Undamped, T = 1 s, h = 0.45 s (ωh = 0.9π < π): u = −sτ/ω² + cos ωτ with the slope s
        // chosen so u̇ = ω(½ − sin ωτ) is positive at both ends and negative between 30° and
        // 150° of phase: a maximum then a minimum inside the step, neither at its ends.
        let (t, h) = (1.0, 0.45);
        let o = Oscillator::new(t, 0.0, h);
        let w = 2.0 * PI / t;
        let s = -0.5 * w * w * w;
        let (u0, v0, a0, a1) = (1.0, 0.5 * w, 0.0, s * h);
        let (u1, v1) = o.step(u0, v0, a0, a1);
        assert!(v0 > 0.0 && v1 > 0.0, "u̇ positive at both ends");
        let u = |tau: f64| -s * tau / (w * w) + (w * tau).cos();
        let want = u((PI / 6.0) / w).abs().max(u((5.0 * PI / 6.0) / w).abs());
        let exact = o.step_peak(u0, v0, a0, a1, u0.abs().max(u1.abs()));
        assert!(want > u0.abs().max(u1.abs()), "an interior extremum beats the ends");
        assert!((exact / want - 1.0).abs() < 1e-13, "{exact} vs {want}");
    }
}
