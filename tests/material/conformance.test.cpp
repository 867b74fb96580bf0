// The conformance kit catches what it is for: models broken in one way each fail the check that
// names that way, and only checks of that kind.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <span>
#include <string>
#include <type_traits>
#include <vector>

#include "conformance.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"

using cosmpm::SymTensor2D;
using namespace cosmpm::material;
namespace conformance = cosmpm::material::conformance;

namespace {

constexpr double kE = 2.76e6, kNu = 0.2;  // corn, the paper's Table 1

enum class Flaw {
  none,
  anisotropic,   // an extra xx stiffness, in the model's own elastic law too
  packed,        // update_values one ulp off
  batched,       // update_batch one ulp off at every 100th point
  tangent_path,  // update() with the tangent one ulp off
  elastic_step,  // an elastic step moved by one ulp
  off_surface,   // the plastic return stops halfway
  tangent,       // the elastic tangent where the consistent one belongs
};

// A model (LinearElastic or MohrCoulomb) with one flaw.
template <class Base, Flaw flaw>
struct Broken {
  using scalar_type = double;
  using stress_type = typename Base::stress_type;
  using strain_type = typename Base::strain_type;
  using state_type = typename Base::state_type;
  using tangent_type = typename Base::tangent_type;
  static constexpr bool is_cosserat = false;
  Base base;

  double p_wave_modulus() const { return base.p_wave_modulus(); }
  double shear_modulus() const { return base.shear_modulus(); }
  double yield_function(const stress_type& s) const requires requires { base.yield_function(s); }
  { return base.yield_function(s); }
  tangent_type elastic_tangent() const {
    tangent_type d = base.elastic_tangent();
    if (flaw == Flaw::anisotropic) d(0, 0) *= 1.01;
    return d;
  }
  void update(stress_type& stress, state_type& state, const strain_type& de) const {
    const stress_type old = stress;
    base.update(stress, state, de);
    if constexpr (flaw == Flaw::anisotropic)
      stress[0] += 0.01 * base.elastic_tangent()(0, 0) * de[0];
    bool plastic = false;
    if constexpr (requires { state.plastic; }) plastic = state.plastic == 1.0;
    if (flaw == Flaw::elastic_step && !plastic) stress[1] = next(stress[1]);
    if (flaw == Flaw::off_surface && plastic) {
      stress_type trial = old;
      NoState none;
      LinearElastic<double>(kE, kNu).update(trial, none, de);
      stress = 0.5 * (stress + trial);
    }
  }
  void update(stress_type& stress, state_type& state, const strain_type& de,
              tangent_type& tangent) const {
    stress_type unused = stress;
    state_type unused_state = state;
    base.update(unused, unused_state, de, tangent);
    update(stress, state, de);
    bool plastic = false;
    if constexpr (requires { state.plastic; }) plastic = state.plastic == 1.0;
    if (flaw == Flaw::anisotropic || !plastic) tangent = elastic_tangent();
    if (flaw == Flaw::tangent_path) stress[2] = next(stress[2]);
    if (flaw == Flaw::tangent) tangent = elastic_tangent();
  }
  template <class Stress, class Increment>
  void update_values(Stress& stress, const Increment& de) const requires requires {
    base.update_values(stress, de);
  }
  {
    base.update_values(stress, de);
    if constexpr (flaw == Flaw::packed) stress[3] += 1e-9 * stress[3];
  }
  void update_batch(std::span<stress_type> stress, std::span<state_type> state,
                    std::span<const strain_type> increment) const requires(flaw == Flaw::batched) {
    require_equal_batch_sizes("Broken::update_batch", stress.size(), state.size(),
                              increment.size());
    for (std::size_t i = 0; i < stress.size(); ++i) {
      update(stress[i], state[i], increment[i]);
      if (i % 100 == 99) stress[i][0] = next(stress[i][0]);
    }
  }
  static double next(double x) { return std::nextafter(x, std::numeric_limits<double>::max()); }
};

}  // namespace

