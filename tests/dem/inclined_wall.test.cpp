// A disk and a clump on an inclined plane wall, no damping. Along the slope s (theta from
// the horizontal, friction mu at the wall):
//  - a clump of two disks lying along the slope cannot roll: it stays put while tan(theta) <
//    mu and slides at a = g (sin theta - mu cos theta) above;
//  - a disk rolls without slipping at a = 2/3 g sin theta while tan(theta) <= 3 mu
//    (I = m r^2 / 2 needs friction m g sin(theta) / 3), and slides at g (sin theta - mu cos
//    theta) above, spinning up at 2 mu g cos(theta) / r (counter-clockwise here: downhill is
//    towards -x).
// The accelerations are fitted to the velocity along the slope over 0.05-0.4 s, which averages
// out the small elastic ringing of the undamped springs.
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "cosmpm/dem/simulation.hpp"

namespace {
using namespace cosmpm;

constexpr double g = 9.81;

struct SlopeRun {
  double acceleration = 0.0;  // along the slope, downhill positive
  double displacement = 0.0;  // downhill, at the end
  double spin_rate = 0.0;     // fitted d omega / dt, counter-clockwise positive
  double end_time = 0.0;
};

double fitted_slope(const std::vector<double>& t, const std::vector<double>& y) {
  double st = 0, sy = 0, stt = 0, sty = 0;
  const double n = static_cast<double>(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) {
    st += t[i];
    sy += y[i];
    stt += t[i] * t[i];
    sty += t[i] * y[i];
  }
  return (n * sty - st * sy) / (n * stt - st * st);
}

SlopeRun run(bool clump, double theta_deg, double mu) {
  const double theta = degrees_to_radians(theta_deg);
  const Vec<2> normal(-std::sin(theta), std::cos(theta));
  const Vec<2> downhill(-std::cos(theta), -std::sin(theta));
  const double r = 0.004, density = 855.0, k = 420e3;
  dem::Assembly a;
  // Resting on the plane with the static overlap of its weight's normal component.
  if (clump) {
    const dem::ClumpShape shape = dem::ClumpShape::two_disks(0.014, 2 * r);
    const double mass = density * shape.area();
    const double overlap = 0.5 * mass * g * std::cos(theta) / (0.5 * k);  // two contacts
    a.add_clump(shape, 1.0, (r - overlap) * normal, theta, density);
  } else {
    const double mass = density * pi * r * r;
    const double overlap = mass * g * std::cos(theta) / (0.5 * k);
    a.add_disk((r - overlap) * normal, r, density);
  }
  dem::Parameters p;
  p.gravity = Vec<2>(0.0, -g);
  dem::Simulation<dem::LinearSpring, dem::NoLocalDamping> sim(
      std::move(a), dem::LinearSpring({.normal_stiffness = k, .shear_stiffness = k, .friction = 0}),
      dem::NoLocalDamping(), p);
  sim.add_plane_wall("slope", Vec<2>::Zero(), normal,
                     {.normal_stiffness = k, .shear_stiffness = k, .friction = mu});
  const double dt = 0.2 * sim.critical_time_step();
  std::vector<double> times, speeds, spins;
  const Vec<2> x0 = sim.assembly().position(0);
  while (sim.time() < 0.4) {
    sim.step(dt);
    if (sim.time() >= 0.05) {
      times.push_back(sim.time());
      speeds.push_back(sim.assembly().velocity(0).dot(downhill));
      spins.push_back(sim.assembly().spin(0));
    }
  }
  return {fitted_slope(times, speeds), (sim.assembly().position(0) - x0).dot(downhill),
          fitted_slope(times, spins), sim.time()};
}

}  // namespace

