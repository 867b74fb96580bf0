// Rolling resistance (Ai et al. 2011, model C) on a disk on a slope, no damping, friction
// mu = 0.5 (enough to roll without slipping up to tan(theta) = 1.5): with rolling coefficient
// mu_r the disk stays put while tan(theta) < mu_r and otherwise rolls down at
//   a = g (sin(theta) - mu_r cos(theta)) / (1 + I / (m r^2)) = 2/3 g (sin - mu_r cos).
// And in a biaxial test rolling resistance raises the friction angle of a disk packing.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cosmpm/dem/biaxial.hpp"
#include "cosmpm/dem/rolling_resistance.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;
using Rolling = dem::RollingResistance<dem::LinearSpring>;

constexpr double g = 9.81;

struct Roll {
  double acceleration = 0.0;
  double displacement = 0.0;
};

Roll roll(double theta_deg, double mu_r) {
  const double theta = degrees_to_radians(theta_deg);
  const Vec<2> normal(-std::sin(theta), std::cos(theta));
  const Vec<2> downhill(-std::cos(theta), -std::sin(theta));
  const double r = 0.004, k = 420e3;
  dem::Assembly a;
  const double overlap = 855.0 * pi * r * r * g * std::cos(theta) / (0.5 * k);
  a.add_disk((r - overlap) * normal, r, 855.0);
  const dem::LinearSpringMaterial grain{k, k, 0.5};
  dem::Simulation<Rolling, dem::NoLocalDamping> sim(
      std::move(a), Rolling(dem::LinearSpring(grain), mu_r), dem::NoLocalDamping());
  sim.add_plane_wall("slope", Vec<2>::Zero(), normal, grain);
  const double dt = 0.2 * sim.critical_time_step();
  const Vec<2> x0 = sim.assembly().position(0);
  double st = 0, sv = 0, stt = 0, stv = 0, n = 0;
  while (sim.time() < 0.4) {
    sim.step(dt);
    if (sim.time() < 0.05) continue;
    const double t = sim.time(), v = sim.assembly().velocity(0).dot(downhill);
    st += t;
    sv += v;
    stt += t * t;
    stv += t * v;
    n += 1;
  }
  return {(n * stv - st * sv) / (n * stt - st * st),
          (sim.assembly().position(0) - x0).dot(downhill)};
}

}  // namespace

TEST_CASE("rolling resistance: a disk rests below tan(theta) = mu_r and rolls above it") {
  const double mu_r = 0.3;
  const Roll rest = roll(15.0, mu_r);
  // Held by the rolling spring: it turns at most mu_r r F_n / k_r = 1 / (2.25 mu_r k_n r) x
  // F_n, a few micrometres of travel, where free rolling would cover 0.5 a t^2 = 68 mm.
  CHECK(std::abs(rest.displacement) < 1e-4);
  const Roll down = roll(25.0, mu_r);
  const double t = degrees_to_radians(25.0);
  CHECK(down.acceleration ==
        doctest::Approx(2.0 / 3.0 * g * (std::sin(t) - mu_r * std::cos(t))).epsilon(5e-3));
  // Without it the disk rolls at 2/3 g sin(theta) even at 15 deg.
  CHECK(roll(15.0, 0.0).acceleration ==
        doctest::Approx(2.0 / 3.0 * g * std::sin(degrees_to_radians(15.0))).epsilon(5e-3));
}

TEST_CASE("set_law: a disk held by rolling resistance rolls once the law has none") {
  // Simulation::set_law replaces the law between steps (packing with one law, shearing with
  // another): at 15 deg and mu_r = 0.3 the disk rests; with mu_r = 0 it rolls at 2/3 g sin.
  const double theta = degrees_to_radians(15.0), r = 0.004, k = 420e3;
  const Vec<2> normal(-std::sin(theta), std::cos(theta));
  const Vec<2> downhill(-std::cos(theta), -std::sin(theta));
  dem::Assembly a;
  const double overlap = 855.0 * pi * r * r * g * std::cos(theta) / (0.5 * k);
  a.add_disk((r - overlap) * normal, r, 855.0);
  const dem::LinearSpringMaterial grain{k, k, 0.5};
  dem::Simulation<Rolling, dem::NoLocalDamping> sim(
      std::move(a), Rolling(dem::LinearSpring(grain), 0.3), dem::NoLocalDamping());
  sim.add_plane_wall("slope", Vec<2>::Zero(), normal, grain);
  const double dt = 0.2 * sim.critical_time_step();
  const Vec<2> x0 = sim.assembly().position(0);
  while (sim.time() < 0.2) sim.step(dt);
  CHECK(std::abs((sim.assembly().position(0) - x0).dot(downhill)) < 1e-4);  // as above
  sim.set_law(Rolling(dem::LinearSpring(grain), 0.0));
  const double t0 = sim.time(), v0 = sim.assembly().velocity(0).dot(downhill);
  while (sim.time() < t0 + 0.3) sim.step(dt);
  const double a_measured = (sim.assembly().velocity(0).dot(downhill) - v0) / (sim.time() - t0);
  // The released rolling spring adds a small oscillation: 1 % on the mean acceleration.
  CHECK(a_measured == doctest::Approx(2.0 / 3.0 * g * std::sin(theta)).epsilon(1e-2));
}

TEST_CASE("rolling resistance: it raises the friction angle of a disk packing") {
  dem::Grains grains;
  grains.min_size = 0.008;
  grains.max_size = 0.012;
  dem::BiaxialSettings s;
  s.particles = 400;
  s.axial_strain = 0.15;
  s.local_damping = 0.2;  // see biaxial.test.cpp
  s.strain_rate = 0.5;
  s.critical_from = 0.6;
  const dem::LinearSpringMaterial grain{420e3, 420e3, 0.3};
  const auto free = dem::biaxial_test(Rolling(dem::LinearSpring(grain), 0.0), grains, s);
  const auto held = dem::biaxial_test(Rolling(dem::LinearSpring(grain), 0.3), grains, s);
  MESSAGE("disks, mu = 0.3: critical state " << free.critical_angle_deg << " deg without, "
                                             << held.critical_angle_deg
                                             << " deg with rolling resistance 0.3");
  CHECK(held.critical_angle_deg > free.critical_angle_deg + 3.0);
}
