#pragma once
// The PIC/FLIP blend (the paper's Eq. 18 at SimulationParameters::flip_fraction = 1):
//   v_p <- alpha (v_p + dt sum_i N_ip a_i) + (1 - alpha) sum_i N_ip v_i,
// alpha = flip_fraction; FLIP keeps the particles' velocity detail and with it their noise,
// PIC damps both.
#include "cosmpm/transfer/concept.hpp"

namespace cosmpm::transfer {

struct FlipBlend {
  static constexpr const char* name() { return "PIC/FLIP blend"; }
  static constexpr bool affine = false;
};

static_assert(VelocityTransfer<FlipBlend>);

}  // namespace cosmpm::transfer
