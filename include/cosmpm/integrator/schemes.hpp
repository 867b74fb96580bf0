#pragma once
// The explicit update schemes the library offers, each a type composing the engine's stages
// (integrator/concept.hpp):
//   USF : stress updated from the grid velocity at the start of the step.
//   USL : stress updated at the end, from the new grid velocity (the paper's Appendix).
//   MUSL: USL, but the new particle momenta are mapped back to the grid and the strain rate
//         is computed from that smoothed velocity (Sulsky et al. 1994).
//   FusedUSL, FusedMUSL: USL and MUSL with the next step's particle-to-grid map in the pass
//         that ends the step (integrator/fused.hpp).
#include "cosmpm/integrator/concept.hpp"
#include "cosmpm/integrator/fused.hpp"
#include "cosmpm/integrator/musl.hpp"
#include "cosmpm/integrator/usf.hpp"
#include "cosmpm/integrator/usl.hpp"
