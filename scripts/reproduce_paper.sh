#!/usr/bin/env bash
# The results of Coetzee (2014) from one command: every MPM (nonpolar and polar) and DEM run
# behind the paper's Figs. 1-3 and 6-13, then one PNG per figure beside the statement the
# paper makes about it (OUT/report.md, docs/validation.md "The paper's figures").
#
#   scripts/reproduce_paper.sh [--quick] [--no-dem] [--jobs N] [--out DIR] [--resume]
#
#   --quick   every MPM run on a 3x coarser mesh (40 x 24 for 120 x 70, 27 x 16 for 80 x 50),
#             every DEM run with grains twice as large (an eighth of the cost), the layers' DEM
#             run at 50 mm/s: the same cases and figures in a few minutes; CI runs it. Not for
#             conclusions.
#   --no-dem  the MPM runs only (DEM adds four runs, about as much processor time as the MPM).
#   --jobs N  runs at the same time (default 2, this machine's cores); each run is one thread.
#   --out DIR results (default out/paper, or out/paper_quick with --quick).
#   --resume  run only the cases that have not completed in DIR (after a stop, or a fix).
#
# Each run's log is OUT/runs/NAME.log; a run that stops keeps what it wrote, the figures use
# it, the report names it, and the script exits with 1 after plotting.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
cd "$root"

quick=false
dem=true
resume=false
jobs=2
out=
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) quick=true ;;
    --no-dem) dem=false ;;
    --resume) resume=true ;;
    --jobs) jobs=$2; shift ;;
    --jobs=*) jobs=${1#--jobs=} ;;
    --out) out=$2; shift ;;
    --out=*) out=${1#--out=} ;;
    -h | --help) sed -n '2,16p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "reproduce_paper.sh: unknown argument '$1' (valid: --quick, --no-dem, --jobs N, --out DIR, --resume)" >&2
       exit 2 ;;
  esac
  shift
done
if ! [[ "$jobs" =~ ^[1-9][0-9]*$ ]]; then
  echo "reproduce_paper.sh: --jobs $jobs is not a whole number >= 1" >&2
  exit 2
fi
if [ "$quick" = true ]; then
  out=${out:-out/paper_quick}
  fine=40x24
  coarse=27x16
  # Grains of 16-24 mm: a quarter of the grains, twice the step; a shorter rain.
  dem_grains="--size-min 0.016 --size-max 0.024 --settle-time 1.5"
  dem_flow_speed=0.05
else
  out=${out:-out/paper}
  fine=120x70
  coarse=80x50
  dem_grains=
  dem_flow_speed=0.01  # the experiment's 10 mm/s
fi

"$root/scripts/setup.sh"
cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DCOSMPM_BUILD_EXAMPLES=ON \
  >/dev/null
cmake --build build/release -j "${COSMPM_JOBS:-2}" --target example_03_flat_blade
driver=$root/build/release/examples/example_03_flat_blade

# shellcheck source=scripts/flat_blade_queue.sh
source "$root/scripts/flat_blade_queue.sh"
queue_mesh=$fine
queue_resume=$resume
# DEM (the paper's PFC2D model, the driver's calibrated corn grains): Figs. 1-2 (layers at
# 100-400 mm, h = 200 mm), 8 (drafts at the three depths), 10 (blade stresses at h = 350 mm)
# and 11 (PDR at 15 mm, h = 250 mm). The longest run first: the queue then packs the rest.
if [ "$dem" = true ]; then
  queue_case dem_flow "--method dem --depth 0.2 --travel 0.4 --speed $dem_flow_speed \
    --layer-thickness 0.025 --frame-interval 0.1 $dem_grains"
  for depth in 0.35 0.25 0.15; do
    queue_case "dem_h${depth}" "--method dem --depth $depth $dem_grains"
  done
