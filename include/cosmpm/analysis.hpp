#pragma once
// Umbrella header of the analysis layer: reference solutions and post-processing. The
// post-processing functions read a particle store or a Simulation and return plain data.
#include "cosmpm/analysis/displacement_ratio.hpp"
#include "cosmpm/analysis/earth_pressure.hpp"
#include "cosmpm/analysis/energy.hpp"
#include "cosmpm/analysis/flow_front.hpp"
#include "cosmpm/analysis/free_surface.hpp"
#include "cosmpm/analysis/height_profile.hpp"
#include "cosmpm/analysis/layers.hpp"
#include "cosmpm/analysis/mass.hpp"
#include "cosmpm/analysis/shear_strain_intensity.hpp"
#include "cosmpm/analysis/sokolovski.hpp"
#include "cosmpm/analysis/yield_map.hpp"
