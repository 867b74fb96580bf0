// antilocking::FBar against a hand calculation: after one USL step, each particle's velocity
// gradient differs from the plain continuum's by (div_c - tr L_p) / 2 I, div_c the
// volume-weighted mean of tr L over the particles of its cell, and its stress by the elastic
// response to that shift. A point whose grains have come apart (Mohr-Coulomb with
// separation) neither enters its cell's mean nor takes it.
#include <doctest/doctest.h>

#include <cmath>
#include <map>
#include <vector>

#include "../simulation/verification_helpers.hpp"
#include "cosmpm/continuum/antilocking.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"

namespace {
using namespace cosmpm;
using Plain = continuum::Classical<test::Elastic>;
using Averaged = continuum::Classical<test::Elastic, antilocking::FBar>;

template <class Continuum, class Model = test::Elastic>
auto sheared_block(const Model& model = test::Elastic(1e6, 0.3)) {
  using Sim = Simulation<2, shape::Linear, Continuum, contact::SingleField, integrator::USL>;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(0.4, 0.4), {8, 8});
  SimulationParameters<2> parameters;
  parameters.threads = 1;
  Sim sim(grid, model, parameters);
  const auto seeding = particles::seed_box(grid, Vec<2>(0.1, 0.1), Vec<2>(0.3, 0.3), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1000.0, seeding.half_width);
  // A velocity field with varying dilation and shear inside every cell.
  auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  const auto& x = sim.particles().template get<particles::field::Position<2>>();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    v[p] = Vec<2>(std::sin(17.0 * x[p][0]) + 0.3 * x[p][1], std::cos(23.0 * x[p][1] * x[p][0]));
  }
  return sim;
}

// Each counted particle's F-bar shift by hand, (div_c - tr L_p) / 2, div_c the volume-weighted
// mean of tr L over the counted particles of its start-of-step cell (0.05 m); 0 if not counted.
template <class Positions, class Volumes, class Gradients, class Counted>
std::vector<double> expected_shifts(const Positions& x0, const Volumes& volume0, const Gradients& L,
                                    Counted counted) {
  const auto cell_of = [&](Index p) {
    return std::pair<Index, Index>(static_cast<Index>(x0[p][0] / 0.05),
                                   static_cast<Index>(x0[p][1] / 0.05));
  };
  const auto count = static_cast<Index>(x0.size());
  std::map<std::pair<Index, Index>, std::pair<double, double>> cells;  // volume, volume div v
  for (Index p = 0; p < count; ++p) {
    if (!counted(p)) continue;
    auto& c = cells[cell_of(p)];
    c.first += volume0[p];
    c.second += volume0[p] * L[p].trace();
  }
  std::vector<double> shifts(x0.size(), 0.0);
  for (Index p = 0; p < count; ++p) {
    if (!counted(p)) continue;
    const auto& c = cells[cell_of(p)];
    shifts[static_cast<std::size_t>(p)] = (c.second / c.first - L[p].trace()) / 2.0;
  }
  return shifts;
}
}  // namespace

TEST_CASE("antilocking: F-bar shifts each particle's volumetric rate to its cell's mean") {
  auto plain = sheared_block<Plain>();
  auto averaged = sheared_block<Averaged>();
  const double dt = plain.time_step();
  // Start-of-step cells and volumes, the weights of the mean.
  const auto x0 = plain.particles().get<particles::field::Position<2>>();
  const auto volume0 = plain.particles().get<particles::field::Volume>();
  plain.step(dt);
  averaged.step(dt);
  const auto& L = plain.particles().get<particles::field::VelocityGradient<2>>();
  const auto& L_bar = averaged.particles().get<particles::field::VelocityGradient<2>>();
  const auto& s = plain.particles().get<particles::field::Stress<test::Elastic>>();
  const auto& s_bar = averaged.particles().get<particles::field::Stress<test::Elastic>>();
  const auto shifts = expected_shifts(x0, volume0, L, [](Index) { return true; });
  const test::Elastic model(1e6, 0.3);
  double largest_shift = 0.0;
  for (Index p = 0; p < plain.particles().size(); ++p) {
    CAPTURE(p);
    const double shift = shifts[static_cast<std::size_t>(p)];
    largest_shift = std::max(largest_shift, std::abs(shift));
    const Mat<2> expected = L[p] + shift * Mat<2>::Identity();
    CHECK((L_bar[p] - expected).cwiseAbs().maxCoeff() <= 1e-12 * L[p].cwiseAbs().maxCoeff());
    // The stress differs by the elastic response to the strain shift dt shift (xx, yy):
    // lambda 2 dt shift on xx, yy, zz and 2 G dt shift on xx, yy.
    const double de = dt * shift;
    const double lambda = model.lame_lambda(), shear = model.shear_modulus();
    const Vec<4> difference = s_bar[p] - s[p];
    const double scale = 1e-9 * (s[p].cwiseAbs().maxCoeff() + 1.0);
    CHECK(difference[0] ==
          doctest::Approx(2 * lambda * de + 2 * shear * de).epsilon(1e-6).scale(scale));
    CHECK(difference[1] ==
          doctest::Approx(2 * lambda * de + 2 * shear * de).epsilon(1e-6).scale(scale));
    CHECK(difference[2] == doctest::Approx(2 * lambda * de).epsilon(1e-6).scale(scale));
  }
  CHECK(largest_shift > 0.1);  // 1/s: the field's dilation varies within cells
}

TEST_CASE("antilocking: F-bar leaves out the points whose grains have come apart") {
  using Model = material::MohrCoulomb<>;
  const Model model({.youngs_modulus = 1e6,
                     .poisson_ratio = 0.3,
                     .friction_angle_deg = 30,
                     .dilatancy_angle_deg = 0,
                     .separation = true});
  auto plain = sheared_block<continuum::Classical<Model>>(model);
  auto averaged = sheared_block<continuum::Classical<Model, antilocking::FBar>>(model);
  // Every third point apart by a gap no single step can close.
  const auto apart = [](Index p) { return p % 3 == 0; };
  const auto set_gaps = [&](auto& sim) {
    auto& state = sim.particles().template get<particles::field::MaterialState<Model>>();
    for (Index p = 0; p < sim.particles().size(); ++p) state[p].separation = apart(p) ? 1.0 : 0.0;
  };
  set_gaps(plain);
  set_gaps(averaged);
  const double dt = plain.time_step();
  const auto x0 = plain.particles().get<particles::field::Position<2>>();
  const auto volume0 = plain.particles().get<particles::field::Volume>();
  plain.step(dt);
  averaged.step(dt);
  const auto& L = plain.particles().get<particles::field::VelocityGradient<2>>();
  const auto& L_bar = averaged.particles().get<particles::field::VelocityGradient<2>>();
  const auto shifts = expected_shifts(x0, volume0, L, [&](Index p) { return !apart(p); });
  int shifted = 0;
  for (Index p = 0; p < plain.particles().size(); ++p) {
    CAPTURE(p);
    const double tolerance = 1e-12 * L[p].cwiseAbs().maxCoeff();
    if (apart(p)) {
      CHECK((L_bar[p] - L[p]).cwiseAbs().maxCoeff() <= tolerance);  // its own rate
      continue;
    }
    const double shift = shifts[static_cast<std::size_t>(p)];
    shifted += std::abs(shift) > 0.1 ? 1 : 0;
    const Mat<2> expected = L[p] + shift * Mat<2>::Identity();
    CHECK((L_bar[p] - expected).cwiseAbs().maxCoeff() <= tolerance);
  }
  CHECK(shifted > 10);  // the packed points' rates did move to their cells' means
}
