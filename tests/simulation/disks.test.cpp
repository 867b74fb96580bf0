// Two elastic disks colliding (Sulsky, Zhou and Schreyer 1995, Sect. 5.1): unit square,
// radius 0.2, centres (0.25, 0.25) and (0.75, 0.75), velocities +-(0.1, 0.1), E = 1000 Pa,
// nu = 0.3, rho = 1000 kg/m^3. Single-field MPM: they touch, stick while compressed, and
// rebound; total energy is conserved up to the scheme's dissipation.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;

template <class Scheme>
struct Disks {
  using Sim = Simulation<2, shape::Linear, test::ElasticContinuum, contact::SingleField, Scheme>;
  Sim sim;
  Index second_body_first = 0;

  explicit Disks(int threads, Index cells = 20)
      : sim(grid::Grid<2>(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {cells, cells}),
            test::Elastic(1000.0, 0.3), make_parameters(threads)) {
    const auto& g = sim.grid();
    const auto lower = particles::seed_disk(g, Vec<2>(0.25, 0.25), 0.2, 2);
    const auto upper = particles::seed_disk(g, Vec<2>(0.75, 0.75), 0.2, 2);
    sim.add_particles(lower.positions, lower.volume, 1000.0, lower.half_width, 0);
    second_body_first =
        sim.add_particles(upper.positions, upper.volume, 1000.0, upper.half_width, 1);
    auto& v = sim.particles().template get<particles::field::Velocity<2>>();
    for (Index p = 0; p < sim.particles().size(); ++p) {
      v[p] = p < second_body_first ? Vec<2>(0.1, 0.1) : Vec<2>(-0.1, -0.1);
    }
  }
  static SimulationParameters<2> make_parameters(int threads) {
    SimulationParameters<2> parameters;
    parameters.time_step = 1e-3;  // Sulsky et al.'s step
    parameters.threads = threads;
    return parameters;
  }
  double lower_disk_velocity() const {
    const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
    const auto& m = sim.particles().template get<particles::field::Mass>();
    double momentum = 0.0, mass = 0.0;
    for (Index p = 0; p < second_body_first; ++p) {
      momentum += m[p] * v[p][0];
      mass += m[p];
    }
    return momentum / mass;
  }
};
}  // namespace

TEST_CASE("two elastic disks collide and rebound with energy bounded") {
  Disks<integrator::USL> disks(1);
  const double dt = disks.sim.time_step();
  const double energy0 = test::kinetic_energy(disks.sim);
  double min_energy = energy0, max_energy = energy0;
  double min_velocity = 0.1;
  const int steps = static_cast<int>(std::round(3.5 / dt));
  for (int i = 0; i < steps; ++i) {
    disks.sim.step(dt);
    const double energy = test::kinetic_energy(disks.sim) + test::strain_energy(disks.sim);
    min_energy = std::min(min_energy, energy);
    max_energy = std::max(max_energy, energy);
    min_velocity = std::min(min_velocity, disks.lower_disk_velocity());
  }
  const double final_velocity = disks.lower_disk_velocity();
  MESSAGE("lower disk x-velocity after 3.5 s: " << final_velocity << " (min " << min_velocity
                                                << "); energy range [" << min_energy / energy0
                                                << ", " << max_energy / energy0 << "] of E0");
  // Rebound: the lower disk moves back (Sulsky et al. Fig. 6 shows a near-elastic bounce).
  CHECK(final_velocity < -0.05);
  // Energy bound: the paper's energy plot stays within a few % of E0; we accept 10 %.
  CHECK(min_energy >= 0.90 * energy0);
  CHECK(max_energy <= 1.02 * energy0);
}

TEST_CASE("results do not depend on the thread count (bit for bit)") {
  // 64 x 64 cells: about 4,100 particles and 4,225 nodes, above cosmpm::parallel_threshold,
  // so the two-thread run really runs its loops on two threads.
  Disks<integrator::USL> one(1, 64);
  Disks<integrator::USL> two(2, 64);
  REQUIRE(one.sim.particles().size() >= cosmpm::parallel_threshold);
  const double dt = one.sim.time_step();
  for (int i = 0; i < 1300; ++i) {  // past first contact at about 1.1 s
    one.sim.step(dt);
    two.sim.step(dt);
  }
  const auto& x1 = one.sim.particles().template get<particles::field::Position<2>>();
  const auto& x2 = two.sim.particles().template get<particles::field::Position<2>>();
  const auto& s1 = one.sim.particles().template get<particles::field::Stress<test::Elastic>>();
  const auto& s2 = two.sim.particles().template get<particles::field::Stress<test::Elastic>>();
  bool identical = true;
  double largest_stress = 0.0;
  for (Index p = 0; p < one.sim.particles().size(); ++p) {
    identical = identical && x1[p] == x2[p] && s1[p] == s2[p];
    largest_stress = std::max(largest_stress, s1[p].cwiseAbs().maxCoeff());
  }
#if defined(_OPENMP)
  CHECK(two.sim.threads() == 2);
  CHECK(two.sim.last_team_size() == 2);  // the parallel path ran
#endif
  CHECK(largest_stress > 1.0);  // the disks have met: the comparison covers stressed states
  CHECK(identical);
}
