#!/usr/bin/env bash
# The validation runs of docs/validation.md: the flat blade at h = 150, 250, 350 mm on the
# 120 x 70 and 80 x 50 meshes, nonpolar and polar, then a table of average draft forces
# against Sokolovski (out/validation/table.md) and the plots of each run.
#   scripts/validate_flat_blade.sh [nonpolar|polar|all] [extra example arguments...]
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
which=${1:-all}
shift || true
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
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
  *) echo "usage: $0 [nonpolar|polar|all] [example arguments...]" >&2; exit 2 ;;
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
