#!/usr/bin/env bash
# Sets up, builds and runs the main example: the flat blade of Coetzee (2014), nonpolar MPM,
# h = 250 mm, 120 x 70 cells, 35 mm of travel, then plots it and renders the paper's
# coloured-layer view. Extra arguments go to the example (e.g. --depth 0.15, --mesh 80x50,
# --polar true, --case examples/03_flat_blade/cases/paper_h150.case; --method dem for the
# discrete model; --help lists them).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  -DCOSMPM_BUILD_TESTS=OFF -DCOSMPM_HEADER_CHECK=OFF >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
log=$(mktemp)
# Running this command again replaces the results of the same case (unless told otherwise).
extra=(--replace true)
for arg in "$@"; do
  case "$arg" in --replace* | --restart* | --check* | --help | -h) extra=() ;; esac
done
./build/release/examples/example_03_flat_blade "${extra[@]}" "$@" | tee "$log"
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
  if [ -f "$out/frames/flat_blade.xdmf" ]; then
    echo "ParaView: $out/frames/flat_blade.xdmf and $out/frames/flat_blade_bodies.xdmf (either reader)"
    # The paper's coloured-layer view; a failing virtual X server does not fail the run.
    if command -v pvbatch >/dev/null && command -v xvfb-run >/dev/null; then
      xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch --force-offscreen-rendering \
        scripts/paraview_layers.py "$out" 2>/dev/null | grep '^paraview_layers' \
        || echo "layers: not rendered (ParaView under xvfb failed; see README, How to open the results)"
    fi
  fi
fi
