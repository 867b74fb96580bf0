#!/usr/bin/env bash
# A flat-blade run stopped by SIGTERM and restarted (--restart true) writes the same
# forces.csv, blade_stress.csv and frames as one that was not stopped; so does a restart
# from a --checkpoint-every checkpoint, nonpolar, polar and with fused MUSL; a second run into a folder in
# use is refused; a stopped run leaves no temporary file and an index of complete frames.
# Run by ctest:
#   scripts/check_flat_blade_restart.sh BUILD/examples/example_03_flat_blade WORK_DIR
set -euo pipefail
program=$1
work=$2
root=$(cd "$(dirname "$0")/.." && pwd)
rm -rf "$work" && mkdir -p "$work"
cd "$work"
# 40 x 24 cells, 10 mm of travel: about 4400 steps, a second or two.
case_options=(--case "$root/examples/03_flat_blade/cases/smoke.case" --travel 0.01
  --average-to 0.01 --profile-at 0.005 --frame-interval 0.002 --checkpoint-every 0.003
  --threads 1)
fail() { echo "check_flat_blade_restart: FAILED: $*" >&2; exit 1; }

"$program" "${case_options[@]}" --out straight > straight.log 2>&1 || fail "the straight run: $(tail -3 straight.log)"

# Stopped by SIGTERM once the blade moves, then restarted.
"$program" "${case_options[@]}" --out stopped > stopped.log 2>&1 &
pid=$!
for _ in $(seq 1 600); do
  [ -f stopped/forces.csv ] && [ "$(wc -l < stopped/forces.csv)" -gt 20 ] && break
  sleep 0.02
done
# While it runs, a second run into its folder meets the lock.
if "$program" "${case_options[@]}" --out stopped --replace true > second.log 2>&1; then
  fail "a second run into a folder in use was not refused"
fi
grep -q "is in use by another run" second.log || fail "the lock message: $(cat second.log)"
kill -TERM "$pid" 2>/dev/null || true
status=0
wait "$pid" || status=$?
[ "$status" -eq 143 ] || fail "the stopped run ended with $status, not 143 (SIGTERM); did it end first? $(tail -2 stopped.log)"
grep -q "stopped by SIGTERM" stopped.log || fail "no stop message: $(tail -3 stopped.log)"
[ -z "$(find stopped -name '*.tmp[0-9]*')" ] || fail "temporary files left: $(find stopped -name '*.tmp*')"
"$program" "${case_options[@]}" --out stopped --restart true > restarted.log 2>&1 || fail "the restart: $(tail -3 restarted.log)"

# Restarted from the last --checkpoint-every checkpoint of a complete run.
cp -r straight from_checkpoint
rm -f from_checkpoint/.cosmpm-lock
"$program" "${case_options[@]}" --out from_checkpoint --restart true > from_checkpoint.log 2>&1 || fail "the restart from a checkpoint: $(tail -3 from_checkpoint.log)"

# Polar (Cosserat: micro-rotations and their settings): a complete run, then a restart from
# its last checkpoint.
polar_options=(--case "$root/examples/03_flat_blade/cases/smoke.case" --polar true --travel 0.004
  --equilibrium-time 0.005 --average-to 0.004 --profile-at 0.002 --frame-interval 0.001
  --checkpoint-every 0.0015 --threads 1)
"$program" "${polar_options[@]}" --out polar > polar.log 2>&1 || fail "the polar run: $(tail -3 polar.log)"
cp -r polar polar_from_checkpoint
rm -f polar_from_checkpoint/.cosmpm-lock
"$program" "${polar_options[@]}" --out polar_from_checkpoint --restart true > polar_restart.log 2>&1 || fail "the polar restart: $(tail -3 polar_restart.log)"
grep -q "^polar = true" polar_from_checkpoint/case.used || fail "the polar run's case.used does not say polar"

# Fused MUSL (integrator/fused.hpp): the records its last pass scattered are not in the
# checkpoint; the restarted run scatters afresh in the fused pass's order, so it writes the
# same bits.
"$program" "${case_options[@]}" --integrator fused-musl --out fused > fused.log 2>&1 || fail "the fused run: $(tail -3 fused.log)"
cp -r fused fused_from_checkpoint
rm -f fused_from_checkpoint/.cosmpm-lock
"$program" "${case_options[@]}" --integrator fused-musl --out fused_from_checkpoint --restart true > fused_restart.log 2>&1 || fail "the fused restart: $(tail -3 fused_restart.log)"

compare() {
/usr/bin/python3 - "$@" <<'PYTHON'
import csv, pathlib, sys
import h5py, numpy as np

def same_h5(a, b, path=""):
    diffs = []
    for key in set(a.attrs) | set(b.attrs):
        if key not in a.attrs or key not in b.attrs or \
                np.asarray(a.attrs[key]).tobytes() != np.asarray(b.attrs[key]).tobytes():
            diffs.append(path + "@" + key)
    if isinstance(a, h5py.Dataset):
        if a.shape != b.shape or a.dtype != b.dtype or a[()].tobytes() != b[()].tobytes():
            diffs.append(path)
        return diffs
    for key in set(a) | set(b):
        if key not in a or key not in b:
            diffs.append(path + "/" + key)
        else:
            diffs += same_h5(a[key], b[key], path + "/" + key)
    return diffs

straight = pathlib.Path(sys.argv[1])
problems = []
for other in map(pathlib.Path, sys.argv[2:]):
    for name in ("forces.csv", "blade_stress.csv", "frames/flat_blade.xdmf",
                 "frames/flat_blade_bodies.xdmf", "case.used"):
        if (straight / name).read_bytes() != (other / name).read_bytes():
            problems.append("%s/%s differs" % (other, name))
    with open(straight / "summary.csv") as a, open(other / "summary.csv") as b:
        ra, rb = next(csv.DictReader(a)), next(csv.DictReader(b))
        for key in ra:
            if key not in ("run_seconds", "steps") and ra[key] != rb[key]:
                problems.append("%s summary.csv %s: %s vs %s" % (other, key, rb[key], ra[key]))
    frames = sorted((straight / "frames").glob("flat_blade_*.h5"))
    if len(frames) != len(list((other / "frames").glob("flat_blade_*.h5"))):
        problems.append("%s has another number of frames" % other)
    for frame in frames:
        with h5py.File(frame, "r") as a, h5py.File(other / "frames" / frame.name, "r") as b:
            diffs = same_h5(a, b)
            if diffs:
                problems.append("%s/frames/%s: %s" % (other, frame.name, ", ".join(diffs[:5])))
    print("check_flat_blade_restart: %s: %d frames, forces and profile compared" % (other, len(frames)))
if problems:
    sys.exit("check_flat_blade_restart: FAILED:\n  " + "\n  ".join(problems))
PYTHON
}
compare straight stopped from_checkpoint
compare polar polar_from_checkpoint
compare fused fused_from_checkpoint
echo "check_flat_blade_restart: stopped and restarted runs wrote what the straight run wrote" >&2
