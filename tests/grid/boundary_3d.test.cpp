// Boundary conditions on the six faces of a 3D grid box: fixed, roller and Coulomb-friction
// walls by hand on every face, their application to the nodes of each face (edges and corners
// take every face they lie on), and a block sliding diagonally on a rough floor against the
// rigid-block solution.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/initial/geostatic.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace {
using namespace cosmpm;
using BC = grid::BoundaryConditions<3>;
using grid::BoundaryKind;

Vec<3> applied(BoundaryKind kind, int axis, bool upper, double mu, const Vec<3>& v,
               unsigned* imposed = nullptr) {
  Vec<3> out = v;
  const unsigned components = BC::apply({kind, mu}, axis, upper, out);
  if (imposed != nullptr) *imposed = components;
  return out;
}
}  // namespace

TEST_CASE("3D face conditions by hand on each of the six faces") {
  for (int face = 0; face < BC::face_count; ++face) {
    const int axis = face / 2;
    const bool upper = face % 2 == 1;
    CAPTURE(face);
    const double outward_sign = upper ? 1.0 : -1.0;
    // Tangential velocity (3, 4) in the face's two tangential axes, |v_t| = 5.
    Vec<3> tangential = Vec<3>::Zero();
    const int t1 = (axis + 1) % 3, t2 = (axis + 2) % 3;
    tangential[t1] = 3.0;
    tangential[t2] = 4.0;
    const Vec<3> normal = Vec<3>::Unit(axis) * outward_sign;
    // Approaching the wall at 2 (into the face).
    const Vec<3> v = tangential + 2.0 * normal;
    unsigned imposed = 0;
    CHECK(applied(BoundaryKind::fixed, axis, upper, 0.0, v, &imposed) == Vec<3>::Zero());
    CHECK(imposed == 7u);
    CHECK(applied(BoundaryKind::roller, axis, upper, 0.0, v, &imposed) == tangential);
    CHECK(imposed == (1u << axis));
    CHECK(applied(BoundaryKind::free, axis, upper, 0.0, v, &imposed) == v);
    CHECK(imposed == 0u);
    // Friction mu = 0.5: the removed normal velocity 2 bounds the tangential reduction by 1,
    // along the tangential direction: |v_t| 5 -> 4, (3, 4) -> (2.4, 3.2).
    const Vec<3> slipping = applied(BoundaryKind::friction, axis, upper, 0.5, v, &imposed);
    CHECK((slipping - 0.8 * tangential).norm() < 1e-15);
    // Kinematically it imposes only its normal; the friction is a resistance a rigid body
    // pushing the material along the wall overcomes (RigidContact::conditions_applied).
    CHECK(imposed == (1u << axis));
    // mu = 3: the bound 6 exceeds |v_t| = 5, stuck.
    CHECK(applied(BoundaryKind::friction, axis, upper, 3.0, v) == Vec<3>::Zero());
    // Separating: free.
    const Vec<3> leaving = tangential - 2.0 * normal;
    CHECK(applied(BoundaryKind::friction, axis, upper, 0.5, leaving, &imposed) == leaving);
    CHECK(imposed == 0u);
  }
}

TEST_CASE("3D face conditions reach exactly the nodes of their face, edges and corners") {
  const grid::Grid<3> g(Vec<3>(-0.1, 0.2, 0.0), Vec<3>(0.3, 0.4, 0.5), {3, 4, 5});
  BC conditions;
  // Rollers on every face: a node's imposed components are the normals of the faces it lies on.
  for (int face = 0; face < BC::face_count; ++face) conditions.set(face, BoundaryKind::roller);
  std::vector<Vec<3>> velocity(static_cast<std::size_t>(g.node_count()), Vec<3>(1.0, 2.0, 3.0));
  std::vector<unsigned char> imposed(velocity.size(), 0);
  grid::apply_boundary_conditions(conditions, g, velocity, &imposed);
  int corners = 0, interior = 0;
  for (Index n = 0; n < g.node_count(); ++n) {
    const auto ijk = g.node_ijk(n);
    unsigned expected = 0;
    Vec<3> v(1.0, 2.0, 3.0);
    for (int d = 0; d < 3; ++d) {
      if (ijk[d] == 0 || ijk[d] == g.nodes(d) - 1) {
        expected |= 1u << d;
        v[d] = 0.0;
      }
    }
    CHECK(imposed[static_cast<std::size_t>(n)] == expected);
    CHECK(velocity[static_cast<std::size_t>(n)] == v);
    corners += expected == 7u ? 1 : 0;
    interior += expected == 0u ? 1 : 0;
  }
  CHECK(corners == 8);
  CHECK(interior == 2 * 3 * 4);  // (3 - 1) (4 - 1) (5 - 1) interior nodes
  // A fixed face wins over nothing else: the lower z face fixed, the rest free.
  BC floor;
  floor.set(BC::face(2, false), BoundaryKind::fixed);
  std::vector<Vec<3>> w(static_cast<std::size_t>(g.node_count()), Vec<3>(1.0, 2.0, 3.0));
  grid::apply_boundary_conditions(floor, g, w);
  for (Index n = 0; n < g.node_count(); ++n) {
    const bool on_floor = g.node_ijk(n)[2] == 0;
    CHECK(w[static_cast<std::size_t>(n)] == (on_floor ? Vec<3>::Zero() : Vec<3>(1.0, 2.0, 3.0)));
  }
}

