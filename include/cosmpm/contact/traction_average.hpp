#pragma once
// Time average of a traction profile over several steps (nodal contact forces flicker as
// particles cross grid lines; the paper's DEM profile of Fig. 10 is averaged the same way).
// The bins must not move along the edge between the steps added, which holds for a blade
// moving normal to the face (its bins stay centred on the grid lines crossing it).
#include <cmath>
#include <string>
#include <vector>

#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/core/error.hpp"

namespace cosmpm::contact {

class TractionAverage {
 public:
  void add(const std::vector<TractionBin>& profile) {
    if (samples_ == 0) {
      sum_ = profile;
      for (auto& bin : sum_) bin.nodes = 0;
    } else {
      require(profile.size() == sum_.size(),
              "contact::TractionAverage::add: the profile has " + std::to_string(profile.size()) +
                  " bins, the average " + std::to_string(sum_.size()) +
                  " (the edge must keep its bins between samples)");
    }
    for (std::size_t k = 0; k < profile.size(); ++k) {
      const double tolerance = 1e-9 * profile[k].width;
      if (std::abs(profile[k].centre - sum_[k].centre) > tolerance ||
          std::abs(profile[k].width - sum_[k].width) > tolerance) {
        throw Error("contact::TractionAverage::add: bin " + std::to_string(k) + " moved from " +
                    detail::format_number(sum_[k].centre) + " to " +
                    detail::format_number(profile[k].centre) +
                    " along the edge (valid: the same bin centres and widths in every sample)");
      }
      if (samples_ > 0) {
        sum_[k].normal_traction += profile[k].normal_traction;
        sum_[k].shear_traction += profile[k].shear_traction;
      }
      sum_[k].nodes += profile[k].nodes;
    }
    ++samples_;
  }

  int samples() const { return samples_; }

  // Mean tractions per bin; `nodes` is the total count of pressing node-samples in the bin.
  std::vector<TractionBin> mean() const {
    require(samples_ > 0, "contact::TractionAverage::mean: no profile has been added");
    std::vector<TractionBin> result = sum_;
    for (auto& bin : result) {
      bin.normal_traction /= samples_;
      bin.shear_traction /= samples_;
    }
    return result;
  }

  void clear() {
    sum_.clear();
    samples_ = 0;
  }

 private:
  std::vector<TractionBin> sum_;
  int samples_ = 0;
};

}  // namespace cosmpm::contact
