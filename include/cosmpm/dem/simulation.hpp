#pragma once
// The explicit DEM engine: a composition of a contact law (LinearSpring, HertzMindlin, or a
// user's) and a body damping policy (LocalDamping, NoLocalDamping), over an Assembly of disks
// and clumps and a set of walls. One step (docs/theory/dem.md):
//   1. contact lists: rebuilt when an element drifted more than skin / 2 since the last build
//   2. pair forces: every candidate pair on its own (no write conflicts)
//   3. wall forces: every element-wall candidate on its own
//   4. bodies: gather each element's forces in a fixed order, sum them on the body with the
//      moments about its centroid, add gravity, damp, and advance by central differences
//        v(t + dt/2) = v(t - dt/2) + dt F(t) / m,   x(t + dt) = x(t) + dt v(t + dt/2)
//      (the same for the spin with the torque and the moment of inertia)
//   5. walls move with their mid-step velocities; their forces are summed in list order
// Every result lands in a slot of its own and sums run in a fixed order, so results are
// bit-identical for any thread count. A step that moves an element by more than its radius
// (or makes it non-finite) throws cosmpm::Error after the step.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/parallel.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/assembly.hpp"
#include "cosmpm/dem/contact_law.hpp"
#include "cosmpm/dem/contact_lists.hpp"
#include "cosmpm/dem/damping.hpp"
#include "cosmpm/dem/detail/parallel.hpp"
#include "cosmpm/dem/detail/step_kernels.hpp"
#include "cosmpm/dem/linear_spring.hpp"
#include "cosmpm/dem/walls.hpp"

namespace cosmpm::dem {

struct Parameters {
  Vec<2> gravity = Vec<2>(0.0, -9.81);  // m/s^2
  // Verlet skin, m; 0 picks half the smallest element radius.
  double skin = 0.0;
  // Contacts per element assumed by the critical time step (6: a disk among equal disks).
  double coordination = 6.0;
  int threads = 0;  // 0: OpenMP's default
};

template <class Law = LinearSpring, class Damping = LocalDamping>
class Simulation {
  static_assert(check_contact_law<Law>());
  static_assert(BodyDamping<Damping>,
                "dem::Simulation: Damping needs damp(force, velocity) -> double "
                "(see dem/damping.hpp)");

 public:
  using Material = typename Law::Material;
  using Walls = WallSet<Material>;

  // A contact with a force, after a step (for output and analysis).
  struct PairContact {
    Index first = 0, second = 0;     // elements
    Vec<2> normal = Vec<2>::Zero();  // from first to second
    double overlap = 0.0;
    double normal_force = 0.0;  // N/m, compression positive
    double shear_force = 0.0;   // N/m, on second along (-n_y, n_x)
  };

  Simulation(Assembly assembly, Law law = Law(), Damping damping = Damping(),
             Parameters parameters = {})
      : assembly_(std::move(assembly)),
        law_(std::move(law)),
        damping_(std::move(damping)),
        parameters_(parameters) {
    require(parameters_.gravity.allFinite(), "dem::Simulation: gravity must be finite");
    require_non_negative("dem::Simulation", "skin [m]", parameters_.skin);
    require_positive("dem::Simulation", "coordination", parameters_.coordination);
    require_in_range("dem::Simulation", "threads", parameters_.threads, 0, 4096, Bounds::closed);
  }

  Assembly& assembly() { return assembly_; }
  const Assembly& assembly() const { return assembly_; }
  const Law& law() const { return law_; }
  // Replaces the contact law from the next step on: PFC's practice of depositing or compacting
  // a packing with low friction and then shearing it with the calibrated law. Contact histories
  // are kept; the new law caps them at its own limits in the next step.
  void set_law(Law law) {
    law_ = std::move(law);
    wall_constants_.clear();
    for (Index w = 0; w < walls_.size(); ++w) {
      wall_constants_.push_back(law_.wall_constants(walls_[w].material));
    }
    critical_ = 0.0;  // the time-step estimate depends on the law's stiffnesses
  }
  Damping& damping() { return damping_; }
  const Damping& damping() const { return damping_; }
  Parameters& parameters() { return parameters_; }
  const Parameters& parameters() const { return parameters_; }
  Walls& walls() { return walls_; }
  const Walls& walls() const { return walls_; }
  const ContactLists& contact_lists() const { return lists_; }

