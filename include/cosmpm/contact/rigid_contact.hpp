#pragma once
// Contact between the material on the grid and rigid bodies with prescribed motion: the
// multi-velocity-field algorithm of Bardenhagen, Brackbill and Sulsky (2000) with one field
// infinitely massive. At a contact node (material mass on the node and the body reaching the
// node's support) the material's velocity v is compared with the body's V(x_i):
//   v_rel = v - V,  v_n = v_rel . n  (n: the body's outward unit normal at the node)
//   v_n >= 0: separating, nothing is imposed (free separation);
//   v_n <  0: approach; the normal part is removed (no interpenetration) and the tangential
//             part v_t is stuck (|v_t| <= mu |v_n|) or reduced by mu |v_n| (Coulomb slip).
// The nodal force on the material m_i (v_corrected - v_trial) / dt is recorded in the
// end-of-step phase, per node (normal and shear parts relative to the body's face) and in
// total; the force on the body is its negative. See docs/theory/mpm.md, "## Contact".
//
//   contact::RigidContact<2> law;
//   const int blade = law.add_body(
//       contact::RigidBody<2>::box(lower, upper).set_velocity(Vec<2>(0.01, 0.0)),
//       contact::Interface::coulomb_angle(14.0));
//   Simulation<2, shape::Linear, Continuum, contact::RigidContact<2>> sim(grid, model, p, law);
//   sim.step(dt);
//   sim.contact().force_on_material(blade);        // (draft, vertical) on the soil, N/m
//   sim.contact().traction_profile(blade, 1);      // bins along the right face (edge 1)
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/detail/body_on_grid.hpp"
#include "cosmpm/contact/detail/contact_point.hpp"
#include "cosmpm/contact/detail/coulomb_slip.hpp"
#include "cosmpm/contact/detail/gaps.hpp"
#include "cosmpm/contact/detail/traction_bins.hpp"
#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/interface.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/contact/wall_rotation.hpp"
#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"
#include "cosmpm/grid/grid.hpp"

namespace cosmpm::contact {

template <int Dim>
class RigidContact {
  static_assert(Dim == 2 || Dim == 3,
                "contact::RigidContact: 2D (polygonal bodies) or 3D (convex polyhedra)");

 public:
  static constexpr const char* name() { return "rigid bodies, Bardenhagen Coulomb contact"; }

  // Adds a body; returns its index.
  int add_body(RigidBody<Dim> body, const Interface& interface) {
    if (interface.kind == Interface::Kind::coulomb) {
      require_non_negative("contact::RigidContact::add_body", "friction coefficient mu",
                           interface.friction_coefficient);
    }
    if (Dim == 3 && interface.rotation != Interface::Rotation::free) {
      throw Error(std::string("contact::RigidContact<3>::add_body: the grain rotation at a body "
                              "is ") +
                  Interface::rotation_name(interface.rotation) +
                  " (valid: free; the Cosserat continuum, whose rotation it holds or couples, is "
                  "2D only)");
    }
    if (interface.rotation == Interface::Rotation::coupled) {
      require(interface.kind == Interface::Kind::coulomb,
              "contact::RigidContact::add_body: a coupled grain rotation needs a Coulomb "
              "interface (its friction acts on the grains' slip), not no_slip");
      require_positive("contact::RigidContact::add_body", "grain radius r (m)",
                       interface.grain_radius);
    }
    bodies_.push_back({std::move(body), interface, Vec<Dim>::Zero()});
    return static_cast<int>(bodies_.size()) - 1;
  }

  // Nairn, Hammerquist and Smith (2020) correct the start-of-step velocity as well as the
  // updated one: the trial velocity then starts from a field that does not penetrate, and
  // the recorded impulse is the step's contact force alone, without the re-correction of a
  // penetrating velocity the particles carried in. Off by default (the paper's algorithm,
  // Bardenhagen et al. 2000, corrects the updated velocity only).
  RigidContact& set_start_of_step_correction(bool on) {
    start_of_step_correction_ = on;
    return *this;
  }
  bool corrects_start_of_step() const { return start_of_step_correction_; }

  // Gap check (a displacement check beside the approach check, after Nairn, Hammerquist and
  // Smith 2020): a node approaching the body is corrected only if the material on it would
  // reach the body within the step, min_p (d_p - e_p) + dt v_n <= tolerance * cell, with d_p
  // the signed distance of a particle in the node's support from the body, e_p its half
  // extent along the body's normal (half-width in cell units times the cell size) and v_n
  // the node's approach velocity. Without it a body's support reaches material up to
  // node_reach cells away, which makes a thin blade push up to a cell thick. Off by default.
  RigidContact& set_gap_check(bool on, double tolerance_cells = 0.0) {
    require_in_range("contact::RigidContact::set_gap_check", "tolerance_cells", tolerance_cells,
                     0.0, 1.0, Bounds::closed);
    gap_check_ = on;
    gap_tolerance_cells_ = tolerance_cells;
    return *this;
  }
  bool checks_gap() const { return gap_check_; }

