// Two equal disks colliding head-on in their centre-of-mass frame (no gravity). The relative
// motion is a mass m/2 on the contact spring k = k_p / 2 (PFC's series stiffness), so:
//  - without damping the disks separate with the speed they met with (energy conserved);
//  - with viscous damping of ratio beta (total normal force allowed to pull) the coefficient
//    of restitution is e = exp(-pi beta / sqrt(1 - beta^2)), the damped oscillator's decay
//    over half a period; keeping the force >= 0 removes less energy, so e is larger;
//  - with local damping alpha the force is (1 + alpha) k delta while approaching and
//    (1 - alpha) k delta while separating: e = sqrt((1 - alpha) / (1 + alpha)).
// Central differences with a force switched on between steps converge to these at second
// order in omega dt: the runs use omega dt = 0.003 (1000 steps per contact), where that error
// is about 1e-5, so the tolerances are set by the formulas, not by the integrator.
#include <doctest/doctest.h>

#include <cmath>

#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

constexpr double radius = 0.005;
constexpr double density = 855.0;    // Table 1
constexpr double stiffness = 420e3;  // Table 1, per particle
constexpr double speed = 0.1;        // m/s of each disk towards the other

const double mass = density * pi * radius * radius;
const double contact_frequency = std::sqrt(0.5 * stiffness / (0.5 * mass));  // omega, rad/s

struct Collision {
  double restitution = 0.0;
  double energy_ratio = 0.0;    // kinetic energy after / before
  double momentum_after = 0.0;  // total x momentum after (0 before)
  double max_overlap = 0.0;
};

template <class Damping>
Collision collide(const dem::LinearSpring& law, const Damping& damping, double omega_dt) {
  dem::Assembly a;
  a.add_disk(Vec<2>(-radius - 1e-4, 0.0), radius, density, Vec<2>(speed, 0.0));
  a.add_disk(Vec<2>(radius + 1e-4, 0.0), radius, density, Vec<2>(-speed, 0.0));
  dem::Parameters parameters;
  parameters.gravity = Vec<2>::Zero();
  dem::Simulation<dem::LinearSpring, Damping> sim(std::move(a), law, damping, parameters);
  const double dt = omega_dt / contact_frequency;
  REQUIRE(dt < sim.critical_time_step());
  const double before = sim.kinetic_energy();
  Collision c;
  // Until the disks have separated again (the gap closes in 1e-3 s, contact lasts ~1.3 ms).
  while (sim.time() < 0.01) {
    sim.step(dt);
    sim.for_each_pair_contact(
        [&](const auto& contact) { c.max_overlap = std::max(c.max_overlap, contact.overlap); });
  }
  const dem::Assembly& s = sim.assembly();
  c.restitution = (s.velocity(1)[0] - s.velocity(0)[0]) / (2.0 * speed);
  c.energy_ratio = sim.kinetic_energy() / before;
  c.momentum_after = s.mass(0) * s.velocity(0)[0] + s.mass(1) * s.velocity(1)[0];
  return c;
}

}  // namespace

TEST_CASE("head-on collision without damping: speed and energy come back") {
  const Collision c = collide(dem::LinearSpring(), dem::NoLocalDamping(), 0.003);
  // The largest overlap of an undamped spring: v_rel / omega = 0.2 / 2500 = 80 um.
  CHECK(c.max_overlap == doctest::Approx(2 * speed / contact_frequency).epsilon(1e-3));
  CHECK(c.restitution == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(c.energy_ratio == doctest::Approx(1.0).epsilon(1e-5));
  CHECK(std::abs(c.momentum_after) < 1e-15);
}

TEST_CASE("head-on collision: the energy error shrinks at second order in the step") {
  // Halving omega dt from 0.1 to 0.05 divides |1 - e^2| by about 4 (central differences).
  const double coarse =
      std::abs(1.0 - collide(dem::LinearSpring(), dem::NoLocalDamping(), 0.1).energy_ratio);
  const double fine =
      std::abs(1.0 - collide(dem::LinearSpring(), dem::NoLocalDamping(), 0.05).energy_ratio);
  MESSAGE("energy error at omega dt = 0.1: " << coarse << ", at 0.05: " << fine);
  CHECK(coarse < 0.01);  // bounded by (omega dt)^2
  CHECK(fine < 0.0025);  // (omega dt)^2 again
  CHECK(fine < coarse);
}

TEST_CASE("head-on collision: viscous damping gives e = exp(-pi beta / sqrt(1 - beta^2))") {
  for (const double beta : {0.05, 0.2, 0.5}) {
    const double expected = std::exp(-pi * beta / std::sqrt(1.0 - beta * beta));
    const dem::LinearSpring pulling(
        {}, {.normal_ratio = beta, .shear_ratio = 0.0, .no_tension = false});
    const Collision c = collide(pulling, dem::NoLocalDamping(), 0.003);
    CAPTURE(beta);
    CHECK(c.restitution == doctest::Approx(expected).epsilon(2e-3));
    CHECK(std::abs(c.momentum_after) < 1e-15);
    const dem::LinearSpring pushing({},
                                    {.normal_ratio = beta, .shear_ratio = 0.0, .no_tension = true});
    CHECK(collide(pushing, dem::NoLocalDamping(), 0.003).restitution > expected);
  }
}

TEST_CASE("head-on collision: local damping gives e = sqrt((1 - alpha) / (1 + alpha))") {
  for (const double alpha : {0.3, 0.7}) {
    const double expected = std::sqrt((1.0 - alpha) / (1.0 + alpha));  // 0.734, 0.420
    const Collision c = collide(dem::LinearSpring(), dem::LocalDamping(alpha), 0.003);
    CAPTURE(alpha);
    CHECK(c.restitution == doctest::Approx(expected).epsilon(2e-3));
  }
}
