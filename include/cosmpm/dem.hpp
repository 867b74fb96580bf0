#pragma once
// The discrete element method: disks and rigid clumps of disks (2D, unit thickness, as PFC2D),
// contact laws and damping as policies, walls sharing contact::RigidBody's geometry, packing
// by raining, a servo-controlled biaxial test and the blade-stress estimate of Coetzee (2014).
// Needs only Eigen (and OpenMP if enabled). HDF5/XDMF frames: cosmpm/dem/hdf5_frames.hpp (link
// cosmpm::hdf5).
#include "cosmpm/dem/assembly.hpp"
#include "cosmpm/dem/biaxial.hpp"
#include "cosmpm/dem/blade_stress.hpp"
#include "cosmpm/dem/clump.hpp"
#include "cosmpm/dem/contact_law.hpp"
#include "cosmpm/dem/contact_lists.hpp"
#include "cosmpm/dem/damping.hpp"
#include "cosmpm/dem/fields.hpp"
#include "cosmpm/dem/hertz_mindlin.hpp"
#include "cosmpm/dem/linear_spring.hpp"
#include "cosmpm/dem/packing.hpp"
#include "cosmpm/dem/rolling_resistance.hpp"
#include "cosmpm/dem/simulation.hpp"
#include "cosmpm/dem/walls.hpp"
