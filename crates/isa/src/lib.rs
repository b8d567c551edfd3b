//! stickslip isa: the instruction-set builds of the numerical kernels. Every kernel is compiled
//! for baseline x86-64, AVX2 and AVX-512, and the widest the CPU has is picked at run time.
//!
//! Owns: the builds ([`Isa`]), which one the CPU runs ([`Isa::detected`], [`Isa::available`]),
//! which one the calling thread uses ([`Isa::current`], [`Isa::pinned`]) and the macro that
//! compiles a kernel once per build and dispatches to one ([`widest!`]); the solver's step
//! kernels and seismo's oscillator banks use it. Must not know: what any kernel computes (it
//! depends on nothing).
//!
//! Rust never fuses a multiply and an add on its own, so the three builds of a kernel give the
//! same bits; each user's kernel tests check that, build against build and each against a
//! scalar reference, with every build of [`Isa::available`] forced in turn by [`Isa::pinned`]
//! (which benchmarks use too).
#![deny(missing_docs)]

use std::cell::Cell;
use std::sync::OnceLock;

/// A build of the kernels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Isa {
    /// Baseline x86-64 (SSE2), or the target's default elsewhere.
    Baseline,
    /// AVX2.
    Avx2,
    /// AVX-512 (foundation).
    Avx512,
}

thread_local! {
    static PINNED: Cell<Option<Isa>> = const { Cell::new(None) };
}

impl Isa {
    /// The widest build this CPU runs.
    pub fn detected() -> Isa {
        static DETECTED: OnceLock<Isa> = OnceLock::new();
        *DETECTED.get_or_init(|| {
            #[cfg(target_arch = "x86_64")]
            {
                if std::is_x86_feature_detected!("avx512f") {
                    return Isa::Avx512;
                }
                if std::is_x86_feature_detected!("avx2") {
                    return Isa::Avx2;
                }
            }
            Isa::Baseline
        })
    }

    /// Every build this CPU runs, narrowest first.
    pub fn available() -> Vec<Isa> {
        [Isa::Baseline, Isa::Avx2, Isa::Avx512].into_iter().filter(|&i| i <= Isa::detected()).collect()
    }

    /// The build the calling thread uses now: the pinned one inside [`Isa::pinned`], else the
    /// widest available.
    #[inline]
    pub fn current() -> Isa {
        PINNED.with(Cell::get).unwrap_or_else(Isa::detected)
    }

    /// Runs `f` with every kernel called on this thread in build `isa`. Panics if the CPU does
    /// not have it.
    pub fn pinned<T>(isa: Isa, f: impl FnOnce() -> T) -> T {
        assert!(isa <= Isa::detected(), "{isa:?} is not available on this CPU");
        let before = PINNED.with(|p| p.replace(Some(isa)));
        let out = f();
        PINNED.with(|p| p.set(before));
        out
    }
}

impl PartialOrd for Isa {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Isa {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        let rank = |i: &Isa| match i {
            Isa::Baseline => 0,
            Isa::Avx2 => 1,
            Isa::Avx512 => 2,
        };
        rank(self).cmp(&rank(other))
    }
}

