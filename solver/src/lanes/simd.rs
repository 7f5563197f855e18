//! Lanes and the instruction set the batched kernels run on, chosen at run time.
//!
//! The batched kernels ([`crate::kernels::batch`]) are the scalar path's kernels instantiated with
//! [`Lanes`] ([`crate::lanes::real::Real`]), plain Rust over `[f64; LANES]` arrays: every lane does
//! the scalar path's arithmetic in the scalar path's order, and LLVM turns the lane loops
//! into vector instructions. [`dispatch`] runs a chunk's kernel inside a function
//! compiled for AVX-512 or AVX2 (+FMA) when the processor has them (detected once with
//! `is_x86_feature_detected!`), and as plain x86-64 (SSE2) or another architecture's baseline
//! otherwise: the portable fallback is the same code.
//!
//! Why `std::arch` detection and not a crate: the whole mechanism is one `match` over three
//! `#[target_feature]` functions that inline the kernel; `multiversion` (not in this
//! project's dependency cache) would generate the same three clones, and `pulp` / `wide`
//! would mean writing the kernels in their vector types instead of plain lane loops.
//!
//! Bits: Rust never contracts `a * b + c` into a fused multiply-add (no fast-math), so enabling
//! `fma` changes nothing as long as no code calls `mul_add`; `+ - * / sqrt` are correctly
//! rounded in vector and scalar alike. The batched results are therefore bit-identical to the
//! scalar path on every instruction set (tested in `solver/tests/batched_kernels.rs`).

/// Elements per batch: one AVX-512 register of `f64` (two AVX2 registers).
pub const LANES: usize = 8;

/// One `f64` per lane. Its operators work lane by lane, one IEEE operation each (so an
/// expression written like the scalar one rounds like it in every lane); each is a plain
/// loop over the lanes, which LLVM compiles to one vector instruction per register.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Lanes(pub [f64; LANES]);

/// One word per lane, all ones (set) or all zeros: the form a vector comparison gives on
/// AVX2 and that AVX-512 turns into a mask register and back in one instruction each, so a
/// comparison, blend or masked store compiles to one or two instructions. (A bit per lane,
/// `u8`, took ~20 instructions per comparison to pack the bits: measured in the AVX-512
/// kernel's profile, ~15 % of its instructions.)
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(C, align(64))]
pub struct Mask(pub [u64; LANES]);

/// `[f(0), .., f(LANES - 1)]`, always inlined. (`std::array::from_fn` is not: in a kernel
/// compiled into the solver crate LLVM left one call of it out of line, compiled for the
/// baseline instruction set, ~4 % of the yielding kernel.)
#[inline(always)]
pub fn each_lane<T: Copy + Default>(f: impl Fn(usize) -> T) -> [T; LANES] {
    let mut out = [T::default(); LANES];
    for (l, x) in out.iter_mut().enumerate() {
        *x = f(l);
    }
    out
}

impl Mask {
    /// The first `n` lanes.
    #[inline(always)]
    pub fn first(n: usize) -> Mask {
        Mask(each_lane(|l| if l < n { !0 } else { 0 }))
    }

    /// Lane `l`.
    #[inline(always)]
    pub fn on(self, l: usize) -> bool {
        self.0[l] != 0
    }
}

impl Default for Lanes {
    #[inline(always)]
    fn default() -> Lanes {
        Lanes([0.0; LANES])
    }
}

impl Lanes {
    #[inline(always)]
    pub const fn splat(x: f64) -> Lanes {
        Lanes([x; LANES])
    }

    /// `f` applied to every lane.
    #[inline(always)]
    pub fn map(self, f: impl Fn(f64) -> f64) -> Lanes {
        let mut out = self;
        for x in &mut out.0 {
            *x = f(*x);
        }
        out
    }
}

macro_rules! lane_op {
    ($trait:ident, $method:ident, $assign:ident, $assign_method:ident, $op:tt) => {
        impl std::ops::$trait for Lanes {
            type Output = Lanes;
            #[inline(always)]
            fn $method(self, o: Lanes) -> Lanes {
                let mut out = self;
                for l in 0..LANES {
                    out.0[l] = self.0[l] $op o.0[l];
                }
                out
            }
        }
        impl std::ops::$trait<f64> for Lanes {
            type Output = Lanes;
            #[inline(always)]
            fn $method(self, o: f64) -> Lanes {
                self.map(|v| v $op o)
            }
        }
        impl std::ops::$trait<Lanes> for f64 {
            type Output = Lanes;
            #[inline(always)]
            fn $method(self, o: Lanes) -> Lanes {
                o.map(|v| self $op v)
            }
        }
        impl std::ops::$assign for Lanes {
            #[inline(always)]
            fn $assign_method(&mut self, o: Lanes) {
                *self = *self $op o;
            }
        }
    };
}
lane_op!(Add, add, AddAssign, add_assign, +);
lane_op!(Sub, sub, SubAssign, sub_assign, -);
lane_op!(Mul, mul, MulAssign, mul_assign, *);
lane_op!(Div, div, DivAssign, div_assign, /);

