#pragma once
// The Cosserat (polar) continuum in 2D plane strain: each particle also carries the
// micro-rotation omega_3, its rate and a micro-inertia J (per unit mass); stresses are
// non-symmetric and couple stresses m_31, m_32 appear. Conventions are the material's
// (material/cosserat_elastic.hpp): s_ij acts in direction j on the face with normal x_i,
//   e_xy = du_y/dx - omega_3,  e_yx = du_x/dy + omega_3,  kappa_3i = d omega_3 / dx_i,
// and the balances are d s_ij / dx_i + b_j = rho a_j and
//   rho J d^2 omega_3 / dt^2 = d m_3i / dx_i + s_xy - s_yx.
// Their weak forms give, per particle of volume V and node shape function N:
//   f_j = -V s_ij dN/dx_i,   moment = -V m_3i dN/dx_i + V (s_xy - s_yx) N.
#include <array>

#include "cosmpm/continuum/particle_fields.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"

namespace cosmpm::continuum {

template <material::ConstitutiveModel Model>
requires(Model::is_cosserat) struct Cosserat {
  using model_type = Model;
  static constexpr bool is_cosserat = true;

  template <int Dim>
  using particle_store =
      particle_store_with<Dim, Model, particles::field::MicroRotation, particles::field::MicroSpin,
                          particles::field::MicroInertia>;

  template <int Dim>
  using rates_type = ParticleRates<Dim, true>;

  // The in-plane stress is rotated with the continuum spin (Jaumann, valid for a
  // non-symmetric tensor: S += dt (W S - S W)) and the couple-stress vector with it
  // (m += dt W m); then the model integrates the Cosserat deformation increment.
  static void update_stress(const Model& model, const rates_type<2>& rates, double dt,
                            typename Model::stress_type& stress, typename Model::state_type& state,
                            typename Model::strain_type& accumulated_strain) {
    const typename Model::strain_type increment = rotate_and_increment(rates, dt, stress);
    model.update(stress, state, increment);
    accumulate_strain(accumulated_strain, increment);
  }

  // update_stress in parts, for callers that hand the model many points in one call
  // (material::update_batch): the rotation, returning the deformation increment the model
  // then integrates, and the strain's accumulation.
  static typename Model::strain_type rotate_and_increment(const rates_type<2>& rates, double dt,
                                                          typename Model::stress_type& stress) {
    const Mat<2>& L = rates.velocity_gradient;
    const double w = 0.5 * (L(0, 1) - L(1, 0)) * dt;
    const double sxx = stress[0], syy = stress[1], sxy = stress[3], syx = stress[4];
    // Tensor S with S(0,1) = s_xy, S(1,0) = s_yx: (W S - S W) entries.
    stress[0] = sxx + w * (syx + sxy);
    stress[1] = syy - w * (sxy + syx);
    stress[3] = sxy + w * (syy - sxx);
    stress[4] = syx + w * (syy - sxx);
    const double m1 = stress[5], m2 = stress[6];
    stress[5] = m1 + w * m2;
    stress[6] = m2 - w * m1;

    typename Model::strain_type increment;
    increment[0] = L(0, 0) * dt;
    increment[1] = L(1, 1) * dt;
    increment[2] = 0.0;
    increment[3] = (L(1, 0) - rates.spin) * dt;  // du_y/dx - omega_3
    increment[4] = (L(0, 1) + rates.spin) * dt;  // du_x/dy + omega_3
    increment[5] = rates.spin_gradient[0] * dt;
    increment[6] = rates.spin_gradient[1] * dt;
    return increment;
  }
  static void accumulate_strain(typename Model::strain_type& accumulated_strain,
                                const typename Model::strain_type& increment) {
    accumulated_strain += increment;
  }

  // A particle's nodal force -V s_ij dN/dx_i as sum_i dN/dx_i b[j][i] for component j.
  static std::array<std::array<double, 2>, 2> internal_force_coefficients(
      const typename Model::stress_type& stress, double volume) {
    return {
        {{-volume * stress[0], -volume * stress[4]}, {-volume * stress[3], -volume * stress[1]}}};
  }

  // A particle's nodal moment -V m_3i dN/dx_i + V (s_xy - s_yx) N as N weighted +
  // sum_i dN/dx_i by_gradient[i].
  static void moment_coefficients(const typename Model::stress_type& stress, double volume,
                                  double& weighted, std::array<double, 2>& by_gradient) {
    weighted = volume * (stress[3] - stress[4]);
    by_gradient = {-volume * stress[5], -volume * stress[6]};
  }
};

}  // namespace cosmpm::continuum
