#!/bin/sh
# Busy-machine benchmark: demvv bench on 1 and on all cores, idle and beside
# one competing CPU-bound process (a shell loop), with OpenMP's waits as
# libgomp has them by default (spin about 300 000 times, then sleep),
# passive (sleep at once) and active (spin); then the thread count demvv
# picks by default; then the cost of each contact law on one thread.
#
# usage: bench/busy_machine.sh [DEMVV] [STEPS]     (from the repository root)
# Prints one line per configuration: particle-steps/s, best of 3.
set -eu
demvv=${1:-build/demvv}
steps=${2:-1000}
cores=$(nproc)
run() { # LABEL THREADS|default WAITS (default, passive or active)
  if [ "$2" = default ]; then flag=""; else flag="--threads $2"; fi
  if [ "$3" = default ]; then waits=""; else waits="OMP_WAIT_POLICY=$3"; fi
  line=$(env $waits "$demvv" bench --steps "$steps" --repeat 3 $flag 2>&1 | tail -1)
  rate=$(echo "$line" | sed -n 's/.*particle-steps\/s \([0-9.e+]*\),.*/\1/p')
  used=$(echo "$line" | sed -n 's/.*threads \([0-9]*\) .*/\1/p')
  printf '%-34s %-8s %2s threads  %-7s %s particle-steps/s\n' "$1" "$2" "$used" "$3" "$rate"
}
table() { # LABEL
  for t in $(printf '%s\n' 1 $((cores - 1)) "$cores" | sort -nu); do
    [ "$t" -ge 1 ] || continue
    run "$1" "$t" default
    run "$1" "$t" passive
    run "$1" "$t" active
  done
  run "$1" default default
}
table "idle"
sh -c 'while :; do :; done' &
competitor=$!
trap 'kill $competitor 2>/dev/null' EXIT
table "beside one CPU-bound process"
kill $competitor 2>/dev/null || true
trap - EXIT
# The contact laws' cost on one thread, idle.
for law in linear burgers modified_burgers; do
  rate=$("$demvv" bench --steps "$steps" --repeat 3 --threads 1 --law "$law" 2>&1 |
         sed -n 's/.*particle-steps\/s \([0-9.e+]*\),.*/\1/p')
  printf '%-34s %-8s %2s threads  %-7s %s particle-steps/s\n' "idle, law $law" 1 1 default "$rate"
done
