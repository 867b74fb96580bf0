// The scatter of a pack of particles at the host's width (records transposed in registers and
// added lane after lane) equals the particles scattered one after the other, bit for bit. Built
// with multiply-adds left unfused (tests/CMakeLists.txt): GCC fuses a different product of a
// sum in the two paths, in the last bit (docs/performance.md, "The scatter across particles"),
// so fused sums compare the compiler's choices, not the operations and their order.
#include <doctest/doctest.h>

#include <type_traits>
#include <utility>

#include "cosmpm/shape.hpp"
#include "shape/scatter_lanes_paths.hpp"
#include "simulation/sliding_block.hpp"

using namespace cosmpm::shape;

TEST_CASE_TEMPLATE(
    "shape::scatter_lanes equals the lanes' particles scattered in turn at the "
    "host's width",
    K, Linear, QuadraticBSpline, CubicBSpline) {
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 3, 5>(1) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<3, K, 4, 7>(2) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 5, 8>(3) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 2, 2>(4) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 1, 6>(5) == 0);
}

namespace {

// The continuum with its force terms on doubles only, so the fused passes scatter its packs
// particle by particle (stages::detail::scatters_packs is false).
template <class Base>
struct ScalarTerms : Base {
  using Base::Base;
  static auto internal_force_coefficients(const typename Base::stress_type& stress, double volume) {
    return Base::internal_force_coefficients(stress, volume);
  }
};

template <class Sim>
using StateOf = std::remove_cvref_t<decltype(std::declval<const Sim&>().engine())>;

// `steps` of the plastic sliding block with the continuum's terms on packs and on doubles.
template <class Continuum, class Scheme>
void check_fused_scatter(int steps) {
  using cosmpm::Simulation, cosmpm::contact::SingleField;
  using Packs = Simulation<2, Linear, Continuum, SingleField, Scheme>;
  using Lanes = Simulation<2, Linear, ScalarTerms<Continuum>, SingleField, Scheme>;
  static_assert(cosmpm::stages::detail::scatters_packs<StateOf<Packs>, 4>);
  static_assert(!cosmpm::stages::detail::scatters_packs<StateOf<Lanes>, 4>);
  Packs packs = cosmpm::test::sliding_block<Packs>(1, false);
  Lanes lanes = cosmpm::test::sliding_block<Lanes>(1, false);
  const double dt = packs.time_step();
  REQUIRE(dt == lanes.time_step());
  for (int i = 0; i < steps; ++i) {
    packs.step(dt);
    lanes.step(dt);
  }
  cosmpm::test::check_same_fields(packs, lanes);
}

}  // namespace

// The fused passes' scatter of a pack (stages/fused_scatter.hpp, scatter_pack: the continuum's
// terms formed on packs, then shape::scatter_lanes) against the same packs scattered particle by
// particle: every field bit for bit after 100 steps of plastic flow.
TEST_CASE_TEMPLATE(
    "fused schemes: a pack's scatter across its particles gives the bits of its "
    "particles scattered one by one",
    Scheme, cosmpm::integrator::FusedUSL, cosmpm::integrator::FusedMUSL) {
  if constexpr (cosmpm::pack_width != 4 || !cosmpm::detail::transposes_records) {
    MESSAGE("packs of " << cosmpm::pack_width << " doubles: the fused passes scatter by particle");
  } else {
    SUBCASE("Mohr-Coulomb") {
      check_fused_scatter<cosmpm::continuum::Classical<cosmpm::test::Soil>, Scheme>(100);
    }
    SUBCASE("Cosserat Drucker-Prager") {
      check_fused_scatter<cosmpm::test::PolarContinuum, Scheme>(100);
    }
  }
}
