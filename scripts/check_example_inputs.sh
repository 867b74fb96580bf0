#!/usr/bin/env bash
# Bad and extreme inputs to the three examples: each must end with exit status 1 and a
# message naming what to change (checked by a fragment of it), never a crash, a hang or an
# exit 0 without its results. Run by ctest (examples/CMakeLists.txt):
#   scripts/check_example_inputs.sh BUILD/examples WORK_DIR
set -uo pipefail
bin=$1
work=$2
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$work" && mkdir -p "$work"
cd "$work"
e1=$bin/example_01_elastic_column
e2=$bin/example_02_earth_pressure
e3=$bin/example_03_flat_blade
smoke=(--case "$root/examples/03_flat_blade/cases/smoke.case")
failures=0
count=0

# expect STATUS FRAGMENT COMMAND...: the command ends with STATUS within 60 s, its output
# (stdout and stderr) contains FRAGMENT, and it leaves no temporary file in the work folder.
expect() {
  local status=$1 fragment=$2
  shift 2
  count=$((count + 1))
  local output
  output=$(timeout 60 "$@" 2>&1)
  local got=$?
  local leftovers
  leftovers=$(find . -name '*.tmp[0-9]*' | head -3)
  if [ "$got" -ne "$status" ] || [[ "$output" != *"$fragment"* ]] || [ -n "$leftovers" ]; then
    failures=$((failures + 1))
    echo "FAILED: $* (exit $got, expected $status; expected '$fragment')" >&2
    [ -n "$leftovers" ] && echo "  temporary files left: $leftovers" >&2
    echo "$output" | tail -5 | sed 's/^/  | /' >&2
  fi
}

touch a_file
long=$(printf 'x%.0s' $(seq 1 300))
printf 'depth = 0.1\ncells-x = 40\ndepth = 0.2\n' > twice.case
printf '\xef\xbb\xbfcells-x = 40\ncells-y = 24\ntravel = 0.002\nequilibrium-time = 0.02\naverage-from = 0\naverage-to = 0.002\nprofile-at = 0.0019\nframes = false\nout = hash#dir  # a comment\n' > bom.case

# --- example 03
expect 0 "Soil (corn" "$e3" --help
expect 0 "results in hash#dir" "$e3" --case bom.case
expect 1 "is a file, not a folder" "$e3" "${smoke[@]}" --out a_file
expect 1 "cannot create it (Not a directory)" "$e3" "${smoke[@]}" --out a_file/sub
expect 1 "cannot create it (File name too long)" "$e3" "${smoke[@]}" --out "$long"
expect 1 "cannot create it" "$e3" "${smoke[@]}" --out /proc/cosmpm
expect 1 "moves the blade" "$e3" "${smoke[@]}" --speed 100 --out speed
expect 1 "moves the blade" "$e3" "${smoke[@]}" --youngs-modulus 1e-300 --out soft
expect 1 "is outside the valid range (0, 1e+12]" "$e3" --youngs-modulus 1e308
expect 1 "days on" "$e3" "${smoke[@]}" --density 1e-300
expect 1 "days on" "$e3" "${smoke[@]}" --cfl 1e-300
expect 1 "days on" "$e3" "${smoke[@]}" --speed 1e-12 --threads 1
expect 1 "days on" "$e3" --mesh 100000x4 --threads 1
expect 1 "GB of memory" "$e3" --mesh 100000x100000
expect 1 "within one step of the end of --travel" "$e3" --profile-at 0.035
expect 1 "--cells-x = '1e20' is not a whole number" "$e3" --cells-x 1e20
expect 1 "--threads = 'nan' is not a whole number" "$e3" --threads nan
expect 1 "--rig-angle = 60 deg is outside the valid range [-45, 45]" "$e3" --rig-angle 60
expect 0 "rig turned 35 deg against the grid" "$e3" "${smoke[@]}" --rig-angle 35 --out turned
expect 1 "--threads = '1.7' is not a whole number" "$e3" --threads 1.7
expect 1 "'40.6x24.4' is not NXxNY with whole numbers" "$e3" --mesh 40.6x24.4
expect 1 "--depth is given twice" "$e3" --depth 0.1 --depth 0.2
expect 1 "line 3: 'depth' is already set on line 1" "$e3" --case twice.case
expect 1 "is a folder, not a file" "$e3" --case .
expect 1 "is not a regular file" "$e3" --case /dev/zero
expect 1 "--phi = 95 deg is outside the valid range (0, 60]" "$e3" --phi 95
expect 1 "--psi = 30 deg (command line): exceeds --phi = 26 deg (default)" "$e3" --psi 30
expect 1 "--average-to = 0.035 m (default): lies beyond --travel = 0.002 m (command line)" \
  "$e3" --travel 0.002
