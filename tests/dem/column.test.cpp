// A settled column of 750 disks (7-9 mm) between two side walls, width W = 80 mm, height
// H ~ 7 W, rained in and settled under local damping, on a smooth floor.
//  - Smooth side walls (hydrostatic limit): the walls carry nothing vertically, so the floor
//    carries the whole weight, and the wall pressure grows linearly with depth,
//    s_h = K gamma z (gamma: the layer's bulk unit weight).
//  - Rough side walls (Janssen): a slice of the column is held by the wall friction
//    tau = mu s_h with s_h = K s_v, so s_v(z) = gamma L (1 - exp(-z / L)), L = W / (2 mu K)
//    (mu: the wall friction mobilised, at most mu_w; disks roll along the wall):
//    the floor carries less than the weight and the wall pressure saturates with depth instead
//    of growing linearly. K is fitted to the floor load, then the wall pressure profile is
//    predicted and compared with the measured one.
// Stresses are per metre of thickness; the wall pressure is measured over the top and the
// bottom half of the column from the wall contact forces. The tolerances (25 %) reflect a
// column only ten grains wide: the contact forces along a wall fluctuate from grain to grain.
#include <doctest/doctest.h>

#include <array>
#include <cmath>
#include <vector>

#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

constexpr double width = 0.08;
constexpr double g = 9.81;

struct Column {
  double weight = 0.0;               // N/m
  double floor_load = 0.0;           // N/m, vertical
  double height = 0.0;               // m, of the layer (from the solid area and the porosity)
  double unit_weight = 0.0;          // N/m^3, weight / (W H)
  std::array<double, 2> pressure{};  // Pa, mean over the side walls, top and bottom half
  double mobilised = 0.0;            // wall friction mobilised: vertical over normal wall force
};

Column settle_column(double wall_friction) {
  dem::Assembly a;
  dem::Grains grains;
  grains.min_size = 0.007;
  grains.max_size = 0.009;
  dem::rain(a, grains, 750, {0.0, width, 0.01, 2.0}, 21);
  Column c;
  for (Index b = 0; b < a.body_count(); ++b) c.weight += g * a.mass(b);
  dem::Simulation<> sim(
      std::move(a),
      dem::LinearSpring({.normal_stiffness = 420e3, .shear_stiffness = 420e3, .friction = 0.5}),
      // Light local damping: the column falls and compacts three times faster than at PFC's
      // 0.7, and a column at rest carries the same loads whatever damping brought it there.
      dem::LocalDamping(0.3));
  const Index floor = sim.add_plane_wall("floor", Vec<2>(0, 0), Vec<2>(0, 1), {.friction = 0});
  const Index left =
      sim.add_plane_wall("left", Vec<2>(0, 0), Vec<2>(1, 0), {.friction = wall_friction});
  const Index right =
      sim.add_plane_wall("right", Vec<2>(width, 0), Vec<2>(-1, 0), {.friction = wall_friction});
  const double dt = 0.8 * sim.critical_time_step();
  REQUIRE(dem::settle(sim, dt, 4.0, 1e-3, 0.3).settled);
  // Janssen's state: the column sinks a little (as when a silo starts to discharge), which
  // mobilises the wall friction fully. Lowering the floor 1 mm (100 times the shear springs'
  // elastic travel) does it; then it settles again.
  sim.walls().set_velocity(floor, Vec<2>(0.0, -0.01));
  while (sim.walls()[floor].point[1] > -0.001) sim.step(dt);
  sim.walls().set_velocity(floor, Vec<2>::Zero());
  REQUIRE(dem::settle(sim, dt, 2.0, 1e-5, 0.2).settled);
  c.floor_load = -sim.wall_force(floor)[1];
  const double base = sim.walls()[floor].point[1];
  const double n = dem::porosity(sim.assembly(), Vec<2>(0.005, base + 0.02),
                                 Vec<2>(width - 0.005, base + 0.3), 2e-4);
  double solid = 0.0;
  for (const double r : sim.assembly().elements().get<dem::field::Radius>()) solid += pi * r * r;
  c.height = solid / ((1.0 - n) * width);
  c.unit_weight = c.weight / (width * c.height);
  std::array<double, 2> force{};
  sim.for_each_wall_contact([&](const dem::WallContact& w) {
    if (w.wall != left && w.wall != right) return;
    const double depth = base + c.height - w.point[1];
    force[depth < 0.5 * c.height ? 0 : 1] += 0.5 * w.normal_force;  // two walls
  });
  for (std::size_t k = 0; k < 2; ++k) c.pressure[k] = force[k] / (0.5 * c.height);
  // The particles push the left wall towards -x, the right one towards +x, and drag both down.
  const double normal = -sim.wall_force(left)[0] + sim.wall_force(right)[0];
  c.mobilised = -(sim.wall_force(left)[1] + sim.wall_force(right)[1]) / normal;
  MESSAGE("mu_w = " << wall_friction << ": H = " << c.height << " m (" << c.height / width
                    << " W), porosity " << n << ", floor / weight = " << c.floor_load / c.weight
                    << ", mobilised wall friction = " << c.mobilised
                    << ", wall pressure top / bottom half: " << c.pressure[0] << " / "
                    << c.pressure[1] << " Pa");
  return c;
}

}  // namespace

