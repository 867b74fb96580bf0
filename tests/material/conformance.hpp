#pragma once
// The conformance kit of the constitutive models: the contract of material/concept.hpp checked
// on sample steps, for any model. Every model's tests call it:
//
//   const auto report = conformance::check_constitutive_model(model, elastic, steps,
//   tangent_steps); CHECK_MESSAGE(report.passed(), report.summary());
//
// What it checks, on every step (old stress, state, strain increment):
//   one path     update() with and without the tangent give the same stress and state, bit for
//                bit;
//   elastic      a step the model calls elastic returns the elastic trial of `elastic` (the
//                model's elastic part as a model of its own) bit for bit, keeps the plastic
//                strain and gives the elastic tangent; that trial lies inside the yield surface;
//                and `elastic` itself agrees with old + D de;
//   yield        a plastic step starts outside the yield surface and ends on it (|f| <= tol of
//                the stress scale); no step ends outside; the plastic strain does not decrease;
//   isotropy     rotating the old stress and the increment rotates the new stress (random
//                rotations: about z for plane strain, any for 3D);
//   packed       update_values on packs of 1, 2 and the engine's width (HasPackedUpdate) equals
//                update() lane by lane, bit for bit;
//   batched      material::update_batch over all steps and over runs of many sizes, and the
//                model's own update_batch (HasBatchUpdate), equal update() bit for bit, or within
//                the model's declared batch_rounding; spans of different sizes throw;
//   packs        update_packs at width 2 and the engine's (HasPacksUpdate), the rest of the
//                steps through update_batch, likewise;
// and on the tangent steps (one per return region, chosen by the caller away from region
// boundaries): the consistent tangent against central differences of update().
//
// It reports instead of asserting, so a test can also show that it catches a broken model. The
// steps, their random generation (random_steps) and the rotations are in sample_steps.hpp.
#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <random>
#include <span>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/pack.hpp"
#include "cosmpm/material/concept.hpp"
#include "sample_steps.hpp"

namespace cosmpm::material::conformance {

struct Options {
  double stress_scale = 1e3;          // Pa: the smallest stress scale of the yield checks
  double yield_tolerance = 1e-10;     // |f| / stress scale on the surface
  double rotation_tolerance = 1e-10;  // relative, rotated result against rotated stress
  double strain_tolerance = 1e-8;     // relative, the plastic strain of the rotated step
  double tangent_tolerance = 1e-6;    // against central differences, max norm, relative to
                                      // the larger tangent or the elastic stiffness
  double fd_relative_step = 1e-6;     // of the largest increment component
  unsigned seed = 1;                  // of the random rotations
};

struct Report {
  std::size_t steps = 0, elastic = 0, plastic = 0, rotations = 0, tangents = 0;
  std::size_t packed_lanes = 0, batch_points = 0;
  double batch_max_difference = 0.0;  // relative, of update_batch from update()
  std::size_t failure_count = 0;
  std::vector<std::string> failures;  // the first of each kind (the text before " at step")

