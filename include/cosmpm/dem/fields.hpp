#pragma once
// The DEM's typed fields. A body is a rigid particle (a disk, or a clump of disks) carrying
// the degrees of freedom; an element is one disk of a body, carrying the contact geometry.
// Labels are the HDF5 dataset names. The engine's own tags (position, velocity, mass, body)
// are reused where they mean the same thing.
#include <cstdint>

#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"

namespace cosmpm::dem::field {

struct Angle {  // rad, counter-clockwise rotation of the body from its template pose
  using value_type = double;
  static constexpr const char* label() { return "rotation"; }
};
struct Spin {  // rad/s, counter-clockwise
  using value_type = double;
  static constexpr const char* label() { return "spin"; }
};
struct Inertia {  // kg m^2 per m of thickness, about the centroid
  using value_type = double;
  static constexpr const char* label() { return "inertia"; }
};
struct Force {  // N per m of thickness: contacts plus gravity, before damping, last step
  using value_type = Vec<2>;
  static constexpr const char* label() { return "force"; }
};
struct Torque {  // N m per m of thickness about the centroid, before damping, last step
  using value_type = double;
  static constexpr const char* label() { return "torque"; }
};
struct FirstElement {  // the body's elements are [first, first + count)
  using value_type = std::int32_t;
  static constexpr const char* label() { return "first_element"; }
};
struct ElementCount {
  using value_type = std::int32_t;
  static constexpr const char* label() { return "element_count"; }
};
struct Radius {  // m
  using value_type = double;
  static constexpr const char* label() { return "radius"; }
};
struct Offset {  // element centre relative to the body centroid, in the body's template frame
  using value_type = Vec<2>;
  static constexpr const char* label() { return "offset"; }
};
struct BodyMass {  // the owning body's mass (viscous contact damping needs it per contact)
  using value_type = double;
  static constexpr const char* label() { return "body_mass"; }
};
struct ContactCount {  // active contacts of the element (other elements and walls), last step
  using value_type = std::int32_t;
  static constexpr const char* label() { return "contact_count"; }
};

}  // namespace cosmpm::dem::field

namespace cosmpm::dem {

namespace tag = particles::field;

// Bodies: the rigid degrees of freedom. Positions are centroids; velocities and spins are the
// leapfrog's half-step values (v at t - dt/2 after a step to t).
using BodyStore =
    particles::Store<tag::Position<2>, tag::InitialPosition<2>, tag::Velocity<2>, field::Angle,
                     field::Spin, tag::Mass, field::Inertia, field::Force, field::Torque,
                     field::FirstElement, field::ElementCount>;

// Elements: the disks. Position, velocity and spin are kept in step with their body's after
// every step, so the contact loops read elements only.
using ElementStore =
    particles::Store<tag::Position<2>, tag::Velocity<2>, field::Spin, field::Radius, tag::Body,
                     field::Offset, field::BodyMass, field::ContactCount>;

}  // namespace cosmpm::dem
