#pragma once
// The kinematic update every continuum shares: F <- (I + dt L) F and V = det(F) V0, for W
// particles side by side (W = 1: one particle, as a plain double).
#include <array>

#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::stages {

template <int Dim, class T>
T determinant(const std::array<std::array<T, Dim>, Dim>& a) {
  static_assert(Dim == 2 || Dim == 3, "stages::determinant: 2D and 3D only");
  if constexpr (Dim == 2) {
    return a[0][0] * a[1][1] - a[0][1] * a[1][0];
  } else {
    return a[0][0] * (a[1][1] * a[2][2] - a[1][2] * a[2][1]) -
           a[0][1] * (a[1][0] * a[2][2] - a[1][2] * a[2][0]) +
           a[0][2] * (a[1][0] * a[2][1] - a[1][1] * a[2][0]);
  }
}

// Particles p, ..., p + W - 1 with velocity gradients L (lane l for particle p + l); returns
// det(F), the volume ratio.
template <int W, int Dim, class Store>
COSMPM_ALWAYS_INLINE Pack<W> update_deformation(Store& particles, Index p,
                                                const std::array<std::array<Pack<W>, Dim>, Dim>& L,
                                                double dt) {
  using P = Pack<W>;
  auto& F = particles.template get<particles::field::DeformationGradient<Dim>>();
  // F(i, j) is component i + Dim j of a particle's record (column-major).
  constexpr int C = Dim * Dim;
  const auto record = [&](int l) { return F[p + l].data(); };
  const std::array<P, C> old = load_by_component<W, C>(record);
  std::array<P, C> updated;
  for (int i = 0; i < Dim; ++i) {
    for (int j = 0; j < Dim; ++j) {
      P lf = L[i][0] * old[0 + Dim * j];
      for (int k = 1; k < Dim; ++k) lf += L[i][k] * old[k + Dim * j];
      updated[i + Dim * j] = old[i + Dim * j] + dt * lf;
    }
  }
  store_by_component<W, C>(record, updated);
  std::array<std::array<P, Dim>, Dim> a;
  for (int i = 0; i < Dim; ++i) {
    for (int j = 0; j < Dim; ++j) a[i][j] = updated[i + Dim * j];
  }
  const P J = determinant<Dim>(a);
  const auto& initial_volume = particles.template get<particles::field::InitialVolume>();
  auto& volume = particles.template get<particles::field::Volume>();
  const P V = J * make_pack<W>([&](int l) { return initial_volume[p + l]; });
  for (int l = 0; l < W; ++l) volume[p + l] = lane<W>(V, l);
  return J;
}

}  // namespace cosmpm::stages
