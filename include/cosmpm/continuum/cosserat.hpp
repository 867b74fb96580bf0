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
// The rotation is one more nodal degree of freedom (rotational_dofs = 1), with its own
// inertia sum N m J, momentum, moment and boundary conditions (CosseratSettings).
//
//   continuum::Cosserat<material::CosseratDruckerPrager<>> polar(model, {.micro_inertia = J});
//   polar.set_rotation_fixed(grid::BoundaryConditions<2>::face(1, false));  // rough floor
//   Simulation<2, shape::Linear, decltype(polar), ...> sim(grid, polar, parameters);
#include <algorithm>
#include <array>
#include <cmath>
#include <span>

#include "cosmpm/continuum/objective_update.hpp"
#include "cosmpm/continuum/particle_fields.hpp"
#include "cosmpm/continuum/rates.hpp"
#include "cosmpm/core/compiler.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/core/pack_records.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::continuum {

// What a Cosserat continuum needs besides its model.
struct CosseratSettings {
  // Micro-inertia J per unit mass of every particle, m^2 (> 0); the paper's corn:
  // 0.5 (0.5 l)^2 = 12.5e-6 m^2 for l = 10 mm.
  double micro_inertia = 0.0;
  // Multiplies the micro-inertia the dynamics uses (> 0, default 1). The rotational step
  // bound grows as its square root, so a quasi-static run can raise it until the p-wave bound
  // limits the step (docs/theory/mpm.md, "Stable time step"); the statics do not depend on J.
  double micro_inertia_scale = 1.0;
  // Faces of the grid box (BoundaryConditions<2>::face numbering) whose nodes hold the
  // micro-rotation rate at zero.
  std::array<bool, 4> rotation_fixed{};
};

