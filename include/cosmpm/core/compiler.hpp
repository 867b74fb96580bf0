#pragma once
// Compiler hints for the particle loops, empty where the compiler has no equivalent.
//
// COSMPM_UNROLL: the stencil loops have compile-time trip counts of at most 16; unrolled,
// every index is a constant and the per-axis factors stay in registers.
// COSMPM_ALWAYS_INLINE: per-particle helpers that must not become calls.
// COSMPM_INLINE_LAMBDA: a per-particle lambda inlined into its loop, so the loop keeps the
// captured array addresses in registers instead of reloading them for every particle.
#if defined(__clang__)
#define COSMPM_UNROLL _Pragma("clang loop unroll(full)")
#elif defined(__GNUC__)
#define COSMPM_UNROLL _Pragma("GCC unroll 16")
#else
#define COSMPM_UNROLL
#endif

#if defined(__GNUC__)
#define COSMPM_ALWAYS_INLINE [[gnu::always_inline]] inline
#define COSMPM_INLINE_LAMBDA __attribute__((always_inline))
#else
#define COSMPM_ALWAYS_INLINE inline
#define COSMPM_INLINE_LAMBDA
#endif
