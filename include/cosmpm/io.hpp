#pragma once
// Input and output: HDF5 frames with XDMF indexes for ParaView, CSV series, checkpoints, a
// progress line, command-line and case-file options, run folders and stop requests. Needs
// HDF5 (link cosmpm::hdf5); without it, include the headers other than io/hdf5*.hpp and
// io/checkpoint.hpp one by one.
#include "cosmpm/io/atomic_file.hpp"
#include "cosmpm/io/checkpoint.hpp"
#include "cosmpm/io/csv.hpp"
#include "cosmpm/io/field_layout.hpp"
#include "cosmpm/io/frame_layout.hpp"
#include "cosmpm/io/hdf5.hpp"
#include "cosmpm/io/options.hpp"
#include "cosmpm/io/progress.hpp"
#include "cosmpm/io/run_directory.hpp"
#include "cosmpm/io/stop_request.hpp"
#include "cosmpm/io/xdmf.hpp"
