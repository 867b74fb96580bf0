#pragma once
// Rolling resistance added to any contact law: the elastic-plastic rolling spring of Ai et al.
// (2011, their model C), a stand-in for the non-round shape and asperities of real grains that
// disks and smooth clumps lack. At a contact with effective radius R and normal force F_n:
//   M_r <- M_r - k_r (omega_B - omega_A) dt,   |M_r| <= mu_r R F_n,   k_r = 2.25 k_n mu_r^2 R^2
// (M_r acts on B, its opposite on A; k_n is the inner law's normal stiffness). The rolling
// coefficient mu_r is dimensionless: a disk on a slope stays put while tan(theta) < mu_r and
// rolls down at 2/3 g (sin(theta) - mu_r cos(theta)) above (tested). It applies to wall
// contacts too.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "cosmpm/core/error.hpp"
#include "cosmpm/dem/contact_law.hpp"

namespace cosmpm::dem {

template <class Inner>
class RollingResistance {
  static_assert(check_contact_law<Inner>());
  static_assert(
      requires(const typename Inner::Constants& k) {
        { Inner::normal_stiffness(k, 0.0, 0.0) } -> std::convertible_to<double>;
      },
      "dem::RollingResistance: the inner law needs static normal_stiffness(Constants, overlap, "
      "radius)");

 public:
  using Material = typename Inner::Material;
  struct Constants {
    typename Inner::Constants inner;
    double rolling_friction = 0.0;
  };

  explicit RollingResistance(Inner inner = Inner(), double rolling_friction = 0.1)
      : inner_(std::move(inner)), rolling_friction_(rolling_friction) {
    require_non_negative("dem::RollingResistance", "rolling friction coefficient mu_r",
                         rolling_friction_);
  }

  static void check_material(const Material& m, const std::string& where) {
    Inner::check_material(m, where);
  }
  const Material& particle_material() const { return inner_.particle_material(); }
  const Inner& inner() const { return inner_; }
  double rolling_friction() const { return rolling_friction_; }

  Constants pair_constants() const { return {inner_.pair_constants(), rolling_friction_}; }
  Constants wall_constants(const Material& wall) const {
    return {inner_.wall_constants(wall), rolling_friction_};
  }

  static double rolling_stiffness(const Constants& k, double overlap, double radius) {
    const double kn = Inner::normal_stiffness(k.inner, overlap, radius);
    return 2.25 * kn * k.rolling_friction * k.rolling_friction * radius * radius;
  }

  static ContactForce force(const Constants& k, const ContactKinematics& c, ContactHistory& history,
                            double dt) {
    ContactForce f = Inner::force(k.inner, c, history, dt);
    const double radius = c.effective_radius;
    double& moment = history.rolling;
    moment -= rolling_stiffness(k, c.overlap, radius) * c.relative_spin * dt;
    const double limit = k.rolling_friction * radius * std::max(f.normal, 0.0);
    if (std::abs(moment) > limit) moment = std::copysign(limit, moment);
    f.rolling_moment = moment;
    return f;
  }

  // The rolling spring stiffens the rotational mode: k_r / R^2 adds to the estimate's k.
  static double time_step_stiffness(const Constants& k, double radius) {
    return Inner::time_step_stiffness(k.inner, radius) +
           rolling_stiffness(k, 0.01 * radius, radius) / (radius * radius);
  }

 private:
  Inner inner_;
  double rolling_friction_;
};

}  // namespace cosmpm::dem
