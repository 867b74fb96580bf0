#pragma once
// Shared set-ups of the contact tests: an elastic block on the real engine (linear kernel,
// USL) next to rigid bodies.
#include <cmath>
#include <vector>

#include "cosmpm/contact.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace cosmpm::test {

using Elastic = material::LinearElastic<double>;
using ElasticContinuum = continuum::Classical<Elastic>;
template <class Kernel = shape::Linear, class Scheme = integrator::USL>
using RigidSimOf = Simulation<2, Kernel, ElasticContinuum, contact::RigidContact<2>, Scheme>;
using RigidSim = RigidSimOf<>;

// Soft enough for a large time step, stiff enough that elastic strains stay below 1e-3 in
// these set-ups: E = 1 MPa, nu = 0.3, rho = 1000 kg/m^3 (p-wave speed 36.7 m/s).
inline constexpr double youngs_modulus = 1e6;
inline constexpr double poisson_ratio = 0.3;
inline constexpr double density = 1000.0;

// Adds particles at rest, explicitly (the store zeroes new Eigen entries since the contact
// work; before, add_particles left the velocity uninitialised).
template <class Sim>
void add_at_rest(Sim& sim, const particles::Seeding<Sim::dim>& seeding) {
  const Index first =
      sim.add_particles(seeding.positions, seeding.volume, density, seeding.half_width);
  auto& v = sim.particles().template get<particles::field::Velocity<Sim::dim>>();
  for (Index p = first; p < sim.particles().size(); ++p) v[p].setZero();
}

template <class Sim>
Vec<Sim::dim> centre_of_mass(const Sim& sim) {
  const auto& x = sim.particles().template get<particles::field::Position<Sim::dim>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  Vec<Sim::dim> sum = Vec<Sim::dim>::Zero();
  double mass = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    sum += m[p] * x[p];
    mass += m[p];
  }
  return sum / mass;
}

template <class Sim>
Vec<Sim::dim> momentum(const Sim& sim) {
  const auto& v = sim.particles().template get<particles::field::Velocity<Sim::dim>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  Vec<Sim::dim> sum = Vec<Sim::dim>::Zero();
  for (Index p = 0; p < sim.particles().size(); ++p) sum += m[p] * v[p];
  return sum;
}

template <class Sim>
double total_mass(const Sim& sim) {
  double mass = 0.0;
  for (double m : sim.particles().template get<particles::field::Mass>()) mass += m;
  return mass;
}

// |value - expected| <= tolerance * |expected| (doctest's Approx adds an absolute 1.0 to its
// scale, too loose for values of order one).
inline bool within_relative(double value, double expected, double tolerance) {
  return std::abs(value - expected) <= tolerance * std::abs(expected);
}

// Least-squares slope of y(t).
inline double fitted_slope(const std::vector<double>& t, const std::vector<double>& y) {
  double tm = 0.0;
  double ym = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    tm += t[i];
    ym += y[i];
  }
  tm /= static_cast<double>(t.size());
  ym /= static_cast<double>(t.size());
  double sty = 0.0;
  double stt = 0.0;
  for (std::size_t i = 0; i < t.size(); ++i) {
    sty += (t[i] - tm) * (y[i] - ym);
    stt += (t[i] - tm) * (t[i] - tm);
  }
  return sty / stt;
}

// Smallest signed distance of any particle centre from the body (negative: a centre inside).
template <class Sim>
double closest_particle_distance(const Sim& sim, const contact::RigidBody<Sim::dim>& body) {
  const auto& x = sim.particles().template get<particles::field::Position<Sim::dim>>();
  double smallest = INFINITY;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    smallest = std::min(smallest, body.signed_distance(x[p]));
  }
  return smallest;
}

}  // namespace cosmpm::test
