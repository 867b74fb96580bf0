#pragma once
// PFC2D's simplified Hertz-Mindlin contact (its "Hertz model"), an alternative to the linear
// springs: the normal force grows with the overlap to the power 3/2 and the shear stiffness
// with the normal force to the power 1/3. With the shear modulus G and Poisson's ratio nu
// (averaged over the two sides, as PFC does) and R = 2 r_A r_B / (r_A + r_B) (r_B at a wall):
//   F_n = k_hat delta^(3/2),  k_hat = 2 G sqrt(2 R) / (3 (1 - nu))
//   k_s = 2 (3 G^2 (1 - nu) R)^(1/3) / (2 - nu) * F_n^(1/3)
// The shear force is incremental with Coulomb's cap, as for the linear springs; the dashpots
// use the tangent stiffnesses dF_n/d delta = 3/2 k_hat delta^(1/2) and k_s.
// The time-step estimate uses the tangent stiffnesses at an overlap of
// `reference_overlap` times the particle radius (default 1 %), since they grow with the force.
#include <algorithm>
#include <cmath>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/dem/contact_law.hpp"

namespace cosmpm::dem {

struct HertzMindlinMaterial {
  double shear_modulus = 1e8;  // Pa
  double poisson_ratio = 0.3;
  double friction = 0.5;
};

class HertzMindlin {
 public:
  using Material = HertzMindlinMaterial;
  struct Constants {
    double shear_modulus = 0.0;
    double poisson_ratio = 0.0;
    double friction = 0.0;
    double damping_ratio = 0.0;
    double reference_overlap = 0.01;
  };

  explicit HertzMindlin(Material particle = Material(), double damping_ratio = 0.0,
                        double reference_overlap = 0.01)
      : particle_(particle), damping_ratio_(damping_ratio), reference_overlap_(reference_overlap) {
    check_material(particle_, "dem::HertzMindlin (particle)");
    require_in_range("dem::HertzMindlin", "viscous damping ratio", damping_ratio_, 0.0, 1.0,
                     Bounds::left_closed);
    require_in_range("dem::HertzMindlin", "reference overlap (fraction of the radius)",
                     reference_overlap_, 0.0, 1.0);
  }

  static void check_material(const Material& m, const std::string& where) {
    require_positive(where, "shear modulus G [Pa]", m.shear_modulus);
    require_in_range(where, "Poisson's ratio", m.poisson_ratio, -1.0, 0.5, Bounds::right_closed);
    require_non_negative(where, "friction coefficient mu", m.friction);
  }

  const Material& particle_material() const { return particle_; }
  Constants pair_constants() const { return combine(particle_, particle_, particle_.friction); }
  Constants wall_constants(const Material& wall) const {
    return combine(particle_, wall, wall.friction);
  }

  static double normal_coefficient(const Constants& k, double radius) {
    return 2.0 * k.shear_modulus * std::sqrt(2.0 * radius) / (3.0 * (1.0 - k.poisson_ratio));
  }
  static double shear_stiffness(const Constants& k, double radius, double normal_force) {
    const double nu = k.poisson_ratio;
    return 2.0 * std::cbrt(3.0 * k.shear_modulus * k.shear_modulus * (1.0 - nu) * radius) /
           (2.0 - nu) * std::cbrt(std::max(normal_force, 0.0));
  }

  static ContactForce force(const Constants& k, const ContactKinematics& c, ContactHistory& history,
                            double dt) {
    double& shear = history.shear;
    ContactForce f;
    const double root = std::sqrt(c.overlap);
    const double k_hat = normal_coefficient(k, c.effective_radius);
    const double elastic = k_hat * c.overlap * root;
    const double ks = shear_stiffness(k, c.effective_radius, elastic);
    f.normal = elastic;
    if (k.damping_ratio > 0.0) {
      const double kn = 1.5 * k_hat * root;
      f.normal -= 2.0 * k.damping_ratio * std::sqrt(kn * c.effective_mass) * c.normal_velocity;
      f.normal = std::max(f.normal, 0.0);
    }
    shear -= ks * c.tangential_velocity * dt;
    const double limit = k.friction * elastic;
    if (std::abs(shear) > limit) {
      shear = std::copysign(limit, shear);
      f.sliding = true;
    }
    f.shear = shear;
    if (k.damping_ratio > 0.0 && !f.sliding) {
      f.shear -= 2.0 * k.damping_ratio * std::sqrt(ks * c.effective_mass) * c.tangential_velocity;
    }
    return f;
  }

  static double normal_stiffness(const Constants& k, double overlap, double radius) {
    return 1.5 * normal_coefficient(k, radius) * std::sqrt(std::max(overlap, 0.0));
  }

  static double time_step_stiffness(const Constants& k, double radius) {
    const double overlap = k.reference_overlap * radius;
    const double k_hat = normal_coefficient(k, radius);
    const double normal_force = k_hat * overlap * std::sqrt(overlap);
    return 1.5 * k_hat * std::sqrt(overlap) + shear_stiffness(k, radius, normal_force);
  }

 private:
  Constants combine(const Material& a, const Material& b, double friction) const {
    Constants k;
    k.shear_modulus = 0.5 * (a.shear_modulus + b.shear_modulus);
    k.poisson_ratio = 0.5 * (a.poisson_ratio + b.poisson_ratio);
    k.friction = friction;
    k.damping_ratio = damping_ratio_;
    k.reference_overlap = reference_overlap_;
    return k;
  }

  Material particle_;
  double damping_ratio_;
  double reference_overlap_;
};

static_assert(check_contact_law<HertzMindlin>());

}  // namespace cosmpm::dem