fi
# Each case: the paper's defaults (Table 1, h = 250 mm, psi = 2 deg, fixed floor, MUSL, linear
# shape functions) unless its arguments say otherwise.
# Figs. 1-3: h = 200 mm pushed 400 mm for psi = 2, 10, 26 deg. On a Coulomb floor (the fixed
# floor holds the bottom row under the blade's tip), and with dilatancy stopping at a plastic
# shear strain of 0.1 for psi = 10 and 26 (without it the unbounded dilation of perfect
# plasticity stops those runs: docs/validation.md, "Large travel"). At 20 mm/s, twice the
# experiment's speed: the run is quasi-static either way (no damping while cutting; the kinetic
# energy is negligible), and at psi = 2 the free surface ahead of the blade at 100-400 mm moves
# by under 1 mm and the draft by under 1 % against 10 mm/s (docs/validation.md) for half the
# processor time.
flow="--depth 0.2 --travel 0.4 --speed 0.02 --floor friction --frame-interval 0.1 --average-to 0.1"
queue_case flow_psi26 "$flow --psi 26 --dilatancy-cutoff 0.1"
queue_case flow_psi10 "$flow --psi 10 --dilatancy-cutoff 0.1"
queue_case flow_psi2 "$flow --psi 2"
# Fig. 8 (polar), 9 (polar, both rotation conditions at the blade), 11 (polar PDR).
for depth in 0.35 0.25 0.15; do
  queue_case "polar_h${depth}" "--polar true --depth $depth"
done
queue_case polar_h0.35_free "--polar true --depth 0.35 --blade-rotation free"
# Fig. 6: h = 350 mm, 100 mm of travel, the three dilatancy angles on the paper's fixed floor,
# psi = 10 and 26 with the same cut-off as Figs. 1-3, all three with 5 % PIC (--flip 0.95):
# under pure FLIP a point that fell over the blade's top bounces on the floor behind it until it
# is crushed (psi = 10 stopped at 74 mm), and the psi effect here (under 1 % over 15-35 mm) is
# as small as the transfer's (docs/validation.md, "What stops"), so the three share one.
# The Coulomb floor at h = 350 mm serves Fig. 8 over 15-35 mm only: beyond 45-96 mm points
# that fell behind the blade end those runs (docs/validation.md, "Material over the blade's top").
for psi in 26 10 2; do
  cutoff=
  [ "$psi" = 2 ] || cutoff="--dilatancy-cutoff 0.1"
  queue_case "fig6_psi${psi}" "--depth 0.35 --travel 0.1 --psi $psi $cutoff --flip 0.95"
done
queue_case h0.35_psi2_floor "--depth 0.35 --floor friction"
# Fig. 7: psi = 2 at the three depths to 100 mm, with Fig. 6's 5 % PIC (h = 350 mm is
# fig6_psi2): under pure FLIP the h = 350 mm run, too, can stop where the heap spills over the
# blade (at 71 mm on 2026-12-02). Figs. 8-9 and 11-13: psi = 2 at the three depths on the
# paper's fixed floor to 35 mm, pure FLIP as the polar runs; Fig. 8 also on the Coulomb floor;
# Figs. 12-13 on the coarser mesh too.
for depth in 0.25 0.15; do
  queue_case "fig7_h${depth}" "--depth $depth --travel 0.1 --flip 0.95"
done
for depth in 0.35 0.25 0.15; do
  queue_case "h${depth}" "--depth $depth"
done
for depth in 0.25 0.15; do
  queue_case "h${depth}_floor" "--depth $depth --floor friction"
done
queue_case h0.25_coarse "--depth 0.25 --mesh $coarse"

queue_run "$driver" "$out/runs" "$jobs" paper
wall=$queue_wall

flags=()
[ "$quick" = true ] && flags+=(--quick)
# The set's wall time means something only when this call ran all of it.
[ "$resume" = false ] && flags+=(--wall-seconds "$wall")
/usr/bin/python3 scripts/plot_paper.py "$out" --meshes "$fine" "$coarse" \
  "${flags[@]+"${flags[@]}"}"
if [ "$queue_failed" -gt 0 ]; then
  echo "reproduce_paper.sh: $queue_failed run(s) stopped; their figures show what they wrote ($out/report.md)" >&2
  exit 1
fi
echo "reproduce_paper.sh: figures and report in $out (report.md)" >&2
