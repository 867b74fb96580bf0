#pragma once
// The stress on a wall face from discrete contact forces, as Coetzee (2014, Sect. 3.2, Fig. 10)
// estimated it for the blade: "the average contacting force of two neighbouring contacts
// divided by the distance between the contacting points along the blade", averaged over
// time (18-22 mm of blade travel) because the particles move in steps. Beside it, the plain
// estimate: the forces of the contacts in a bin divided by the bin's length, which adds up
// exactly to the total force on the face.
//
// Per metre of thickness, so a force in N/m over a length in m is a stress in Pa. Signs at the
// output edge (as analysis::WallStress): normal stress compression positive, shear stress
// positive along the face's direction (up the blade for the cutting face).
#include <algorithm>
#include <cmath>
#include <vector>

#include "cosmpm/core/error.hpp"

namespace cosmpm::dem {

struct FaceContact {
  double along = 0.0;   // m from the face's start vertex
  double normal = 0.0;  // N/m the particle pushes on the face with, compression positive
  double shear = 0.0;   // N/m the particle drags the face with, along the face
};

struct FaceStress {
  double along = 0.0;   // m
  double normal = 0.0;  // Pa
  double shear = 0.0;   // Pa
};

// The paper's estimate for one instant: one value at the midpoint of each pair of neighbouring
// contacts (sorted along the face). Contacts at the same point share the next gap.
inline std::vector<FaceStress> neighbour_stress(std::vector<FaceContact> contacts) {
  std::sort(contacts.begin(), contacts.end(),
            [](const FaceContact& a, const FaceContact& b) { return a.along < b.along; });
  std::vector<FaceStress> out;
  for (std::size_t k = 0; k + 1 < contacts.size(); ++k) {
    const double gap = contacts[k + 1].along - contacts[k].along;
    if (!(gap > 0.0)) continue;
    out.push_back({0.5 * (contacts[k].along + contacts[k + 1].along),
                   0.5 * (contacts[k].normal + contacts[k + 1].normal) / gap,
                   0.5 * (contacts[k].shear + contacts[k + 1].shear) / gap});
  }
  return out;
}

// Time average over many instants in bins of equal length along a face of length L.
class FaceStressAverage {
 public:
  struct Bin {
    double centre = 0.0;            // m along the face
    double neighbour_normal = 0.0;  // Pa, the paper's estimate (mean of its samples)
    double neighbour_shear = 0.0;
    long samples = 0;            // neighbour-pair values that fell in the bin
    double binned_normal = 0.0;  // Pa, contact forces in the bin / bin length, time averaged
    double binned_shear = 0.0;
  };

  FaceStressAverage(double face_length, double bin_length) : length_(face_length) {
    require_positive("dem::FaceStressAverage", "face length", face_length);
    require_in_range("dem::FaceStressAverage", "bin length", bin_length, 0.0, face_length,
                     Bounds::right_closed);
    bins_ = static_cast<std::size_t>(std::ceil(face_length / bin_length - 1e-9));
    bin_ = face_length / static_cast<double>(bins_);
    normal_sum_.assign(bins_, 0.0);
    shear_sum_.assign(bins_, 0.0);
    samples_.assign(bins_, 0);
    binned_normal_.assign(bins_, 0.0);
    binned_shear_.assign(bins_, 0.0);
  }

  // One instant's contacts on the face.
  void add(const std::vector<FaceContact>& contacts) {
    ++instants_;
    for (const FaceStress& s : neighbour_stress(contacts)) {
      const std::size_t b = bin_of(s.along);
      normal_sum_[b] += s.normal;
      shear_sum_[b] += s.shear;
      ++samples_[b];
    }
    for (const FaceContact& c : contacts) {
      const std::size_t b = bin_of(c.along);
      binned_normal_[b] += c.normal / bin_;
      binned_shear_[b] += c.shear / bin_;
    }
  }

  long instants() const { return instants_; }
  double bin_length() const { return bin_; }

  std::vector<Bin> bins() const {
    std::vector<Bin> out(bins_);
    for (std::size_t b = 0; b < bins_; ++b) {
      out[b].centre = (static_cast<double>(b) + 0.5) * bin_;
      out[b].samples = samples_[b];
      if (samples_[b] > 0) {
        out[b].neighbour_normal = normal_sum_[b] / static_cast<double>(samples_[b]);
        out[b].neighbour_shear = shear_sum_[b] / static_cast<double>(samples_[b]);
      }
      if (instants_ > 0) {
        out[b].binned_normal = binned_normal_[b] / static_cast<double>(instants_);
        out[b].binned_shear = binned_shear_[b] / static_cast<double>(instants_);
      }
    }
    return out;
  }

 private:
  std::size_t bin_of(double along) const {
    const double clamped = std::clamp(along, 0.0, length_);
    return std::min(bins_ - 1, static_cast<std::size_t>(clamped / bin_));
  }

  double length_;
  std::size_t bins_ = 1;
  double bin_ = 1.0;
  std::vector<double> normal_sum_, shear_sum_, binned_normal_, binned_shear_;
  std::vector<long> samples_;
  long instants_ = 0;
};

}  // namespace cosmpm::dem
