#pragma once
// Shape functions: the 1D kernels and their tensor-product stencil.
#include "cosmpm/shape/concept.hpp"
#include "cosmpm/shape/cubic_bspline.hpp"
#include "cosmpm/shape/gimp.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/shape/separable.hpp"
#include "cosmpm/shape/stencil.hpp"
#include "cosmpm/shape/stencil_grid.hpp"
#include "cosmpm/shape/transfer.hpp"
