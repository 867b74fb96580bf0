#!/usr/bin/env bash
# Sets up, builds and runs every check: clang-format, a Release build of tests, examples,
# benchmarks and the header check (ctest includes the examples' bad-input and restart
# checks), short example runs opened in both ParaView XDMF readers, an ASan+UBSan test build
# with a longer fuzz of the option parsers, and the consumer project built against the
# installed package (with and without HDF5, compiling docs/usage.md's examples) and through
# add_subdirectory.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
jobs=${COSMPM_JOBS:-2}
# ctest runs tests side by side; OpenMP threads that spin at barriers while another process
# holds the core turn a one-second test into a minute. Sleeping waits cost little here.
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
"$root/scripts/setup.sh"

# A compiler cache shared by every clone on this machine: no object depends on where the clone
# lives (CCACHE_BASEDIR makes the compiler's paths relative, CCACHE_NOHASHDIR keeps the working
# directory out of the hash; tests take their output directory from the environment).
launcher=()
if command -v ccache >/dev/null; then
  export CCACHE_BASEDIR="$root" CCACHE_NOHASHDIR=true CCACHE_MAXSIZE=${CCACHE_MAXSIZE:-12G}
  launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
  ccache --zero-stats >/dev/null
fi

echo "== clang-format" >&2
mapfile -t sources < <(git ls-files '*.hpp' '*.cpp' 2>/dev/null || find include tests examples benchmarks -name '*.[hc]pp')
clang-format --dry-run -Werror "${sources[@]}"

echo "== Release build" >&2
cmake "${launcher[@]}" -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=ON -DCOSMPM_BUILD_BENCHMARKS=ON \
  -DCOSMPM_HEADER_CHECK=ON -DCMAKE_INSTALL_PREFIX="$root/build/install" >/dev/null
cmake --build build/release -j "$jobs"
ctest --test-dir build/release -j "$jobs" --output-on-failure

