#pragma once
// The compositions of the engine this program is built with, chosen at run time by
// --material, --shape and --integrator: each is one type behind a std::variant, and the run
// of each is compiled once, in the run_*.cpp file of its model (ninja builds them side by
// side). The library stays free of run-time choices.
//
// Built in: the default method (linear shape functions, MUSL, PIC/FLIP, no anti-locking) with
// each model; every shape function with MUSL; every integrator with linear shape functions,
// fused MUSL included: 7 per model; and for the nonpolar models APIC (quadratic B-splines, MUSL)
// and F-bar (linear, MUSL): 25 in all. Each costs about 11 s of compile time (the example went from
// 24 to 215 s of CPU with 18, docs/usage.md), so the full product is not built; another composition
// is one line in CompositionsOf and one in a run_*.cpp file.
#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>

#include "case.hpp"
#include "cosmpm/continuum/antilocking.hpp"
#include "cosmpm/integrator/schemes.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/shape/cubic_bspline.hpp"
#include "cosmpm/shape/gimp.hpp"
#include "cosmpm/shape/linear.hpp"
#include "cosmpm/shape/quadratic_bspline.hpp"
#include "cosmpm/transfer/apic.hpp"
#include "cosmpm/transfer/flip_blend.hpp"

namespace cosmpm::io {
class Options;
class RunDirectory;
class StopRequest;
}  // namespace cosmpm::io

namespace flat_blade {

template <class Kernel, class Scheme, class Model, class Transfer = cosmpm::transfer::FlipBlend,
          class AntiLocking = cosmpm::antilocking::None>
struct Composition {
  using kernel = Kernel;
  using scheme = Scheme;
  using model = Model;
  using transfer = Transfer;
  using antilocking = AntiLocking;
};

using MohrCoulomb = cosmpm::material::MohrCoulomb<>;
using DruckerPrager = cosmpm::material::DruckerPrager<>;
using CosseratDruckerPrager = cosmpm::material::CosseratDruckerPrager<>;
namespace shape = cosmpm::shape;
namespace integrator = cosmpm::integrator;
namespace transfer = cosmpm::transfer;
namespace antilocking = cosmpm::antilocking;

template <class Model>
using CompositionsOf = std::variant<Composition<shape::Linear, integrator::MUSL, Model>,
                                    Composition<shape::Linear, integrator::USL, Model>,
                                    Composition<shape::Linear, integrator::USF, Model>,
                                    Composition<shape::Linear, integrator::FusedMUSL, Model>,
                                    Composition<shape::GIMP, integrator::MUSL, Model>,
                                    Composition<shape::QuadraticBSpline, integrator::MUSL, Model>,
                                    Composition<shape::CubicBSpline, integrator::MUSL, Model>>;
// The transfer and anti-locking policies, with the nonpolar models.
template <class Model>
using MethodsOf = std::variant<
    Composition<shape::QuadraticBSpline, integrator::MUSL, Model, transfer::APIC>,
    Composition<shape::Linear, integrator::MUSL, Model, transfer::FlipBlend, antilocking::FBar>>;

template <class... A, class... B, class... C, class... D, class... E>
auto join(std::variant<A...>, std::variant<B...>, std::variant<C...>, std::variant<D...>,
          std::variant<E...>) -> std::variant<A..., B..., C..., D..., E...>;

using AnyComposition = decltype(join(CompositionsOf<MohrCoulomb>{}, CompositionsOf<DruckerPrager>{},
                                     CompositionsOf<CosseratDruckerPrager>{},
                                     MethodsOf<MohrCoulomb>{}, MethodsOf<DruckerPrager>{}));

// The option values that name each policy.
template <class T>
constexpr const char* option_name() {
  if constexpr (std::is_same_v<T, shape::Linear>) return "linear";
  if constexpr (std::is_same_v<T, shape::GIMP>) return "gimp";
  if constexpr (std::is_same_v<T, shape::QuadraticBSpline>) return "quadratic-bspline";
  if constexpr (std::is_same_v<T, shape::CubicBSpline>) return "cubic-bspline";
  if constexpr (std::is_same_v<T, integrator::USL>) return "usl";
  if constexpr (std::is_same_v<T, integrator::MUSL>) return "musl";
  if constexpr (std::is_same_v<T, integrator::USF>) return "usf";
  if constexpr (std::is_same_v<T, integrator::FusedMUSL>) return "fused-musl";
  if constexpr (std::is_same_v<T, MohrCoulomb>) return "mohr-coulomb";
  if constexpr (std::is_same_v<T, DruckerPrager>) return "drucker-prager";
  if constexpr (std::is_same_v<T, CosseratDruckerPrager>) return "cosserat-drucker-prager";
  if constexpr (std::is_same_v<T, transfer::FlipBlend>) return "flip-blend";
  if constexpr (std::is_same_v<T, transfer::APIC>) return "apic";
  if constexpr (std::is_same_v<T, antilocking::None>) return "none";
  if constexpr (std::is_same_v<T, antilocking::FBar>) return "fbar";
}

// The options that choose a composition, as given on the command line.
struct CompositionNames {
  const char* material;
  const char* shape;
  const char* integrator;
  const char* transfer;
  const char* antilocking;

