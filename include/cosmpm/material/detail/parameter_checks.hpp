#pragma once
// Checks shared by the models' parameter structs (MohrCoulombParameters, ...). A field the user
// must give starts as `unset` (NaN), so leaving it out of the designated initialiser is an error
// that names it, not a silent zero.
#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>

#include "cosmpm/core/error.hpp"

namespace cosmpm::material::detail {

inline constexpr double unset = std::numeric_limits<double>::quiet_NaN();

// Throws if a required field was not given (still NaN).
inline void require_set(std::string_view where, std::string_view parameters, std::string_view field,
                        double value) {
  if (!std::isnan(value)) return;
  throw Error(std::string(where) + ": " + std::string(field) + " is not set (NaN); give it, e.g. " +
              std::string(parameters) + "{." + std::string(field) + " = ...}");
}

// require_set for each named field of a parameters struct.
struct NamedField {
  std::string_view name;
  double value;
};
inline void require_set(std::string_view where, std::string_view parameters,
                        std::initializer_list<NamedField> fields) {
  for (const NamedField& field : fields) require_set(where, parameters, field.name, field.value);
}

// Friction and dilatancy angles in degrees: 0 < phi < 90 and 0 <= psi <= phi.
inline void check_friction_angles(std::string_view where, double friction_angle_deg,
                                  double dilatancy_angle_deg) {
  require_in_range(where, "friction_angle_deg", friction_angle_deg, 0.0, 90.0, Bounds::open);
  require_in_range(where, "dilatancy_angle_deg", dilatancy_angle_deg, 0.0, friction_angle_deg,
                   Bounds::closed);
}

}  // namespace cosmpm::material::detail
