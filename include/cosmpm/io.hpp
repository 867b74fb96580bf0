#pragma once
// Output and restart: HDF5 frames with an XDMF index for ParaView, CSV time series,
// checkpoints and a progress line. Needs HDF5 (link cosmpm::hdf5).
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/xdmf.hpp"
