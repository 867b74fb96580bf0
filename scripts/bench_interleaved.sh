#!/bin/bash
# Runs benchmark binaries in turn, round after round, on one pinned core, so that
# builds compared before and after share the machine's mood; prints the medians.
# usage: scripts/bench_interleaved.sh [-r ROUNDS] [-c CORE] -f FILTER LABEL=BINARY [LABEL=BINARY ...]
set -euo pipefail
rounds=5 core=0 filter=
while getopts "r:c:f:" opt; do
  case $opt in
    r) rounds=$OPTARG ;;
    c) core=$OPTARG ;;
    f) filter=$OPTARG ;;
    *) exit 2 ;;
  esac
done
shift $((OPTIND - 1))
if [[ -z $filter || $# -lt 1 ]]; then
  echo "usage: $0 [-r ROUNDS] [-c CORE] -f FILTER LABEL=BINARY [LABEL=BINARY ...]" >&2
  exit 2
fi
csv=$(mktemp) errors=$(mktemp)
trap 'rm -f "$csv" "$errors"' EXIT
echo "uptime before: $(uptime)" >&2
for ((round = 1; round <= rounds; ++round)); do
  for pair in "$@"; do
    label=${pair%%=*} binary=${pair#*=}
    OMP_WAIT_POLICY=passive taskset -c "$core" "$binary" --benchmark_filter="$filter" \
      --benchmark_repetitions=5 --benchmark_enable_random_interleaving=true \
      --benchmark_report_aggregates_only=true --benchmark_min_time=0.5 \
      --benchmark_format=csv 2>"$errors" | { grep '_median"' || true; } |
      sed "s/^/$label,$round,/" >>"$csv" || {
      status=$?  # the benchmark's own message (an exception's, say) is in its standard error
      echo "$binary failed (status $status) in round $round; its standard error ends:" >&2
      tail -n 5 "$errors" >&2
      exit "$status"
    }
    if ! grep -q "^$label,$round," "$csv"; then
      echo "$binary: no benchmark matches '$filter'" >&2
      exit 1
    fi
  done
  echo "round $round of $rounds done" >&2
done
echo "uptime after: $(uptime)" >&2
/usr/bin/python3 - "$csv" <<'PY'
import csv, statistics, sys, collections
times = collections.defaultdict(list)
for label, _, name, _, real, *_ in csv.reader(open(sys.argv[1])):
    times[(name.removesuffix("_median"), label)].append(float(real))
print("benchmark,build,median of round medians (real time),rounds (same unit)")
for (name, label), values in sorted(times.items()):
    rounds = " ".join(f"{v:.4g}" for v in values)
    print(f"{name},{label},{statistics.median(values):.4g},{rounds}")
PY
