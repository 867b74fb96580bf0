#pragma once
// What a particle's stress update needs from the grid in one step: the velocity gradient
// L_ij = d v_i / d x_j and, for a continuum with rotational degrees of freedom (Cosserat: the
// micro-rotation omega_3 in 2D), their rates and the gradients of those rates.
#include <array>

#include "cosmpm/core/types.hpp"

namespace cosmpm::continuum {

template <int Dim, int RotationalDofs>
struct ParticleRates {
  Mat<Dim> velocity_gradient = Mat<Dim>::Zero();
  // Empty (no storage) for a classical continuum.
  [[no_unique_address]] std::array<double, RotationalDofs> spin{};  // d omega_k / dt
  [[no_unique_address]] std::array<Vec<Dim>, RotationalDofs> spin_gradient =
      zero_vectors();  // grad (d omega_k / dt)

 private:
  static std::array<Vec<Dim>, RotationalDofs> zero_vectors() {
    std::array<Vec<Dim>, RotationalDofs> zero;
    for (auto& v : zero) v.setZero();
    return zero;
  }
};

}  // namespace cosmpm::continuum
