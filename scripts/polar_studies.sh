#!/usr/bin/env bash
# The polar flat-blade studies of issue 15 from one command, at h = 150, 250 and 350 mm
# (docs/validation.md, "Polar MPM: what makes the difference"):
#   mc       nonpolar Mohr-Coulomb (the paper's nonpolar model)
#   dp       nonpolar Drucker-Prager with the polar run's cone (the cone without Cosserat)
#   dp_ps    nonpolar Drucker-Prager, the exact plane-strain cone
#   held     polar, rotation held at the blade (the paper's)
#   free     polar, rotation free at the blade
#   coupled  polar, Cosserat wall friction at the blade (v_t - r w)
#   gc05     polar, Gc = 0.5 G (the paper: -1.3 %)
#   l2       polar, l = 2 mm (the paper: -1.9 %)
#   ps       polar, the exact plane-strain cone instead of the per-angle one
#   held_d7, held_d0  polar with blade friction delta = 7 and 0 deg (what the paper's drafts need)
#   rot35_*  mc and held with the whole rig turned 35 deg against the grid
#
#   scripts/polar_studies.sh [--jobs N] [--out DIR] [--resume] [--mesh NXxNY]
#
# POLAR_STUDIES_DRIVER=PATH runs another build of the driver (a copy, so that rebuilding
# build/release does not change the program under a running set).
#
# Results: DIR/runs/NAME (each run's folder), DIR/studies.md (the tables). About 46 processor
# minutes on 120 x 70 (about 25 minutes of wall time at 2 jobs).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"
resume=false
jobs=2
out=out/polar_studies
mesh=120x70
while [ $# -gt 0 ]; do
  case "$1" in
    --resume) resume=true ;;
    --jobs) jobs=$2; shift ;;
    --jobs=*) jobs=${1#--jobs=} ;;
    --out) out=$2; shift ;;
    --out=*) out=${1#--out=} ;;
    --mesh) mesh=$2; shift ;;
    --mesh=*) mesh=${1#--mesh=} ;;
    -h | --help) sed -n '2,22p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "polar_studies.sh: unknown argument '$1' (valid: --jobs N, --out DIR, --resume, --mesh NXxNY)" >&2
       exit 2 ;;
  esac
  shift
done
if ! [[ "$jobs" =~ ^[1-9][0-9]*$ ]]; then
  echo "polar_studies.sh: --jobs $jobs is not a whole number >= 1" >&2
  exit 2
fi
"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
driver=${POLAR_STUDIES_DRIVER:-$root/build/release/examples/example_03_flat_blade}
# shellcheck source=scripts/flat_blade_queue.sh
source "$root/scripts/flat_blade_queue.sh"
queue_mesh=$mesh
queue_resume=$resume
# The polar runs first: they are the long ones, so two jobs finish together.
for depth in 0.35 0.25 0.15; do
  queue_case "held_h$depth" "--depth $depth --polar true"
  queue_case "free_h$depth" "--depth $depth --polar true --blade-rotation free"
  queue_case "coupled_h$depth" "--depth $depth --polar true --blade-rotation coupled"
  queue_case "gc05_h$depth" "--depth $depth --polar true --gc-over-g 0.5"
  queue_case "l2_h$depth" "--depth $depth --polar true --length-scale 0.002"
  queue_case "ps_h$depth" "--depth $depth --polar true --cone plane-strain"
done
for depth in 0.35 0.25 0.15; do
  queue_case "mc_h$depth" "--depth $depth"
  queue_case "dp_h$depth" "--depth $depth --material drucker-prager --cone plane-strain-per-angle"
  queue_case "dp_ps_h$depth" "--depth $depth --material drucker-prager --cone plane-strain"
done
# Less blade friction in the polar model: what the paper's lower polar drafts would need. With
# less friction material slips down the face and under the blade's tip; the few particles that
# then leave the rig behind the blade are removed (counted in summary.csv) instead of ending it.
for depth in 0.35 0.25 0.15; do
  queue_case "held_d7_h$depth" "--depth $depth --polar true --delta 7 --stray-particles remove"
  queue_case "held_d0_h$depth" "--depth $depth --polar true --delta 0 --stray-particles remove"
done
# The mesh-orientation study: the whole rig turned 35 deg against the grid (the paper's Sect. 3.3).
for depth in 0.35 0.25 0.15; do
  queue_case "rot35_held_h$depth" "--depth $depth --polar true --rig-angle 35"
  queue_case "rot35_mc_h$depth" "--depth $depth --rig-angle 35"
done
queue_case rot35_free_h0.25 "--depth 0.25 --polar true --rig-angle 35 --blade-rotation free"
queue_run "$driver" "$out/runs" "$jobs" polar-studies
/usr/bin/python3 scripts/polar_studies_table.py "$out" >"$out/studies.md"
echo "polar_studies.sh: tables in $out/studies.md" >&2
if [ "$queue_failed" -gt 0 ]; then
  echo "polar_studies.sh: $queue_failed run(s) stopped (their logs: $out/runs/NAME.log)" >&2
  exit 1
fi
