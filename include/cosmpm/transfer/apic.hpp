#pragma once
// The affine particle-in-cell transfer (APIC; Jiang, Schroeder, Selle, Teran and Stomakhin
// 2015). Each particle carries an affine velocity field v_p + C_p (x - x_p):
//   particle to grid:  p_i = sum_p N_ip m_p (v_p + C_p (x_i - x_p))
//   grid to particle:  v_p = sum_i N_ip v_i,   C_p = B_p D_p^-1,
//                      B_p = sum_i N_ip v_i (x_i - x_p)^T,  D_p = sum_i N_ip (x_i - x_p)(x_i -
//                      x_p)^T
// Both maps conserve linear and angular momentum, and the transfer keeps the velocity detail
// FLIP keeps without FLIP's noise. For the engine's tensor-product kernels, which reproduce
// linear fields, D_p is diagonal (per axis, sum_i N_i (x_i - x_p)_d^2).
//
// APIC needs a kernel with a continuous gradient (GIMP, the B-splines): with the bilinear hat,
// C_p = B_p D_p^-1 is the grid velocity's gradient sum_i v_i grad N_ip^T, and that gradient
// takes v_i of nodes of vanishing mass (where dt f_i / m_i grows without bound) at full weight.
// A spinning elastic disk blew up within 30 to 100 steps with it under USL, MUSL and USF
// (tests/transfer/apic.test.cpp), and runs with every other kernel; the simulation rejects the
// composition at compile time.
//
// The particle keeps B_p (field::AffineMoment) and the particle-to-grid map divides by the D_p
// of the stencil it builds, as Jiang et al. do: D_p depends on where the particle sits in its
// cell (GIMP, and the B-splines next to the grid's faces), and angular momentum is conserved
// only with the D_p of the map that spreads it. That map scatters m_p (v_p - C_p x_p) and
// m_p C_p (positions from the grid origin) and adds (sum_p N_ip m_p C_p) x_i per node: the same
// sum, with one record for all of a node's affine terms.
#include <array>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
#include "cosmpm/transfer/concept.hpp"

namespace cosmpm::transfer {

struct APIC {
  static constexpr const char* name() { return "APIC"; }
  static constexpr bool affine = true;
};

static_assert(VelocityTransfer<APIC>);

namespace detail {

// The index of a stencil's first node along axis d, from its first node's linear index.
inline Index first_along(Index first_node, const Index stride, const Index nodes) {
  return (first_node / stride) % nodes;
}

// B_p for the W particles of a packed stencil: component c of the first Dim of the
// C-component node records is the velocity. `xi(l)` is lane l's position in cell units.
template <int C, int Dim, class Kernel, int W, class Position>
COSMPM_ALWAYS_INLINE std::array<std::array<Pack<W>, Dim>, Dim> affine_moment(
    const shape::PackedStencil<Dim, Kernel, W>& st, const shape::StencilGrid<Dim>& grid,
    Position&& xi, const double* records) {
  using P = Pack<W>;
  // The moment stencil: the weights' factors times (x_i - x_p)_d along each axis, which the
  // gather's gradient sum then turns into B_p.
  shape::PackedStencil<Dim, Kernel, W> moment = st;
  for (int d = 0; d < Dim; ++d) {
    const double h = 1.0 / grid.inverse_cell_size[d];
    const P first = make_pack<W>([&](int l) {
      return static_cast<double>(first_along(st.first_node[l], grid.stride[d], grid.nodes[d]));
    });
    const P position = make_pack<W>([&](int l) { return xi(l)[d]; });
    for (int i = 0; i < Kernel::support; ++i) {
      moment.dw[d][i] = st.w[d][i] * ((first + static_cast<double>(i) - position) * h);
    }
  }
  const auto b = shape::gather<C, Dim>(moment, records);
  std::array<std::array<P, Dim>, Dim> out;
  for (int c = 0; c < Dim; ++c) out[c] = b.gradient[c];
  return out;
}

// C_p = B_p D_p^-1 with the D_p of stencil `st` of a particle at `xi` (cell units): D_p is
// diagonal, sum_i N_i (x_i - x_p)_d^2 per axis.
template <int Dim, class Kernel>
Mat<Dim> affine_velocity(const Mat<Dim>& b, const shape::SeparableStencil<Dim, Kernel>& st,
                         const shape::StencilGrid<Dim>& grid, const Vec<Dim>& xi) {
  Mat<Dim> c;
  for (int d = 0; d < Dim; ++d) {
    const double h = 1.0 / grid.inverse_cell_size[d];
    const auto first =
        static_cast<double>(first_along(st.first_node, grid.stride[d], grid.nodes[d]));
    double second_moment = 0.0;
    for (int i = 0; i < Kernel::support; ++i) {
      const double offset = (first + static_cast<double>(i) - xi[d]) * h;
      second_moment += st.w[d][i] * offset * offset;
    }
    c.col(d) = b.col(d) / second_moment;
  }
  return c;
}

}  // namespace detail
}  // namespace cosmpm::transfer
