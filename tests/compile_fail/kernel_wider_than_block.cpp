// Must not compile: a kernel whose support (5 nodes, e.g. a quartic spline) is wider than a
// particle block (4 cells): the parallel scatter would race.
#include <array>

#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
struct FiveNodeKernel {
  static constexpr int support = 5;
  static const char* name() { return "five-node (test)"; }
  static Index evaluate(double, double, Index, std::array<double, 5>& w,
                        std::array<double, 5>& dw) {
    w.fill(0.2);
    dw.fill(0.0);
    return 0;
  }
};
static_assert(shape::Kernel<FiveNodeKernel>);
using Wrong = Simulation<2, FiveNodeKernel, continuum::Classical<material::LinearElastic<>>>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
