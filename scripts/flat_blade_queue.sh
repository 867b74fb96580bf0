# shellcheck shell=bash
# A queue of flat-blade runs for the scripts that run sets of them (reproduce_paper.sh,
# refinement_study.sh); source it, add cases, run. Each run is one thread; JOBS run at once;
# a one-line report per finished run with the ETA from the planned particle-steps.
#
#   source scripts/flat_blade_queue.sh
#   queue_case NAME "ARGUMENTS"        # driver options; --mesh QUEUE_MESH is added unless given
#                                      # (or the case is a DEM one, --method dem)
#   queue_run DRIVER RUNS_DIR JOBS TAG # RUNS_DIR/NAME (output), NAME.log, NAME.status
#
# With queue_resume=true a case whose NAME.status says it completed is not run again (a set
# that was stopped, or had runs that stopped, continues with what is missing).
#
# After queue_run: queue_wall (s) and queue_failed (runs that stopped). A run that stops keeps
# what it wrote; its status file holds the exit code and its wall time, NAME.times the
# processor time (bash `times`).
queue_names=()
queue_arguments=()
queue_mesh=
queue_resume=false

queue_case() {
  queue_names+=("$1")
  shift
  queue_arguments+=("$*")
}

# A DEM case (--method dem) has no mesh.
queue_mesh_option() {
  case "$1" in *--mesh* | *"--method dem"*) ;; *) [ -n "$queue_mesh" ] && echo "--mesh $queue_mesh" ;; esac
  return 0
}

queue_format_seconds() { printf '%d:%02d' $(($1 / 60)) $(($1 % 60)); }

queue_run() {
  local driver=$1 runs=$2 jobs=$3 tag=$4
  local i line particles steps total=0 done_weight=0 finished=0 next=0 started
  local -a weights=() running=() still=()
  mkdir -p "$runs"
  local -a pending=()
  for i in "${!queue_names[@]}"; do
    if [ "$queue_resume" = true ] && [ -f "$runs/${queue_names[$i]}.status" ] &&
      [ "$(cut -d' ' -f1 "$runs/${queue_names[$i]}.status")" = 0 ]; then
      continue
    fi
    pending+=("$i")
  done
  for i in "${pending[@]+"${pending[@]}"}"; do
    # shellcheck disable=SC2086,SC2046
    line=$("$driver" --check ${queue_arguments[$i]} $(queue_mesh_option "${queue_arguments[$i]}") 2>&1 | tail -1)
    particles=$(sed -n 's/.*checked: \([0-9]*\) particles, \([0-9]*\) steps.*/\1/p' <<<"$line")
    steps=$(sed -n 's/.*checked: \([0-9]*\) particles, \([0-9]*\) steps.*/\2/p' <<<"$line")
    if [ -z "$particles" ] || [ -z "$steps" ]; then
      echo "[$tag] the case ${queue_names[$i]} does not check: $line" >&2
      return 2
    fi
    weights[i]=$((particles * steps / 1000))  # by case index, as the report reads it
    total=$((total + particles * steps / 1000))
  done
  echo "[$tag] ${#pending[@]} of ${#queue_names[@]} runs into $runs, $jobs at a time" >&2
  for i in "${pending[@]+"${pending[@]}"}"; do rm -f "$runs/${queue_names[$i]}.status"; done
  started=$(date +%s)
  while [ "$finished" -lt "${#pending[@]}" ]; do
    while [ "$next" -lt "${#pending[@]}" ] && [ "${#running[@]}" -lt "$jobs" ]; do
      queue_start_ "$driver" "$runs" "${pending[$next]}" &
      running+=("${pending[$next]}")
      next=$((next + 1))
    done
    sleep 1
    still=()
    for i in "${running[@]}"; do
      if [ -f "$runs/${queue_names[$i]}.status" ]; then
        finished=$((finished + 1))
        done_weight=$((done_weight + weights[i]))
        queue_report_ "$runs" "$i" "$tag" "$finished/${#pending[@]}" "$started" "$total" \
          "$done_weight"
      else
        still+=("$i")
      fi
    done
    running=("${still[@]+"${still[@]}"}")
  done
  wait
  queue_wall=$(($(date +%s) - started))
  queue_failed=0
  for i in "${!queue_names[@]}"; do
    read -r line _ <"$runs/${queue_names[$i]}.status"
    [ "$line" = 0 ] || queue_failed=$((queue_failed + 1))
  done
  echo "[$tag] all runs finished in $(queue_format_seconds $queue_wall) of wall time;" \
    "$queue_failed stopped" >&2
}

queue_start_() {
  local driver=$1 runs=$2 i=$3 name t0 status
  name=${queue_names[$i]}
  t0=$(date +%s)
  # shellcheck disable=SC2086,SC2046
  if "$driver" ${queue_arguments[$i]} $(queue_mesh_option "${queue_arguments[$i]}") \
    --threads 1 --replace true --out "$runs/$name" >"$runs/$name.log" 2>&1; then
    status=0
  else
    status=$?
  fi
  # The processor time of the run (its user and system time: the second line of `times`),
  # which a loaded machine does not inflate the way it does the wall time.
  times >"$runs/$name.times"
  echo "$status $(($(date +%s) - t0))" >"$runs/$name.status"
}

queue_report_() {
  local runs=$1 i=$2 tag=$3 finished=$4 started=$5 total=$6 done_weight=$7
  local name status seconds elapsed eta
  name=${queue_names[$i]}
  read -r status seconds <"$runs/$name.status"
  elapsed=$(($(date +%s) - started))
  eta=$((elapsed * (total - done_weight) / (done_weight > 0 ? done_weight : 1)))
  if [ "$status" = 0 ]; then
    printf '[%s] %s %s done in %s | elapsed %s | ETA %s\n' "$tag" "$finished" \
      "$name" "$(queue_format_seconds "$seconds")" \
      "$(queue_format_seconds $elapsed)" "$(queue_format_seconds $eta)" >&2
  else
    printf '[%s] %s %s STOPPED (exit %s) after %s: %s\n' "$tag" "$finished" \
      "$name" "$status" "$(queue_format_seconds "$seconds")" \
      "$(grep -m1 '^error' "$runs/$name.log" || tail -1 "$runs/$name.log")" >&2
  fi
}
