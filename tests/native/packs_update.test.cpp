// The models' update on packs (material::HasPacksUpdate) at the host's pack width (4 with AVX),
// which the portable tests never compile for Mohr-Coulomb (its lanes need 4 doubles) and compile
// at 2 for Cosserat Drucker-Prager: bit for bit update_batch, which for Mohr-Coulomb is
// update() bit for bit (tests/material/mohr_coulomb_batch.test.cpp).
#include <doctest/doctest.h>

#include <map>
#include <string>

#include "cosmpm/core/pack.hpp"
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "material/cosserat_points.hpp"
#include "material/mohr_coulomb_points.hpp"
#include "material/packs_check.hpp"

namespace {
constexpr int W = cosmpm::pack_width;
}  // namespace

TEST_CASE("MohrCoulomb::update_packs equals update_batch bit for bit at the host's width") {
  using cosmpm::material::MohrCoulomb;
  if constexpr (!cosmpm::material::HasPacksUpdate<MohrCoulomb<double>, W>) {
    MESSAGE("no update_packs at pack width " << W << " (its lanes need AVX): nothing to check");
  } else {
    std::map<std::string, cosmpm::material::MohrCoulombParameters> variants;
    variants["corn"] = mohr_coulomb_points::corn();
    variants["separation"] = mohr_coulomb_points::corn();
    variants["separation"].separation = true;
    variants["dilatancy cut-off"] = mohr_coulomb_points::corn();
    variants["dilatancy cut-off"].dilatancy_cutoff_strain = 0.05;
    variants["tension cut-off below the apex"] = mohr_coulomb_points::corn();
    variants["tension cut-off below the apex"].cohesion = 2e3;
    variants["tension cut-off below the apex"].tension_cutoff = 1e3;
    for (const auto& [name, parameters] : variants) {
      CAPTURE(name);
      const MohrCoulomb<double> model(parameters);
      auto points = mohr_coulomb_points::random_points(4000, 31);
      const auto kinds = packs_check::sort_second_half<W>(model, points);
      // Every kind is exercised: of the 1000 packs of 4, 197-271 all elastic, 286-386 all
      // plastic and 417-443 mixed in the four variants with this seed.
      CHECK(kinds[0] > 100);
      CHECK(kinds[1] > 100);
      CHECK(kinds[2] > 100);
      CHECK(packs_check::packs_differences<W>(model, points.stress, points.state, points.increment,
                                              points.stress.size() / W) == 0);
    }
  }
}

TEST_CASE(
    "CosseratDruckerPrager::update_packs equals update_batch bit for bit at the host's width") {
  using cosmpm::material::CosseratDruckerPrager;
  if constexpr (!cosmpm::material::HasPacksUpdate<CosseratDruckerPrager<double>, W>) {
    MESSAGE("no update_packs at pack width " << W << ": nothing to check");
  } else {
    for (const auto& model : cosserat_points::models_by_rates()) {
      CAPTURE(model.cosserat_shear_modulus());
      auto points = cosserat_points::benchmark_like(2400, 23, 0.2, model.apex_pressure());
      const auto kinds = packs_check::sort_second_half<W>(model, points);
      // Of the 600 packs of 4, 117-168 all elastic, 165-242 all plastic, 241-267 mixed.
      CHECK(kinds[0] > 50);
      CHECK(kinds[1] > 50);
      CHECK(kinds[2] > 50);
      CHECK(packs_check::packs_differences<W>(model, points.stress, points.state, points.increment,
                                              points.stress.size() / W) == 0);
    }
  }
}