/// Defines `$name(isa, …)`, which runs the `#[inline(always)]` kernel `$kernel` compiled for
/// instruction set `isa` (see [`Isa`]; callers pass [`Isa::current`]). The generics are
/// optional: none, or `const L: usize` with at most one more bounded type parameter. An
/// `unsafe fn` dispatcher forwards its kernel's safety contract.
///
/// ```ignore
/// use stickslip_isa::{Isa, widest};
///
/// widest! {
///     /// Scales `x` by `k` in instruction set `isa`.
///     fn scale_dispatch(k: f64, x: &mut [f64]) => scale
/// }
///
/// #[inline(always)]
/// fn scale(k: f64, x: &mut [f64]) {
///     x.iter_mut().for_each(|v| *v *= k);
/// }
///
/// scale_dispatch(Isa::current(), 2.0, &mut data);
/// ```
#[macro_export]
macro_rules! widest {
    ($(#[$m:meta])* fn $name:ident $(<const $l:ident: usize $(, $g:ident: $b:path)?>)? ($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        fn $name $(<const $l: usize $(, $g: $b)?>)? (isa: $crate::Isa, $($a: $t),*) {
            // SAFETY: `$kernel` is safe; the builds differ only in instruction set, and a build is
            // only chosen when the CPU has it (`Isa::current`).
            unsafe { $crate::widest!(@run isa; $kernel; [$(const $l: usize $(, $g: $b)?)?]; $($a: $t),*) }
        }
    };
    ($(#[$m:meta])* unsafe fn $name:ident $(<const $l:ident: usize $(, $g:ident: $b:path)?>)? ($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        unsafe fn $name $(<const $l: usize $(, $g: $b)?>)? (isa: $crate::Isa, $($a: $t),*) {
            // SAFETY: the caller's contract is `$kernel`'s; the build is one the CPU has.
            unsafe { $crate::widest!(@run isa; $kernel; [$(const $l: usize $(, $g: $b)?)?]; $($a: $t),*) }
        }
    };
    (@run $isa:ident; $kernel:ident; [$(const $l:ident: usize $(, $g:ident: $b:path)?)?]; $($a:ident: $t:ty),*) => {{
        #[cfg(target_arch = "x86_64")]
        {
            #[target_feature(enable = "avx512f")]
            #[allow(unused_unsafe)]
            unsafe fn avx512 $(<const $l: usize $(, $g: $b)?>)? ($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            #[target_feature(enable = "avx2")]
            #[allow(unused_unsafe)]
            unsafe fn avx2 $(<const $l: usize $(, $g: $b)?>)? ($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            match $isa {
                $crate::Isa::Avx512 => return avx512($($a),*),
                $crate::Isa::Avx2 => return avx2($($a),*),
                $crate::Isa::Baseline => {}
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = $isa;
        #[allow(unused_unsafe)]
        unsafe { $kernel($($a),*) }
    }};
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builds_are_ordered_and_the_detected_one_is_the_widest_available() {
        let all = Isa::available();
        assert_eq!(all[0], Isa::Baseline);
        assert_eq!(*all.last().unwrap(), Isa::detected());
        assert!(all.windows(2).all(|w| w[0] < w[1]));
        println!("builds on this CPU: {all:?}");
    }

    #[test]
    fn pinning_holds_inside_the_closure_only_and_nests() {
        assert_eq!(Isa::current(), Isa::detected());
        for isa in Isa::available() {
            let seen = Isa::pinned(isa, || {
                let inner = Isa::pinned(Isa::Baseline, Isa::current);
                (Isa::current(), inner)
            });
            assert_eq!(seen, (isa, Isa::Baseline));
            assert_eq!(Isa::current(), Isa::detected());
        }
    }

    widest! {
        /// The safe form without generics.
        fn sum_dispatch(x: &[f64], out: &mut f64) => sum
    }

    widest! {
        /// The unsafe form with generics.
        ///
        /// # Safety
        /// `x` has at least `L` elements.
        unsafe fn first_dispatch<const L: usize, T: Copy>(x: &[T], out: &mut [T; L]) => first
    }

    #[inline(always)]
    fn sum(x: &[f64], out: &mut f64) {
        *out = x.iter().sum();
    }

    #[inline(always)]
    unsafe fn first<const L: usize, T: Copy>(x: &[T], out: &mut [T; L]) {
        for l in 0..L {
            // SAFETY: `x` has at least `L` elements (the contract).
            out[l] = unsafe { *x.get_unchecked(l) };
        }
    }

    #[test]
    fn every_build_runs_the_kernel() {
        let x: Vec<f64> = (0..37).map(|i| 1.0 / (i as f64 + 1.0)).collect();
        let want: f64 = x.iter().sum();
        for isa in Isa::available() {
            let mut got = 0.0;
            sum_dispatch(isa, &x, &mut got);
            assert_eq!(got.to_bits(), want.to_bits(), "{isa:?}");
            let mut out = [0u8; 4];
            // SAFETY: 5 ≥ 4 elements.
            unsafe { first_dispatch(isa, &[1, 2, 3, 4, 5], &mut out) };
            assert_eq!(out, [1, 2, 3, 4], "{isa:?}");
        }
    }
}
