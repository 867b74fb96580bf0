// Must not compile: a plane-strain model in a 3D simulation.
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
using Wrong = Simulation<3, shape::Linear, continuum::Classical<material::LinearElastic<>>>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
