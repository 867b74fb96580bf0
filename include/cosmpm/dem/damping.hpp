#pragma once
// Damping of the bodies' motion, as a policy of the integrator. PFC's local non-viscous
// damping (Cundall) removes a fixed fraction of the unbalanced force on every degree of
// freedom, against that degree of freedom's velocity:
//   F_d = -alpha |F| sign(v)   (and the same for the torque against the spin)
// It needs no calibration of a time scale and vanishes at rest and in steady motion. In a
// collision it acts with the force while the bodies approach and against it while they
// separate, so the restitution is sqrt((1 - alpha) / (1 + alpha)) (0.42 at PFC's default
// alpha = 0.7). Viscous contact damping belongs to the contact law (LinearSpring).
#include <cmath>
#include <concepts>

#include "cosmpm/core/error.hpp"

namespace cosmpm::dem {

template <class D>
concept BodyDamping = requires(const D& damping, double force, double velocity) {
  { damping.damp(force, velocity) } -> std::convertible_to<double>;
};

struct NoLocalDamping {
  double damp(double force, double /*velocity*/) const { return force; }
};

class LocalDamping {
 public:
  explicit LocalDamping(double coefficient = 0.7) : coefficient_(coefficient) {
    require_in_range("dem::LocalDamping", "local damping coefficient alpha", coefficient_, 0.0, 1.0,
                     Bounds::left_closed);
  }
  double coefficient() const { return coefficient_; }
  void set_coefficient(double coefficient) { *this = LocalDamping(coefficient); }
  double damp(double force, double velocity) const {
    const double sign = velocity > 0.0 ? 1.0 : (velocity < 0.0 ? -1.0 : 0.0);
    return force - coefficient_ * std::abs(force) * sign;
  }

 private:
  double coefficient_;
};

static_assert(BodyDamping<NoLocalDamping> && BodyDamping<LocalDamping>);

}  // namespace cosmpm::dem
