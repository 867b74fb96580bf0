// Compiled without cosmpm::hdf5 by the consumer project: must fail with cosmpm's message.
#include <cosmpm/io/hdf5.hpp>

int main() {
  return 0;
}
