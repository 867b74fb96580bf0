// Must not compile: a material given where a continuum belongs.
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
using Wrong = Simulation<2, shape::Linear, material::MohrCoulomb<>>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
