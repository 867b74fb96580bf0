#pragma once
// Geostatic (at-rest) initial stress of a horizontal soil layer, tension positive, with the
// vertical the last axis (y in 2D, z in 3D):
//   2D:  sigma_yy = -rho g depth,  sigma_xx = sigma_zz = K0 sigma_yy,  no shear;
//   3D:  sigma_zz = -rho g depth,  sigma_xx = sigma_yy = K0 sigma_zz,  no shear;
// with Jaky's K0 = 1 - sin(phi) by default (the paper initialises its layer this way).
#include <cmath>
#include <limits>
#include <string>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/material/stress_space.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::initial {

// Jaky's coefficient of earth pressure at rest, K0 = 1 - sin(phi); phi in degrees, (0, 90).
inline double jaky_k0(double friction_angle_deg) {
  require_in_range("jaky_k0", "friction_angle_deg", friction_angle_deg, 0.0, 90.0);
  return 1.0 - std::sin(degrees_to_radians(friction_angle_deg));
}

// Stress at `depth` (m, >= 0) below the free surface: density (kg/m^3, > 0), gravity (m/s^2,
// the magnitude, > 0), k0 (>= 0).
template <class T = double>
SymTensor2D<T> geostatic_stress(T density, T gravity, T depth, T k0) {
  require_positive("geostatic_stress", "density", static_cast<double>(density));
  require_positive("geostatic_stress", "gravity", static_cast<double>(gravity));
  require_non_negative("geostatic_stress", "depth", static_cast<double>(depth));
  require_non_negative("geostatic_stress", "k0", static_cast<double>(k0));
  const T vertical = -density * gravity * depth;
  return SymTensor2D<T>(k0 * vertical, vertical, k0 * vertical, T(0));
}

// The 3D stress at `depth` below the free surface, z up: the same checks and numbers as
// geostatic_stress, with both horizontal axes at K0 (order of material/stress_space.hpp).
template <class T = double>
material::SymmetricTensor<3, T> geostatic_stress_3d(T density, T gravity, T depth, T k0) {
  const SymTensor2D<T> s = geostatic_stress<T>(density, gravity, depth, k0);
  material::SymmetricTensor<3, T> out;
  out << s[0], s[0], s[1], T(0), T(0), T(0);
  return out;
}

// The Cosserat variant: the same force stresses (s_xy = s_yx = 0) and no couple stresses, which
// is an equilibrium state of the layer since nothing varies horizontally.
template <class T = double>
CosseratTensor2D<T> geostatic_cosserat_stress(T density, T gravity, T depth, T k0) {
  const SymTensor2D<T> s = geostatic_stress<T>(density, gravity, depth, k0);
  CosseratTensor2D<T> out;
  out << s[0], s[1], s[2], 0, 0, 0, 0;
  return out;
}

// Sets every particle of a classical simulation (2D or 3D) to the geostatic stress of a layer
// whose free surface is at height `surface` on the last axis: depth = surface - x_last, the
// particle's density m / V, gravity from the simulation's parameters, which must point down the
// last axis (its other components zero). A particle above the surface is an error.
template <class Sim>
void set_geostatic_stress(Sim& sim, double surface, double k0) {
  constexpr int Dim = Sim::dim;
  static_assert(!Sim::is_cosserat,
                "initial::set_geostatic_stress: classical continua (for the Cosserat one use "
                "geostatic_cosserat_stress per particle)");
  const Vec<Dim>& g = sim.parameters().gravity;
  for (int d = 0; d + 1 < Dim; ++d) {
    if (g[d] != 0.0) {
      throw Error("initial::set_geostatic_stress: gravity component " + std::to_string(d) + " = " +
                  detail::format_number(g[d]) +
                  " must be 0 (valid: gravity along the last axis only, from "
                  "SimulationParameters::gravity)");
    }
  }
  require_in_range("initial::set_geostatic_stress", "gravity along the last axis", g[Dim - 1],
                   -std::numeric_limits<double>::infinity(), 0.0, Bounds::open);
  namespace field = particles::field;
  auto& store = sim.particles();
  const auto& x = store.template get<field::Position<Dim>>();
  const auto& mass = store.template get<field::Mass>();
  const auto& volume = store.template get<field::Volume>();
  auto& stress = store.template get<field::Stress<typename Sim::model_type>>();
  for (Index p = 0; p < store.size(); ++p) {
    const double depth = surface - x[p][Dim - 1];
    if (depth < 0.0) {
      throw Error("initial::set_geostatic_stress: particle " + std::to_string(p) + " at height " +
                  detail::format_number(x[p][Dim - 1]) + " lies above the surface " +
                  detail::format_number(surface) + " (valid: depth = surface - height >= 0)");
    }
    const double density = mass[p] / volume[p];
    if constexpr (Dim == 2) {
      stress[p] = geostatic_stress(density, -g[1], depth, k0);
    } else {
      stress[p] = geostatic_stress_3d(density, -g[2], depth, k0);
    }
  }
}

}  // namespace cosmpm::initial
