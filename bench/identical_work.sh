#!/bin/sh
# Identical work, demvv against LIGGGHTS: the prepared 6000-ball sample's
# balls (listed in a shuffled order), unbonded, pressed in their cylinder by
# the top plane; the same contacts, stiffnesses, friction, time step and
# number of steps in both engines (bench/identical_work.py writes the files).
# Rounds interleave the engines: demvv on 1 thread, LIGGGHTS on 1 rank,
# demvv on 2 threads, LIGGGHTS on 2 ranks, demvv with its default thread
# count (set against LIGGGHTS on 2 ranks), under each of the chosen loads;
# LIGGGHTS runs twice each time, with the peers' neighbour skin (0.2 mm) and
# with one as narrow as demvv's adaptive skin at rest (faster on this slow
# compression), and each round's ratio is also given against the faster:
#   idle   nothing else runs;
#   half   a loop that keeps one core busy half of the time (50 ms on, 50 ms off);
#   full   a loop that keeps one core busy all the time.
# Prints every run (speed, threads used, contacts and top stress at the end),
# each round's demvv / LIGGGHTS ratio, and whether every run did the same
# work (contacts and top stress within 0.5 %).  LIGGGHTS is skipped when
# `liggghts` is not installed (Debian: apt-get install liggghts openmpi-bin).
#
# GNU/Linux: the half load times itself with `date +%s%N` and `sleep 0.05`.
#
# The table ends with each ratio's median over the rounds of a load and a
# distribution-free interval for it: nine rounds give it 96 % coverage,
# three only 75 % (a single round under a load scatters by 10-30 %).
# Each round starts with the time a cache line takes between two cores and
# back (demvv_core_round_trip, built beside demvv; skipped when absent): on
# a virtual machine it changes within the hour (150-550 ns seen on one), and
# two threads' speed changes with it.
#
# usage: bench/identical_work.sh [DEMVV] [STEPS] [ROUNDS] [LOADS]
#   defaults: build/demvv 5000 3 "idle half full"      (from the repository root)
set -eu
demvv=${1:-build/demvv}
steps=${2:-5000}
rounds=${3:-3}
loads=${4:-idle half full}
work=$(mktemp -d)
load_pid=""
cleanup() {
  [ -z "$load_pid" ] || kill "$load_pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT
trap 'cleanup; exit 130' INT TERM
here=$(dirname "$0")
"$demvv" run cases/p01_thesis_6000/case.prm --out "$work/prepared" --quiet
python3 "$here/identical_work.py" write "$work/prepared/sample.json" "$work" "$steps"
start_load() { # idle | half | full
  case $1 in
    idle) load_pid="" ;;
    half) sh -c 'while :; do end=$(($(date +%s%N) + 50000000)); while [ "$(date +%s%N)" -lt "$end" ]; do :; done; sleep 0.05; done' &
      load_pid=$! ;;
    full) sh -c 'while :; do :; done' & load_pid=$! ;;
  esac
}
stop_load() {
  [ -z "$load_pid" ] || kill "$load_pid" 2>/dev/null || true
  load_pid=""
}
results=$work/results.txt
# demvv_core_round_trip (bench/core_round_trip.cpp), built beside demvv.
probe=$(dirname "$demvv")/bench/demvv_core_round_trip
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), $(nproc) cores, load before $(cut -d' ' -f1-3 /proc/loadavg), $(python3 "$here/identical_work.py" build "$work/prepared")"
for load in $loads; do
  start_load "$load"
  round=1
  while [ "$round" -le "$rounds" ]; do
    # The machine's cross-core round trip, which two threads' (and ranks')
    # speed follows on a virtual machine, measured under this round's load.
    if [ -x "$probe" ]; then
      trip=$("$probe" | sed -n 's/^core round trip \([0-9.]*\) ns.*/\1/p')
      echo "$load round_trip $round ns=$trip" | tee -a "$results"
    fi
    for n in 1 2 default; do
      if [ "$n" = default ]; then threads=""; else threads="--threads $n"; fi
      # shellcheck disable=SC2086
      "$demvv" run "$work/scene.prm" --out "$work/demvv_run" --replace $threads --quiet
      python3 "$here/identical_work.py" demvv "$work/demvv_run" "$load demvv $n $round" | tee -a "$results"
      if [ "$n" != default ] && command -v liggghts > /dev/null; then
        for input in liggghts liggghts_narrow; do
          if [ "$n" = 1 ]; then
            (cd "$work" && liggghts -in $input.in -log none > liggghts.log 2>&1) || true
          else
            (cd "$work" && mpirun --allow-run-as-root --oversubscribe -np "$n" liggghts -in $input.in -log none \
              > liggghts.log 2>&1) || true
          fi
          python3 "$here/identical_work.py" liggghts "$work/liggghts.log" "$load $input $n $round" | tee -a "$results"
        done
      fi
    done
    round=$((round + 1))
  done
  stop_load
done
echo
python3 "$here/identical_work.py" table "$results"
