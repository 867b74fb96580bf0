#pragma once
// The constitutive-model concept: a point-level kernel that turns a strain increment into a
// new stress and state. The engine stores stress_type and state_type per particle, so both
// are fixed-size: stress_type an Eigen fixed-size vector, state_type trivially copyable
// (SoA arrays, checkpoints, HDF5).
#include <array>
#include <concepts>
#include <cstddef>
#include <span>
#include <string>
#include <string_view>
#include <type_traits>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"

namespace cosmpm::material {

// A state that can be written to output: a fixed list of scalar labels and their values.
template <class S>
concept OutputState = requires(const S& state) {
  { S::labels } -> std::convertible_to<std::array<std::string_view, S::labels.size()>>;
  { state.values() } -> std::convertible_to<std::array<double, S::labels.size()>>;
};

// State of a model without internal variables.
struct NoState {
  static constexpr std::array<std::string_view, 0> labels{};
  std::array<double, 0> values() const { return {}; }
};

// State of the perfectly plastic models: the paper's yield-point maps use `plastic`.
struct PlasticState {
  double plastic_shear_strain = 0.0;  // accumulated equivalent plastic shear strain
  double plastic = 0.0;               // 1 if the last update returned to the yield surface
  // Volumetric strain by which a cohesionless packing has come apart (models with separation,
  // e.g. MohrCoulombParameters::separation): stress-free until compression closes it.
  double separation = 0.0;
  static constexpr std::array<std::string_view, 3> labels{"plastic_shear_strain", "plastic",
                                                          "separation"};
  std::array<double, 3> values() const { return {plastic_shear_strain, plastic, separation}; }
};

// Whether a model's state records separated grains (PlasticState::separation).
template <class State>
inline constexpr bool records_separation = requires(const State& state) {
  state.separation;
};

// A point whose grains have come apart: stress-free until compression closes the gap.
template <class State>
bool grains_apart(const State& state) {
  if constexpr (records_separation<State>) {
    return state.separation > 0.0;
  } else {
    return false;
  }
}

// A model of a material point. Contract, checked for every model by the conformance kit
// (tests/material/conformance.hpp):
//   - update(stress, state, de): `stress` holds the stress at the start of the increment and
//     receives the new one, `de` is the strain increment of the step (tension positive, tensor
//     shear), `state` the model's internal variables, updated in place;
//   - an increment whose elastic trial stress lies inside the yield surface returns that trial
//     exactly (the elastic law of the model's elastic part, bit for bit) and a state marked
//     elastic;
//   - isotropy: rotating the old stress and the increment rotates the new stress;
//   - a plastic step ends on the yield surface (|f| within rounding of the stress scale).
template <class M>
concept ConstitutiveModel = requires(const M& model, typename M::stress_type& stress,
                                     typename M::state_type& state,
                                     const typename M::strain_type& strain_increment) {
  typename M::scalar_type;
  typename M::stress_type;
  typename M::strain_type;
  typename M::state_type;
  // Stress in, stress out: `stress` holds the stress at the start of the increment.
  { model.update(stress, state, strain_increment) } -> std::same_as<void>;
  // Stiffest wave modulus (p-wave, constrained) for the stable time step.
  { model.p_wave_modulus() } -> std::convertible_to<typename M::scalar_type>;
  { model.shear_modulus() } -> std::convertible_to<typename M::scalar_type>;
  { M::is_cosserat } -> std::convertible_to<bool>;
}
&&std::is_trivially_copyable_v<typename M::state_type>&& OutputState<typename M::state_type>;

// A model that also gives the algorithmic (consistent) tangent d(stress)/d(strain increment),
// for implicit solvers. Layout: tangent(i, j) = d stress[i] / d strain_increment[j]. Contract:
// the stress and state are those of update() without the tangent, bit for bit (one path), and
// the tangent agrees with finite differences of update() away from the boundaries of the
// return regions.
template <class M>
concept HasConsistentTangent = ConstitutiveModel<M> &&
    requires(const M& model, typename M::stress_type& stress, typename M::state_type& state,
             const typename M::strain_type& strain_increment, typename M::tangent_type& tangent) {
  typename M::tangent_type;
  { model.update(stress, state, strain_increment, tangent) } -> std::same_as<void>;
};

// The packed hook: a model that updates several points at once on packs of their components
// (core/pack.hpp), e.g. LinearElastic, which the engine's grid-to-particle loop then runs side
// by side for W particles. Contract:
//   model.update_values(stress, de), stress and de std::array<Value, n> (n the components of
//   stress_type), lane l of every value belonging to point l, does to every lane what
//   update(stress, state, de) does to that point, bit for bit: the same operations in the same
//   order (both are written once, as one template on the value type). Value is T or a pack of
//   T. A packed update carries no state, so only models without one (NoState) qualify.
template <class M, class Value>
concept HasPackedUpdate = ConstitutiveModel<M> && std::same_as<typename M::state_type, NoState> &&
    requires(const M& model,
             std::array<Value, static_cast<std::size_t>(M::stress_type::RowsAtCompileTime)>& stress,
             const std::array<Value, static_cast<std::size_t>(M::stress_type::RowsAtCompileTime)>&
                 increment) {
  { model.update_values(stress, increment) } -> std::same_as<void>;
};

// The batched hook: a model that updates whole arrays of points in one call, faster than a loop
// over update() when it has a batched return (CosseratDruckerPrager: its plastic points in SIMD
// lanes). Contract:
//   model.update_batch(stress, state, increment) over spans of one size that do not overlap
//   equals update(stress[i], state[i], increment[i]) for every i: bit for bit, unless the
//   model declares `static constexpr double batch_rounding` > 0, the largest relative
//   difference it allows itself where the batch reorders floating-point operations (the norm of
//   the stress difference over the stress norm, and likewise the plastic strain). Spans of
//   different sizes throw cosmpm::Error before anything is written; no allocation.
// material::update_batch(model, ...) below is the one call for any model.
template <class M>
concept HasBatchUpdate = ConstitutiveModel<M> &&
    requires(const M& model, std::span<typename M::stress_type> stress,
             std::span<typename M::state_type> state,
             std::span<const typename M::strain_type> increment) {
  { model.update_batch(stress, state, increment) } -> std::same_as<void>;
};

// HasPacksUpdate<M, W>: update_batch for points whose stresses and increments come by
// component in packs of W (core/pack.hpp): model.update_packs<W>(stress, increment, state) gives
// point l of pack k, with state state[k W + l], the values update_batch would. The engine's stage
// 4b, which holds the rotated stresses and the increments so, calls it for its whole packs and
// update_batch for the rest. A model declares it for the widths it runs in registers.
template <class M, int W>
concept HasPacksUpdate = HasBatchUpdate<M> && requires(
    const M& model,
    std::span<std::array<Pack<W>, static_cast<std::size_t>(M::stress_type::SizeAtCompileTime)>>
        stress,
    std::span<
        const std::array<Pack<W>, static_cast<std::size_t>(M::stress_type::SizeAtCompileTime)>>
        increment,
    typename M::state_type* state) {
  model.template update_packs<W>(stress, increment, state);
};

// The relative difference of a model's update_batch from update() (see HasBatchUpdate): 0 for
// every model that does not declare one.
template <class M>
inline constexpr double batch_rounding = [] {
  if constexpr (requires { M::batch_rounding; }) {
    return static_cast<double>(M::batch_rounding);
  } else {
    return 0.0;
  }
}();

// The dimension of a model's stress space: M::dimension, 2 (plane strain) for models that do
// not say.
template <class M>
inline constexpr int dimension_of = [] {
  if constexpr (requires { M::dimension; }) {
    return static_cast<int>(M::dimension);
  } else {
    return 2;
  }
}();

// The check of a batch update's arguments: one size for the stress, state and increment spans.
inline void require_equal_batch_sizes(std::string_view where, std::size_t stress, std::size_t state,
                                      std::size_t increment) {
  if (stress != state || stress != increment)
    throw Error(std::string(where) + ": stress has " + std::to_string(stress) + " points, state " +
                std::to_string(state) + " and increment " + std::to_string(increment) +
                "; the three sizes must be equal");
}

// The check of update_packs' arguments: as many increment packs as stress packs.
inline void require_equal_pack_counts(std::string_view where, std::size_t stress,
                                      std::size_t increment) {
  if (stress != increment)
    throw Error(std::string(where) + ": stress has " + std::to_string(stress) +
                " packs and increment " + std::to_string(increment) + "; the two must be equal");
}

// update(stress[i], state[i], increment[i]) for every i, by the model's update_batch when it
// has one and otherwise by a loop over update(): one call for any model. The spans must have
// the same size and must not overlap.
template <ConstitutiveModel M>
void update_batch(const M& model, std::span<typename M::stress_type> stress,
                  std::span<typename M::state_type> state,
                  std::span<const typename M::strain_type> increment) {
  if constexpr (HasBatchUpdate<M>) {
    model.update_batch(stress, state, increment);
  } else {
    require_equal_batch_sizes("material::update_batch", stress.size(), state.size(),
                              increment.size());
    for (std::size_t i = 0; i < stress.size(); ++i) model.update(stress[i], state[i], increment[i]);
  }
}

}  // namespace cosmpm::material
