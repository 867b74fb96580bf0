#pragma once
// A plastic test block shared by the tests that compare two runs bit for bit
// (stress_from_grid.test.cpp, grid_from_records.test.cpp, records.test.cpp,
// node_range.test.cpp), and their comparison.
#include <doctest/doctest.h>

#include <bit>
#include <cstdint>
#include <cstring>
#include <type_traits>
#include <vector>

#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "verification_helpers.hpp"

namespace cosmpm::test {

using Soil = material::MohrCoulomb<>;
using PolarSoil = material::CosseratDruckerPrager<>;
using PolarContinuum = continuum::Cosserat<PolarSoil>;

// The step benchmarks' soils (benchmarks/simulation/step_support.hpp): corn, and the paper's
// Cosserat parameters (Gc = 2.3 MPa, l = 10 mm, micro-inertia 12.5e-6 m^2).
// Continuum: these continua, or types built on them with their constructors.
template <class Continuum>
Continuum benchmark_soil() {
  if constexpr (std::is_base_of_v<PolarContinuum, Continuum>) {
    return Continuum(PolarSoil(2.76e6, 0.2, 2.3e6, 0.01, 26.0, 2.0), {.micro_inertia = 12.5e-6});
  } else {
    return Continuum(Soil({.youngs_modulus = 2.76e6,
                           .poisson_ratio = 0.2,
                           .friction_angle_deg = 26.0,
                           .dilatancy_angle_deg = 2.0}));
  }
}

// A block of 2 x 2 particles per cell sliding at 0.5 m/s over a fixed floor, which shears its
// base into plastic flow: 0.25 x 0.06 m on a 40 x 12 grid, or (`wide`) 1.55 x 0.1 m, 6,200
// particles, above cosmpm::parallel_threshold, on a 200 x 12 grid.
template <class Sim>
Sim sliding_block(int threads, bool wide) {
  const double length = wide ? 2.0 : 0.4;
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(length, 0.12), {wide ? 200 : 40, 12});
  SimulationParameters<2> parameters;
  parameters.gravity = Vec<2>(0.0, -9.81);
  parameters.threads = threads;
  Sim sim(grid, benchmark_soil<typename Sim::continuum_type>(), parameters);
  const auto seeding =
      particles::seed_box(grid, Vec<2>(0.05, 0.0), Vec<2>(wide ? 1.6 : 0.25, wide ? 0.1 : 0.06), 2);
  sim.add_particles(seeding.positions, seeding.volume, 1500.0, seeding.half_width);
  for (auto& v : sim.particles().template get<particles::field::Velocity<2>>()) {
    v = Vec<2>(0.5, 0.0);
  }
  sim.boundary_conditions().set(grid::BoundaryConditions<2>::face(1, false),
                                grid::BoundaryKind::fixed);
  return sim;
}

// Bit for bit. memcmp takes no null pointer, which an empty vector may hold (a classical
// continuum's rotational fields).
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}

// Two 2D runs' particle fields and every node field, bit for bit.
template <class A, class B>
void check_same_fields(const A& a, const B& b) {
  namespace field = particles::field;
  using Model = typename A::model_type;
  const auto& p = a.particles();
  const auto& q = b.particles();
  CHECK(same_bits(p.template get<field::Position<2>>(), q.template get<field::Position<2>>()));
  CHECK(same_bits(p.template get<field::Velocity<2>>(), q.template get<field::Velocity<2>>()));
  CHECK(same_bits(p.template get<field::Stress<Model>>(), q.template get<field::Stress<Model>>()));
  CHECK(same_bits(p.template get<field::Strain<Model>>(), q.template get<field::Strain<Model>>()));
  // The states by their values: NoState's one byte is never written.
  const auto& state_a = p.template get<field::MaterialState<Model>>();
  const auto& state_b = q.template get<field::MaterialState<Model>>();
  REQUIRE(state_a.size() == state_b.size());
  bool same_states = true;
  for (std::size_t i = 0; i < state_a.size(); ++i) {
    const auto u = state_a[i].values();
    const auto v = state_b[i].values();
    for (std::size_t k = 0; k < u.size(); ++k) {
      same_states =
          same_states && std::bit_cast<std::uint64_t>(u[k]) == std::bit_cast<std::uint64_t>(v[k]);
    }
  }
  CHECK(same_states);
  CHECK(same_bits(p.template get<field::VelocityGradient<2>>(),
                  q.template get<field::VelocityGradient<2>>()));
  CHECK(same_bits(p.template get<field::DeformationGradient<2>>(),
                  q.template get<field::DeformationGradient<2>>()));
  CHECK(same_bits(p.template get<field::Volume>(), q.template get<field::Volume>()));
  if constexpr (A::continuum_type::rotational_dofs > 0) {
    CHECK(same_bits(p.template get<field::MicroSpin>(), q.template get<field::MicroSpin>()));
    CHECK(
        same_bits(p.template get<field::MicroRotation>(), q.template get<field::MicroRotation>()));
  }
  const auto& n = a.nodes();
  const auto& m = b.nodes();
  CHECK(same_bits(n.mass, m.mass));
  CHECK(same_bits(n.momentum, m.momentum));
  CHECK(same_bits(n.force, m.force));
  CHECK(same_bits(n.velocity, m.velocity));
  CHECK(same_bits(n.acceleration, m.acceleration));
  CHECK(same_bits(n.rotational_inertia, m.rotational_inertia));
  CHECK(same_bits(n.spin_momentum, m.spin_momentum));
  CHECK(same_bits(n.moment, m.moment));
  CHECK(same_bits(n.spin, m.spin));
  CHECK(same_bits(n.spin_acceleration, m.spin_acceleration));
}

}  // namespace cosmpm::test
