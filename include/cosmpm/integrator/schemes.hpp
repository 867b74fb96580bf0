#pragma once
// The explicit update schemes, as tags the simulation dispatches on at compile time.
//   USF : stress updated from the grid velocity at the start of the step.
//   USL : stress updated at the end, from the new grid velocity (the paper's Appendix).
//   MUSL: USL, but the new particle momenta are mapped back to the grid and the strain rate
//         is computed from that smoothed velocity (Sulsky et al. 1994).
#include <concepts>

namespace cosmpm::integrator {

enum class Scheme { usf, usl, musl };

struct USF {
  static constexpr Scheme scheme = Scheme::usf;
  static constexpr const char* name() { return "USF"; }
};
struct USL {
  static constexpr Scheme scheme = Scheme::usl;
  static constexpr const char* name() { return "USL"; }
};
struct MUSL {
  static constexpr Scheme scheme = Scheme::musl;
  static constexpr const char* name() { return "MUSL"; }
};

template <class I>
concept Integrator = requires {
  { I::scheme } -> std::convertible_to<Scheme>;
  { I::name() } -> std::convertible_to<const char*>;
};

}  // namespace cosmpm::integrator
