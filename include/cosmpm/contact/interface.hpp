#pragma once
// How the material meets a rigid body (the interface's law), and what a contact law records
// of each contact node and of the traction along a body's edge.
#include <cmath>

#include "cosmpm/core/error.hpp"
#include "cosmpm/core/types.hpp"

namespace cosmpm::contact {

// How the material meets one rigid body.
struct Interface {
  enum class Kind {
    coulomb,  // Bardenhagen: no interpenetration, free separation, Coulomb friction
    no_slip,  // single field: the material node moves with the body (no separation either)
    fixed,    // a grid face's fixed condition for a body at any angle: the nodes inside the
              // body or straddling its surface move with it, the rest are free
  };
  Kind kind = Kind::coulomb;
  double friction_coefficient = 0.0;  // mu = tan(delta), for Kind::coulomb
  // Cosserat runs: the condition on the nodal micro-spin at the body (contact/wall_rotation.hpp).
  enum class Rotation {
    free,     // nothing imposed (zero couple traction)
    held,     // spin = the body's angular velocity at the nodes straddling its surface
    coupled,  // Coulomb friction on the grains' contact-point slip v_t - r (omega - Omega)
  };
  Rotation rotation = Rotation::free;
  double grain_radius = 0.0;  // r = d50 / 2 (m), > 0 for Rotation::coupled

  static Interface coulomb(double mu) {
    require_non_negative("contact::Interface::coulomb", "friction coefficient mu", mu);
    Interface i;
    i.friction_coefficient = mu;
    return i;
  }
  // mu = tan(delta) from the interface friction angle delta in degrees, 0 <= delta < 90.
  static Interface coulomb_angle(double delta_degrees) {
    require_in_range("contact::Interface::coulomb_angle", "interface friction angle (degrees)",
                     delta_degrees, 0.0, 90.0, Bounds::left_closed);
    return coulomb(std::tan(degrees_to_radians(delta_degrees)));
  }
  static Interface frictionless() { return coulomb(0.0); }
  static Interface no_slip() {
    Interface i;
    i.kind = Kind::no_slip;
    return i;
  }
  // Where no_slip holds every node whose support reaches the body (up to a cell and a half
  // from a surface turned against the grid), fixed holds only the nodes a grid face would:
  // those whose control volume (half a cell either side) the surface crosses, and those inside.
  static Interface fixed() {
    Interface i;
    i.kind = Kind::fixed;
    return i;
  }
  Interface& with_rotation_held(bool hold = true) {
    rotation = hold ? Rotation::held : Rotation::free;
    return *this;
  }
  // The grains at the face roll and slide: Coulomb friction acts on the slip of their contact
  // point, and its moment (friction force x r) turns them. r: the mean grain radius d50 / 2.
  Interface& with_grain_rotation_coupled(double radius) {
    require_positive("contact::Interface::with_grain_rotation_coupled", "grain radius r (m)",
                     radius);
    rotation = Rotation::coupled;
    grain_radius = radius;
    return *this;
  }
  static constexpr const char* rotation_name(Rotation r) {
    return r == Rotation::held ? "held" : r == Rotation::coupled ? "coupled" : "free";
  }
};

enum class NodeState { separating, stick, slip, bonded };

// One contact node of the last end-of-step correction.
template <int Dim>
struct ContactNode {
  Index node = 0;
  int body = 0;
  int edge = 0;  // the body's edge (2D) or face (3D) the node was attributed to
  // The node's foot point on it: along the edge from its start vertex (2D); in 3D (along,
  // across) are its (u, v) coordinates in the face's frame (ConvexPolyhedron).
  double along = 0.0;
  double across = 0.0;
  Vec<Dim> position = Vec<Dim>::Zero();
  Vec<Dim> normal = Vec<Dim>::Zero();   // the body's outward unit normal used at the node
  Vec<Dim> tangent = Vec<Dim>::Zero();  // unit vector along the edge (2D) or the face's u (3D)
  double mass = 0.0;
  // m (v_corrected - v_trial) / dt, less any component a boundary condition then imposed,
  // plus the push back out of the body after a friction wall (RigidContact::conditions_applied)
  Vec<Dim> force_on_material = Vec<Dim>::Zero();
  double normal_force = 0.0;  // force_on_material . normal: >= 0 when the body pushes
  double shear_force = 0.0;   // force_on_material . tangent (3D: the u part of the shear)
  // I (spin_corrected - spin_trial) / dt on the rotational degree of freedom (N m per m of
  // width; I: the node's rotational inertia), from a held or coupled rotation; 0 when free.
  double moment_on_material = 0.0;
  NodeState state = NodeState::separating;
};

// Traction the material exerts on one stretch of a body's edge, per unit out-of-plane width.
struct TractionBin {
  double centre = 0.0;  // along the edge from its start vertex
  double width = 0.0;
  double normal_traction = 0.0;  // pressure on the body's face (compression positive)
  double shear_traction = 0.0;   // on the body along the edge tangent
  int nodes = 0;                 // contact nodes pressing in the bin
};

// Traction the material exerts on one patch of a 3D body's face: bins of the face's (u, v)
// frame (ConvexPolyhedron), per unit area.
struct TractionPatch {
  Vec<2> centre = Vec<2>::Zero();  // (u, v) in the face's frame
  Vec<2> size = Vec<2>::Zero();
  double normal_traction = 0.0;            // pressure on the face (compression positive)
  Vec<2> shear_traction = Vec<2>::Zero();  // on the body along u and v
  int nodes = 0;                           // contact nodes pressing in the patch
};

}  // namespace cosmpm::contact
