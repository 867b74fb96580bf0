#pragma once
// What a DEM contact law is: a policy type that turns the kinematics of one contact into a
// normal and a shear force (and optionally a rolling moment), carrying its history in a
// ContactHistory: the elastic shear force (PFC's incremental shear spring; in 2D the tangent
// turns with the normal, so a scalar along t is the shear force rotated with the contact) and
// the elastic rolling moment. The engine calls it for particle-particle and particle-wall
// contacts alike; constants are combined once per contact kind, never per contact.
//
// Conventions at a contact between A and B (A is the wall for a wall contact):
//   n points from A to B, t = (-n_y, n_x); u is the velocity of B's contact point minus A's.
//   ContactForce::normal is compression positive and acts on B along +n (on A along -n);
//   ContactForce::shear acts on B along +t (on A along -t);
//   ContactForce::rolling_moment acts on B (counter-clockwise positive), its opposite on A.
#include <concepts>
#include <type_traits>

namespace cosmpm::dem {

struct ContactKinematics {
  double overlap = 0.0;              // m, > 0 in contact
  double normal_velocity = 0.0;      // m/s, u.n: negative while the bodies approach
  double tangential_velocity = 0.0;  // m/s, u.t at the contact point
  double effective_mass = 0.0;       // kg/m: m_A m_B / (m_A + m_B), or m_B against a wall
  double effective_radius = 0.0;     // m: 2 r_A r_B / (r_A + r_B), or r_B against a wall (PFC)
  double relative_spin = 0.0;        // rad/s: omega_B - omega_A
};

// What a contact remembers from step to step.
struct ContactHistory {
  double shear = 0.0;    // N/m: elastic shear force on B along t
  double rolling = 0.0;  // N m/m: elastic rolling moment on B
};

struct ContactForce {
  double normal = 0.0;          // N/m, compression positive
  double shear = 0.0;           // N/m, on B along t
  double rolling_moment = 0.0;  // N m/m, on B
  bool sliding = false;
};

// A contact law: a Material per particle kind and per wall, Constants for one kind of contact,
// a force evaluation, and the stiffness the critical time step must respect.
template <class Law>
concept ContactLaw = requires(const Law& law, const typename Law::Material& wall,
                              const typename Law::Constants& constants,
                              const ContactKinematics& kinematics, ContactHistory& history,
                              double dt) {
  { law.particle_material() } -> std::convertible_to<const typename Law::Material&>;
  { law.pair_constants() } -> std::same_as<typename Law::Constants>;
  { law.wall_constants(wall) } -> std::same_as<typename Law::Constants>;
  {Law::check_material(wall, "where")};
  { Law::force(constants, kinematics, history, dt) } -> std::same_as<ContactForce>;
  // (k_n + k_s) of one contact for a particle of radius r: the time-step estimate sums it.
  { Law::time_step_stiffness(constants, dt) } -> std::convertible_to<double>;
};

// Names what is missing when a type is not a contact law.
template <class Law>
constexpr bool check_contact_law() {
  static_assert(
      requires { typename Law::Material; },
      "dem::ContactLaw: the law needs a nested Material type (per particle or wall)");
  static_assert(
      requires { typename Law::Constants; },
      "dem::ContactLaw: the law needs a nested Constants type (per kind of contact)");
  static_assert(ContactLaw<Law>,
                "dem::ContactLaw: the law needs particle_material(), pair_constants(), "
                "wall_constants(Material), static check_material(Material, where), static "
                "force(Constants, ContactKinematics, ContactHistory&, double dt) -> ContactForce "
                "and static time_step_stiffness(Constants, double radius)");
  return true;
}

}  // namespace cosmpm::dem