  bool passed() const { return failure_count == 0; }
  void fail(const std::string& what) {
    ++failure_count;
    const std::string kind = what.substr(0, what.find(" at step"));
    for (const auto& f : failures)
      if (f.compare(0, kind.size(), kind) == 0) return;
    if (failures.size() < 20) failures.push_back(what);
  }
  std::string summary() const {
    std::ostringstream out;
    out << steps << " steps (" << elastic << " elastic, " << plastic << " plastic), " << rotations
        << " rotations, " << tangents << " tangents, " << packed_lanes << " packed lanes, "
        << batch_points << " batch points (max relative difference " << batch_max_difference
        << "); " << failure_count << " failures";
    for (const auto& f : failures) out << "\n  " << f;
    return out.str();
  }
};

namespace detail {

template <class A, class B>
double relative_difference(const A& a, const B& b) {
  const double scale = std::max(a.cwiseAbs().maxCoeff(), b.cwiseAbs().maxCoeff());
  return (a - b).cwiseAbs().maxCoeff() / std::max(scale, 1e-300);
}

template <class S>
bool same_state(const S& a, const S& b) {
  return a.values() == b.values();
}

// Central differences of update() in the increment.
template <class M>
typename M::tangent_type finite_difference_tangent(const M& model, const Step<M>& step,
                                                   double relative_step) {
  typename M::tangent_type tangent;
  const double h = relative_step * std::max(step.increment.cwiseAbs().maxCoeff(), 1e-12);
  for (int j = 0; j < step.increment.size(); ++j) {
    typename M::strain_type plus = step.increment, minus = step.increment;
    plus[j] += h;
    minus[j] -= h;
    typename M::stress_type s_plus = step.old, s_minus = step.old;
    typename M::state_type st_plus = step.state, st_minus = step.state;
    model.update(s_plus, st_plus, plus);
    model.update(s_minus, st_minus, minus);
    tangent.col(j) = (s_plus - s_minus) / (2 * h);
  }
  return tangent;
}

// update_values on packs of W points against update() point by point.
template <int W, class M>
void check_packed(const M& model, std::span<const Step<M>> steps, Report& report) {
  using P = Pack<W>;
  constexpr std::size_t n = static_cast<std::size_t>(M::stress_type::RowsAtCompileTime);
  if constexpr (HasPackedUpdate<M, P>) {
    for (std::size_t i = 0; i + W <= steps.size(); i += W) {
      std::array<P, n> s, d;
      for (std::size_t c = 0; c < n; ++c) {
        s[c] = make_pack<W>([&](int l) { return steps[i + l].old[c]; });
        d[c] = make_pack<W>([&](int l) { return steps[i + l].increment[c]; });
      }
      model.update_values(s, d);
      for (int l = 0; l < W; ++l) {
        typename M::stress_type expected = steps[i + l].old;
        typename M::state_type state = steps[i + l].state;
        model.update(expected, state, steps[i + l].increment);
        for (std::size_t c = 0; c < n; ++c) {
          if (lane<W>(s[c], l) != expected[c]) {
            report.fail("packed (W = " + std::to_string(W) + ") differs from update() at step " +
                        std::to_string(i + l));
            break;
          }
        }
        ++report.packed_lanes;
      }
    }
  }
}

// A batch update over steps [first, first + count) against update() point by point.
template <class M, class Batch>
void check_batch(const M& model, std::span<const Step<M>> steps, std::size_t first,
                 std::size_t count, const Batch& batch, const char* name, Report& report) {
  std::vector<typename M::stress_type> stress, expected;
  std::vector<typename M::state_type> state, expected_state;
  std::vector<typename M::strain_type> increment;
  for (std::size_t i = first; i < first + count; ++i) {
    stress.push_back(steps[i].old);
    state.push_back(steps[i].state);
    increment.push_back(steps[i].increment);
  }
  expected = stress;
  expected_state = state;
  for (std::size_t i = 0; i < count; ++i)
    model.update(expected[i], expected_state[i], increment[i]);
  batch(std::span(stress), std::span(state), std::span<const typename M::strain_type>(increment));
  constexpr double allowed = batch_rounding<M>;
  for (std::size_t i = 0; i < count; ++i) {
    const double stress_difference =
        (stress[i] - expected[i]).norm() / std::max(expected[i].norm(), 1e-300);
    double state_difference = 0.0;
    const auto a = state[i].values(), b = expected_state[i].values();
    for (std::size_t k = 0; k < a.size(); ++k)
      state_difference =
          std::max(state_difference, std::abs(a[k] - b[k]) / std::max(std::abs(b[k]), 1e-300));
    if constexpr (plastic_state<M>) {
      if (state[i].plastic != expected_state[i].plastic) state_difference = 1.0;
    }
    const double difference = std::max(stress_difference, state_difference);
    report.batch_max_difference = std::max(report.batch_max_difference, difference);
    const bool equal = allowed == 0.0
                           ? (stress[i] == expected[i] && same_state(state[i], expected_state[i]))
                           : difference <= allowed;
    if (!equal) {
      std::ostringstream out;
      out << name << " differs from update() at step " << first + i << " by " << difference
          << " (allowed " << allowed << ")";
      report.fail(out.str());
    }
    ++report.batch_points;
  }
}

// update_packs (HasPacksUpdate) at width W as a batch update: the whole packs through it, the
// rest through update_batch.
template <int W, class M>
void check_packs(const M& model, std::span<const Step<M>> steps, std::size_t first,
                 std::size_t count, Report& report) {
  if constexpr (HasPacksUpdate<M, W>) {
    using Packs = std::array<Pack<W>, static_cast<std::size_t>(M::stress_type::SizeAtCompileTime)>;
    const auto through_packs = [&](auto stress, auto state, auto increment) {
      const std::size_t packs = stress.size() / W;
      std::vector<Packs> s(packs), d(packs);
      for (std::size_t k = 0; k < packs; ++k) {
        for (std::size_t c = 0; c < s[k].size(); ++c) {
          for (int l = 0; l < W; ++l) {
            s[k][c][l] = stress[k * W + l][c];
            d[k][c][l] = increment[k * W + l][c];
          }
        }
      }
      model.template update_packs<W>(std::span(s), std::span<const Packs>(d), state.data());
      for (std::size_t k = 0; k < packs; ++k) {
        for (std::size_t c = 0; c < s[k].size(); ++c) {
          for (int l = 0; l < W; ++l) stress[k * W + l][c] = s[k][c][l];
        }
      }
      const std::size_t done = packs * W;
      model.update_batch(stress.subspan(done), state.subspan(done), increment.subspan(done));
    };
    check_batch(model, steps, first, count, through_packs, "update_packs", report);
  }
}

}  // namespace detail

template <class M, class Elastic>
Report check_constitutive_model(const M& model, const Elastic& elastic,
                                std::span<const Step<std::type_identity_t<M>>> steps,
                                std::span<const Step<std::type_identity_t<M>>> tangent_steps,
                                const Options& options = {}) {
  static_assert(ConstitutiveModel<M> && HasConsistentTangent<M>);
  static_assert(std::is_same_v<typename Elastic::stress_type, typename M::stress_type>);
  constexpr int n = M::stress_type::RowsAtCompileTime;
  using Stress = typename M::stress_type;
  using State = typename M::state_type;
  Report report;
  std::mt19937_64 rng(options.seed);
  const auto scale_of = [&](const Stress& s) {
    return std::max(s.cwiseAbs().maxCoeff(), options.stress_scale);
  };
  const auto where = [](const char* what, std::size_t i) {
    return std::string(what) + " at step " + std::to_string(i);
  };
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const Step<M>& step = steps[i];
    ++report.steps;
    Stress stress = step.old;
    State state = step.state;
    model.update(stress, state, step.increment);
    // One path: with the tangent, the same stress and state.
    Stress with_tangent = step.old;
    State tangent_state = step.state;
    typename M::tangent_type tangent;
    model.update(with_tangent, tangent_state, step.increment, tangent);
    if (!(with_tangent == stress) || !detail::same_state(state, tangent_state))
      report.fail(where("update() with the tangent differs from update()", i));
    // The elastic trial, by the model's elastic part, and that part against old + D de.
    Stress trial = step.old;
    typename Elastic::state_type elastic_state{};
    elastic.update(trial, elastic_state, step.increment);
    const Stress by_matrix = step.old + elastic.elastic_tangent() * step.increment;
    if (detail::relative_difference(trial, by_matrix) > 1e-12)
      report.fail(where("the elastic part differs from old + D de", i));
    bool plastic = false;
    if constexpr (detail::plastic_state<M>) plastic = state.plastic == 1.0;
    if (!plastic) {
      ++report.elastic;
      if (!(stress == trial)) report.fail(where("an elastic step is not the elastic trial", i));
      if (!(tangent == model.elastic_tangent()))
        report.fail(where("an elastic step's tangent is not the elastic tangent", i));
      if constexpr (detail::plastic_state<M>) {
        if (state.plastic_shear_strain != step.state.plastic_shear_strain)
          report.fail(where("an elastic step changed the plastic strain", i));
      }
      if constexpr (detail::has_yield<M>) {
        if (model.yield_function(trial) > options.yield_tolerance * scale_of(trial))
          report.fail(where("a trial outside the yield surface was taken as elastic", i));
      }
    } else {
      ++report.plastic;
      if constexpr (detail::has_yield<M>) {
        const double f = model.yield_function(stress) / scale_of(stress);
        if (std::abs(f) > options.yield_tolerance)
          report.fail(where("a plastic step ended off the yield surface", i) + " (f / scale " +
                      std::to_string(f) + ")");
        if (model.yield_function(trial) < -options.yield_tolerance * scale_of(trial))
          report.fail(where("a trial inside the yield surface was returned", i));
      }
      if constexpr (detail::plastic_state<M>) {
        if (!(state.plastic_shear_strain >= step.state.plastic_shear_strain))
          report.fail(where("the plastic strain decreased", i));
      }
    }
    if constexpr (detail::has_yield<M>) {
      if (model.yield_function(stress) > options.yield_tolerance * scale_of(stress))
        report.fail(where("a step ended outside the yield surface", i));
    }
    // Isotropy.
    const Eigen::Matrix3d r = random_rotation<n>(rng);
    Stress turned = rotated(step.old, r);
    State turned_state = step.state;
    model.update(turned, turned_state, rotated(step.increment, r));
    ++report.rotations;
    if (detail::relative_difference(turned, rotated(stress, r)) > options.rotation_tolerance)
      report.fail(where("rotating the step does not rotate the result", i));
    if constexpr (detail::plastic_state<M>) {
      if (turned_state.plastic != state.plastic ||
          std::abs(turned_state.plastic_shear_strain - state.plastic_shear_strain) >
              options.strain_tolerance * std::max(std::abs(state.plastic_shear_strain), 1e-300))
        report.fail(where("the rotated step has another plastic state", i));
    }
  }
  // The consistent tangent against central differences.
  for (std::size_t i = 0; i < tangent_steps.size(); ++i) {
    const Step<M>& step = tangent_steps[i];
    Stress stress = step.old;
    State state = step.state;
    typename M::tangent_type tangent;
    model.update(stress, state, step.increment, tangent);
    const auto numeric = detail::finite_difference_tangent(model, step, options.fd_relative_step);
    ++report.tangents;
    // Relative to the larger of the two and the elastic stiffness: a tangent that is zero (the
    // apex) meets differences of rounding noise divided by the step.
    const double scale = std::max({tangent.cwiseAbs().maxCoeff(), numeric.cwiseAbs().maxCoeff(),
                                   model.elastic_tangent().cwiseAbs().maxCoeff()});
    const double difference = (tangent - numeric).cwiseAbs().maxCoeff() / scale;
    if (difference > options.tangent_tolerance) {
      std::ostringstream out;
      out << "tangent step " << i << ": the consistent tangent differs from finite differences by "
          << difference;
      report.fail(out.str());
    }
  }
  // Packed and batched updates against update().
  detail::check_packed<1>(model, steps, report);
  detail::check_packed<2>(model, steps, report);
  if constexpr (pack_width > 2) detail::check_packed<pack_width>(model, steps, report);
  const auto free_batch = [&](auto s, auto st, auto d) { update_batch(model, s, st, d); };
  detail::check_batch(model, steps, 0, steps.size(), free_batch, "material::update_batch", report);
  std::size_t first = 0;
  for (const std::size_t count : {0, 1, 2, 3, 5, 7, 8, 9, 63, 64, 65, 127, 128, 129, 257}) {
    if (first + count > steps.size()) break;
    detail::check_batch(model, steps, first, count, free_batch, "material::update_batch", report);
    first += count;
  }
  if constexpr (HasBatchUpdate<M>) {
    const auto member = [&](auto s, auto st, auto d) { model.update_batch(s, st, d); };
    detail::check_batch(model, steps, 0, steps.size(), member, "update_batch", report);
  }
  detail::check_packs<2>(model, steps, 0, steps.size(), report);
  if constexpr (pack_width > 2)
    detail::check_packs<pack_width>(model, steps, 0, steps.size(), report);
  // Spans of different sizes throw before anything is written.
  if (steps.size() >= 2) {
    std::vector<Stress> stress{steps[0].old, steps[1].old};
    std::vector<State> state{steps[0].state};
    std::vector<typename M::strain_type> increment{steps[0].increment, steps[1].increment};
    bool threw = false;
    try {
      update_batch(model, std::span(stress), std::span(state),
                   std::span<const typename M::strain_type>(increment));
    } catch (const Error&) {
      threw = true;
    }
    if (!threw || !(stress[0] == steps[0].old))
      report.fail("material::update_batch with spans of different sizes did not throw cleanly");
  }
  return report;
}

}  // namespace cosmpm::material::conformance
