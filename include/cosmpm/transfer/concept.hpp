#pragma once
// The velocity transfer between particles and grid: how a particle's velocity field is mapped
// to the grid and back. The engine implements the transfers; a policy selects one and says
// what it needs:
//   static const char* name()
//   static constexpr bool affine    the particle carries an affine velocity field
//                                   v_p + C_p (x - x_p) (C_p = B_p D_p^-1, field::AffineMoment
//                                   holds B_p), which the
//                                   particle-to-grid map spreads and the grid-to-particle map
//                                   sets (APIC); false: one velocity per particle (PIC/FLIP)
//   template <int Dim> using fields a particles::Store tag list the transfer adds
#include <concepts>
#include <tuple>

namespace cosmpm::transfer {

template <class T>
concept VelocityTransfer = requires {
  { T::name() } -> std::convertible_to<const char*>;
  { T::affine } -> std::convertible_to<bool>;
};

}  // namespace cosmpm::transfer
