#!/usr/bin/env bash
# Sets up, builds and runs the main example. Extra arguments go to the example.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  -DCOSMPM_BUILD_TESTS=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_01_elastic_column
./build/release/examples/example_01_elastic_column "$@"
