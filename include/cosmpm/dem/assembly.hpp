#pragma once
// The particles of a DEM model: bodies (rigid degrees of freedom) and their elements (disks),
// in two structure-of-arrays stores. 2D disks have unit thickness (PFC2D): a mass is
// density * area * 1 m, and every force is per metre of thickness.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/clump.hpp"
#include "cosmpm/dem/fields.hpp"

namespace cosmpm::dem {

class Assembly {
 public:
  BodyStore& bodies() { return bodies_; }
  const BodyStore& bodies() const { return bodies_; }
  ElementStore& elements() { return elements_; }
  const ElementStore& elements() const { return elements_; }
  Index body_count() const { return bodies_.size(); }
  Index element_count() const { return elements_.size(); }

  // Body b's state (convenience; the stores hold the arrays).
  const Vec<2>& position(Index b) const { return bodies_.get<tag::Position<2>>()[at(b)]; }
  const Vec<2>& velocity(Index b) const { return bodies_.get<tag::Velocity<2>>()[at(b)]; }
  double angle(Index b) const { return bodies_.get<field::Angle>()[at(b)]; }
  double spin(Index b) const { return bodies_.get<field::Spin>()[at(b)]; }
  double mass(Index b) const { return bodies_.get<tag::Mass>()[at(b)]; }
  double inertia(Index b) const { return bodies_.get<field::Inertia>()[at(b)]; }

  // Changes whenever bodies are added or removed: contact lists built before are stale.
  std::uint64_t revision() const { return revision_; }

  // A disk of `radius` at `centre`.
  Index add_disk(const Vec<2>& centre, double radius, double density,
                 const Vec<2>& velocity = Vec<2>::Zero(), double spin = 0.0) {
    const char* where = "dem::Assembly::add_disk";
    require_positive(where, "radius", radius);
    require_positive(where, "density", density);
    const double mass = density * pi * radius * radius;
    return add_body(where, centre, 0.0, velocity, spin, mass, 0.5 * mass * radius * radius,
                    {{Vec<2>::Zero(), radius}}, 1.0);
  }

  // A clump of `shape` scaled by `scale`, centroid at `centroid`, rotated by `angle` (rad).
  Index add_clump(const ClumpShape& shape, double scale, const Vec<2>& centroid, double angle,
                  double density, const Vec<2>& velocity = Vec<2>::Zero(), double spin = 0.0) {
    const char* where = "dem::Assembly::add_clump";
    require_positive(where, "scale", scale);
    require_positive(where, "density", density);
    require(std::isfinite(angle), std::string(where) + ": the angle must be finite");
    const double mass = density * shape.area() * scale * scale;
    const double inertia = density * shape.polar_moment() * std::pow(scale, 4);
    return add_body(where, centroid, angle, velocity, spin, mass, inertia, shape.members(), scale);
  }

  // Removes the bodies for which `remove(body)` is true (and their elements); the others keep
  // their order. Returns how many were removed.
  template <class Predicate>
  Index remove_bodies_if(Predicate remove) {
    std::vector<char> gone(static_cast<std::size_t>(body_count()));
    for (Index b = 0; b < body_count(); ++b) gone[static_cast<std::size_t>(b)] = remove(b) ? 1 : 0;
    BodyStore bodies;
    ElementStore elements;
    Index removed = 0;
    for (Index b = 0; b < body_count(); ++b) {
      if (gone[static_cast<std::size_t>(b)] != 0) {
        ++removed;
        continue;
      }
      const Index nb = bodies.append(1);
      copy_row(bodies_, b, bodies, nb);
      const auto first = bodies_.get<field::FirstElement>()[static_cast<std::size_t>(b)];
      const auto count = bodies_.get<field::ElementCount>()[static_cast<std::size_t>(b)];
      bodies.get<field::FirstElement>()[static_cast<std::size_t>(nb)] =
          static_cast<std::int32_t>(elements.size());
      for (std::int32_t e = first; e < first + count; ++e) {
        const Index ne = elements.append(1);
        copy_row(elements_, e, elements, ne);
        elements.get<tag::Body>()[static_cast<std::size_t>(ne)] = static_cast<std::int32_t>(nb);
      }
    }
    bodies_ = std::move(bodies);
    elements_ = std::move(elements);
    ++revision_;
    return removed;
  }

  // The largest and smallest element radius (0 when empty).
  double max_radius() const {
    const auto& r = elements_.get<field::Radius>();
    return r.empty() ? 0.0 : *std::max_element(r.begin(), r.end());
  }
  double min_radius() const {
    const auto& r = elements_.get<field::Radius>();
    return r.empty() ? 0.0 : *std::min_element(r.begin(), r.end());
  }

