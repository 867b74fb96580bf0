#pragma once
// The three loops of a DEM step over raw arrays (pointers captured by value, components
// written one by one: see docs/architecture.md on what makes a particle loop reload its
// pointers). Each iteration writes only its own slots.
#include <cmath>
#include <cstdint>
#include <vector>

#include "cosmpm/core/types.hpp"
#include "cosmpm/dem/assembly.hpp"
#include "cosmpm/dem/contact_law.hpp"
#include "cosmpm/dem/contact_lists.hpp"
#include "cosmpm/dem/detail/parallel.hpp"
#include "cosmpm/dem/walls.hpp"

namespace cosmpm::dem::detail {

template <class Law, class Damping>
struct StepKernels {
  using Constants = typename Law::Constants;
  Assembly& assembly;
  const WallSet<typename Law::Material>& walls;
  ContactLists& lists;
  Constants pair;
  const std::vector<Constants>& wall_constants;
  const Damping& damping;
  Vec<2> gravity;
  double dt;
  std::vector<Vec<2>>& pair_force;
  std::vector<Vec<2>>& pair_torque;
  std::vector<double>& pair_normal;
  std::vector<double>& pair_shear;
  std::vector<double>& pair_overlap;
  std::vector<WallContact>& wall_contacts;

  int pair_forces(int threads) {
    auto& e = assembly.elements();
    const Vec<2>* x = e.template get<tag::Position<2>>().data();
    const Vec<2>* v = e.template get<tag::Velocity<2>>().data();
    const double* w = e.template get<field::Spin>().data();
    const double* r = e.template get<field::Radius>().data();
    const double* mass = e.template get<field::BodyMass>().data();
    const std::int32_t* first = lists.first.data();
    const std::int32_t* second = lists.second.data();
    ContactHistory* history = lists.history.data();
    Vec<2>* force = pair_force.data();
    Vec<2>* torque = pair_torque.data();
    double* normal_out = pair_normal.data();
    double* shear_out = pair_shear.data();
    double* overlap_out = pair_overlap.data();
    const Constants k = pair;
    const double step = dt;
    return parallel_for(threads, lists.pair_count(), [=](Index p) {
      const auto i = static_cast<std::size_t>(first[p]);
      const auto j = static_cast<std::size_t>(second[p]);
      const double dx = x[j][0] - x[i][0];
      const double dy = x[j][1] - x[i][1];
      const double reach = r[i] + r[j];
      const double d2 = dx * dx + dy * dy;
      if (!(d2 < reach * reach)) {
        history[p] = ContactHistory{};  // a contact that opens forgets its history
        force[p][0] = force[p][1] = 0.0;
        torque[p][0] = torque[p][1] = 0.0;
        normal_out[p] = shear_out[p] = overlap_out[p] = 0.0;
        return;
      }
      const double distance = std::sqrt(d2);
      const double nx = distance > 0.0 ? dx / distance : 1.0;
      const double ny = distance > 0.0 ? dy / distance : 0.0;
      const double overlap = reach - distance;
      const double li = r[i] - 0.5 * overlap;  // contact point: the middle of the overlap
      const double lj = r[j] - 0.5 * overlap;
      const double tx = -ny, ty = nx;
      const double spin = w[j] * lj + w[i] * li;
      const double ux = v[j][0] - v[i][0] - spin * tx;
      const double uy = v[j][1] - v[i][1] - spin * ty;
      ContactKinematics c;
      c.overlap = overlap;
      c.normal_velocity = ux * nx + uy * ny;
      c.tangential_velocity = ux * tx + uy * ty;
      c.effective_mass = mass[i] * mass[j] / (mass[i] + mass[j]);
      c.effective_radius = 2.0 * r[i] * r[j] / reach;
      c.relative_spin = w[j] - w[i];
      const ContactForce f = Law::force(k, c, history[p], step);
      force[p][0] = f.normal * nx + f.shear * tx;
      force[p][1] = f.normal * ny + f.shear * ty;
      torque[p][0] = -li * f.shear - f.rolling_moment;
      torque[p][1] = -lj * f.shear + f.rolling_moment;
      normal_out[p] = f.normal;
      shear_out[p] = f.shear;
      overlap_out[p] = overlap;
    });
  }