  int body_count() const { return static_cast<int>(bodies_.size()); }
  const RigidBody<Dim>& body(int b) const { return entry(b).body; }
  RigidBody<Dim>& body(int b) { return entry(b).body; }
  const Interface& interface(int b) const { return entry(b).interface; }

  // --- results of the last end-of-step correction --------------------------------------
  const std::vector<ContactNode<Dim>>& contact_nodes() const { return records_; }
  // Total force the body applied to the material in the last step (draft = x component for a
  // blade pushing along +x); the force on the body is its negative.
  const Vec<Dim>& force_on_material(int b) const { return entry(b).force_on_material; }
  Vec<Dim> force_on_body(int b) const { return -entry(b).force_on_material; }

  // Normal and shear traction along edge `edge` of body `b` from the last step's nodal forces:
  // the forces of the nodes attributed to the edge, binned by their foot point along it and
  // divided by the bin width (the node's tributary length). Bins are centred where grid lines
  // cross the edge when it is axis-aligned, so each bin holds one row of nodes. bin_width = 0
  // means the cell size along the edge (|t_x| h_x + |t_y| h_y for the edge's unit tangent t).
  // Sum of traction * width over the bins = the edge's total force.
  std::vector<TractionBin> traction_profile(int b, int edge, double bin_width = 0.0) const
      requires(Dim == 2) {
    const auto& e = entry(b);
    require_in_range("contact::RigidContact::traction_profile", "edge", edge, 0,
                     e.body.edge_count() - 1, Bounds::closed);
    require_non_negative("contact::RigidContact::traction_profile", "bin_width", bin_width);
    require(recorded_,
            "contact::RigidContact::traction_profile: no step has been recorded yet (call it "
            "after Simulation::step)");
    return detail::edge_traction_bins(records_, e.body, b, edge, bin_width, cell_size_, origin_);
  }

  // 3D: the traction over face `face` of body b from the last step's nodal forces, in patches
  // of the face's (u, v) frame (ConvexPolyhedron): the forces of the nodes attributed to the
  // face, binned by their foot point and divided by the patch area. Patches are centred where
  // grid lines cross an axis-aligned face, so each holds one node; a size of 0 means the cell
  // size along u or v. Patches run u fastest. Sum of traction * area = the face's force.
  std::vector<TractionPatch> traction_map(int b, int face, Vec<2> size = Vec<2>::Zero()) const
      requires(Dim == 3) {
    const auto& e = entry(b);
    require_in_range("contact::RigidContact::traction_map", "face", face, 0,
                     e.body.face_count() - 1, Bounds::closed);
    require_non_negative("contact::RigidContact::traction_map", "patch size along u", size[0]);
    require_non_negative("contact::RigidContact::traction_map", "patch size along v", size[1]);
    require(recorded_,
            "contact::RigidContact::traction_map: no step has been recorded yet (call it after "
            "Simulation::step)");
    return detail::face_traction_patches(records_, e.body, b, face, size, cell_size_, origin_);
  }

  // --- checkpoints (io/checkpoint.hpp): the bodies' poses, 3 values per body -------------
  std::vector<double> checkpoint_values() const {
    std::vector<double> values;
    values.reserve(pose_size * bodies_.size());
    for (const auto& e : bodies_) {
      const auto pose = e.body.pose_values();
      values.insert(values.end(), pose.begin(), pose.end());
    }
    return values;
  }
  void restore_checkpoint_values(const std::vector<double>& values) {
    if (values.size() != pose_size * bodies_.size()) {
      throw Error("contact::RigidContact::restore_checkpoint_values: " +
                  std::to_string(values.size()) + " values for " + std::to_string(bodies_.size()) +
                  " bodies (valid: " + std::to_string(pose_size) + " per body, " +
                  std::to_string(pose_size * bodies_.size()) + ")");
    }
    for (std::size_t b = 0; b < bodies_.size(); ++b) {
      bodies_[b].body.set_pose_values(values.data() + pose_size * b);
    }
  }

  // --- the contact-policy interface ----------------------------------------------------
  void correct(GridView<Dim>& view) {
    const bool record = view.phase == Phase::end_velocity;
    examined_.clear();
    if (record) {
      records_.clear();
      recorded_ = true;
      cell_size_ = view.grid.cell_size();
      origin_ = view.grid.origin();
      for (auto& e : bodies_) e.force_on_material.setZero();
    }
    for (int b = 0; b < body_count(); ++b) correct_body(view, b, record);
  }

