// Must not compile: APIC with the bilinear hat, whose gradient takes the velocity of nodes of
// vanishing mass at full weight (transfer/apic.hpp).
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
using Wrong = Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<>>,
                         contact::SingleField, integrator::MUSL, transfer::APIC>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
