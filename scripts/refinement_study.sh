#!/usr/bin/env bash
# The flat blade's draft under mesh refinement (docs/validation.md, "Refinement"): h = 150,
# 250, 350 mm on 80 x 50, 120 x 70 and 240 x 140 cells, for three discretisations: the
# paper's (bilinear shape functions, MUSL, FLIP), with F-bar anti-locking, and quadratic
# B-splines with APIC. Then OUT/refinement.md (drafts against Sokolovski and against the
# Davis-reduced collapse load of the non-associated soil) and OUT/refinement.png.
#
#   scripts/refinement_study.sh [--floor fixed|friction] [--meshes "80x50 120x70 240x140"]
#                               [--variants "linear fbar apic"] [--options "..."] [--jobs N]
#                               [--out DIR]
#
# --options: more options of example_03_flat_blade for every run, e.g. "--separated-pic
# true". A point that leaves the rig is frozen and counted (--stray-particles freeze; the
# table says how many), so one point cannot stop a 40-minute run.
#
# Default: the Coulomb floor (on the paper's fixed floor the bottom row held under the blade
# adds 10-11 points to every draft, docs/validation.md); about 75 min of one core in all, most
# of it on 240 x 140.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
floor=friction
meshes="80x50 120x70 240x140"
variants="linear fbar apic"
jobs=2
extra=
out=
while [ $# -gt 0 ]; do
  case "$1" in
    --floor) floor=$2; shift ;;
    --meshes) meshes=$2; shift ;;
    --variants) variants=$2; shift ;;
    --options) extra=$2; shift ;;
    --jobs) jobs=$2; shift ;;
    --out) out=$2; shift ;;
    -h | --help) sed -n '2,18p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "refinement_study.sh: unknown argument '$1'" >&2; exit 2 ;;
  esac
  shift
done
case "$floor" in fixed | friction) ;; *)
  echo "refinement_study.sh: --floor $floor is not one of fixed, friction" >&2; exit 2 ;;
esac
out=${out:-out/refinement_$floor}

"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade \
  example_02_earth_pressure
driver=$root/build/release/examples/example_03_flat_blade

# shellcheck source=scripts/flat_blade_queue.sh
source "$root/scripts/flat_blade_queue.sh"
for variant in $variants; do
  case "$variant" in
    linear) options="" ;;
    fbar) options="--antilocking fbar" ;;
    apic) options="--shape quadratic-bspline --transfer apic" ;;
    *) echo "refinement_study.sh: variant '$variant' is not one of linear, fbar, apic" >&2
       exit 2 ;;
  esac
  # The finest mesh first: the longest runs, so the two slots end together.
  for mesh in $(tr ' ' '\n' <<<"$meshes" | sort -t x -k1,1nr); do
    for depth in 0.35 0.25 0.15; do
      queue_case "${variant}_${mesh}_h${depth}" \
        "--depth $depth --mesh $mesh --floor $floor --frames false --stray-particles freeze $options $extra"
    done
  done
done
queue_run "$driver" "$out/runs" "$jobs" refinement
/usr/bin/python3 scripts/plot_refinement.py "$out" \
  --earth-pressure build/release/examples/example_02_earth_pressure
[ "$queue_failed" -eq 0 ]
