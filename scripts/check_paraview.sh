#!/usr/bin/env bash
# Opens XDMF series in both of ParaView's XDMF readers under a virtual X server and checks
# that every array and cell is read, equal in both, and renders (scripts/check_paraview.py).
#   scripts/check_paraview.sh OUTPUT_DIR SERIES.xdmf [SERIES.xdmf ...]
# Under heavy load the X connection of pvbatch sometimes fails ("bad X server connection":
# measured 35 % of XOpenDisplay calls at a load of 13 on two cores); such a failure, and only
# such, is retried.
set -uo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
log=$(mktemp)
for attempt in 1 2 3 4 5; do
  xvfb-run -a -s "-screen 0 1280x1024x24" pvbatch --force-offscreen-rendering \
    "$root/scripts/check_paraview.py" "$@" > "$log" 2>&1
  status=$?
  if [ "$status" -eq 0 ]; then
    grep '^check_paraview' "$log"
    rm -f "$log"
    exit 0
  fi
  grep -q "bad X server connection" "$log" || break
  echo "check_paraview: the X server connection failed (attempt $attempt); retrying" >&2
  sleep 2
done
grep -v '^\s*[0-9]* *0x' "$log" | tail -20 >&2
rm -f "$log"
exit 1