TEST_CASE("column: smooth walls give the hydrostatic limit") {
  const Column c = settle_column(0.0);
  // Nothing holds the column but the floor (to the settling's unbalanced force).
  CHECK(c.floor_load == doctest::Approx(c.weight).epsilon(2e-3));
  // s_h = K gamma z: the halves' mean pressures are K gamma H / 4 and 3 K gamma H / 4.
  const double k = (c.pressure[0] + c.pressure[1]) / (c.unit_weight * c.height);
  MESSAGE("K = s_h / (gamma z) = " << k);
  CHECK(k > 0.2);
  CHECK(k < 1.0);
  CHECK(c.pressure[1] / c.pressure[0] == doctest::Approx(3.0).epsilon(0.25));
}

TEST_CASE("column: rough walls carry part of the weight as Janssen predicts") {
  const double mu_w = 0.4;
  const Column c = settle_column(mu_w);
  CHECK(c.floor_load < 0.7 * c.weight);
  // Disks roll along a wall instead of sliding, so less than mu_w is mobilised; Janssen's
  // coefficient is the mobilised one (the wall's vertical force over its normal force).
  CHECK(c.mobilised <= mu_w);
  CHECK(c.mobilised > 0.1);
  const double mu = c.mobilised;
  // K from the floor load: W gamma L (1 - exp(-H / L)) = floor load, L = W / (2 mu K), by
  // bisection (the load falls as K grows).
  const double gamma = c.unit_weight, h = c.height;
  auto floor_load = [&](double k) {
    const double l = width / (2 * mu * k);
    return width * gamma * l * (1 - std::exp(-h / l));
  };
  double lo = 1e-3, hi = 10.0;
  for (int it = 0; it < 100; ++it) {
    const double mid = 0.5 * (lo + hi);
    (floor_load(mid) > c.floor_load ? lo : hi) = mid;
  }
  const double k = 0.5 * (lo + hi);
  const double l = width / (2 * mu * k);
  // The halves' mean wall pressures: K gamma L (1 - L (exp(-z0/L) - exp(-z1/L)) / (z1 - z0)).
  auto mean = [&](double z0, double z1) {
    return k * gamma * l * (1 - l * (std::exp(-z0 / l) - std::exp(-z1 / l)) / (z1 - z0));
  };
  const double top = mean(0.0, 0.5 * h), bottom = mean(0.5 * h, h);
  MESSAGE("Janssen K = " << k << ", L = " << l << " m; predicted halves " << top << " / " << bottom
                         << " Pa");
  CHECK(k > 0.2);
  CHECK(k < 1.5);
  CHECK(c.pressure[0] == doctest::Approx(top).epsilon(0.25));
  CHECK(c.pressure[1] == doctest::Approx(bottom).epsilon(0.25));
  // Saturating, not linear: well below the hydrostatic 3 : 1.
  CHECK(c.pressure[1] / c.pressure[0] < 2.4);
}