  // After the grid's boundary conditions of a velocity phase. A kinematic condition (fixed,
  // roller, a friction wall's normal) wins: the body applied nothing in a component it
  // imposed (the condition's reaction took it), so the records drop that component. A friction
  // wall's friction does not win: it may have slowed material the body pushes back into the
  // body (the blade's tip scraping a rough floor); the body, moving as prescribed, pushes it
  // out again through the components no condition imposed, and that push (the floor friction
  // the body overcomes) is part of the body's force. The records and totals are then the
  // forces the material actually received from the body.
  void conditions_applied(GridView<Dim>& view) {
    if (view.imposed.empty()) return;
    const bool record = view.phase == Phase::end_velocity;
    if (record) {
      for (auto& e : bodies_) e.force_on_material.setZero();
      for (auto& r : records_) {
        const unsigned imposed = view.imposed[static_cast<std::size_t>(r.node)];
        for (int d = 0; d < Dim; ++d) {
          if ((imposed >> d) & 1u) r.force_on_material[d] = 0.0;
        }
      }
    }
    for (const auto& a : examined_) {
      const unsigned imposed = view.imposed[static_cast<std::size_t>(a.node)];
      if (imposed == 0) continue;  // no condition touched it: the correction stands
      Vec<Dim> free_normal = a.normal;
      for (int d = 0; d < Dim; ++d) {
        if ((imposed >> d) & 1u) free_normal[d] = 0.0;
      }
      // |free_normal|^2: how much of the normal the free components can still move along.
      const double reach = free_normal.squaredNorm();
      Vec<Dim>& v = view.velocity[static_cast<std::size_t>(a.node)];
      const double approach = (v - a.body_velocity).dot(a.normal);
      if (approach >= 0.0 || reach < 1e-12) continue;
      const Vec<Dim> push = (-approach / reach) * free_normal;
      v += push;
      if (record && a.record >= 0) {
        records_[static_cast<std::size_t>(a.record)].force_on_material += a.mass * push / view.dt;
      }
    }
    if (!record) return;
    for (auto& r : records_) {
      r.normal_force = r.force_on_material.dot(r.normal);
      r.shear_force = r.force_on_material.dot(r.tangent);
      bodies_[static_cast<std::size_t>(r.body)].force_on_material += r.force_on_material;
    }
  }

  void advance(double dt, double time) {
    for (auto& e : bodies_) e.body.advance(dt, time);
  }

 private:
  static constexpr std::size_t pose_size = RigidBody<Dim>::pose_size;

  struct Entry {
    RigidBody<Dim> body;
    Interface interface;
    Vec<Dim> force_on_material;
  };

  const Entry& entry(int b) const {
    require_in_range("contact::RigidContact", "body index", b, 0, body_count() - 1, Bounds::closed);
    return bodies_[static_cast<std::size_t>(b)];
  }
  Entry& entry(int b) {
    require_in_range("contact::RigidContact", "body index", b, 0, body_count() - 1, Bounds::closed);
    return bodies_[static_cast<std::size_t>(b)];
  }

  void measure_gaps(const GridView<Dim>& view, const RigidBody<Dim>& body, int b) {
    detail::smallest_gaps(view, body, b, gaps_);
  }

  bool reaches_within_step(Index n, double v_n, double dt, const grid::Grid<Dim>& g) const {
    if (!gap_check_) return true;
    const double tolerance = gap_tolerance_cells_ * g.cell_size().minCoeff();
    return gaps_[static_cast<std::size_t>(n)] + dt * v_n <= tolerance;
  }

