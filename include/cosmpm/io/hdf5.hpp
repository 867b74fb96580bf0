#pragma once
// HDF5 output: the file API (io/hdf5_file.hpp) and the frame writer with its XDMF index for
// ParaView (io/hdf5_frames.hpp). Needs HDF5: link the CMake target cosmpm::hdf5.
#include "cosmpm/io/hdf5_file.hpp"
#include "cosmpm/io/hdf5_frames.hpp"
