#!/bin/sh
# Scaling of the engine: demvv_dem_bench (a static binary, bench/dem_bench.cpp)
# on lattice cylinders of about 6000, 60 000, 300 000 and 1 000 000 bonded
# balls, each on 1, 2, 4, 8 and 16 threads; one line per run with
# particle-steps/s (best of 3 timings), parallel efficiency against one
# thread, and peak resident memory per ball.  Thread counts above the
# machine's cores are skipped.  Copy the binary and this script to the
# machine to measure; nothing else is needed there.
#
# usage: bench/scaling.sh [BENCH] [BALLS...]
#   BENCH   default build/bench/demvv_dem_bench
#   BALLS   default 6000 60000 300000 1000000
# THREADS="1 2 4" overrides the thread counts.  The timed steps shrink with
# the ball count so that each run takes seconds (about 1e8 particle-steps
# per timing); building a million-ball specimen takes about a minute.
set -eu
bench=${1:-build/bench/demvv_dem_bench}
[ $# -gt 0 ] && shift
sizes=${*:-6000 60000 300000 1000000}
threads=${THREADS:-1 2 4 8 16}
cores=$(nproc)
echo "# $(uname -n), $cores cores, $(date -u '+%Y-%m-%d %H:%M UTC'), load: $(cut -d' ' -f1-3 /proc/loadavg)"
printf '%-9s %-8s %-14s %-11s %s\n' balls threads particle-steps/s efficiency bytes/ball
for n in $sizes; do
  steps=$(( 100000000 / n ))
  [ "$steps" -ge 20 ] || steps=20
  [ "$steps" -le 2000 ] || steps=2000
  one=""
  for t in $threads; do
    [ "$t" -le "$cores" ] || continue
    line=$("$bench" "$n" "$t" "$steps")
    rate=$(echo "$line" | sed -n 's/.*particle-steps\/s \([0-9.e+]*\),.*/\1/p')
    balls=$(echo "$line" | sed -n 's/.*balls \([0-9]*\),.*/\1/p')
    per_ball=$(echo "$line" | sed -n 's/.* \([0-9]*\) bytes\/ball.*/\1/p')
    [ -n "$one" ] || one=$rate
    eff=$(awk -v r="$rate" -v o="$one" -v t="$t" 'BEGIN { printf "%.0f %%", 100 * r / (o * t) }')
    printf '%-9s %-8s %-14s %-11s %s\n' "$balls" "$t" "$rate" "$eff" "$per_ball"
  done
done
