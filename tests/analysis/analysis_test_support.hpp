#pragma once
// Particle stores of known shapes for the analysis tests: particles seeded like the engine
// seeds them (particles::seed_box / seed_polygon), with mass, volumes and initial positions.
#include <vector>

#include "cosmpm/continuum/particle_fields.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/particles/seeding.hpp"

namespace cosmpm::test {

using AnalysisStore = continuum::particle_store_with<2, material::MohrCoulomb<>>;

// Appends the seeded particles at rest, volume V, density rho (mass rho V), initial position
// equal to the position.
inline void append(AnalysisStore& store, const particles::Seeding<2>& seeding,
                   double density = 1000.0) {
  namespace field = particles::field;
  const Index first = store.append(static_cast<Index>(seeding.positions.size()));
  for (std::size_t i = 0; i < seeding.positions.size(); ++i) {
    const Index p = first + static_cast<Index>(i);
    store.get<field::Position<2>>()[p] = seeding.positions[i];
    store.get<field::InitialPosition<2>>()[p] = seeding.positions[i];
    store.get<field::Volume>()[p] = seeding.volume;
    store.get<field::InitialVolume>()[p] = seeding.volume;
    store.get<field::Mass>()[p] = density * seeding.volume;
    store.get<field::DeformationGradient<2>>()[p].setIdentity();
  }
}

inline AnalysisStore seeded(const particles::Seeding<2>& seeding, double density = 1000.0) {
  AnalysisStore store;
  append(store, seeding, density);
  return store;
}

}  // namespace cosmpm::test
