#!/usr/bin/env bash
# Sets up, builds and runs the main example: the flat blade of Coetzee (2014), nonpolar MPM,
# h = 250 mm, 120 x 70 cells, 35 mm of travel, then plots it. Extra arguments go to the
# example (e.g. --depth 0.15, --mesh 80x50, --polar true; --method dem for the discrete model;
# --help lists them all).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  -DCOSMPM_BUILD_TESTS=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
log=$(mktemp)
./build/release/examples/example_03_flat_blade "$@" | tee "$log"
out=$(sed -n 's/^results in \([^:]*\):.*/\1/p' "$log")
rm -f "$log"
if [ -n "$out" ] && [ -f "$out/biaxial.csv" ]; then  # --method dem --experiment biaxial
  /usr/bin/python3 scripts/plot_dem_flat_blade.py biaxial "$out" --out "$out/biaxial.png"
elif [ -n "$out" ] && [ -f "$out/packing.csv" ]; then  # --method dem
  dem_plot="/usr/bin/python3 scripts/plot_dem_flat_blade.py"
  $dem_plot forces "$out" --out "$out/forces.png"
  $dem_plot stress "$out" --out "$out/blade_stress.png"
  at=15  # the paper's Fig. 11; else the first particle snapshot (--pdr-at)
  [ -f "$out/particles_15mm.csv" ] ||
    at=$(ls "$out" | sed -n 's/^particles_\([0-9]*\)mm\.csv$/\1/p' | sort -n | head -1)
  [ -n "$at" ] && $dem_plot pdr "$out" --at "$at" --out "$out/pdr.png"
  echo "plots: $out/forces.png, $out/blade_stress.png, $out/pdr.png"
  echo "       (layers: --travel 0.4, then scripts/plot_dem_flat_blade.py layers $out --out ...)"
  echo "CSV:   $out/forces.csv, $out/blade_stress.csv, $out/summary.csv"
  echo "ParaView: $out/frames/dem_flat_blade.xdmf"
elif [ -n "$out" ]; then
  /usr/bin/python3 scripts/plot_flat_blade.py "$out"
  echo "plots: $out/forces.png, $out/blade_stress.png, $out/fields.png"
  echo "CSV:   $out/forces.csv, $out/blade_stress.csv, $out/summary.csv"
  [ -f "$out/frames/flat_blade.xdmf" ] && echo "ParaView: $out/frames/flat_blade.xdmf"
fi
