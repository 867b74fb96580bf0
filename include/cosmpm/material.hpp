#pragma once
// Every constitutive model of cosmpm.
#include "cosmpm/material/concept.hpp"
#include "cosmpm/material/cosserat_drucker_prager.hpp"
#include "cosmpm/material/cosserat_elastic.hpp"
#include "cosmpm/material/drucker_prager.hpp"
#include "cosmpm/material/drucker_prager_matching.hpp"
#include "cosmpm/material/linear_elastic.hpp"
#include "cosmpm/material/mohr_coulomb.hpp"
#include "cosmpm/material/stress_space.hpp"
