// SimulationParameters::free_surface_flow: the constructor rejects, naming why, the
// compositions that failed free-surface flows to rest in docs/validation.md (shape::Linear,
// pure FLIP), and runs them when allow_fragile_composition is set.
#include <doctest/doctest.h>

#include <string>

#include "verification_helpers.hpp"

namespace {
using namespace cosmpm;

template <class Kernel, class Transfer = transfer::FlipBlend>
using SimOf =
    Simulation<2, Kernel, test::ElasticContinuum, contact::SingleField, integrator::MUSL, Transfer>;

template <class Sim>
std::string error_of(const SimulationParameters<2>& parameters) {
  const grid::Grid<2> grid(Vec<2>(0.0, 0.0), Vec<2>(1.0, 1.0), {10, 10});
  try {
    Sim sim(grid, test::Elastic(1e6, 0.3), parameters);
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

SimulationParameters<2> free_surface(double flip_fraction = -1.0) {
  SimulationParameters<2> parameters;
  parameters.free_surface_flow = true;
  if (flip_fraction >= 0.0) parameters.flip_fraction = flip_fraction;
  return parameters;
}
}  // namespace

TEST_CASE("free-surface flow: linear shape functions are rejected up front, naming why") {
  const std::string message = error_of<SimOf<shape::Linear>>(free_surface());
  CHECK(contains(message, "not expected to hold for a free-surface flow to rest"));
  CHECK(contains(message, "shape::Linear"));
  CHECK(contains(message, "allow_fragile_composition"));
  CHECK(!contains(message, "pure FLIP"));  // the default blend is not a concern
}

TEST_CASE("free-surface flow: pure FLIP is rejected; the default blend and APIC are not") {
  const std::string message = error_of<SimOf<shape::QuadraticBSpline>>(free_surface(1.0));
  CHECK(contains(message, "pure FLIP (flip_fraction = 1)"));
  CHECK(!contains(message, "shape::Linear"));
  CHECK(error_of<SimOf<shape::QuadraticBSpline>>(free_surface()) == "");
  CHECK(error_of<SimOf<shape::GIMP>>(free_surface(0.99)) == "");
  CHECK(error_of<SimOf<shape::CubicBSpline, transfer::APIC>>(free_surface()) == "");
  // APIC with flip_fraction = 1 has no FLIP part: not pure FLIP.
  CHECK(error_of<SimOf<shape::QuadraticBSpline, transfer::APIC>>(free_surface(1.0)) == "");
}

TEST_CASE("free-surface flow: both concerns at once are both named") {
  const auto concerns =
      free_surface_flow_concerns<shape::Linear, transfer::FlipBlend>(free_surface(1.0));
  CHECK(concerns.size() == 2);
  const std::string message = error_of<SimOf<shape::Linear>>(free_surface(1.0));
  CHECK(contains(message, "shape::Linear"));
  CHECK(contains(message, "pure FLIP"));
}

TEST_CASE("free-surface flow: allow_fragile_composition runs it; undeclared flows run too") {
  SimulationParameters<2> allowed = free_surface(1.0);
  allowed.allow_fragile_composition = true;
  CHECK(error_of<SimOf<shape::Linear>>(allowed) == "");
  SimulationParameters<2> undeclared;
  undeclared.flip_fraction = 1.0;  // the flat blade's composition: linear, pure FLIP
  CHECK(error_of<SimOf<shape::Linear>>(undeclared) == "");
}
