//! Wider vector instructions for the assembler's element loops, chosen when the program runs.
//!
//! The build targets the x86-64 baseline (SSE2), so that one binary runs on any x86-64
//! machine. The element loops of the assembly (a tangent's `B × B` blocks of outer products,
//! the force rows of a Taylor sweep) are short fixed-length loops that LLVM vectorises over
//! 4 lanes with AVX2. [`wide`] runs a piece of work compiled for AVX2 when the processor has
//! it (detected once, then a cached flag), and as built otherwise.
//!
//! **Same bits either way.** Rust never contracts `a * b + c` into a fused multiply-add nor
//! reorders floating-point sums on its own (no fast-math), and FMA is not enabled here: the
//! wider code performs the same IEEE operations in the same order per entry, only several
//! entries at a time, so results do not depend on the machine (checked by the assembly's
//! unit tests and the bit-identical paths in `docs/benchmarks.md`).

/// Whether this processor has AVX2 (detected once; `false` off x86-64).
#[inline]
pub(crate) fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    {
        std::arch::is_x86_feature_detected!("avx2")
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        false
    }
}
