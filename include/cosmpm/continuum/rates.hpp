#pragma once
// What a particle's stress update needs from the grid in one step: the velocity gradient
// L_ij = d v_i / d x_j and, for a Cosserat continuum, the micro-spin and its gradient.
#include "cosmpm/core/types.hpp"

namespace cosmpm::continuum {

template <int Dim, bool cosserat>
struct ParticleRates {
  Mat<Dim> velocity_gradient = Mat<Dim>::Zero();
};

template <int Dim>
struct ParticleRates<Dim, true> {
  Mat<Dim> velocity_gradient = Mat<Dim>::Zero();
  double spin = 0.0;                          // d omega_3 / dt at the particle
  Vec<Dim> spin_gradient = Vec<Dim>::Zero();  // grad (d omega_3 / dt)
};

}  // namespace cosmpm::continuum
