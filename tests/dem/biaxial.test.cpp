// The servo-controlled biaxial test on small samples (400 grains, 15 % axial strain): the
// side walls hold the confining stress while the platens shear the sample, and the friction
// angles respond to the micro-parameters as granular physics says they must:
//  - frictionless disks still have a small critical-state angle (geometric interlocking only:
//    sin(phi) about 0.1 in 2D, i.e. about 6 deg; we accept 3-10 deg for 400 grains);
//  - interparticle friction raises it, and elongated clumps (which cannot roll freely)
//    raise it further at the same friction;
//  - a peak at or above the critical-state value;
//  - compacted frictionless, the grains pack denser and keep their critical state.
// The full-size test of the corn grains (2,000 clumps, 20 % strain) is the example's
// `--experiment biaxial` (docs/validation.md).
#include <doctest/doctest.h>

#include <cmath>
#include <optional>
#include <string>

#include "cosmpm/dem/biaxial.hpp"

namespace {
using namespace cosmpm;

dem::BiaxialResult test(double friction, bool clumps, bool compact_frictionless = false) {
  dem::Grains grains;
  if (clumps) grains.shape = dem::ClumpShape::two_disks(1.0, 0.6);
  grains.min_size = 0.008;
  grains.max_size = 0.012;
  dem::BiaxialSettings s;
  s.particles = 400;
  s.axial_strain = 0.15;
  // Local damping resists every motion with alpha |F|: while the sample flows it adds a
  // rate-dependent strength (frictionless disks: 19 deg at alpha = 0.7 and 1/s, 8 deg at 0.1/s).
  // A light damping at a moderate rate keeps the test short and the angles quasi-static.
  s.local_damping = 0.2;
  s.strain_rate = 0.5;
  s.critical_from = 0.6;
  const dem::LinearSpring law(
      {.normal_stiffness = 420e3, .shear_stiffness = 420e3, .friction = friction});
  const dem::LinearSpring frictionless(
      {.normal_stiffness = 420e3, .shear_stiffness = 420e3, .friction = 0.0});
  const dem::BiaxialResult r = dem::biaxial_test(
      law, grains, s, {}, compact_frictionless ? std::optional(frictionless) : std::nullopt);
  const std::string grains_name =
      std::string(clumps ? "clumps" : "disks") + (compact_frictionless ? " packed at 0" : "");
  MESSAGE(grains_name << ", mu = " << friction << ": porosity " << r.porosity << ", peak "
                      << r.peak_angle_deg << " deg at " << r.peak_strain << ", critical state "
                      << r.critical_angle_deg << " deg, dilatancy " << r.critical_dilatancy);
  CHECK(r.compacted);
  // The side walls keep s3 within 5 % of the target once shearing is under way.
  for (const auto& p : r.curve) {
    if (p.axial_strain > 0.01) CHECK(p.sigma3 == doctest::Approx(s.confining_stress).epsilon(0.05));
  }
  CHECK(r.peak_angle_deg >= r.critical_angle_deg);
  return r;
}

}  // namespace

TEST_CASE("biaxial: friction angles grow with particle friction and elongation") {
  const auto smooth = test(0.0, false);
  const auto rough = test(0.5, false);
  const auto corn = test(0.1, true);
  CHECK(smooth.critical_angle_deg > 3.0);
  CHECK(smooth.critical_angle_deg < 10.0);
  CHECK(rough.critical_angle_deg > smooth.critical_angle_deg + 5.0);
  CHECK(corn.critical_angle_deg > test(0.1, false).critical_angle_deg);
  // Compacted frictionless (PFC's way to a dense sample, the rig's calibrated packing), the same
  // grains pack denser; the critical state belongs to the grains, not to the packing.
  const auto dense = test(0.1, true, true);
  CHECK(dense.porosity < corn.porosity - 0.01);
  CHECK(dense.critical_angle_deg == doctest::Approx(corn.critical_angle_deg).epsilon(0.15));
}
