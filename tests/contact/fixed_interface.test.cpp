// Interface::fixed by hand: a grid face's fixed condition for a body turned against the grid.
// The body's top surface is the line y = x + 0.2 (45 deg to the grid), the body below it;
// cells of 1 m. A node (i, j) lies inside for j - i < 0.2, and its control volume (the closed
// box of half a cell about it) meets the line for |j - i - 0.2| <= 1, so the nodes with
// j - i <= 1 move with the body and those with j - i >= 2 are free. no_slip holds every node
// whose support (the open box of one cell) meets the body: j - i - 0.2 < 2, so j - i <= 2.
#include <doctest/doctest.h>

#include <vector>

#include "contact_test_support.hpp"

namespace {
using namespace cosmpm;

struct TurnedFloor {
  grid::Grid<2> grid{Vec<2>(-3.0, -3.0), Vec<2>(6.0, 6.0), {6, 6}};
  std::vector<double> mass = std::vector<double>(49, 1.0);
  std::vector<Vec<2>> velocity = std::vector<Vec<2>>(49, Vec<2>(1.0, -2.0));
  const Vec<2> body_velocity = Vec<2>(0.5, 0.5);  // along its surface
  contact::RigidContact<2> law;

  explicit TurnedFloor(const contact::Interface& interface) {
    // A triangle whose long edge lies on y = x + 0.2, far larger than the grid.
    contact::RigidBody<2> body({Vec<2>(-10.0, -9.8), Vec<2>(10.0, -9.8), Vec<2>(10.0, 10.2)},
                               Vec<2>(0.0, 0.0));
    body.set_velocity(body_velocity);
    law.add_body(std::move(body), interface);
  }
  void correct(const Vec<2>& trial) {
    std::fill(velocity.begin(), velocity.end(), trial);
    contact::GridView<2> view{grid, mass, velocity, 1e-12, 0.1, 0.0, contact::Phase::end_velocity};
    law.correct(view);
  }
  const Vec<2>& at(Index i, Index j) const {
    return velocity[static_cast<std::size_t>(grid.node_index({i + 3, j + 3}))];
  }
};

}  // namespace

TEST_CASE("fixed interface: the nodes inside or straddling a turned surface move with it") {
  TurnedFloor floor(contact::Interface::fixed());
  const Vec<2> trial(1.0, -2.0);
  floor.correct(trial);
  for (Index i = -3; i <= 3; ++i) {
    for (Index j = -3; j <= 3; ++j) {
      CAPTURE(i);
      CAPTURE(j);
      CHECK(floor.at(i, j) == (j - i <= 1 ? floor.body_velocity : trial));
    }
  }
  // The recorded force of a held node: m (V - v) / dt = 1 (-0.5, 2.5) / 0.1.
  double held_force_x = 0.0;
  for (const auto& r : floor.law.contact_nodes()) {
    if (r.state == contact::NodeState::bonded) {
      CHECK(r.force_on_material.isApprox(Vec<2>(-5.0, 25.0)));
      held_force_x += r.force_on_material[0];
    }
  }
  // 7 x 7 nodes, j - i <= 1: 49 less the 15 with j - i >= 2 (5 + 4 + 3 + 2 + 1) = 34 held.
  CHECK(held_force_x == doctest::Approx(-5.0 * 34));
  CHECK(floor.law.force_on_body(0)[0] == doctest::Approx(5.0 * 34));
}

TEST_CASE("fixed interface: no separation either, as a fixed grid face") {
  TurnedFloor floor(contact::Interface::fixed());
  floor.correct(Vec<2>(-3.0, 4.0));  // leaving the surface fast
  CHECK(floor.at(0, 1) == floor.body_velocity);
  CHECK(floor.at(0, 2) == Vec<2>(-3.0, 4.0));
}

TEST_CASE("no_slip reaches one node row further from a turned surface than fixed") {
  TurnedFloor floor(contact::Interface::no_slip());
  floor.correct(Vec<2>(1.0, -2.0));
  CHECK(floor.at(0, 2) == floor.body_velocity);  // j - i = 2: its support meets the body
  CHECK(floor.at(0, 3) == Vec<2>(1.0, -2.0));
  CHECK(floor.at(-3, 0) == Vec<2>(1.0, -2.0));
}
