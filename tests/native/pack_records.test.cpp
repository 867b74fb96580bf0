// Built for the host's instruction set (-march=native with COSMPM_NATIVE, as the benchmarks
// and examples are), so the wide-pack paths the portable tests never compile are checked
// here: the records transposed in registers (core/pack_records.hpp) and the gather that uses
// them. Both only move data, so they must equal the lane-by-lane path bit for bit.
#include <doctest/doctest.h>

#include <array>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/transfer.hpp"

using cosmpm::Index;
using cosmpm::Pack;
using cosmpm::Vec;

namespace {

constexpr int W = cosmpm::pack_width;

bool same_bits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

// Lane l's record of C doubles at a scattered offset in a buffer of random values (some of
// them -0.0, NaN and infinity, which a transpose must carry unchanged), with guard values around.
template <int C>
struct ScatteredRecords {
  std::vector<double> buffer;
  std::array<std::size_t, W> offset;

  explicit ScatteredRecords(unsigned seed) : buffer(64 * W + 64) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> value(-5.0, 5.0);
    for (double& v : buffer) v = value(rng);
    buffer[3] = -0.0;
    buffer[7] = std::numeric_limits<double>::quiet_NaN();
    buffer[11] = -std::numeric_limits<double>::infinity();
    for (int l = 0; l < W; ++l) {  // lanes out of order, unaligned, apart
      offset[static_cast<std::size_t>(l)] = static_cast<std::size_t>(3 + 37 * ((l * 3 + 1) % W));
    }
  }
  double* record(int l) { return buffer.data() + offset[static_cast<std::size_t>(l)]; }
};

template <int C>
void check_round_trip(unsigned seed) {
  CAPTURE(C);
  ScatteredRecords<C> in(seed);
  const auto packs = cosmpm::load_by_component<W, C>([&](int l) { return in.record(l); });
  for (int c = 0; c < C; ++c) {
    for (int l = 0; l < W; ++l) CHECK(same_bits(cosmpm::lane_of(packs[c], l), in.record(l)[c]));
  }
  // Stored into a buffer of other values: the records come back, nothing around them moves.
  ScatteredRecords<C> out(seed + 1000);
  const std::vector<double> before = out.buffer;
  cosmpm::store_by_component<W, C>([&](int l) { return out.record(l); }, packs);
  std::vector<bool> written(out.buffer.size(), false);
  for (int l = 0; l < W; ++l) {
    for (int c = 0; c < C; ++c) {
      CHECK(same_bits(out.record(l)[c], in.record(l)[c]));
      written[out.offset[static_cast<std::size_t>(l)] + static_cast<std::size_t>(c)] = true;
    }
  }
  for (std::size_t i = 0; i < before.size(); ++i) {
    if (!written[i]) CHECK(same_bits(out.buffer[i], before[i]));
  }
}

}  // namespace

TEST_CASE("load_by_component and store_by_component move records of 1 to 9 doubles exactly") {
  check_round_trip<1>(1);
  check_round_trip<2>(2);
  check_round_trip<3>(3);
  check_round_trip<4>(4);
  check_round_trip<5>(5);
  check_round_trip<6>(6);
  check_round_trip<7>(7);
  check_round_trip<8>(8);
  check_round_trip<9>(9);
}

TEST_CASE_TEMPLATE(
    "PackedStencil at the host's pack width: the gather equals lanes built one by one", K,
    cosmpm::shape::Linear, cosmpm::shape::QuadraticBSpline, cosmpm::shape::CubicBSpline) {
  using namespace cosmpm::shape;
  const cosmpm::grid::Grid<2> grid(Vec<2>(-0.3, 0.1), Vec<2>(1.2, 0.9), {12, 9});
  const StencilGrid<2> stencil_grid(grid);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  // Records of 2 to 6 doubles: the engine's gathers (MUSL's rates, USL's velocity and
  // acceleration, Cosserat's with spins).
  const auto check = [&]<int C>() {
    CAPTURE(C);
    std::vector<double> records(static_cast<std::size_t>(C * grid.node_count()));
    for (double& r : records) r = 4.0 * unit(rng) - 2.0;
    for (int trial = 0; trial < 50; ++trial) {
      std::array<Vec<2>, W> xi;  // positions in cell units, as the engine caches them
      for (auto& x : xi) {
        for (int d = 0; d < 2; ++d) x[d] = unit(rng) * stencil_grid.last[d];
      }
      PackedStencil<2, K, W> st;
      st.compute_from_cell_units(
          stencil_grid, [&](int l) -> const Vec<2>& { return xi[static_cast<std::size_t>(l)]; },
          [&](int) -> const Vec<2>& { return xi[0]; });
      const auto fast = gather<C, 2>(st, records.data());
      const auto reference = detail::gather_rows<C, 2>(st, [&](int r, int i, int c) {
        return cosmpm::make_pack<W>([&](int l) {
          return records[static_cast<std::size_t>((st.first_node[l] + st.row_offset(r) + i) * C +
                                                  c)];
        });
      });
      for (int c = 0; c < C; ++c) {
        for (int l = 0; l < W; ++l) {
          CHECK(
              same_bits(cosmpm::lane_of(fast.value[c], l), cosmpm::lane_of(reference.value[c], l)));
          if (c < 2) {
            for (int d = 0; d < 2; ++d) {
              CHECK(same_bits(cosmpm::lane_of(fast.gradient[c][d], l),
                              cosmpm::lane_of(reference.gradient[c][d], l)));
            }
          }
        }
      }
    }
  };
  check.template operator()<2>();
  check.template operator()<3>();
  check.template operator()<4>();
  check.template operator()<6>();
}
