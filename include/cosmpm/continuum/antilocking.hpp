#pragma once
// How a classical continuum forms the volumetric part of its strain rate, against volumetric
// locking: with linear shape functions and a few particles per cell, nearly isochoric flow
// (elasticity near nu = 1/2, plastic flow at small dilatancy) over-constrains the velocity
// field and the material stiffens (Coombs, Charlton, Cortis and Augarde 2018).
//   antilocking::None  each particle's own velocity gradient (the default);
//   antilocking::FBar  F-bar in rate form: each particle's volumetric strain rate is replaced
//                      by the volume-weighted average over the particles of its cell (the cell
//                      that held it at the start of the step), the deviatoric part kept:
//                        L_p <- L_p + (div_c - tr L_p) / Dim I,
//                        div_c = sum_{q in c} V_q tr L_q / sum_{q in c} V_q;
//                      the stress update and the deformation gradient take the averaged L_p,
//                      so det F follows the cell's average volume change. A point whose
//                      grains have come apart (state.separation > 0) keeps its own rate and
//                      stays out of the mean: its gap is not the packing's volume change.
// The engine applies it as a stage before the stress update (stages/stress_update.hpp).

namespace cosmpm::antilocking {

struct None {
  static constexpr const char* name() { return "none"; }
  static constexpr bool averages_volume = false;
};

struct FBar {
  static constexpr const char* name() { return "F-bar (cell-averaged volumetric strain rate)"; }
  static constexpr bool averages_volume = true;
};

}  // namespace cosmpm::antilocking
