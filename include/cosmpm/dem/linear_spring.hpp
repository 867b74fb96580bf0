#pragma once
// The linear contact model of PFC2D with Coulomb friction and optional viscous dashpots.
//
// Each particle and wall has a normal and a shear stiffness (the paper's corn: k_n = k_s =
// 420 kN/m per particle); a contact's stiffness is the two in series, k = k_A k_B / (k_A +
// k_B), so two corn grains touch with 210 kN/m. Forces per metre of thickness:
//   F_n = k_n delta - c_n u_n,                    c_n = 2 beta_n sqrt(k_n m_eff)
//   F_s <- F_s - k_s u_t dt, |F_s| <= mu F_n^el,  then F_s - c_s u_t while not sliding
// (u_n < 0 while approaching, so the normal dashpot resists both approach and separation).
// With no_tension the total normal force is kept >= 0 (PFC's default for its dashpots).
// The friction coefficient is the particle's between particles and the WALL's against a wall
// (PFC takes the smaller of the two; the flat blade needs the corn-steel value).
#include <algorithm>
#include <cmath>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/dem/contact_law.hpp"

namespace cosmpm::dem {

// A particle's or a wall's springs and friction.
struct LinearSpringMaterial {
  double normal_stiffness = 420e3;  // N/m per m of thickness (Table 1)
  double shear_stiffness = 420e3;   // N/m
  double friction = 0.1;            // mu (Table 1: particle friction)
};

// Dashpots in parallel with the springs, as fractions of critical damping of the contact.
struct ViscousDamping {
  double normal_ratio = 0.0;  // beta_n, [0, 1)
  double shear_ratio = 0.0;   // beta_s, [0, 1)
  bool no_tension = true;     // keep the total normal force >= 0
};

class LinearSpring {
 public:
  using Material = LinearSpringMaterial;
  using ViscousDamping = dem::ViscousDamping;
  struct Constants {
    double normal_stiffness = 0.0;
    double shear_stiffness = 0.0;
    double friction = 0.0;
    double normal_ratio = 0.0;
    double shear_ratio = 0.0;
    bool no_tension = true;
  };

  explicit LinearSpring(Material particle = Material(), ViscousDamping damping = ViscousDamping())
      : particle_(particle), damping_(damping) {
    check_material(particle_, "dem::LinearSpring (particle)");
    require_in_range("dem::LinearSpring", "viscous normal damping ratio", damping_.normal_ratio,
                     0.0, 1.0, Bounds::left_closed);
    require_in_range("dem::LinearSpring", "viscous shear damping ratio", damping_.shear_ratio, 0.0,
                     1.0, Bounds::left_closed);
  }

  static void check_material(const Material& m, const std::string& where) {
    require_positive(where, "normal stiffness k_n [N/m]", m.normal_stiffness);
    require_positive(where, "shear stiffness k_s [N/m]", m.shear_stiffness);
    require_non_negative(where, "friction coefficient mu", m.friction);
  }

  const Material& particle_material() const { return particle_; }
  const ViscousDamping& viscous_damping() const { return damping_; }

  Constants pair_constants() const { return combine(particle_, particle_, particle_.friction); }
  Constants wall_constants(const Material& wall) const {
    return combine(particle_, wall, wall.friction);
  }

  static ContactForce force(const Constants& k, const ContactKinematics& c, ContactHistory& history,
                            double dt) {
    double& shear = history.shear;
    ContactForce f;
    const double elastic = k.normal_stiffness * c.overlap;
    f.normal = elastic;
    if (k.normal_ratio > 0.0) {
      f.normal -= 2.0 * k.normal_ratio * std::sqrt(k.normal_stiffness * c.effective_mass) *
                  c.normal_velocity;
      if (k.no_tension) f.normal = std::max(f.normal, 0.0);
    }
    shear -= k.shear_stiffness * c.tangential_velocity * dt;
    const double limit = k.friction * elastic;
    if (std::abs(shear) > limit) {
      shear = std::copysign(limit, shear);
      f.sliding = true;
    }
    f.shear = shear;
    if (k.shear_ratio > 0.0 && !f.sliding) {
      f.shear -= 2.0 * k.shear_ratio * std::sqrt(k.shear_stiffness * c.effective_mass) *
                 c.tangential_velocity;
    }
    return f;
  }

  static double time_step_stiffness(const Constants& k, double /*radius*/) {
    return k.normal_stiffness + k.shear_stiffness;
  }
  // The normal stiffness at an overlap (for laws built on this one, e.g. rolling resistance).
  static double normal_stiffness(const Constants& k, double /*overlap*/, double /*radius*/) {
    return k.normal_stiffness;
  }

 private:
  Constants combine(const Material& a, const Material& b, double friction) const {
    Constants k;
    k.normal_stiffness =
        a.normal_stiffness * b.normal_stiffness / (a.normal_stiffness + b.normal_stiffness);
    k.shear_stiffness =
        a.shear_stiffness * b.shear_stiffness / (a.shear_stiffness + b.shear_stiffness);
    k.friction = friction;
    k.normal_ratio = damping_.normal_ratio;
    k.shear_ratio = damping_.shear_ratio;
    k.no_tension = damping_.no_tension;
    return k;
  }

  Material particle_;
  ViscousDamping damping_;
};

static_assert(check_contact_law<LinearSpring>());

}  // namespace cosmpm::dem
