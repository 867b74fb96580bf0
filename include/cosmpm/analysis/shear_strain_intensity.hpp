#pragma once
// The shear-strain intensity of Coetzee (2014), Sect. 3.3 and Fig. 13 (nonpolar MPM):
//   J' = [(e_xx - e_yy)^2 + e_yy^2 + e_xx^2] / 6 + e_xy^2,
// with e the accumulated strain and e_xy its tensor (not engineering) shear component. It is
// the second invariant of the deviatoric strain of a plane-strain point with e_zz = 0; it is
// a squared strain (no unit). Pure shear e_xy = g gives g^2; uniaxial strain e_xx = e gives
// e^2 / 3.
#include <span>
#include <type_traits>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/particles/fields.hpp"

namespace cosmpm::analysis {

// J' of one plane-strain strain [xx, yy, zz, xy] (zz is not used: the paper's formula).
inline double shear_strain_intensity(const SymTensor2D<double>& strain) {
  const double xx = strain[0];
  const double yy = strain[1];
  const double xy = strain[3];
  return ((xx - yy) * (xx - yy) + yy * yy + xx * xx) / 6.0 + xy * xy;
}

inline std::vector<double> shear_strain_intensity(std::span<const SymTensor2D<double>> strains) {
  std::vector<double> intensity(strains.size());
  for (std::size_t p = 0; p < strains.size(); ++p)
    intensity[p] = shear_strain_intensity(strains[p]);
  return intensity;
}

// J' of every particle of a classical (nonpolar) simulation.
template <class Sim>
requires requires {
  typename Sim::model_type;
}
std::vector<double> shear_strain_intensity(const Sim& sim) {
  using Model = typename Sim::model_type;
  static_assert(std::is_same_v<typename Model::strain_type, SymTensor2D<double>>,
                "analysis::shear_strain_intensity: defined for the plane-strain strain of a "
                "classical (nonpolar) continuum, [xx, yy, zz, xy]");
  const auto& strain = sim.particles().template get<particles::field::Strain<Model>>();
  return shear_strain_intensity(std::span<const SymTensor2D<double>>(strain));
}

}  // namespace cosmpm::analysis
