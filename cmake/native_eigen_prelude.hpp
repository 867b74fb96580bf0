// Force-included (-include) first in every benchmark and example source when COSMPM_NATIVE
// compiles them for the host with GCC. With AVX-512, GCC 12 reports false positives
// inside Eigen's own code even though Eigen is a system include:
// - -Wmaybe-uninitialized, or -Wuninitialized, on `__Y` in _mm256/_mm512_undefined_pd(), the
//   "don't care" operand of intrinsics Eigen's packet reductions, min/max and matrix-product
//   kernels use: https://gcc.gnu.org/bugzilla/show_bug.cgi?id=105593 (fixed in GCC 12.3, 13);
// - -Warray-bounds on 512-bit packet loads of small dynamic-size matrices with a fixed maximum
//   size (FullPivLU of at most 3 x 3, material/detail/multisurface_return.hpp), in branches
//   that only run for sizes of eight and more: https://gcc.gnu.org/bugzilla/show_bug.cgi?id=106247,
//   https://gitlab.com/libeigen/eigen/-/issues/2506.
// GCC checks a pragma at every inlined location of a warning, so Eigen included here, inside
// the pragma, has these warnings off for its own lines only: the same warnings in our code
// stay errors. If another Eigen module starts to fire, include it here too.
#pragma once
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#pragma GCC diagnostic ignored "-Wuninitialized"
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <Eigen/Core>
#include <Eigen/LU>
#pragma GCC diagnostic pop
#endif