  int wall_forces(int threads) {
    auto& e = assembly.elements();
    const Vec<2>* x = e.template get<tag::Position<2>>().data();
    const Vec<2>* v = e.template get<tag::Velocity<2>>().data();
    const double* w = e.template get<field::Spin>().data();
    const double* r = e.template get<field::Radius>().data();
    const double* mass = e.template get<field::BodyMass>().data();
    const std::int32_t* element = lists.wall_element.data();
    const std::int32_t* wall = lists.wall_index.data();
    ContactHistory* history = lists.wall_history.data();
    WallContact* out = wall_contacts.data();
    const Constants* constants = wall_constants.data();
    const auto* set = &walls;
    const double step = dt;
    return parallel_for(threads, lists.wall_candidate_count(), [=](Index c) {
      const auto i = static_cast<std::size_t>(element[c]);
      const Index wi = wall[c];
      const WallPoint g = set->locate(wi, x[i]);
      WallContact& o = out[c];
      o.element = static_cast<Index>(i);
      o.wall = wi;
      o.overlap = r[i] - g.gap;
      o.edge = g.edge;
      o.along = g.along;
      o.normal = g.normal;
      if (!(o.overlap > 0.0)) {
        history[c] = ContactHistory{};
        o.normal_force = o.shear_force = o.rolling_moment = 0.0;
        o.point = g.point;
        return;
      }
      const double nx = g.normal[0], ny = g.normal[1];
      const double tx = -ny, ty = nx;
      const double l = r[i] - 0.5 * o.overlap;
      o.point = Vec<2>(x[i][0] - l * nx, x[i][1] - l * ny);
      const Vec<2> uw = set->velocity_at(wi, o.point);
      const double ux = v[i][0] - w[i] * l * tx - uw[0];
      const double uy = v[i][1] - w[i] * l * ty - uw[1];
      ContactKinematics k;
      k.overlap = o.overlap;
      k.normal_velocity = ux * nx + uy * ny;
      k.tangential_velocity = ux * tx + uy * ty;
      k.effective_mass = mass[i];
      k.effective_radius = r[i];
      k.relative_spin = w[i] - set->spin_of(wi);
      const ContactForce f = Law::force(constants[wi], k, history[c], step);
      o.normal_force = f.normal;
      o.shear_force = f.shear;
      o.rolling_moment = f.rolling_moment;
    });
  }