template <material::ConstitutiveModel Model>
requires(Model::is_cosserat&& material::dimension_of<Model> == 2) class Cosserat {
 public:
  using model_type = Model;
  using stress_type = typename Model::stress_type;
  using strain_type = typename Model::strain_type;
  using state_type = typename Model::state_type;
  static constexpr bool is_cosserat = true;
  static constexpr int dim = 2;
  static constexpr int rotational_dofs = 1;  // omega_3
  static constexpr const char* name() { return "cosserat"; }

  template <int Dim>
  using particle_store =
      particle_store_with<Dim, Model, particles::field::MicroRotation, particles::field::MicroSpin,
                          particles::field::MicroInertia>;
  template <int Dim>
  using rates_type = ParticleRates<Dim, rotational_dofs>;

  Cosserat(const Model& model, const CosseratSettings& settings)
      : model_(model), settings_(settings) {
    require_positive("continuum::Cosserat", "micro_inertia (m^2, per unit mass)",
                     settings.micro_inertia);
    require_positive("continuum::Cosserat", "micro_inertia_scale", settings.micro_inertia_scale);
  }
  const Model& model() const { return model_; }
  const CosseratSettings& settings() const { return settings_; }

  // Holds the micro-rotation rate at zero on a face of the grid box (or frees it again).
  Cosserat& set_rotation_fixed(int face, bool fixed = true) {
    require_in_range("continuum::Cosserat::set_rotation_fixed", "face", face, 0, 3, Bounds::closed);
    settings_.rotation_fixed[static_cast<std::size_t>(face)] = fixed;
    return *this;
  }
  bool rotation_fixed(int face) const { return settings_.rotation_fixed.at(face); }

  // The micro-inertia the dynamics uses: micro_inertia x micro_inertia_scale, m^2.
  double effective_micro_inertia() const {
    return settings_.micro_inertia * settings_.micro_inertia_scale;
  }

  // --- the stress update ----------------------------------------------------------------

  static void update_stress(const Model& model, const rates_type<2>& rates, double dt,
                            stress_type& stress, state_type& state, strain_type& strain) {
    objective_update<Cosserat>(model, rates, dt, stress, state, strain);
  }

  // The in-plane stress is rotated with the continuum spin (Jaumann, valid for a
  // non-symmetric tensor: S += dt (W S - S W)) and the couple-stress vector with it
  // (m += dt W m); returns the Cosserat deformation increment the model integrates.
  static strain_type rotate_and_increment(const rates_type<2>& rates, double dt,
                                          stress_type& stress) {
    const Mat<2>& L = rates.velocity_gradient;
    const auto values = rotate_and_increment_values(
        std::array<std::array<double, 2>, 2>{{{L(0, 0), L(0, 1)}, {L(1, 0), L(1, 1)}}},
        rates.spin[0], std::array<double, 2>{rates.spin_gradient[0][0], rates.spin_gradient[0][1]},
        dt, stress);
    strain_type increment;
    for (int c = 0; c < 7; ++c) increment[c] = values[c];
    return increment;
  }

  // rotate_and_increment on a double or on packs of several particles' values (lane l of every
  // value belongs to one particle), the stress indexable by component: the one place the
  // arithmetic is written.
  template <class Value, class Stress>
  COSMPM_ALWAYS_INLINE static std::array<Value, 7> rotate_and_increment_values(
      const std::array<std::array<Value, 2>, 2>& L, const Value& spin,
      const std::array<Value, 2>& spin_gradient, double dt, Stress& stress) {
    const Value w = 0.5 * (L[0][1] - L[1][0]) * dt;
    const Value sxx = stress[0], syy = stress[1], sxy = stress[3], syx = stress[4];
    // Tensor S with S(0,1) = s_xy, S(1,0) = s_yx: (W S - S W) entries.
    stress[0] = sxx + w * (syx + sxy);
    stress[1] = syy - w * (sxy + syx);
    stress[3] = sxy + w * (syy - sxx);
    stress[4] = syx + w * (syy - sxx);
    const Value m1 = stress[5], m2 = stress[6];
    stress[5] = m1 + w * m2;
    stress[6] = m2 - w * m1;
    const Value yx = (L[1][0] - spin) * dt;  // du_y/dx - omega_3
    const Value xy = (L[0][1] + spin) * dt;  // du_x/dy + omega_3
    const Value curvature_x = spin_gradient[0] * dt, curvature_y = spin_gradient[1] * dt;
    return {L[0][0] * dt, L[1][1] * dt, Value{}, yx, xy, curvature_x, curvature_y};
  }
  // Every component accumulates. Strain and increment are indexable by the components (an
  // Eigen vector, or packs of them by component).
  template <class Strain, class Increment>
  COSMPM_ALWAYS_INLINE static void accumulate_strain(Strain& strain, const Increment& increment) {
    for (int c = 0; c < 7; ++c) strain[c] += increment[c];
  }

  // No update on packs: the engine updates Cosserat stresses per particle or in batches.
  template <class Value>
  static constexpr bool updates_values = false;

  // --- how a particle loads the grid ----------------------------------------------------

  // A particle's nodal force -V s_ij dN/dx_i as sum_i dN/dx_i b[j][i] for component j; Value a
  // double, or a pack for W particles (each lane the double's arithmetic).
  template <class Stress, class Value>
  static std::array<std::array<Value, 2>, 2> internal_force_coefficients(const Stress& stress,
                                                                         const Value& volume) {
    return {
        {{-volume * stress[0], -volume * stress[4]}, {-volume * stress[3], -volume * stress[1]}}};
  }

  // A particle's nodal moment -V m_3i dN/dx_i + V (s_xy - s_yx) N as N weighted[0] +
  // sum_i dN/dx_i by_gradient[0][i].
  template <class Stress, class Value>
  static void rotational_force_terms(const Stress& stress, const Value& volume, Value* weighted,
                                     std::array<Value, 2>* by_gradient) {
    weighted[0] = volume * (stress[3] - stress[4]);
    by_gradient[0] = {-volume * stress[5], -volume * stress[6]};
  }

  // --- the rotational degree of freedom -------------------------------------------------

  // A particle's rotational inertia m J and spin, which the particle-to-grid map spreads as
  // N m J and N m J spin; V a double, or a pack for particles p, ..., p + W - 1.
  template <class Store, class V>
  static std::array<V, 1> rotational_inertia(const Store& particles, Index p, const V& mass) {
    const double* const inertia = &particles.template get<particles::field::MicroInertia>()[p];
    return {mass * cosmpm::detail::load_pack<lane_count<V>()>(inertia)};
  }
  template <int W = 1, class Store>
  static std::array<Pack<W>, 1> rotational_velocity(const Store& particles, Index p) {
    return {
        cosmpm::detail::load_pack<W>(&particles.template get<particles::field::MicroSpin>()[p])};
  }

  // Grid to particle: spin (PIC/FLIP blend, as the velocity) and micro-rotation from the
  // nodal spin and spin acceleration at the particle; V a double, or a pack of W doubles for
  // particles p, ..., p + W - 1 (each lane the double's arithmetic).
  template <class Store, class V>
  static void update_rotations(Store& particles, Index p, double dt, double flip,
                               const std::array<V, 1>& spin_grid,
                               const std::array<V, 1>& spin_acceleration) {
    double* const spin = &particles.template get<particles::field::MicroSpin>()[p];
    double* const rotation = &particles.template get<particles::field::MicroRotation>()[p];
    constexpr int W = lane_count<V>();
    using cosmpm::detail::load_pack, cosmpm::detail::store_pack;
    store_pack<W>(spin, flip * (load_pack<W>(spin) + dt * spin_acceleration[0]) +
                            (1.0 - flip) * spin_grid[0]);
    store_pack<W>(rotation, load_pack<W>(rotation) + dt * spin_grid[0]);
  }

  // New particles take the (scaled) micro-inertia of the settings.
  template <class Store>
  void initialise_particles(Store& particles, Index first, Index count) const {
    auto& inertia = particles.template get<particles::field::MicroInertia>();
    const double j = effective_micro_inertia();
    for (Index p = first; p < first + count; ++p) inertia[p] = j;
  }

  // Zero nodal spin on the faces whose rotation is fixed.
  void apply_rotation_conditions(const grid::Grid<2>& grid, std::span<double> spin) const {
    apply_rotation_conditions(grid, spin, 0, grid.node_count());
  }
  // The same on the nodes [first, last) only (a thread's share of the grid update).
  void apply_rotation_conditions(const grid::Grid<2>& grid, std::span<double> spin, Index first,
                                 Index last) const {
    for (int face = 0; face < 4; ++face) {
      if (!settings_.rotation_fixed[static_cast<std::size_t>(face)]) continue;
      grid::for_each_face_node_in(grid, face / 2, face % 2 == 1, first, last,
                                  [&](Index n) { spin[static_cast<std::size_t>(n)] = 0.0; });
    }
  }

  // rho J omega_max^2 (Pa): the largest eigenvalue of the lumped operator on the nodal
  // rotations, translations held, times rho J (derived in docs/theory/mpm.md, "Cosserat
  // continuum"). Over regular particle arrangements with the linear kernel (and GIMP) it is
  //   max(4 Gc, 4 B / h_min^2 + 4 Gc rho_q),  B = 2 G l^2,
  // with rho_q = mean (1 - 2 xi)^2 over the particles' cell coordinates xi, below 1/3 for
  // any count per cell; we take 1/3. The B-splines' eigenvalues lie below it.
  double rotational_stiffness_bound(const grid::Grid<2>& grid) const {
    const double h = grid.min_cell_size();
    const double cosserat_shear = 4.0 * model_.cosserat_shear_modulus();
    return std::max(cosserat_shear,
                    4.0 * model_.bending_modulus() / (h * h) + cosserat_shear / 3.0);
  }

  // The critical step of the rotational dofs, dt = 2 / omega_max.
  double stable_time_step(const grid::Grid<2>& grid, double max_density) const {
    const double omega =
        std::sqrt(rotational_stiffness_bound(grid) / (max_density * effective_micro_inertia()));
    return 2.0 / omega;
  }

 private:
  Model model_;
  CosseratSettings settings_;
};

}  // namespace cosmpm::continuum