  // Sets every body's initial position to its current one (displacements count from now).
  void reset_initial_positions() {
    bodies_.get<tag::InitialPosition<2>>() = bodies_.get<tag::Position<2>>();
  }

  // Recomputes the elements' positions, velocities and spins from their bodies'.
  void sync_elements() {
    const auto& xb = bodies_.get<tag::Position<2>>();
    const auto& vb = bodies_.get<tag::Velocity<2>>();
    const auto& theta = bodies_.get<field::Angle>();
    const auto& omega = bodies_.get<field::Spin>();
    const auto& offset = elements_.get<field::Offset>();
    const auto& body = elements_.get<tag::Body>();
    auto& xe = elements_.get<tag::Position<2>>();
    auto& ve = elements_.get<tag::Velocity<2>>();
    auto& we = elements_.get<field::Spin>();
    for (std::size_t e = 0; e < xe.size(); ++e) {
      const auto b = static_cast<std::size_t>(body[e]);
      const double c = std::cos(theta[b]), s = std::sin(theta[b]);
      const Vec<2> r(c * offset[e][0] - s * offset[e][1], s * offset[e][0] + c * offset[e][1]);
      xe[e] = xb[b] + r;
      ve[e] = vb[b] + omega[b] * Vec<2>(-r[1], r[0]);
      we[e] = omega[b];
    }
  }

 private:
  static std::size_t at(Index i) { return static_cast<std::size_t>(i); }

  template <class Store>
  static void copy_row(const Store& from, Index i, Store& to, Index j) {
    [&]<class... Tags>(std::tuple<Tags...>*) {
      ((to.template get<Tags>()[static_cast<std::size_t>(j)] =
            from.template get<Tags>()[static_cast<std::size_t>(i)]),
       ...);
    }(static_cast<typename Store::tags*>(nullptr));
  }

  Index add_body(const char* where, const Vec<2>& centroid, double angle, const Vec<2>& velocity,
                 double spin, double mass, double inertia, const std::vector<ClumpMember>& members,
                 double scale) {
    require(centroid.allFinite(), std::string(where) + ": the position must be finite");
    require(velocity.allFinite() && std::isfinite(spin),
            std::string(where) + ": the velocity and spin must be finite");
    if (body_count() >= static_cast<Index>(INT32_MAX) ||
        element_count() + static_cast<Index>(members.size()) >= static_cast<Index>(INT32_MAX)) {
      throw Error(std::string(where) + ": more than 2^31 - 1 bodies or elements");
    }
    const Index b = bodies_.append(1);
    const auto ub = static_cast<std::size_t>(b);
    bodies_.get<tag::Position<2>>()[ub] = centroid;
    bodies_.get<tag::InitialPosition<2>>()[ub] = centroid;
    bodies_.get<tag::Velocity<2>>()[ub] = velocity;
    bodies_.get<field::Angle>()[ub] = angle;
    bodies_.get<field::Spin>()[ub] = spin;
    bodies_.get<tag::Mass>()[ub] = mass;
    bodies_.get<field::Inertia>()[ub] = inertia;
    bodies_.get<field::FirstElement>()[ub] = static_cast<std::int32_t>(element_count());
    bodies_.get<field::ElementCount>()[ub] = static_cast<std::int32_t>(members.size());
    const double c = std::cos(angle), s = std::sin(angle);
    for (const ClumpMember& member : members) {
      const auto ue = static_cast<std::size_t>(elements_.append(1));
      const Vec<2> o = scale * member.offset;
      const Vec<2> r(c * o[0] - s * o[1], s * o[0] + c * o[1]);
      elements_.get<tag::Position<2>>()[ue] = centroid + r;
      elements_.get<tag::Velocity<2>>()[ue] = velocity + spin * Vec<2>(-r[1], r[0]);
      elements_.get<field::Spin>()[ue] = spin;
      elements_.get<field::Radius>()[ue] = scale * member.radius;
      elements_.get<tag::Body>()[ue] = static_cast<std::int32_t>(b);
      elements_.get<field::Offset>()[ue] = o;
      elements_.get<field::BodyMass>()[ue] = mass;
    }
    ++revision_;
    return b;
  }

  BodyStore bodies_;
  ElementStore elements_;
  std::uint64_t revision_ = 0;
};

}  // namespace cosmpm::dem
