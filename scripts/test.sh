#!/usr/bin/env bash
# Sets up, builds and runs every check: clang-format, a Release build of tests, examples,
# benchmarks and the header check, an ASan+UBSan test build, and the consumer project built
# against the installed package and through add_subdirectory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=${COSMPM_JOBS:-2}
# ctest runs tests side by side; OpenMP threads that spin at barriers while another process
# holds the core turn a one-second test into a minute. Sleeping waits cost little here.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
"$root/scripts/setup.sh"

echo "== clang-format" >&2
mapfile -t sources < <(git ls-files '*.hpp' '*.cpp' 2>/dev/null || find include tests examples benchmarks -name '*.[hc]pp')
clang-format --dry-run -Werror "${sources[@]}"

echo "== Release build" >&2
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=ON -DCOSMPM_BUILD_BENCHMARKS=ON \
  -DCOSMPM_HEADER_CHECK=ON -DCMAKE_INSTALL_PREFIX="$root/build/install" >/dev/null
cmake --build build/release -j "$jobs"
ctest --test-dir build/release -j "$jobs" --output-on-failure

echo "== portable build: one particle per pack, no OpenMP" >&2
# The engine's scalar-lane path (pack width 1, what compilers without vector extensions get)
# and its serial path (no OpenMP) must give the same tested results.
cmake -S . -B build/portable -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-DCOSMPM_PACK_WIDTH=1" \
  -DCOSMPM_ENABLE_OPENMP=OFF -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/portable -j "$jobs"
ctest --test-dir build/portable -j "$jobs" --output-on-failure -E "compile-fail"

echo "== examples (short runs)" >&2
smoke=$(mktemp -d)
./build/release/examples/example_01_elastic_column 16 "$smoke/01"
./build/release/examples/example_02_earth_pressure --out "$smoke/02"
./build/release/examples/example_03_flat_blade --mesh 40x24 --travel 0.002 --equilibrium-time 0.02 \
  --average-from 0 --average-to 0.002 --profile-at 0.002 --frame-interval 0.001 --out "$smoke/03"
/usr/bin/python3 scripts/plot_flat_blade.py "$smoke/03"
./build/release/examples/example_03_flat_blade --polar true --mesh 40x24 --travel 0.001 \
  --equilibrium-time 0.005 --average-from 0 --average-to 0.001 --profile-at 0.001 --out "$smoke/03p"
./build/release/examples/example_03_flat_blade --method dem --depth 0.06 --rig-length 0.3 --rain-height 0.1 \
  --travel 0.003 --average-from 0 --average-to 0.003 --stress-from 0 --stress-to 0.003 --pdr-at 0.003 \
  --frame-interval 0.003 --out "$smoke/03dem"
/usr/bin/python3 scripts/plot_dem_flat_blade.py forces "$smoke/03dem" --out "$smoke/03dem/forces.png"
# Exit status 2: ended at --end-time before coming to rest, as a 0.05 s run does.
./build/release/examples/example_04_granular_collapse --cell 0.005 --end-time 0.05 \
  --frame-interval 0.025 --out "$smoke/04" || [ $? -eq 2 ]
./build/release/examples/example_04_granular_collapse --cell 0.005 --end-time 0.05 \
  --transfer apic --wall 0.2 --frames false --out "$smoke/04w" || [ $? -eq 2 ]
/usr/bin/python3 scripts/plot_granular_collapse.py "$smoke/04"
rm -rf "$smoke"

echo "== ASan + UBSan build" >&2
# -O1 -g1: sanitizers want some optimisation for speed and line numbers for reports; more of
# either costs minutes of compile time on two cores.
cmake -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DCOSMPM_SANITIZE=ON \
  -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/sanitize -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/sanitize -j "$jobs" --output-on-failure

echo "== consumer project: find_package and add_subdirectory" >&2
rm -rf build/install
cmake --install build/release >/dev/null
cmake -S tests/consumer -B build/consumer-installed -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_CONSUMER_MODE=find_package -DCMAKE_PREFIX_PATH="$root/build/install" >/dev/null
cmake --build build/consumer-installed -j "$jobs"
./build/consumer-installed/cosmpm_consumer
cmake -S tests/consumer -B build/consumer-subdirectory -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_CONSUMER_MODE=add_subdirectory -DCOSMPM_SOURCE_DIR="$root" >/dev/null
cmake --build build/consumer-subdirectory -j "$jobs"
./build/consumer-subdirectory/cosmpm_consumer

echo "== all checks passed" >&2