  Index add_plane_wall(std::string name, const Vec<2>& point, const Vec<2>& normal,
                       const Material& material) {
    Law::check_material(material, "dem wall '" + name + "'");
    return walls_.add_plane(std::move(name), point, normal, material);
  }
  Index add_polygon_wall(std::string name, contact::RigidBody<2> body, const Material& material) {
    Law::check_material(material, "dem wall '" + name + "'");
    return walls_.add_polygon(std::move(name), std::move(body), material);
  }

  double time() const { return time_; }
  std::int64_t step_count() const { return steps_; }
  void set_time(double time) { time_ = time; }

  double skin() const {
    return parameters_.skin > 0.0 ? parameters_.skin : 0.5 * assembly_.min_radius();
  }

  // PFC's estimate: each body a mass on springs, dt_b = min(sqrt(m / K_t), sqrt(I / K_r)) with
  // K_t = sum over its elements of z (k_n + k_s) and K_r the same times (|offset| + r)^2, for
  // the stiffest kind of contact (z = Parameters::coordination). It is about half the step at
  // which central differences go unstable for a dense packing (docs/theory/dem.md).
  double critical_time_step() const {
    const auto pair = law_.pair_constants();
    std::vector<typename Law::Constants> wall_constants;
    for (Index w = 0; w < walls_.size(); ++w) {
      if (walls_[w].enabled) wall_constants.push_back(law_.wall_constants(walls_[w].material));
    }
    const auto& m = assembly_.bodies().template get<tag::Mass>();
    const auto& inertia = assembly_.bodies().template get<field::Inertia>();
    const auto& first = assembly_.bodies().template get<field::FirstElement>();
    const auto& count = assembly_.bodies().template get<field::ElementCount>();
    const auto& radius = assembly_.elements().template get<field::Radius>();
    const auto& offset = assembly_.elements().template get<field::Offset>();
    double dt = std::numeric_limits<double>::infinity();
    for (Index b = 0; b < assembly_.body_count(); ++b) {
      const auto ub = static_cast<std::size_t>(b);
      double k_t = 0.0, k_r = 0.0;
      for (std::int32_t e = first[ub]; e < first[ub] + count[ub]; ++e) {
        const auto ue = static_cast<std::size_t>(e);
        double k = Law::time_step_stiffness(pair, radius[ue]);
        for (const auto& wc : wall_constants)
          k = std::max(k, Law::time_step_stiffness(wc, radius[ue]));
        const double lever = offset[ue].norm() + radius[ue];
        k_t += parameters_.coordination * k;
        k_r += parameters_.coordination * k * lever * lever;
      }
      dt = std::min({dt, std::sqrt(m[ub] / k_t), std::sqrt(inertia[ub] / k_r)});
    }
    return dt;
  }

  // Gives body b the impulse J (N s per m) at `point`: dv = J / m, d omega = (r x J) / I.
  void apply_impulse(Index b, const Vec<2>& impulse, const Vec<2>& point) {
    auto& bodies = assembly_.bodies();
    const auto ub = static_cast<std::size_t>(b);
    const Vec<2> r = point - bodies.template get<tag::Position<2>>()[ub];
    bodies.template get<tag::Velocity<2>>()[ub] += impulse / bodies.template get<tag::Mass>()[ub];
    bodies.template get<field::Spin>()[ub] +=
        (r[0] * impulse[1] - r[1] * impulse[0]) / bodies.template get<field::Inertia>()[ub];
    assembly_.sync_elements();
  }

  void step(double dt) {
    require_positive("dem::Simulation::step", "time step dt [s]", dt);
    const double critical = cached_critical_time_step();
    if (dt > critical) {
      throw Error("dem::Simulation::step: dt = " + cosmpm::detail::format_number(dt) +
                  " s exceeds the critical time step " + cosmpm::detail::format_number(critical) +
                  " s of the stiffest contact and lightest body (valid range (0, " +
                  cosmpm::detail::format_number(critical) + "])");
    }
    prepare_lists();
    const int threads = resolve_thread_count(parameters_.threads);
    auto kernels = make_kernels(dt);
    team_size_ = kernels.pair_forces(threads);
    team_size_ = std::max(team_size_, kernels.wall_forces(threads));
    detail::MotionReport report;
    team_size_ = std::max(team_size_, kernels.bodies(threads, report));
    walls_.advance(dt, time_);
    time_ += dt;
    ++steps_;
    sum_wall_forces();
    drift_ = std::sqrt(report.max_drift_squared);
    if (report.first_unstable != std::numeric_limits<Index>::max()) {
      throw unstable(report.first_unstable, dt, critical);
    }
  }

