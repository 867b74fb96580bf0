#pragma once
// Contact laws: the single-field default and rigid bodies with Bardenhagen Coulomb contact.
#include "cosmpm/contact/rigid_body.hpp"
#include "cosmpm/contact/rigid_contact.hpp"
#include "cosmpm/contact/single_field.hpp"
#include "cosmpm/contact/traction_average.hpp"
