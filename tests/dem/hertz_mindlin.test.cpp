// The Hertz-Mindlin policy: its normal force grows as the overlap to the power 3/2, an
// undamped collision gives the energy back, and the contact lasts as v^(-1/5) (Hertz: the
// duration of an elastic impact scales with the approach speed to the power -1/5).
#include <doctest/doctest.h>

#include <cmath>

#include "cosmpm/dem/hertz_mindlin.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

struct Impact {
  double restitution = 0.0;
  double duration = 0.0;
};

Impact collide(double speed) {
  const double r = 0.005;
  dem::Assembly a;
  a.add_disk(Vec<2>(-r - 1e-5, 0), r, 855.0, Vec<2>(speed, 0));
  a.add_disk(Vec<2>(r + 1e-5, 0), r, 855.0, Vec<2>(-speed, 0));
  dem::Parameters p;
  p.gravity = Vec<2>::Zero();
  const dem::HertzMindlin law({.shear_modulus = 1e7, .poisson_ratio = 0.3, .friction = 0.5});
  dem::Simulation<dem::HertzMindlin, dem::NoLocalDamping> sim(std::move(a), law,
                                                              dem::NoLocalDamping(), p);
  const double dt = 0.01 * sim.critical_time_step();
  Impact impact;
  bool touching = false;
  while (sim.time() < 0.02) {
    sim.step(dt);
    const bool now = sim.active_contacts() > 0;
    if (now) impact.duration += dt;
    if (touching && !now) break;
    touching = now;
  }
  impact.restitution =
      (sim.assembly().velocity(1)[0] - sim.assembly().velocity(0)[0]) / (2 * speed);
  return impact;
}

}  // namespace

TEST_CASE("Hertz-Mindlin: F_n grows as delta^(3/2), k_s as F_n^(1/3)") {
  const dem::HertzMindlin law({.shear_modulus = 1e7, .poisson_ratio = 0.3, .friction = 0.5});
  const auto k = law.pair_constants();
  dem::ContactHistory shear;
  dem::ContactKinematics c;
  c.effective_radius = 0.005;
  c.overlap = 1e-5;
  const double f1 = dem::HertzMindlin::force(k, c, shear, 1e-6).normal;
  c.overlap = 2e-5;
  const double f2 = dem::HertzMindlin::force(k, c, shear, 1e-6).normal;
  CHECK(f2 / f1 == doctest::Approx(std::pow(2.0, 1.5)).epsilon(1e-12));
  // F_n = 2 G sqrt(2 R) / (3 (1 - nu)) delta^(3/2).
  CHECK(f1 == doctest::Approx(2 * 1e7 * std::sqrt(0.01) / (3 * 0.7) * std::pow(1e-5, 1.5)));
  CHECK(dem::HertzMindlin::shear_stiffness(k, 0.005, 8.0) /
            dem::HertzMindlin::shear_stiffness(k, 0.005, 1.0) ==
        doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("Hertz-Mindlin: an undamped impact is elastic and lasts as v^(-1/5)") {
  const Impact slow = collide(0.01);
  const Impact fast = collide(0.32);
  CHECK(slow.restitution == doctest::Approx(1.0).epsilon(1e-3));
  CHECK(fast.restitution == doctest::Approx(1.0).epsilon(1e-3));
  // 32 times faster: 32^(1/5) = 2 times shorter.
  CHECK(slow.duration / fast.duration == doctest::Approx(2.0).epsilon(0.01));
}