echo "== portable build: one particle per pack, no OpenMP" >&2
# The engine's scalar-lane path (pack width 1, what compilers without vector extensions get)
# and its serial path (no OpenMP) must give the same tested results. Only the areas with packed
# or threaded code: analysis and io have neither, and their builds cost minutes.
portable_areas=(core shape grid initial material continuum transfer integrator contact simulation dem)
cmake "${launcher[@]}" -S . -B build/portable -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-DCOSMPM_PACK_WIDTH=1" \
  -DCOSMPM_ENABLE_OPENMP=OFF -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/portable -j "$jobs" --target "${portable_areas[@]/#/cosmpm_test_}"
ctest --test-dir build/portable -j "$jobs" --output-on-failure \
  -R "^($(IFS='|'; echo "${portable_areas[*]}")):"

echo "== examples (short runs), ParaView's readers, the coloured-layer view" >&2
smoke=$(mktemp -d)
./build/release/examples/example_01_elastic_column --cells 16 --out "$smoke/01"
./build/release/examples/example_02_earth_pressure --out "$smoke/02"
./build/release/examples/example_03_flat_blade --case examples/03_flat_blade/cases/smoke.case \
  --out "$smoke/03"
/usr/bin/python3 scripts/plot_flat_blade.py "$smoke/03"
./build/release/examples/example_03_flat_blade --case examples/03_flat_blade/cases/smoke.case \
  --polar true --travel 0.001 --equilibrium-time 0.005 --average-to 0.001 --profile-at 0.0009 \
  --frame-interval 0.0005 --out "$smoke/03p"
for case_file in examples/03_flat_blade/cases/*.case; do
  ./build/release/examples/example_03_flat_blade --case "$case_file" --check true >/dev/null
done
# Both ParaView XDMF readers read every array and cell of a nonpolar and a polar frame.
scripts/check_paraview.sh "$smoke/paraview" "$smoke/03/frames/flat_blade.xdmf" \
  "$smoke/03/frames/flat_blade_bodies.xdmf" "$smoke/03p/frames/flat_blade.xdmf"
xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch --force-offscreen-rendering \
  scripts/paraview_layers.py "$smoke/03" --output "$smoke/layers.png" 2>&1 | grep '^paraview_layers' \
  || echo "paraview_layers: the X server connection failed (see scripts/check_paraview.sh); not an error of ours" >&2
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
# The 3D flat blade on a small rig: its frames (particles and the blade's faces) in both readers.
./build/release/examples/example_06_flat_blade_3d --depth 0.1 --width 0.04 --rig-length 0.4 \
  --rig-height 0.3 --blade-height 0.15 --glass-friction 10 --settle-time 0.02 --travel 0.003 \
  --average-from 0.001 --average-to 0.003 --profile-at 0.002 --frame-interval 0.0015 \
  --out "$smoke/06"
# Frames at 0, 1.5 and 3 mm: the end of travel gets its frame even when rounding stops the
# run just short of the last mark.
frames06=$(find "$smoke/06/frames" -name 'flat_blade_3d_*.h5' | wc -l)
[ "$frames06" -eq 3 ] || { echo "example 06 wrote $frames06 frames, expected 3" >&2; exit 1; }
# The blade's normal force summed over the node columns is the draft (a vertical face: the
# friction acts up and across), so the width profile loses or doubles no column.
/usr/bin/python3 - "$smoke/06/summary.txt" <<'PY'
import sys
summary = dict(line.split(" = ") for line in open(sys.argv[1]).read().split("\n") if " = " in line)
draft, across = float(summary["draft_N_per_m"]), float(summary["width_profile_mean_N_per_m"])
if abs(across - draft) > 1e-9 * abs(draft):
    sys.exit("example 06: the width profile sums to %r N/m, the draft is %r" % (across, draft))
PY
scripts/check_paraview.sh "$smoke/paraview06" "$smoke/06/frames/flat_blade_3d.xdmf" \
  "$smoke/06/frames/flat_blade_3d_bodies.xdmf"
/usr/bin/python3 scripts/plot_flat_blade_3d.py "$smoke/06" --out "$smoke/06/flat_blade_3d.png"
# The paper's figures on coarse meshes (DEM with coarse grains): every run of the set, every
# plot and the report.
scripts/reproduce_paper.sh --quick --out "$smoke/paper"
for figure in fig01_02_flow fig03_free_surface fig06_forces_psi fig07_forces_depth \
  fig08_draft_depth fig09_blade_stress fig10_dem_blade_stress fig11_pdr fig12_13_yield_shear; do
  test -s "$smoke/paper/$figure.png" || { echo "reproduce_paper.sh made no $figure.png" >&2; exit 1; }
done
rm -rf "$smoke"

echo "== ASan + UBSan build" >&2
# -O1 -g1: sanitizers want some optimisation for speed and line numbers for reports; more of
# either costs minutes of compile time on two cores.
cmake "${launcher[@]}" -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 -g1" -DCOSMPM_SANITIZE=ON \
  -DCOSMPM_BUILD_TESTS=ON -DCOSMPM_BUILD_EXAMPLES=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/sanitize -j "$jobs"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  ctest --test-dir build/sanitize -j "$jobs" --output-on-failure
# The option parsers fuzzed for longer than in ctest, under the sanitizers.
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  COSMPM_FUZZ_SECONDS=5 ./build/sanitize/tests/cosmpm_test_io --test-case='fuzz*'

echo "== consumer project: find_package (with and without HDF5), add_subdirectory, docs/usage.md" >&2
rm -rf build/install
cmake --install build/release >/dev/null
cmake "${launcher[@]}" -S tests/consumer -B build/consumer-installed -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_CONSUMER_MODE=find_package -DCMAKE_PREFIX_PATH="$root/build/install" >/dev/null
cmake --build build/consumer-installed -j "$jobs"
./build/consumer-installed/cosmpm_consumer
./build/consumer-installed/cosmpm_consumer_io
for usage in build/consumer-installed/cosmpm_usage_*; do "$usage" >/dev/null; done
# The core needs no HDF5: configured with find_package(HDF5) disabled.
cmake "${launcher[@]}" -S tests/consumer -B build/consumer-core -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_CONSUMER_MODE=find_package -DCOSMPM_CONSUMER_CORE_ONLY=ON \
  -DCMAKE_DISABLE_FIND_PACKAGE_HDF5=ON -DCMAKE_PREFIX_PATH="$root/build/install" >/dev/null
cmake --build build/consumer-core -j "$jobs"
./build/consumer-core/cosmpm_consumer
cmake "${launcher[@]}" -S tests/consumer -B build/consumer-subdirectory -G Ninja -DCMAKE_BUILD_TYPE=Release \
  -DCOSMPM_CONSUMER_MODE=add_subdirectory -DCOSMPM_SOURCE_DIR="$root" \
  -DCOSMPM_CONSUMER_USAGE=OFF >/dev/null
cmake --build build/consumer-subdirectory -j "$jobs"
./build/consumer-subdirectory/cosmpm_consumer
./build/consumer-subdirectory/cosmpm_consumer_io

[ ${#launcher[@]} -eq 0 ] || ccache --show-stats >&2
echo "== all checks passed" >&2
