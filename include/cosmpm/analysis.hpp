#pragma once
// Umbrella header of the analysis layer: reference solutions and post-processing.
#include "cosmpm/analysis/earth_pressure.hpp"
#include "cosmpm/analysis/sokolovski.hpp"