  // Gathers forces per element in a fixed order, then moves the bodies and their elements.
  int bodies(int threads, MotionReport& report) {
    auto& bs = assembly.bodies();
    auto& es = assembly.elements();
    Vec<2>* xb = bs.template get<tag::Position<2>>().data();
    Vec<2>* vb = bs.template get<tag::Velocity<2>>().data();
    double* theta = bs.template get<field::Angle>().data();
    double* omega = bs.template get<field::Spin>().data();
    const double* m = bs.template get<tag::Mass>().data();
    const double* inertia = bs.template get<field::Inertia>().data();
    Vec<2>* net = bs.template get<field::Force>().data();
    double* moment = bs.template get<field::Torque>().data();
    const std::int32_t* first_element = bs.template get<field::FirstElement>().data();
    const std::int32_t* element_count = bs.template get<field::ElementCount>().data();
    Vec<2>* xe = es.template get<tag::Position<2>>().data();
    Vec<2>* ve = es.template get<tag::Velocity<2>>().data();
    double* we = es.template get<field::Spin>().data();
    const double* r = es.template get<field::Radius>().data();
    const Vec<2>* offset = es.template get<field::Offset>().data();
    std::int32_t* contact_count = es.template get<field::ContactCount>().data();
    const Index* first_off = lists.first_offsets.data();
    const Index* second_off = lists.second_offsets.data();
    const std::int32_t* second_pairs = lists.second_pairs.data();
    const Index* wall_off = lists.wall_offsets.data();
    const Vec<2>* built = lists.built_at.data();
    const Vec<2>* force = pair_force.data();
    const Vec<2>* torque = pair_torque.data();
    const double* overlap = pair_overlap.data();
    const WallContact* wc = wall_contacts.data();
    const Damping damp = damping;
    const double gx = gravity[0], gy = gravity[1];
    const double step = dt;
    return parallel_for_motion(
        threads, assembly.body_count(), report, [=](Index b, MotionReport& local) {
          double fx = 0.0, fy = 0.0, tz = 0.0;
          const std::int32_t e0 = first_element[b];
          const std::int32_t e1 = e0 + element_count[b];
          for (std::int32_t e = e0; e < e1; ++e) {
            double ex = 0.0, ey = 0.0, et = 0.0;
            std::int32_t touching = 0;
            for (Index p = first_off[e]; p < first_off[e + 1]; ++p) {
              ex -= force[p][0];
              ey -= force[p][1];
              et += torque[p][0];
              touching += overlap[p] > 0.0 ? 1 : 0;
            }
            for (Index q = second_off[e]; q < second_off[e + 1]; ++q) {
              const auto p = static_cast<std::size_t>(second_pairs[q]);
              ex += force[p][0];
              ey += force[p][1];
              et += torque[p][1];
              touching += overlap[p] > 0.0 ? 1 : 0;
            }
            for (Index c = wall_off[e]; c < wall_off[e + 1]; ++c) {
              const WallContact& o = wc[c];
              if (!(o.overlap > 0.0)) continue;
              const double nx = o.normal[0], ny = o.normal[1];
              ex += o.normal_force * nx - o.shear_force * ny;
              ey += o.normal_force * ny + o.shear_force * nx;
              et += o.rolling_moment - (r[e] - 0.5 * o.overlap) * o.shear_force;
              ++touching;
            }
            contact_count[e] = touching;
            const double rx = xe[e][0] - xb[b][0], ry = xe[e][1] - xb[b][1];
            fx += ex;
            fy += ey;
            tz += et + rx * ey - ry * ex;
          }
          fx += m[b] * gx;
          fy += m[b] * gy;
          net[b][0] = fx;
          net[b][1] = fy;
          moment[b] = tz;
          vb[b][0] += step * damp.damp(fx, vb[b][0]) / m[b];
          vb[b][1] += step * damp.damp(fy, vb[b][1]) / m[b];
          omega[b] += step * damp.damp(tz, omega[b]) / inertia[b];
          xb[b][0] += step * vb[b][0];
          xb[b][1] += step * vb[b][1];
          theta[b] += step * omega[b];
          if (e1 - e0 == 1 && offset[e0][0] == 0.0 && offset[e0][1] == 0.0) {
            // A disk: its element sits on the centroid (no trigonometry).
            const double mx = xb[b][0] - xe[e0][0], my = xb[b][1] - xe[e0][1];
            if (!(mx * mx + my * my <= r[e0] * r[e0]) && e0 < local.first_unstable) {
              local.first_unstable = e0;
            }
            xe[e0][0] = xb[b][0];
            xe[e0][1] = xb[b][1];
            ve[e0][0] = vb[b][0];
            ve[e0][1] = vb[b][1];
            we[e0] = omega[b];
            const double bx = xb[b][0] - built[e0][0], by = xb[b][1] - built[e0][1];
            local.max_drift_squared = std::max(local.max_drift_squared, bx * bx + by * by);
            return;
          }
          const double cs = std::cos(theta[b]);
          const double sn = std::sin(theta[b]);
          for (std::int32_t e = e0; e < e1; ++e) {
            const double ox = cs * offset[e][0] - sn * offset[e][1];
            const double oy = sn * offset[e][0] + cs * offset[e][1];
            const double nx = xb[b][0] + ox, ny = xb[b][1] + oy;
            const double mx = nx - xe[e][0], my = ny - xe[e][1];
            if (!(mx * mx + my * my <= r[e] * r[e]) && e < local.first_unstable) {
              local.first_unstable = e;
            }
            xe[e][0] = nx;
            xe[e][1] = ny;
            ve[e][0] = vb[b][0] - omega[b] * oy;
            ve[e][1] = vb[b][1] + omega[b] * ox;
            we[e] = omega[b];
            const double bx = nx - built[e][0], by = ny - built[e][1];
            local.max_drift_squared = std::max(local.max_drift_squared, bx * bx + by * by);
          }
        });
  }
};

}  // namespace cosmpm::dem::detail
