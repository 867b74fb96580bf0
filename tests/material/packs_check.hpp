#pragma once
// A model's update_packs (material::HasPacksUpdate) against its update_batch, bit for bit: the
// hook's contract. Shared by the portable material tests (packs of the target's width, 2 with
// SSE2) and the host-width tests (tests/native, 4 with AVX).
#include <array>
#include <cstddef>
#include <cstring>
#include <span>
#include <vector>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/material/concept.hpp"

namespace packs_check {

template <class T>
bool same_bits(const T& a, const T& b) {
  return std::memcmp(&a, &b, sizeof(T)) == 0;
}

// The points [0, packs W) of the arrays, in packs of W by component, through update_packs, and
// the same points through update_batch; returns how many points differ in any bit of the stress
// or the state. The arrays are copied.
template <int W, class Model>
std::size_t packs_differences(const Model& model,
                              const std::vector<typename Model::stress_type>& stress,
                              const std::vector<typename Model::state_type>& state,
                              const std::vector<typename Model::strain_type>& increment,
                              std::size_t packs) {
  static_assert(cosmpm::material::HasPacksUpdate<Model, W>);
  constexpr int n = Model::stress_type::SizeAtCompileTime;
  using Packs = std::array<cosmpm::Pack<W>, n>;
  const std::size_t count = packs * W;
  std::vector<typename Model::stress_type> batch_stress(stress.begin(), stress.begin() + count);
  std::vector<typename Model::state_type> batch_state(state.begin(), state.begin() + count);
  model.update_batch(std::span(batch_stress), std::span(batch_state),
                     std::span(increment.data(), count));

  std::vector<Packs> stress_packs(packs), increment_packs(packs);
  for (std::size_t k = 0; k < packs; ++k) {
    for (int c = 0; c < n; ++c) {
      for (int l = 0; l < W; ++l) {
        stress_packs[k][c][l] = stress[k * W + l][c];
        increment_packs[k][c][l] = increment[k * W + l][c];
      }
    }
  }
  std::vector<typename Model::state_type> packs_state(state.begin(), state.begin() + count);
  model.template update_packs<W>(std::span(stress_packs), std::span<const Packs>(increment_packs),
                                 packs_state.data());
  std::size_t differing = 0;
  for (std::size_t i = 0; i < count; ++i) {
    bool same = same_bits(packs_state[i], batch_state[i]);
    for (int c = 0; c < n; ++c) {
      const double lane = stress_packs[i / W][c][static_cast<int>(i % W)];
      same = same && same_bits(lane, batch_stress[i][c]);
    }
    differing += same ? 0 : 1;
  }
  return differing;
}

// The engine's points come in space order, so its packs are mostly all elastic or all plastic;
// random points mostly mix them. This sorts the second half of `points` (members stress, state,
// increment) by update()'s plastic flag, which leaves runs of both kinds there and the mix in
// the first half, and returns how many packs of W are all elastic, all plastic and mixed.
template <int W, class Model, class Points>
std::array<int, 3> sort_second_half(const Model& model, Points& points) {
  const std::size_t count = points.stress.size();
  std::vector<double> plastic(count);
  for (std::size_t i = 0; i < count; ++i) {
    auto s = points.stress[i];
    auto st = points.state[i];
    model.update(s, st, points.increment[i]);
    plastic[i] = st.plastic;
  }
  Points sorted = points;
  std::size_t next = count / 2;
  for (const double flag : {0.0, 1.0}) {
    for (std::size_t i = count / 2; i < count; ++i) {
      if (plastic[i] != flag) continue;
      sorted.stress[next] = points.stress[i];
      sorted.state[next] = points.state[i];
      sorted.increment[next] = points.increment[i];
      ++next;
    }
  }
  points = sorted;
  std::vector<double> sorted_flag(plastic.begin(), plastic.begin() + count / 2);
  for (const double flag : {0.0, 1.0}) {
    for (std::size_t i = count / 2; i < count; ++i) {
      if (plastic[i] == flag) sorted_flag.push_back(flag);
    }
  }
  std::array<int, 3> kinds{};  // all elastic, all plastic, mixed
  for (std::size_t k = 0; k + W <= count; k += W) {
    int plastic_lanes = 0;
    for (int l = 0; l < W; ++l) plastic_lanes += sorted_flag[k + l] == 1.0 ? 1 : 0;
    ++kinds[plastic_lanes == 0 ? 0 : (plastic_lanes == W ? 1 : 2)];
  }
  return kinds;
}

}  // namespace packs_check
