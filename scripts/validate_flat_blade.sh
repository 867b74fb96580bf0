#!/usr/bin/env bash
# The validation runs of docs/validation.md: the flat blade at h = 150, 250, 350 mm on the
# 120 x 70 and 80 x 50 meshes, nonpolar and polar, then a table of average draft forces
# against Sokolovski (out/validation/table.md) and the plots of each run.
#   scripts/validate_flat_blade.sh [nonpolar|polar|all|dem] [extra example arguments...]
# dem: the discrete model at h = 150, 250, 350 mm (one thread, 10-20 min each), then its drafts
# beside Sokolovski, the experiment and the nonpolar 120 x 70 MPM runs if present
# (out/flat_blade_dem/depths.png).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
which=${1:-all}
shift || true
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
if [ "$which" = dem ]; then
  runs=()
  mpm=()
  for depth in 0.15 0.25 0.35; do
    run=out/flat_blade_dem/dense_mu0.1_rr0.2_h$depth  # the calibrated default
    /usr/bin/time -f "%e s wall" ./build/release/examples/example_03_flat_blade --method dem \
      --depth "$depth" --threads 1 --replace true --out "$run" "$@"
    /usr/bin/python3 scripts/plot_dem_flat_blade.py stress "$run" --out "$run/blade_stress.png"
    /usr/bin/python3 scripts/plot_dem_flat_blade.py pdr "$run" --out "$run/pdr.png"
    runs+=("$run")
    mm=$(awk "BEGIN { print $depth * 1000 }")
    if [ -f "out/flat_blade/h${mm}_120x70_nonpolar_psi0/summary.csv" ]; then
      mpm+=("out/flat_blade/h${mm}_120x70_nonpolar_psi0")
    fi
  done
  /usr/bin/python3 scripts/plot_dem_flat_blade.py forces "${runs[@]}" --out out/flat_blade_dem/forces.png
  /usr/bin/python3 scripts/plot_dem_flat_blade.py depths "${runs[@]}" --mpm "${mpm[@]}" \
    --out out/flat_blade_dem/depths.png
  exit 0
fi
# A rerun replaces the earlier results of the same cases (unless told otherwise).
extra=(--replace true)
for arg in "$@"; do
  case "$arg" in --replace* | --restart* | --out*) extra=() ;; esac
done
modes=()
case "$which" in
  nonpolar) modes=(false) ;;
  polar) modes=(true) ;;
  all) modes=(false true) ;;
  *) echo "usage: $0 [nonpolar|polar|all|dem] [example arguments...]" >&2; exit 2 ;;
esac
for polar in "${modes[@]}"; do
  for mesh in 120x70 80x50; do
    for depth in 0.15 0.25 0.35; do
      /usr/bin/time -f "%e s wall" ./build/release/examples/example_03_flat_blade \
        --polar "$polar" --mesh "$mesh" --depth "$depth" --threads 1 "${extra[@]}" "$@"
    done
  done
done
/usr/bin/python3 scripts/validation_table.py out/flat_blade > out/validation_table.md
cat out/validation_table.md
