#pragma once
// The particle fields every continuum carries, plus whatever a continuum adds.
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/store.hpp"

namespace cosmpm::continuum {

template <int Dim, class Model, class... Extra>
using particle_store_with =
    particles::Store<particles::field::Position<Dim>, particles::field::InitialPosition<Dim>,
                     particles::field::Velocity<Dim>, particles::field::Mass,
                     particles::field::Volume, particles::field::InitialVolume,
                     particles::field::HalfWidth<Dim>, particles::field::VelocityGradient<Dim>,
                     particles::field::DeformationGradient<Dim>, particles::field::Body,
                     particles::field::Stress<Model>, particles::field::Strain<Model>,
                     particles::field::MaterialState<Model>, Extra...>;

}  // namespace cosmpm::continuum
