// Clumps: the mass properties of a union of disks (exact, by Green's theorem along the
// uncovered arcs) and the rigid motion they give.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

// Area and polar moment about the centroid of a union of disks by sampling a fine grid: an
// independent check (error ~ h / size).
struct Sampled {
  double area = 0.0;
  double polar = 0.0;
};
Sampled sample(const std::vector<dem::ClumpMember>& members, double h) {
  Vec<2> lo = Vec<2>::Constant(1e300), hi = Vec<2>::Constant(-1e300);
  for (const auto& m : members) {
    lo = lo.cwiseMin(m.offset - Vec<2>::Constant(m.radius));
    hi = hi.cwiseMax(m.offset + Vec<2>::Constant(m.radius));
  }
  double area = 0.0;
  Vec<2> first = Vec<2>::Zero();
  double second = 0.0;
  for (double y = lo[1] + 0.5 * h; y < hi[1]; y += h) {
    for (double x = lo[0] + 0.5 * h; x < hi[0]; x += h) {
      for (const auto& m : members) {
        if ((Vec<2>(x, y) - m.offset).squaredNorm() <= m.radius * m.radius) {
          area += h * h;
          first += h * h * Vec<2>(x, y);
          second += h * h * (x * x + y * y);
          break;
        }
      }
    }
  }
  const Vec<2> c = first / area;
  return {area, second - area * c.squaredNorm()};
}

}  // namespace

TEST_CASE("clump shape: a single disk has area pi r^2 and polar moment pi r^4 / 2") {
  const dem::ClumpShape disk({{Vec<2>(0.3, -0.2), 2.0}});
  CHECK(disk.area() == doctest::Approx(pi * 4.0).epsilon(1e-14));
  CHECK(disk.polar_moment() == doctest::Approx(0.5 * pi * 16.0).epsilon(1e-14));
  CHECK(disk.members()[0].offset.norm() < 1e-13);  // re-centred on the centroid
}

TEST_CASE("clump shape: touching disks add up; overlapping disks lose the lens") {
  const double r = 1.0;
  const dem::ClumpShape touching({{Vec<2>(-r, 0), r}, {Vec<2>(r, 0), r}});
  CHECK(touching.area() == doctest::Approx(2 * pi * r * r).epsilon(1e-13));
  // Two disks at +-r from the centroid: 2 (pi r^4 / 2 + pi r^2 r^2) (parallel axes).
  CHECK(touching.polar_moment() == doctest::Approx(3 * pi * std::pow(r, 4)).epsilon(1e-13));
  // Centres d = 1.2 r apart: the lens has area 2 r^2 acos(d / 2r) - d/2 sqrt(4 r^2 - d^2).
  const double d = 1.2 * r;
  const dem::ClumpShape overlapping = dem::ClumpShape::two_disks(d + 2 * r, 2 * r);
  const double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
  CHECK(overlapping.area() == doctest::Approx(2 * pi * r * r - lens).epsilon(1e-13));
  const Sampled s = sample(overlapping.members(), 2e-3);
  CHECK(overlapping.polar_moment() == doctest::Approx(s.polar).epsilon(3e-3));
  CHECK(overlapping.bounding_radius() == doctest::Approx(0.5 * d + r).epsilon(1e-14));
}

TEST_CASE("clump shape: uneven disks, a disk inside another, and a ring with a hole") {
  const std::vector<dem::ClumpMember> uneven{
      {Vec<2>(0, 0), 1.0}, {Vec<2>(1.3, 0.4), 0.6}, {Vec<2>(-0.9, 0.8), 0.5}};
  const dem::ClumpShape a(uneven);
  const Sampled sa = sample(a.members(), 2e-3);
  CHECK(a.area() == doctest::Approx(sa.area).epsilon(2e-3));
  CHECK(a.polar_moment() == doctest::Approx(sa.polar).epsilon(3e-3));
  // A disk inside another adds nothing.
  const dem::ClumpShape nested({{Vec<2>(0, 0), 1.0}, {Vec<2>(0.2, 0.1), 0.5}});
  CHECK(nested.area() == doctest::Approx(pi).epsilon(1e-13));
  // Six disks round an empty centre: the union has a hole, which the arcs bound clockwise.
  std::vector<dem::ClumpMember> ring;
  for (int k = 0; k < 6; ++k) {
    const double angle = k * pi / 3.0;
    ring.push_back({Vec<2>(1.9 * std::cos(angle), 1.9 * std::sin(angle)), 1.0});
  }
  const dem::ClumpShape holed(ring);
  const Sampled sr = sample(holed.members(), 2e-3);
  CHECK(holed.area() == doctest::Approx(sr.area).epsilon(2e-3));
  CHECK(holed.polar_moment() == doctest::Approx(sr.polar).epsilon(3e-3));
}