TEST_CASE("inclined wall: a clump rests below tan(theta) = mu and slides above it") {
  const double mu = 0.3;  // tan(16.7 deg)
  const SlopeRun rest = run(true, 15.0, mu);
  // Held by the shear springs: it creeps at most the elastic shear displacement,
  // m g sin(theta) / (2 k_s) = 8 um, where sliding freely would cover 0.5 a t^2 = 8 mm.
  CHECK(std::abs(rest.displacement) < 2e-5);
  CHECK(std::abs(rest.acceleration) < 1e-3);
  const SlopeRun slide = run(true, 25.0, mu);
  const double t = degrees_to_radians(25.0);
  CHECK(slide.acceleration == doctest::Approx(g * (std::sin(t) - mu * std::cos(t))).epsilon(5e-3));
  CHECK(std::abs(slide.spin_rate) < 1e-2);  // it slides flat, without turning
}

TEST_CASE("inclined wall: a disk rolls at 2/3 g sin(theta), slips above tan(theta) = 3 mu") {
  const double mu = 0.3;  // rolling without slip up to tan(theta) = 0.9 (42 deg)
  const double t1 = degrees_to_radians(20.0);
  const SlopeRun roll = run(false, 20.0, mu);
  CHECK(roll.acceleration == doctest::Approx(2.0 / 3.0 * g * std::sin(t1)).epsilon(5e-3));
  // Downhill is towards -x here, so rolling turns the disk counter-clockwise: omega r = v.
  CHECK(roll.spin_rate == doctest::Approx(roll.acceleration / 0.004).epsilon(5e-3));
  const double t2 = degrees_to_radians(50.0);
  const SlopeRun slip = run(false, 50.0, mu);
  CHECK(slip.acceleration == doctest::Approx(g * (std::sin(t2) - mu * std::cos(t2))).epsilon(5e-3));
  CHECK(slip.spin_rate == doctest::Approx(2.0 * mu * g * std::cos(t2) / 0.004).epsilon(5e-3));
}

TEST_CASE("moving polygon wall: a clump on a conveyor is dragged at mu g until it moves with it") {
  // A box wall (the floor) moving at 0.2 m/s under a resting clump: friction accelerates the
  // clump at mu g = 2.943 m/s^2 until, after 0.2 / 2.943 = 68 ms, it rides at the belt's speed.
  const double mu = 0.3, speed = 0.2, r = 0.004, k = 420e3;
  const dem::ClumpShape shape = dem::ClumpShape::two_disks(0.014, 2 * r);
  dem::Assembly a;
  const double overlap = 0.5 * 855.0 * shape.area() * g / (0.5 * k);
  a.add_clump(shape, 1.0, Vec<2>(0.0, r - overlap), 0.0, 855.0);
  dem::Simulation<dem::LinearSpring, dem::NoLocalDamping> sim(
      std::move(a), dem::LinearSpring({.normal_stiffness = k, .shear_stiffness = k, .friction = 0}),
      dem::NoLocalDamping());
  auto belt = contact::RigidBody<2>::box(Vec<2>(-1.0, -0.05), Vec<2>(1.0, 0.0));
  belt.set_velocity(Vec<2>(speed, 0.0));
  const Index w = sim.add_polygon_wall(
      "belt", std::move(belt), {.normal_stiffness = k, .shear_stiffness = k, .friction = mu});
  const double dt = 0.2 * sim.critical_time_step();
  std::vector<double> times, speeds;
  while (sim.time() < 0.05) {
    sim.step(dt);
    if (sim.time() > 0.01) {
      times.push_back(sim.time());
      speeds.push_back(sim.assembly().velocity(0)[0]);
    }
  }
  CHECK(fitted_slope(times, speeds) == doctest::Approx(mu * g).epsilon(5e-3));
  // The belt's drag on the grain is the grain's drag on the belt, reversed.
  CHECK(sim.wall_force(w)[0] == doctest::Approx(-mu * g * sim.assembly().mass(0)).epsilon(1e-2));
  // Then it sticks: its mean speed over 0.1-0.2 s is the belt's (undamped, it rocks on the
  // shear springs about it by a few mm/s).
  double sum = 0.0;
  long n = 0;
  while (sim.time() < 0.2) {
    sim.step(dt);
    if (sim.time() > 0.1) {
      sum += sim.assembly().velocity(0)[0];
      ++n;
    }
  }
  CHECK(sum / static_cast<double>(n) == doctest::Approx(speed).epsilon(1e-3));
}