  // --- results of the last step --------------------------------------------------------
  Vec<2> wall_force(Index w) const { return walls_[w].force; }
  int last_team_size() const { return team_size_; }
  Index active_contacts() const {
    Index n = 0;
    for (const double f : pair_normal_) n += f > 0.0 ? 1 : 0;
    for (const WallContact& c : wall_contacts_) n += c.overlap > 0.0 ? 1 : 0;
    return n;
  }

  // Calls f(PairContact) for every touching pair, in list order.
  template <class F>
  void for_each_pair_contact(F&& f) const {
    const auto& x = assembly_.elements().template get<tag::Position<2>>();
    for (std::size_t p = 0; p < pair_overlap_.size(); ++p) {
      if (!(pair_overlap_[p] > 0.0)) continue;
      PairContact c;
      c.first = lists_.first[p];
      c.second = lists_.second[p];
      const Vec<2> d = x[static_cast<std::size_t>(c.second)] - x[static_cast<std::size_t>(c.first)];
      c.normal = d.norm() > 0.0 ? Vec<2>(d.normalized()) : Vec<2>(1.0, 0.0);
      c.overlap = pair_overlap_[p];
      c.normal_force = pair_normal_[p];
      c.shear_force = pair_shear_[p];
      f(c);
    }
  }
  // Calls f(WallContact) for every element touching a wall, in list order.
  template <class F>
  void for_each_wall_contact(F&& f) const {
    for (const WallContact& c : wall_contacts_) {
      if (c.overlap > 0.0) f(c);
    }
  }

  double kinetic_energy() const {
    const auto& b = assembly_.bodies();
    const auto& v = b.template get<tag::Velocity<2>>();
    const auto& w = b.template get<field::Spin>();
    const auto& m = b.template get<tag::Mass>();
    const auto& inertia = b.template get<field::Inertia>();
    double e = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i) {
      e += 0.5 * m[i] * v[i].squaredNorm() + 0.5 * inertia[i] * w[i] * w[i];
    }
    return e;
  }

  // PFC's equilibrium measure: the mean unbalanced force on the bodies over the mean contact
  // force (0 at static equilibrium; 1 for bodies in free flight).
  double unbalanced_force_ratio() const {
    const auto& force = assembly_.bodies().template get<field::Force>();
    double unbalanced = 0.0;
    for (const Vec<2>& f : force) unbalanced += f.norm();
    double contact = 0.0;
    Index contacts = 0;
    for (std::size_t p = 0; p < pair_normal_.size(); ++p) {
      if (pair_overlap_[p] > 0.0) {
        contact += std::hypot(pair_normal_[p], pair_shear_[p]);
        ++contacts;
      }
    }
    for (const WallContact& c : wall_contacts_) {
      if (c.overlap > 0.0) {
        contact += std::hypot(c.normal_force, c.shear_force);
        ++contacts;
      }
    }
    if (force.empty()) return 0.0;
    if (contacts == 0 || contact == 0.0) return 1.0;
    return (unbalanced / static_cast<double>(force.size())) /
           (contact / static_cast<double>(contacts));
  }

  // How far elements drifted since the contact lists were built (last step), m.
  double drift() const { return drift_; }

 private:
  using Kernels = detail::StepKernels<Law, Damping>;

  double cached_critical_time_step() {
    if (critical_revision_ != assembly_.revision() || critical_walls_ != walls_.revision() ||
        !(critical_ > 0.0)) {
      critical_ = critical_time_step();
      critical_revision_ = assembly_.revision();
      critical_walls_ = walls_.revision();
    }
    return critical_;
  }

