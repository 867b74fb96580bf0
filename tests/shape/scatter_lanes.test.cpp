// The scatter of a pack of particles equals the particles scattered one after the other, bit
// for bit, at the portable width (tests/native checks the host's).
#include <doctest/doctest.h>

#include "cosmpm/shape.hpp"
#include "shape/scatter_lanes_paths.hpp"

using namespace cosmpm::shape;

TEST_CASE_TEMPLATE("shape::scatter_lanes equals the lanes' particles scattered in turn", K, Linear,
                   QuadraticBSpline, CubicBSpline) {
  // The 2D and 3D classical records (mass and momentum weighted only, then the force), a
  // Cosserat-like one, and a record of weighted values only.
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 3, 5>(1) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<3, K, 4, 7>(2) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 5, 8>(3) == 0);
  CHECK(scatter_lanes_paths::differing_doubles<2, K, 2, 2>(4) == 0);
}