expect 1 "contradicts --material = mohr-coulomb" "$e3" --polar true --material mohr-coulomb
expect 1 "applies to polar soil only" "$e3" --length-scale 0.02
expect 1 "--micro-inertia-scale = 0 is outside the valid range (0, 1e+06]" "$e3" --polar true \
  --micro-inertia-scale 0
expect 1 "--micro-inertia-scale = 4 (command line): applies to polar soil only" "$e3" \
  --micro-inertia-scale 4
expect 1 "is not among the compositions built into this program" "$e3" --shape cubic-bspline \
  --integrator usf
expect 1 "unknown option 'dpeth' (did you mean --depth?)" "$e3" --dpeth 0.2
expect 1 "--flip = 0.9 (command line): blends FLIP into --transfer apic" "$e3" --transfer apic \
  --shape quadratic-bspline --flip 0.9
expect 1 "--antilocking = fbar (command line): applies to nonpolar soil only" "$e3" --polar true \
  --antilocking fbar
expect 1 "--transfer apic --antilocking none is not among the compositions" "$e3" --transfer apic
expect 1 "--floor-friction = 20 deg (command line): applies to --floor friction only" "$e3" \
  --floor-friction 20
expect 0 "results in run" "$e3" "${smoke[@]}" --frames false --out run
expect 1 "holds the results of an earlier run" "$e3" "${smoke[@]}" --frames false --out run
expect 0 "results in run" "$e3" "${smoke[@]}" --frames false --out run --replace true
expect 1 "holds no stopped run" "$e3" "${smoke[@]}" --out empty_folder --restart true
# A file-size limit stands in for a full disk: writes fail with EFBIG, reported, exit 1.
expect 1 "File too large" bash -c "ulimit -f 100; exec $e3 --case $root/examples/03_flat_blade/cases/smoke.case --out full3"

# --- example 01
expect 0 "Numerics" "$e1" --help
expect 1 "--cells = 'abc' is not a whole number" "$e1" --cells abc
expect 1 "unexpected argument '16'" "$e1" 16
expect 1 "is a file, not a folder" "$e1" --cells 8 --out a_file
expect 1 "File too large" bash -c "ulimit -f 1; exec $e1 --cells 64 --out full1"

# --- example 02
expect 0 "Net of characteristics" "$e2" --help
expect 1 "--height is given twice" "$e2" --height 0.1 --height 0.2
expect 1 "--delta = 30 deg (command line): exceeds --phi = 26 deg (default)" "$e2" --delta 30
expect 1 "--wall-lines = 20001 is outside the valid range [2, 20000]" "$e2" --wall-lines 20001
expect 1 "is a file, not a folder" "$e2" --out a_file
expect 1 "File too large" bash -c "ulimit -f 4; exec $e2 --out full2"
# A failed write leaves no empty file under its final name.
if find full1 full2 full3 -type f -size 0 2>/dev/null | grep -q .; then
  echo "FAILED: an empty result file was left in place" >&2
  failures=$((failures + 1))
fi

echo "check_example_inputs: $count inputs, $failures failed" >&2
[ "$failures" -eq 0 ]