  void correct_body(GridView<Dim>& view, int b, bool record) {
    Entry& e = bodies_[static_cast<std::size_t>(b)];
    const RigidBody<Dim>& body = e.body;
    const auto& g = view.grid;
    detail::require_body_on_grid(g, body, b);
    if (gap_check_) measure_gaps(view, body, b);
    const double mid = view.time + 0.5 * view.dt;
    const Vec<Dim> body_velocity = body.velocity(mid);
    const typename RigidBody<Dim>::AngularVelocity body_omega = body.angular_velocity(mid);
    const Vec<Dim> reach = view.node_reach * g.cell_size();
    // Nodes whose support box can meet the body's bounding box.
    std::array<Index, Dim> lo{};
    std::array<Index, Dim> hi{};
    for (int d = 0; d < Dim; ++d) {
      const double a = (body.lower_bound()[d] - reach[d] - g.origin()[d]) / g.cell_size()[d];
      const double c = (body.upper_bound()[d] + reach[d] - g.origin()[d]) / g.cell_size()[d];
      lo[d] = static_cast<Index>(std::clamp(std::floor(a), 0.0, static_cast<double>(g.cells(d))));
      hi[d] = static_cast<Index>(std::clamp(std::ceil(c), 0.0, static_cast<double>(g.cells(d))));
    }
    const double mu = e.interface.friction_coefficient;
    const bool held = e.interface.rotation == Interface::Rotation::held && !view.spin.empty();
    const bool coupled = e.interface.rotation == Interface::Rotation::coupled;
    if (coupled) require_rotational_inertia(view, b);
    const Vec<Dim> half_cell = 0.5 * g.cell_size();
    grid::for_each_node_in_box(g, lo, hi, [&](Index n) {
      const double m = view.mass[n];
      if (m <= view.empty_mass) return;
      const Vec<Dim> x = g.node_position(n);
      if (!body.meets_open_box(x, reach)) return;
      const auto p = detail::contact_point(view, body, n, x, reach);
      const Vec<Dim> v_trial = view.velocity[n];
      const Vec<Dim> v_body = body.velocity_at(x, body_velocity, body_omega);
      const Vec<Dim> v_rel = v_trial - v_body;
      const double v_n = v_rel.dot(p.normal);
      const bool approaching = v_n < 0.0 && reaches_within_step(n, v_n, view.dt, g);
      Vec<Dim> v_new = v_trial;
      NodeState state = NodeState::separating;
      const double spin_trial = view.spin.empty() ? 0.0 : view.spin[static_cast<std::size_t>(n)];
      double spin_new = spin_trial;
      if (e.interface.kind == Interface::Kind::no_slip) {
        v_new = v_body;
        state = NodeState::bonded;
      } else if (e.interface.kind == Interface::Kind::fixed) {
        if (body.contains(x) || straddles_surface(body, x, half_cell)) {
          v_new = v_body;
          state = NodeState::bonded;
        }
      } else if (approaching && coupled) {
        if constexpr (Dim == 2) {
          const auto c = grain_wall_friction(v_rel, spin_trial - body_omega, p.normal, m,
                                             inertia_of(view, n), mu, e.interface.grain_radius);
          v_new = v_body + c.velocity;
          spin_new = body_omega + c.spin;
          state = c.state;
        }
      } else if (approaching) {
        const auto c = detail::coulomb_correction<Dim>(
            v_trial, v_body, p.normal, v_n, mu, detail::walled_components(view, n, p.normal));
        v_new = c.velocity;
        state = c.state;
      }
      view.velocity[n] = v_new;
      if constexpr (Dim == 2) {
        if (state != NodeState::separating && held && straddles_surface(body, x, half_cell)) {
          spin_new = body_omega;
        }
      }
      if (!view.spin.empty()) view.spin[static_cast<std::size_t>(n)] = spin_new;
      examined_.push_back(
          {n, record ? static_cast<Index>(records_.size()) : Index{-1}, m, p.normal, v_body});
      if (!record) return;
      ContactNode<Dim> r;
      r.node = n;
      r.body = b;
      r.edge = detail::face_of(p);
      r.along = detail::face_coordinates(p)[0];
      r.across = detail::face_coordinates(p)[1];
      r.position = x;
      r.normal = p.normal;
      r.tangent = body.face_tangent(r.edge);
      r.mass = m;
      r.force_on_material = m * (v_new - v_trial) / view.dt;
      r.normal_force = r.force_on_material.dot(r.normal);
      r.shear_force = r.force_on_material.dot(r.tangent);
      if (spin_new != spin_trial) {
        r.moment_on_material = inertia_of(view, n) * (spin_new - spin_trial) / view.dt;
      }
      r.state = state;
      e.force_on_material += r.force_on_material;
      records_.push_back(r);
    });
  }

  // A node the last correction looked at, kept for conditions_applied.
  struct ExaminedNode {
    Index node;
    Index record;  // into records_, or -1 in a phase that records nothing
    double mass;
    Vec<Dim> normal;
    Vec<Dim> body_velocity;
  };

  std::vector<Entry> bodies_;
  std::vector<ContactNode<Dim>> records_;
  std::vector<ExaminedNode> examined_;
  bool recorded_ = false;
  bool start_of_step_correction_ = false;
  bool gap_check_ = false;
  double gap_tolerance_cells_ = 0.0;
  std::vector<double> gaps_;  // per node, of the body being corrected
  Vec<Dim> cell_size_ = Vec<Dim>::Ones();
  Vec<Dim> origin_ = Vec<Dim>::Zero();
};

static_assert(ContactLaw<RigidContact<2>, 2>);
static_assert(ContactLaw<RigidContact<3>, 3>);

}  // namespace cosmpm::contact