TEST_CASE("clump: an off-centre impulse gives v = J / m and omega = (r x J) / I") {
  const dem::ClumpShape shape = dem::ClumpShape::two_disks(0.010, 0.006);  // the corn grain
  dem::Assembly a;
  const double density = 855.0;
  const Index b = a.add_clump(shape, 1.0, Vec<2>(0.1, 0.2), 0.3, density);
  dem::Parameters p;
  p.gravity = Vec<2>::Zero();
  dem::Simulation<dem::LinearSpring, dem::NoLocalDamping> sim(std::move(a), dem::LinearSpring(),
                                                              dem::NoLocalDamping(), p);
  const double mass = density * shape.area();
  const double inertia = density * shape.polar_moment();
  CHECK(sim.assembly().mass(b) == doctest::Approx(mass).epsilon(1e-14));
  CHECK(sim.assembly().inertia(b) == doctest::Approx(inertia).epsilon(1e-14));
  // 1 mN s at the tip of the grain, across its axis.
  const double c = std::cos(0.3), s = std::sin(0.3);
  const Vec<2> tip = Vec<2>(0.1, 0.2) + 0.005 * Vec<2>(c, s);
  const Vec<2> impulse = 1e-3 * Vec<2>(-s, c);
  sim.apply_impulse(b, impulse, tip);
  const double expected_spin = 0.005 * 1e-3 / inertia;
  CHECK(sim.assembly().spin(b) == doctest::Approx(expected_spin).epsilon(1e-14));
  CHECK((sim.assembly().velocity(b) - impulse / mass).norm() < 1e-15);
  // Free flight: the centroid moves at J / m, the body turns at omega, the disks follow rigidly.
  const double dt = 0.5 * sim.critical_time_step();
  const int steps = 2000;
  for (int k = 0; k < steps; ++k) sim.step(dt);
  const double t = steps * dt;
  // 2000 additions of v dt: round-off of a few 1e-16 m each.
  CHECK((sim.assembly().position(b) - (Vec<2>(0.1, 0.2) + t * impulse / mass)).norm() < 1e-12);
  CHECK(sim.assembly().angle(b) == doctest::Approx(0.3 + expected_spin * t).epsilon(1e-12));
  const auto& x = sim.assembly().elements().get<particles::field::Position<2>>();
  CHECK((x[1] - x[0]).norm() == doctest::Approx(0.004).epsilon(1e-12));
  const double angle = std::atan2(x[1][1] - x[0][1], x[1][0] - x[0][0]);
  CHECK(std::remainder(angle - sim.assembly().angle(b), 2 * pi) == doctest::Approx(0.0));
}

TEST_CASE("clump: a disk striking a clump off-centre conserves momentum and energy") {
  // Frictionless, undamped: linear momentum exactly (equal and opposite forces), angular
  // momentum about the origin and kinetic energy to the integrator's O((omega dt)^2).
  const dem::ClumpShape shape = dem::ClumpShape::two_disks(0.010, 0.006);
  dem::Assembly a;
  a.add_clump(shape, 1.0, Vec<2>(0.0, 0.0), pi / 2, 855.0);  // standing along y
  a.add_disk(Vec<2>(-0.0081, 0.0015), 0.005, 855.0, Vec<2>(0.2, 0.0));
  dem::Parameters p;
  p.gravity = Vec<2>::Zero();
  const dem::LinearSpring law({.normal_stiffness = 420e3, .shear_stiffness = 420e3, .friction = 0});
  dem::Simulation<dem::LinearSpring, dem::NoLocalDamping> sim(std::move(a), law,
                                                              dem::NoLocalDamping(), p);
  auto momentum = [&] {
    Vec<2> m = Vec<2>::Zero();
    for (Index b = 0; b < 2; ++b) m += sim.assembly().mass(b) * sim.assembly().velocity(b);
    return m;
  };
  auto angular = [&] {
    double l = 0.0;
    for (Index b = 0; b < 2; ++b) {
      const Vec<2> x = sim.assembly().position(b);
      const Vec<2> v = sim.assembly().velocity(b);
      l += sim.assembly().mass(b) * (x[0] * v[1] - x[1] * v[0]) +
           sim.assembly().inertia(b) * sim.assembly().spin(b);
    }
    return l;
  };
  const Vec<2> p0 = momentum();
  const double l0 = angular();
  const double e0 = sim.kinetic_energy();
  const double dt = 0.005 * sim.critical_time_step();
  while (sim.time() < 0.01) sim.step(dt);
  CHECK((momentum() - p0).norm() < 1e-15);
  CHECK(sim.assembly().spin(0) < 0.0);  // struck below its centroid from the left: clockwise
  CHECK(angular() == doctest::Approx(l0).epsilon(1e-6));
  CHECK(sim.kinetic_energy() == doctest::Approx(e0).epsilon(1e-4));
}
