// The grid update's boundary conditions in each thread's share of the nodes
// (stages/grid_update.hpp, conditions_in_shares): where the contact law joins no velocity phase,
// every node's face and rotation conditions are applied in the node pass, by the thread that
// updated the node, and its gather record written there too. A law whose correct() does nothing
// takes the path apart (the conditions on the whole grid after the node pass, the records in a
// pass of their own), so the two runs must agree bit for bit: every particle field and every
// node field, the face nodes that no particle reaches among them.
#include <doctest/doctest.h>

#include <algorithm>
#include <iterator>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmpm/grid/boundary.hpp"
#include "sliding_block.hpp"

namespace {
using namespace cosmpm;
using test::sliding_block;
using BC = grid::BoundaryConditions<2>;

// Joins the velocity phases and changes nothing: the conditions are applied apart.
struct PassThrough {
  static constexpr const char* name() { return "test pass-through"; }
  void advance(double, double) {}
  void correct(contact::GridView<2>&) {}
};

template <class Sim>
Sim walled_block(int threads, bool wide) {
  Sim sim = sliding_block<Sim>(threads, wide);
  // A rough floor (friction), a roller wall ahead of the block, a fixed one behind it and a
  // roller lid: every kind, and corners where two of them meet.
  sim.boundary_conditions().set(BC::face(1, false), grid::BoundaryKind::friction, 0.4);
  sim.boundary_conditions().set(BC::face(0, true), grid::BoundaryKind::roller);
  sim.boundary_conditions().set(BC::face(0, false), grid::BoundaryKind::fixed);
  sim.boundary_conditions().set(BC::face(1, true), grid::BoundaryKind::roller);
  if constexpr (Sim::rotational_dofs > 0) {
    sim.continuum().set_rotation_fixed(BC::face(1, false));
    sim.continuum().set_rotation_fixed(BC::face(0, false));
  }
  return sim;
}

template <class Continuum, class Scheme>
void check_shares(int threads, bool wide, const std::string& label) {
  using Sim = Simulation<2, shape::Linear, Continuum, contact::SingleField, Scheme>;
  using SimApart = Simulation<2, shape::Linear, Continuum, PassThrough, Scheme>;
  static_assert(
      stages::detail::conditions_in_shares<
          EngineState<2, shape::Linear, Continuum, contact::SingleField, transfer::FlipBlend>>);
  static_assert(!stages::detail::conditions_in_shares<
                EngineState<2, shape::Linear, Continuum, PassThrough, transfer::FlipBlend>>);
  INFO(label);
  Sim in_shares = walled_block<Sim>(threads, wide);
  SimApart apart = walled_block<SimApart>(threads, wide);
  const double dt = in_shares.time_step();
  for (int i = 1; i <= 100; ++i) {
    in_shares.step(dt);
    apart.step(dt);
    if (i % 25 == 0) test::check_same_fields(in_shares, apart);
  }
}
}  // namespace

TEST_CASE("grid update: conditions in the threads' shares as on the whole grid, bit for bit") {
  using Classical = continuum::Classical<test::Soil>;
  using Polar = test::PolarContinuum;
  SUBCASE("one thread") {
    check_shares<Classical, integrator::USL>(1, false, "USL MC");
    check_shares<Classical, integrator::MUSL>(1, false, "MUSL MC");
    check_shares<Polar, integrator::MUSL>(1, false, "MUSL Cosserat");
    check_shares<Classical, integrator::FusedMUSL>(1, false, "fused MUSL MC");
  }
  SUBCASE("two threads over 6,200 particles") {
    check_shares<Classical, integrator::MUSL>(2, true, "2 threads MUSL MC");
    check_shares<Polar, integrator::FusedMUSL>(2, true, "2 threads fused MUSL Cosserat");
    check_shares<Polar, integrator::USL>(2, true, "2 threads USL Cosserat");
  }
}

TEST_CASE("for_each_face_node_in: a face's nodes within a range, in increasing order") {
  // Every range of a 2D and a 3D grid, against the face's nodes from for_each_face_node.
  const auto check = [](const auto& grid) {
    constexpr int Dim = std::decay_t<decltype(grid)>::dim;
    const Index count = grid.node_count();
    for (int axis = 0; axis < Dim; ++axis) {
      for (const bool upper : {false, true}) {
        std::vector<Index> face;
        grid::for_each_face_node(grid, axis, upper, [&](Index n) { face.push_back(n); });
        std::sort(face.begin(), face.end());
        for (Index first = -2; first <= count + 1; first += 3) {
          for (Index last = first; last <= count + 2; last += 5) {
            std::vector<Index> expected;
            std::copy_if(face.begin(), face.end(), std::back_inserter(expected),
                         [&](Index n) { return n >= first && n < last; });
            std::vector<Index> visited;
            grid::for_each_face_node_in(grid, axis, upper, first, last,
                                        [&](Index n) { visited.push_back(n); });
            CAPTURE(axis);
            CAPTURE(upper);
            CAPTURE(first);
            CAPTURE(last);
            REQUIRE(visited == expected);
          }
        }
      }
    }
  };
  check(grid::Grid<2>(Vec<2>(0.0, 0.0), Vec<2>(0.7, 0.4), {7, 4}));
  check(grid::Grid<3>(Vec<3>(0.0, 0.0, 0.0), Vec<3>(0.5, 0.4, 0.3), {5, 4, 3}));
}
