#!/bin/bash
# Whether the working tree's steps give the same bits as revision REV's (default HEAD): builds
# scripts/bits_check.cpp against each (native, -O3, as the benchmarks and examples build) and
# compares the checksums of every scheme the step benchmarks time, then the working tree's on two
# threads against its own on one. About a minute.
# usage: scripts/bits_check.sh [REV]
set -euo pipefail
rev=${1:-HEAD}
root=$(git rev-parse --show-toplevel)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$work/old"
git -C "$root" archive "$rev" include benchmarks | tar -x -C "$work/old"
build() {  # tree binary
  g++ -std=c++20 -O3 -march=native -fopenmp -DNDEBUG -I"$1/include" -I"$1/benchmarks/simulation" \
    -isystem /usr/include/eigen3 "$root/scripts/bits_check.cpp" -o "$2" -lbenchmark
}
build "$work/old" "$work/old.bin" &
build "$root" "$work/new.bin"
wait
OMP_NUM_THREADS=1 "$work/old.bin" >"$work/old.txt"
OMP_NUM_THREADS=1 "$work/new.bin" >"$work/new.txt"
if diff "$work/old.txt" "$work/new.txt"; then
  echo "same bits as $rev: $(wc -l <"$work/new.txt") runs"
else
  echo "bits differ from $rev (< $rev, > working tree)"
  exit 1
fi
# The working tree's steps on two threads: the same bits as on one.
OMP_NUM_THREADS=2 "$work/new.bin" 2 >"$work/new2.txt"
if diff "$work/new.txt" "$work/new2.txt"; then
  echo "same bits on two threads as on one"
else
  echo "bits differ between one thread and two (< one, > two)"
  exit 1
fi
