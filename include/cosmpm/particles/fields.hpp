#pragma once
// The particle field tags of the engine. `label()` is the HDF5 dataset name.
#include <cstdint>

#include "cosmpm/core/types.hpp"

namespace cosmpm::particles::field {

template <int Dim>
struct Position {
  using value_type = Vec<Dim>;
  static constexpr const char* label() { return "position"; }
};
template <int Dim>
struct InitialPosition {  // for the displacement from the start
  using value_type = Vec<Dim>;
  static constexpr const char* label() { return "initial_position"; }
};
template <int Dim>
struct Velocity {
  using value_type = Vec<Dim>;
  static constexpr const char* label() { return "velocity"; }
};
template <int Dim>
struct VelocityGradient {  // L = grad v of the last step
  using value_type = Mat<Dim>;
  static constexpr const char* label() { return "velocity_gradient"; }
};
template <int Dim>
struct AffineMoment {  // APIC: B_p = sum_i N_ip v_i (x_i - x_p)^T, m^2/s (transfer/apic.hpp)
  using value_type = Mat<Dim>;
  static constexpr const char* label() { return "affine_moment"; }
};
template <int Dim>
struct DeformationGradient {
  using value_type = Mat<Dim>;
  static constexpr const char* label() { return "deformation_gradient"; }
};
template <int Dim>
struct HalfWidth {  // particle half-size in cell units, for GIMP
  using value_type = Vec<Dim>;
  static constexpr const char* label() { return "half_width"; }
};
struct Mass {
  using value_type = double;
  static constexpr const char* label() { return "mass"; }
};
struct Volume {
  using value_type = double;
  static constexpr const char* label() { return "volume"; }
};
struct InitialVolume {
  using value_type = double;
  static constexpr const char* label() { return "initial_volume"; }
};
struct Body {  // which body a particle belongs to (multi-field contact)
  using value_type = std::int32_t;
  static constexpr const char* label() { return "body"; }
};
template <class Model>
struct Stress {
  using value_type = typename Model::stress_type;
  static constexpr const char* label() { return "stress"; }
};
template <class Model>
struct Strain {  // accumulated small (logarithmic-rate) strain, same layout as the stress
  using value_type = typename Model::strain_type;
  static constexpr const char* label() { return "strain"; }
};
template <class Model>
struct MaterialState {
  using value_type = typename Model::state_type;
  static constexpr const char* label() { return "state"; }
};

}  // namespace cosmpm::particles::field

namespace cosmpm::particles::field {

// Cosserat (polar) fields, present only in Cosserat compositions.
struct MicroRotation {  // omega_3, counter-clockwise positive, rad
  using value_type = double;
  static constexpr const char* label() { return "micro_rotation"; }
};
struct MicroSpin {  // d omega_3 / dt, rad/s
  using value_type = double;
  static constexpr const char* label() { return "micro_spin"; }
};
struct MicroInertia {  // J per unit mass, m^2 (the paper: 0.5 (0.5 l)^2)
  using value_type = double;
  static constexpr const char* label() { return "micro_inertia"; }
};

}  // namespace cosmpm::particles::field
