// Must not compile: the Cosserat continuum is 2D only (issue 18 keeps it plane strain).
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
using Wrong = Simulation<3, shape::Linear, continuum::Cosserat<material::CosseratDruckerPrager<>>>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
