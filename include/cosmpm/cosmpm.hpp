#pragma once
// Everything in cosmpm that needs only Eigen (and OpenMP if enabled). The HDF5 parts,
// cosmpm/io/hdf5.hpp and cosmpm/io/checkpoint.hpp (or cosmpm/io.hpp), are included on their
// own and link the cosmpm::hdf5 target.
#include "cosmpm/analysis.hpp"
#include "cosmpm/contact.hpp"
#include "cosmpm/continuum/classical.hpp"
#include "cosmpm/continuum/cosserat.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/boundary.hpp"
#include "cosmpm/grid/grid.hpp"
#include "cosmpm/initial/geostatic.hpp"
#include "cosmpm/integrator/schemes.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/xdmf.hpp"
#include "cosmpm/material.hpp"
#include "cosmpm/particles/fields.hpp"
#include "cosmpm/particles/seeding.hpp"
#include "cosmpm/particles/store.hpp"
#include "cosmpm/shape.hpp"
#include "cosmpm/simulation.hpp"
#include "cosmpm/version.hpp"