  std::string text() const {
    return std::string("--material ") + material + " --shape " + shape + " --integrator " +
           integrator + " --transfer " + transfer + " --antilocking " + antilocking;
  }
  bool chosen_by(const Case& c) const {
    return c.material == material && c.shape == shape && c.integrator == integrator &&
           c.transfer == transfer && c.antilocking == antilocking;
  }
};

template <class C>
CompositionNames names_of() {
  return {option_name<typename C::model>(), option_name<typename C::kernel>(),
          option_name<typename C::scheme>(), option_name<typename C::transfer>(),
          option_name<typename C::antilocking>()};
}

// Calls f(std::in_place_index<I>, names) for each composition.
template <class F>
void for_each_composition(F&& f) {
  [&]<std::size_t... I>(std::index_sequence<I...>) {
    (f(std::in_place_index<I>, names_of<std::variant_alternative_t<I, AnyComposition>>()), ...);
  }
  (std::make_index_sequence<std::variant_size_v<AnyComposition>>{});
}

// One line per composition built in, as the options that choose it.
inline std::string compositions_text() {
  std::string text;
  for_each_composition([&](auto, const CompositionNames& names) { text += "\n  " + names.text(); });
  return text;
}

// The composition the case asks for; an Error listing those built in if there is none.
inline AnyComposition find_composition(const Case& c) {
  std::optional<AnyComposition> found;
  for_each_composition([&](auto index, const CompositionNames& names) {
    if (!found && names.chosen_by(c)) found.emplace(index);
  });
  if (!found) {
    const CompositionNames asked{c.material.c_str(), c.shape.c_str(), c.integrator.c_str(),
                                 c.transfer.c_str(), c.antilocking.c_str()};
    throw cosmpm::Error(asked.text() +
                        " is not among the compositions built into this program (add it in "
                        "examples/03_flat_blade/compositions.hpp); built in:" +
                        compositions_text());
  }
  return *found;
}

// What a run reports back.
struct Outcome {
  double average_draft_per_width = 0.0;     // N/m over [average_from, average_to]
  double average_vertical_per_width = 0.0;  // N/m
  double sokolovski_per_width = 0.0;
  double sokolovski_vertical_per_width = 0.0;
  double run_seconds = 0.0;  // of this session
  long steps = 0;
  long particles = 0;
  double time_step = 0.0;
  bool stopped = false;      // by SIGINT or SIGTERM; a checkpoint was written
  bool checked = false;      // --check: the case was checked, nothing run or written
  double travel = 0.0;       // blade travel reached, m
  long stray_particles = 0;  // that left the rig (--stray-particles freeze or remove)
  double stray_mass = 0.0;   // kg/m
  // At the end: particles inside the blade or behind its front face, below its top, which
  // the blade passed over instead of pushing (the paper's fixed floor holds the bottom cell).
  long overrun_particles = 0;
  double overrun_mass = 0.0;  // kg/m
  // At the end, polar runs: the largest Cosserat rotation |omega_3| (rad) and couple stress
  // |(m_31, m_32)| (N/m) over the particles.
  double max_rotation = 0.0;
  double max_couple_stress = 0.0;
  long separated_particles = 0;  // at the end, points whose grains are apart (--separation)
};

// What the run needs from main: the options (for messages and the run's parameters), the
// output folder (opened only once the case is known to be feasible) and the stop request.
struct RunContext {
  const cosmpm::io::Options& options;
  std::string parameters;  // the settings as a case file
  std::function<cosmpm::io::RunDirectory&()> open_folder;
  const cosmpm::io::StopRequest& stop;
};

// The run of one composition: compiled in run_<model>_*.cpp.
template <class Kernel, class Scheme, class Model, class Transfer, class AntiLocking>
Outcome run(const Case& c, RunContext& context,
            Composition<Kernel, Scheme, Model, Transfer, AntiLocking>);

}  // namespace flat_blade