  void prepare_lists() {
    const bool stale = list_revision_ != assembly_.revision() || list_walls_ != walls_.revision();
    const double skin = this->skin();
    const bool drifted =
        2.0 * drift_ > skin || drift_ + walls_.max_motion_since(wall_poses_) > skin;
    if (!stale && !drifted && lists_.builds > 0) return;
    if (list_revision_ != assembly_.revision()) assembly_.sync_elements();
    // Wall indices never change, so only new elements lose their histories.
    const bool keep = list_revision_ == assembly_.revision();
    lists_.build(
        assembly_.elements(), skin, resolve_thread_count(parameters_.threads), walls_.size(),
        [this](Index w, const Vec<2>& x) { return walls_.locate(w, x).gap; },
        [this](Index w) { return walls_[w].enabled; }, keep && lists_.builds > 0);
    wall_poses_ = walls_.poses();
    list_revision_ = assembly_.revision();
    list_walls_ = walls_.revision();
    drift_ = 0.0;
    const auto pairs = static_cast<std::size_t>(lists_.pair_count());
    const auto walls = static_cast<std::size_t>(lists_.wall_candidate_count());
    pair_force_.assign(pairs, Vec<2>::Zero());
    pair_torque_.assign(pairs, Vec<2>::Zero());
    pair_normal_.assign(pairs, 0.0);
    pair_shear_.assign(pairs, 0.0);
    pair_overlap_.assign(pairs, 0.0);
    wall_contacts_.assign(walls, WallContact{});
    wall_constants_.clear();
    for (Index w = 0; w < walls_.size(); ++w) {
      wall_constants_.push_back(law_.wall_constants(walls_[w].material));
    }
  }

  Kernels make_kernels(double dt) {
    return Kernels{assembly_,
                   walls_,
                   lists_,
                   law_.pair_constants(),
                   wall_constants_,
                   damping_,
                   parameters_.gravity,
                   dt,
                   pair_force_,
                   pair_torque_,
                   pair_normal_,
                   pair_shear_,
                   pair_overlap_,
                   wall_contacts_};
  }

  void sum_wall_forces() {
    for (Index w = 0; w < walls_.size(); ++w) {
      auto& wall = walls_.at(w);
      wall.force = Vec<2>::Zero();
      wall.torque = 0.0;
      wall.contacts = 0;
    }
    for (const WallContact& c : wall_contacts_) {
      if (!(c.overlap > 0.0)) continue;
      auto& wall = walls_.at(c.wall);
      const Vec<2> t(-c.normal[1], c.normal[0]);
      const Vec<2> on_wall = -(c.normal_force * c.normal + c.shear_force * t);
      const Vec<2> centre =
          wall.kind == WallKind::plane ? wall.point : wall.body->reference_point();
      const Vec<2> r = c.point - centre;
      wall.force += on_wall;
      wall.torque += r[0] * on_wall[1] - r[1] * on_wall[0] - c.rolling_moment;
      ++wall.contacts;
    }
  }

  Error unstable(Index element, double dt, double critical) const {
    const auto& e = assembly_.elements();
    const auto ue = static_cast<std::size_t>(element);
    const auto b = static_cast<std::size_t>(e.template get<tag::Body>()[ue]);
    const auto& bodies = assembly_.bodies();
    const Vec<2> v = bodies.template get<tag::Velocity<2>>()[b];
    const Vec<2> f = bodies.template get<field::Force>()[b];
    return Error("dem::Simulation: unstable at step " + std::to_string(steps_) +
                 ", t = " + cosmpm::detail::format_number(time_) + " s: element " +
                 std::to_string(element) + " (body " + std::to_string(b) + ", radius " +
                 cosmpm::detail::format_number(e.template get<field::Radius>()[ue]) +
                 " m) moved more than its radius in one step (speed " +
                 cosmpm::detail::format_number(v.norm()) + " m/s, force " +
                 cosmpm::detail::format_number(f.norm()) +
                 " N/m, dt = " + cosmpm::detail::format_number(dt) + " s, critical step " +
                 cosmpm::detail::format_number(critical) +
                 " s). A wall or body driven into the particles, or a stiffness or overlap "
                 "far beyond the time-step estimate, makes contact forces explode.");
  }

  Assembly assembly_;
  Law law_;
  Damping damping_;
  Parameters parameters_;
  Walls walls_;
  ContactLists lists_;
  std::vector<typename Law::Constants> wall_constants_;
  std::vector<Vec<2>> pair_force_;   // on the second element
  std::vector<Vec<2>> pair_torque_;  // about the first and the second element's centres
  std::vector<double> pair_normal_;
  std::vector<double> pair_shear_;
  std::vector<double> pair_overlap_;
  std::vector<WallContact> wall_contacts_;
  std::vector<typename Walls::Pose> wall_poses_;
  double time_ = 0.0;
  std::int64_t steps_ = 0;
  double drift_ = 0.0;
  int team_size_ = 1;
  double critical_ = 0.0;
  std::uint64_t critical_revision_ = ~std::uint64_t{0};
  std::uint64_t critical_walls_ = ~std::uint64_t{0};
  std::uint64_t list_revision_ = ~std::uint64_t{0};
  std::uint64_t list_walls_ = ~std::uint64_t{0};
};

}  // namespace cosmpm::dem
