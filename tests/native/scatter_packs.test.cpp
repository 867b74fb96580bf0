// The scatter by node packs at the host's width (tests/shape checks the portable one): GCC
// fuses multiply-adds here, and the two paths must still give the same sums bit for bit.
#include <doctest/doctest.h>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/shape.hpp"
#include "shape/scatter_paths.hpp"

using namespace cosmpm::shape;

TEST_CASE_TEMPLATE(
    "shape::scatter by node packs equals the row arrays' scatter at the host's width", K, Linear,
    GIMP, QuadraticBSpline) {
  constexpr int P = cosmpm::pack_width;
  // A weighted-only pack and a mixed one (the 2D Cosserat record at P = 4), one mixed pack,
  // one weighted-only pack, and four packs in 3D (the 3D Cosserat record at P = 4).
  CHECK(scatter_paths::differing_doubles<2, K, P + 1, 2 * P>(3) == 0);
  CHECK(scatter_paths::differing_doubles<2, K, P - 1, P>(4) == 0);
  CHECK(scatter_paths::differing_doubles<2, K, P, P>(5) == 0);
  CHECK(scatter_paths::differing_doubles<3, K, 2 * P + 2, 4 * P>(6) == 0);
}