namespace {

// The kit's failures for a model with `flaw`, and whether one of them names `expected`.
template <class Base, Flaw flaw>
conformance::Report check(const Base& base) {
  const Broken<Base, flaw> model{base};
  const auto steps = conformance::random_steps(model, 600, 3, 5e3, 1e-3);
  // Tangent steps: one elastic, one on the yield plane (for MohrCoulomb; a trial of kPa).
  const SymTensor2D<double> old(-2e3, -1.5e3, -1.8e3, 300);
  const double g = base.shear_modulus();
  const double lambda = base.p_wave_modulus() - 2 * g;
  const auto increment_to = [&](const SymTensor2D<double>& trial) {
    const SymTensor2D<double> d = trial - old;
    const double mean = (d[0] + d[1] + d[2]) / 3, bulk = lambda + 2 * g / 3;
    return SymTensor2D<double>(mean / (3 * bulk) + (d[0] - mean) / (2 * g),
                               mean / (3 * bulk) + (d[1] - mean) / (2 * g),
                               mean / (3 * bulk) + (d[2] - mean) / (2 * g), d[3] / (2 * g));
  };
  const std::vector<conformance::Step<Broken<Base, flaw>>> tangent_steps{
      {old, {}, increment_to({-20e3, -21e3, -10e3, 0})},
      {old, {}, increment_to({-10e3, -40e3, -20e3, 2e3})}};
  if constexpr (std::is_same_v<Base, LinearElastic<double>>) {
    return conformance::check_constitutive_model(model, model, steps, tangent_steps);
  } else {
    return conformance::check_constitutive_model(model, LinearElastic<double>(kE, kNu), steps,
                                                 tangent_steps);
  }
}

bool names(const conformance::Report& report, const std::string& expected) {
  for (const auto& failure : report.failures)
    if (failure.find(expected) != std::string::npos) return true;
  return false;
}

}  // namespace

TEST_CASE("The conformance kit passes sound models and names the flaw of broken ones") {
  const LinearElastic<double> elastic(kE, kNu);
  const MohrCoulomb<double> plastic(kE, kNu, 26.0, 2.0);
  const auto sound_elastic = check<LinearElastic<double>, Flaw::none>(elastic);
  const auto sound_plastic = check<MohrCoulomb<double>, Flaw::none>(plastic);
  CHECK_MESSAGE(sound_elastic.passed(), sound_elastic.summary());
  CHECK_MESSAGE(sound_plastic.passed(), sound_plastic.summary());
  CHECK(sound_elastic.packed_lanes > 0);  // the wrapper forwards the packed hook
  CHECK(sound_plastic.plastic > 100);

  const auto anisotropic = check<LinearElastic<double>, Flaw::anisotropic>(elastic);
  CHECK_MESSAGE(names(anisotropic, "rotating the step does not rotate the result"),
                anisotropic.summary());
  const auto packed = check<LinearElastic<double>, Flaw::packed>(elastic);
  CHECK_MESSAGE(names(packed, "packed (W = 2) differs from update()"), packed.summary());
  const auto batched = check<MohrCoulomb<double>, Flaw::batched>(plastic);
  CHECK_MESSAGE(names(batched, "update_batch differs from update()"), batched.summary());
  const auto tangent_path = check<MohrCoulomb<double>, Flaw::tangent_path>(plastic);
  CHECK_MESSAGE(names(tangent_path, "update() with the tangent differs from update()"),
                tangent_path.summary());
  const auto elastic_step = check<MohrCoulomb<double>, Flaw::elastic_step>(plastic);
  CHECK_MESSAGE(names(elastic_step, "an elastic step is not the elastic trial"),
                elastic_step.summary());
  const auto off_surface = check<MohrCoulomb<double>, Flaw::off_surface>(plastic);
  CHECK_MESSAGE(names(off_surface, "a plastic step ended off the yield surface"),
                off_surface.summary());
  const auto tangent = check<MohrCoulomb<double>, Flaw::tangent>(plastic);
  CHECK_MESSAGE(names(tangent, "the consistent tangent differs from finite differences"),
                tangent.summary());
}