/// The instruction set a batched kernel is compiled for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Isa {
    Avx512,
    Avx2Fma,
    /// The target's baseline (SSE2 on x86-64).
    Baseline,
}

impl Isa {
    /// The best instruction set this processor has.
    pub fn detect() -> Isa {
        #[cfg(target_arch = "x86_64")]
        {
            if is_x86_feature_detected!("avx512f")
                && is_x86_feature_detected!("avx512dq")
                && is_x86_feature_detected!("avx512vl")
                && is_x86_feature_detected!("fma")
            {
                return Isa::Avx512;
            }
            if is_x86_feature_detected!("avx2") && is_x86_feature_detected!("fma") {
                return Isa::Avx2Fma;
            }
        }
        Isa::Baseline
    }

    pub fn name(self) -> &'static str {
        match self {
            Isa::Avx512 => "avx512",
            Isa::Avx2Fma => "avx2+fma",
            Isa::Baseline => "baseline",
        }
    }
}

/// A computation to run compiled for an instruction set: its `run` must be
/// `#[inline(always)]` (and what it calls, down to the lane loops), so that it is compiled
/// inside [`dispatch`]'s `#[target_feature]` functions. (A closure would not do: LLVM may
/// leave it out of line, compiled for the baseline.)
pub trait Kernel {
    type Output;
    fn run(self) -> Self::Output;
}

/// Runs `kernel` compiled for `isa`. `isa` must come from [`Isa::detect`] on this processor
/// (or be [`Isa::Baseline`]).
#[inline]
pub fn dispatch<K: Kernel>(isa: Isa, kernel: K) -> K::Output {
    match isa {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::detect` found these features on this processor.
        Isa::Avx512 => unsafe { avx512(kernel) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above.
        Isa::Avx2Fma => unsafe { avx2(kernel) },
        _ => kernel.run(),
    }
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
unsafe fn avx512<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2,fma")]
unsafe fn avx2<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

/// Runs `kernel` out of line, compiled for `isa`: one copy per instruction set and kernel
/// type however many element kernels call it, for a computation too large to inline into
/// each (the rate laws' Newton solve: inlined into every formulation's kernel on every
/// instruction set it made the solver crate's release build 229 s instead of 143 s, measured
/// 2026-11-29). `isa` must come from [`Isa::detect`] on this processor (or be
/// [`Isa::Baseline`]); the bits are those of [`dispatch`] (the same operations).
#[inline(always)]
pub fn dispatch_out_of_line<K: Kernel>(isa: Isa, kernel: K) -> K::Output {
    match isa {
        #[cfg(target_arch = "x86_64")]
        // SAFETY: `Isa::detect` found these features on this processor.
        Isa::Avx512 => unsafe { avx512_out_of_line(kernel) },
        #[cfg(target_arch = "x86_64")]
        // SAFETY: as above.
        Isa::Avx2Fma => unsafe { avx2_out_of_line(kernel) },
        _ => baseline_out_of_line(kernel),
    }
}

#[cfg(target_arch = "x86_64")]
#[inline(never)]
#[target_feature(enable = "avx512f,avx512dq,avx512vl,avx2,fma")]
unsafe fn avx512_out_of_line<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

#[cfg(target_arch = "x86_64")]
#[inline(never)]
#[target_feature(enable = "avx2,fma")]
unsafe fn avx2_out_of_line<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

#[inline(never)]
fn baseline_out_of_line<K: Kernel>(kernel: K) -> K::Output {
    kernel.run()
}

/// How the element kernels run: the scalar reference, one element at a time, or in batches
/// of [`LANES`] elements on an instruction set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum KernelPath {
    Scalar,
    Batched(Isa),
}

impl KernelPath {
    /// Batched on the best instruction set of this processor.
    pub fn fastest() -> KernelPath {
        KernelPath::Batched(Isa::detect())
    }

    /// The instruction set the path's kernels are compiled for (the scalar path: baseline).
    pub fn isa(self) -> Isa {
        match self {
            KernelPath::Scalar => Isa::Baseline,
            KernelPath::Batched(isa) => isa,
        }
    }

    pub fn name(self) -> String {
        match self {
            KernelPath::Scalar => "scalar".into(),
            KernelPath::Batched(isa) => format!("batched-{}", isa.name()),
        }
    }
}
