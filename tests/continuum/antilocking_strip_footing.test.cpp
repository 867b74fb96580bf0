// antilocking::FBar verified against an analytic collapse load: a rigid smooth strip footing on
// a weightless Tresca layer (nu = 0.49) collapses at Prandtl's (2 + pi) c. On the coarse mesh of
// this test (4 cells per footing half-width, the set-up of example 05 on a smaller box) the
// plain continuum locks: linear shape functions and 2 x 2 particles per cell cannot follow the
// nearly isochoric flow, and the footing pressure keeps well above the collapse load. With F-bar
// it levels off near it. The convergence under refinement (within 5 % at 8 and 16 cells per
// half-width) is example 05's: docs/verification/strip_footing.md.
#include <doctest/doctest.h>

#include "../../examples/05_strip_footing/footing.hpp"

namespace {

// Example 05's case on the coarsest mesh, in a box of 2 B x 1 B (the Prandtl mechanism reaches
// 1.5 B from the axis and 0.71 B deep), pushed to 0.06 B (the plateau starts near 0.025 B) at
// twice the example's velocity, for the sanitizer build's sake (halving it there moved the
// limit pressure by 1 %).
strip_footing::Case coarse_case() {
  strip_footing::Case c;
  c.cells_per_half_width = 4;
  c.half_domain = 2.0;
  c.depth = 1.0;
  c.settlement = 0.06;
  c.velocity = 0.02;
  return c;
}

}  // namespace

TEST_CASE(
    "antilocking: a strip footing on Tresca locks without F-bar and collapses near (2 + pi) c "
    "with it") {
  const strip_footing::Case c = coarse_case();
  const auto plain = strip_footing::run<cosmpm::antilocking::None>(c);
  const auto fbar = strip_footing::run<cosmpm::antilocking::FBar>(c);
  // The limit pressure: the mean over the plateau, settlements of 0.03 to 0.06 B (16 samples).
  const double q_plain = strip_footing::mean_pressure(plain.curve, 0.03, 0.06);
  const double q_fbar = strip_footing::mean_pressure(fbar.curve, 0.03, 0.06);
  const double prandtl = strip_footing::prandtl_factor;
  CAPTURE(q_plain);
  CAPTURE(q_fbar);
  // Measured on this set-up (example 05 with --meshes 4 --half-domain 2 --depth 1
  // --settlement 0.06 --velocity 0.02 --limit-from 0.03): F-bar +18.7 %, and +16.4 to +23.0 %
  // with FLIP 0.99 or 0.5, 3 x 3 particles per cell, without the start-of-step correction or
  // the gap check, or a rough footing (+15.8 to +21.9 % at half the velocity). That excess is
  // the coarse mesh's (the footing's edge smeared over a cell a quarter of b wide; it falls to
  // +4 % at 8 cells per half-width, docs/verification/strip_footing.md): X = 30 %. Below, no
  // more than the finest meshes' 6 % under the load (an F-bar that over-relaxes).
  CHECK(q_fbar > 0.95 * prandtl);
  CHECK(q_fbar < 1.30 * prandtl);
  // Without anti-locking: +96.5 % here, +49.6 to +142 % in the same variants (the least with
  // FLIP 0.99, after a cell-crossing release; +90 % at half the velocity): Y = 40 %.
  CHECK(q_plain > 1.40 * prandtl);
  // The load from the particles' stresses (footing.hpp, Sample::stress_pressure) against the
  // contact force: the same load measured two independent ways. They differ by where the
  // contact nodes are, on grid rows up to a cell from the footing's base: at most h / depth =
  // 12.5 % here (measured 8 %, 5 to 10 % in the variants above).
  double stress_sum = 0.0, contact_sum = 0.0;
  for (const auto* run : {&plain, &fbar}) {
    for (const auto& s : run->curve) {
      if (s.settlement < 0.03) continue;
      stress_sum += s.stress_pressure;
      contact_sum += s.pressure;
    }
  }
  CHECK(stress_sum == doctest::Approx(contact_sum).epsilon(0.125));
}