TEST_CASE("3D bad face index or friction coefficient throws, naming the value and range") {
  BC conditions;
  volatile int past_last = BC::face_count;  // opaque: the compiler would flag faces_[6]
  CHECK_THROWS_WITH_AS(conditions.set(past_last, BoundaryKind::roller),
                       doctest::Contains("face = 6"), Error);
  CHECK_THROWS_WITH_AS(conditions.set(past_last, BoundaryKind::roller), doctest::Contains("[0, 5]"),
                       Error);
  CHECK_THROWS_WITH_AS(conditions.set(BC::face(2, false), BoundaryKind::friction, -0.1),
                       doctest::Contains("friction_coefficient = -0.1"), Error);
}

TEST_CASE("3D friction floor: a block sliding diagonally decelerates at mu g and stops") {
  // Rigid-block solution: v(t) = v0 - mu g t along the initial direction (1, 1, 0) / sqrt 2,
  // until v0 / (mu g) = 0.34 s, distance v0^2 / (2 mu g) = 0.170 m. The Coulomb bound acts on
  // the norm of the two tangential components, so the direction must stay diagonal.
  const double mu = 0.3, g = 9.81, v0 = 1.0, density = 1000.0;
  using Elastic = material::LinearElastic<double, 3>;
  // MUSL, as the 2D test (tests/grid/friction_wall.test.cpp): the block's front crosses cells.
  using Sim = Simulation<3, shape::Linear, continuum::Classical<Elastic>, contact::SingleField,
                         integrator::MUSL>;
  const double cell = 0.04;
  const grid::Grid<3> grid(Vec<3>::Zero(), Vec<3>(0.6, 0.6, 0.2), {15, 15, 5});
  SimulationParameters<3> parameters;
  parameters.gravity = Vec<3>(0.0, 0.0, -g);
  Sim sim(grid, Elastic(1e6, 0.3), parameters);
  const double side = 0.16, height = 2.0 * cell;
  const auto seeding = particles::seed_box(grid, Vec<3>(0.08, 0.08, 0.0),
                                           Vec<3>(0.08 + side, 0.08 + side, height), 2);
  sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  auto& x = sim.particles().get<particles::field::Position<3>>();
  auto& v = sim.particles().get<particles::field::Velocity<3>>();
  auto& stress = sim.particles().get<particles::field::Stress<Elastic>>();
  const Vec<3> direction = Vec<3>(1.0, 1.0, 0.0).normalized();
  for (Index p = 0; p < sim.particles().size(); ++p) {
    v[p] = v0 * direction;
    // At rest vertically from the start, no lateral stress (the block's sides are free).
    stress[p].setZero();
    stress[p][2] = -density * g * (height - x[p][2]);
  }
  sim.boundary_conditions().set(BC::face(2, false), BoundaryKind::friction, mu);
  const auto& m = sim.particles().get<particles::field::Mass>();
  const auto mean_velocity = [&] {
    Vec<3> momentum = Vec<3>::Zero();
    double mass = 0.0;
    for (Index p = 0; p < sim.particles().size(); ++p) {
      momentum += m[p] * v[p];
      mass += m[p];
    }
    return Vec<3>(momentum / mass);
  };
  const auto mean_x = [&] {
    Vec<3> sum = Vec<3>::Zero();
    for (Index p = 0; p < sim.particles().size(); ++p) sum += x[p];
    return Vec<3>(sum / static_cast<double>(sim.particles().size()));
  };
  const Vec<3> x_start = mean_x();
  const double dt = sim.time_step();
  while (sim.time() < 0.15) sim.step(dt);
  const Vec<3> u = mean_velocity();
  MESSAGE("t = " << sim.time() << " s: mean velocity " << u.transpose() << ", rigid block "
                 << v0 - mu * g * sim.time());
  // Tolerance 2 % of v0 on the speed along the diagonal, as the 2D test.
  CHECK(u.dot(direction) == doctest::Approx(v0 - mu * g * sim.time()).epsilon(0.02 / 0.56));
  // The direction stays diagonal: the x and y components agree to round-off of the symmetric
  // set-up (the block, grid and seeding are symmetric about x = y).
  CHECK(std::abs(u[0] - u[1]) < 1e-9);
  while (sim.time() < 0.6) sim.step(dt);
  CHECK(mean_velocity().norm() < 0.01 * v0);
  const Vec<3> travel = mean_x() - x_start;
  MESSAGE("travel " << travel.transpose() << ", rigid block " << v0 * v0 / (2.0 * mu * g));
  CHECK(travel.dot(direction) == doctest::Approx(v0 * v0 / (2.0 * mu * g)).epsilon(0.03));
}
