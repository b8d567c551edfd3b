//! Instruction sets: every kernel is compiled for baseline x86-64, AVX2 and AVX-512, and the
//! widest the CPU has is picked at run time.
//!
//! Rust never fuses a multiply and an add on its own, so the three builds of a kernel give the
//! same bits; the kernel tests check that, build against build and each against a scalar
//! reference. [`Isa::pinned`] runs a closure with one build forced on the calling thread (for
//! those tests and for benchmarks).

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
/// instruction set `isa` (see [`Isa`]). An `unsafe fn` dispatcher forwards its kernel's safety
/// contract.
macro_rules! widest {
    ($(#[$m:meta])* fn $name:ident<const L: usize $(, $g:ident: $b:path)?>($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        fn $name<const L: usize $(, $g: $b)?>(isa: $crate::step::isa::Isa, $($a: $t),*) {
            // SAFETY: `$kernel` is safe; the builds differ only in instruction set, and a build is
            // only chosen when the CPU has it (`Isa::current`).
            unsafe { $crate::step::isa::widest!(@run isa; $kernel; [$($g: $b)?]; $($a: $t),*) }
        }
    };
    ($(#[$m:meta])* unsafe fn $name:ident<const L: usize>($($a:ident: $t:ty),* $(,)?) => $kernel:ident) => {
        $(#[$m])*
        unsafe fn $name<const L: usize>(isa: $crate::step::isa::Isa, $($a: $t),*) {
            // SAFETY: the caller's contract is `$kernel`'s; the build is one the CPU has.
            unsafe { $crate::step::isa::widest!(@run isa; $kernel; []; $($a: $t),*) }
        }
    };
    (@run $isa:ident; $kernel:ident; [$($g:ident: $b:path)?]; $($a:ident: $t:ty),*) => {{
        #[cfg(target_arch = "x86_64")]
        {
            #[target_feature(enable = "avx512f")]
            #[allow(unused_unsafe)]
            unsafe fn avx512<const L: usize $(, $g: $b)?>($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            #[target_feature(enable = "avx2")]
            #[allow(unused_unsafe)]
            unsafe fn avx2<const L: usize $(, $g: $b)?>($($a: $t),*) {
                unsafe { $kernel($($a),*) }
            }
            match $isa {
                $crate::step::isa::Isa::Avx512 => return avx512($($a),*),
                $crate::step::isa::Isa::Avx2 => return avx2($($a),*),
                $crate::step::isa::Isa::Baseline => {}
            }
        }
        #[cfg(not(target_arch = "x86_64"))]
        let _ = $isa;
        #[allow(unused_unsafe)]
        unsafe { $kernel($($a),*) }
    }};
}
pub(crate) use widest;
