// Must not compile: a contact law without advance(dt, time).
#include "cosmpm/cosmpm.hpp"

using namespace cosmpm;
struct NoAdvance {
  static const char* name() { return "no advance (test)"; }
  void correct(contact::GridView<2>&) {}
};
using Wrong =
    Simulation<2, shape::Linear, continuum::Classical<material::LinearElastic<>>, NoAdvance>;
int main() {
  return sizeof(Wrong) > 0 ? 0 : 1;
}
