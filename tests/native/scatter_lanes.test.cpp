// The scatter of a pack of particles at the host's width (records transposed in registers and
// added lane after lane) equals the particles scattered one after the other, bit for bit. Built
// with multiply-adds left unfused (tests/CMakeLists.txt): GCC fuses a different product of a
// sum in the two paths, in the last bit (docs/performance.md, "The scatter across particles"),
// so fused sums compare the compiler's choices, not the operations and their order.
#include <doctest/doctest.h>

#include "cosmpm/shape.hpp"
#include "shape/scatter_lanes_paths.hpp"

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
