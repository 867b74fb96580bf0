#pragma once
// Contact laws: their concept and grid views, the single-field default and rigid bodies with
// Bardenhagen Coulomb contact.
#include "cosmpm/contact/concept.hpp"
#include "cosmpm/contact/convex_polyhedron.hpp"
#include "cosmpm/contact/grid_view.hpp"
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_body_3d.hpp"
#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/contact/single_field.hpp"
#include "cosmpm/contact/traction_average.hpp"
