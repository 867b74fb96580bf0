#pragma once
// Shared set-ups of the engine's verification tests.
#include <cmath>
#include <vector>

#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"

namespace cosmpm::test {

using Elastic = material::LinearElastic<double>;
using ElasticContinuum = continuum::Classical<Elastic>;

template <class Sim>
double kinetic_energy(const Sim& sim) {
  const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  double energy = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) energy += 0.5 * m[p] * v[p].squaredNorm();
  return energy;
}

// Linear elastic strain energy 1/2 sigma : eps V (stress starts at zero in these tests).
template <class Sim>
double strain_energy(const Sim& sim) {
  const auto& s = sim.particles().template get<particles::field::Stress<Elastic>>();
  const auto& e = sim.particles().template get<particles::field::Strain<Elastic>>();
  const auto& vol = sim.particles().template get<particles::field::Volume>();
  double energy = 0.0;
  for (Index p = 0; p < sim.particles().size(); ++p) {
    const double work =
        s[p][0] * e[p][0] + s[p][1] * e[p][1] + s[p][2] * e[p][2] + 2.0 * s[p][3] * e[p][3];
    energy += 0.5 * work * vol[p];
  }
  return energy;
}

template <class Sim>
Vec<2> total_momentum(const Sim& sim) {
  const auto& v = sim.particles().template get<particles::field::Velocity<2>>();
  const auto& m = sim.particles().template get<particles::field::Mass>();
  Vec<2> momentum = Vec<2>::Zero();
  for (Index p = 0; p < sim.particles().size(); ++p) momentum += m[p] * v[p];
  return momentum;
}

// Estimates the period of a signal sampled at uniform dt from its upward zero crossings
// (linear interpolation between samples), averaged over all full periods seen.
inline double period_from_zero_crossings(const std::vector<double>& signal, double dt) {
  std::vector<double> crossings;
  for (std::size_t i = 1; i < signal.size(); ++i) {
    if (signal[i - 1] < 0.0 && signal[i] >= 0.0) {
      const double fraction = -signal[i - 1] / (signal[i] - signal[i - 1]);
      crossings.push_back((static_cast<double>(i - 1) + fraction) * dt);
    }
  }
  if (crossings.size() < 2) return std::nan("");
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

}  // namespace cosmpm::test
