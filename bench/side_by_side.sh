#!/bin/sh
# Two builds of demvv at the same time, one per core: `demvv run DECK` on
# one thread each, the first build pinned to core 0 and the second to core 1
# in odd rounds, the other way round in even ones.  A run on one core does
# not slow a run on the other on the 2-core machine of BENCHMARKS.md (two
# runs at once each ran 0.96-1.05 times a lone run), so both builds see the
# same moment of a machine whose speed drifts; the geometric mean of an odd
# and the next even round cancels the two cores' own difference.
#
# Prints each round (both rates in particle-steps/s, AFTER / BEFORE, whether
# the two series.csv are byte-identical), each pair's geometric mean and
# their median.  One thread per build: a two-thread comparison cannot run
# this way and needs interleaved runs (bench/identical_work.sh).
#
# usage: bench/side_by_side.sh BEFORE_DEMVV AFTER_DEMVV DECK [ROUNDS]
#   ROUNDS default 8 (even).  Needs two cores, taskset (util-linux), python3.
#   Exit 2 on bad arguments, 77 where the machine cannot run it.
set -eu
if [ $# -lt 3 ]; then
  echo "usage: bench/side_by_side.sh BEFORE_DEMVV AFTER_DEMVV DECK [ROUNDS]" >&2
  exit 2
fi
before=$1 after=$2 deck=$3 rounds=${4:-8}
case $rounds in
  '' | *[!0-9]* | 0)
    echo "side_by_side.sh: ROUNDS is '$rounds': expected a positive whole number" >&2
    exit 2
    ;;
esac
for bin in "$before" "$after"; do
  [ -x "$bin" ] || { echo "side_by_side.sh: '$bin' is not an executable" >&2; exit 2; }
done
[ -f "$deck" ] || { echo "side_by_side.sh: deck '$deck' does not exist" >&2; exit 2; }
# A machine that cannot run it (one core, no taskset) is not an input error:
# exit 77, which the smoke test reads as skipped.
[ "$(nproc)" -ge 2 ] || { echo "side_by_side.sh: needs two cores, this machine has $(nproc)" >&2; exit 77; }
command -v taskset > /dev/null || { echo "side_by_side.sh: needs taskset (Debian: util-linux)" >&2; exit 77; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
echo "# $(date -u '+%Y-%m-%d %H:%M UTC'), load $(cut -d' ' -f1-3 /proc/loadavg), deck $deck"
echo "# before $before, after $after"
round=1
while [ "$round" -le "$rounds" ]; do
  core_before=$(((round + 1) % 2)) core_after=$((round % 2))
  taskset -c "$core_before" "$before" run "$deck" --out "$work/before" --replace --quiet --threads 1 > "$work/before.log" 2>&1 &
  pid=$!
  if ! taskset -c "$core_after" "$after" run "$deck" --out "$work/after" --replace --quiet --threads 1 > "$work/after.log" 2>&1; then
    wait "$pid" || true
    echo "side_by_side.sh: $after failed:" >&2
    cat "$work/after.log" >&2
    exit 1
  fi
  if ! wait "$pid"; then
    echo "side_by_side.sh: $before failed:" >&2
    cat "$work/before.log" >&2
    exit 1
  fi
  same=no
  cmp -s "$work/before/series.csv" "$work/after/series.csv" && same=yes
  python3 -c '
import json, sys
before, after = (json.load(open(d + "/summary.json"))["particle_steps_per_second"] for d in sys.argv[1:3])
print(f"round {sys.argv[3]}: before {before:.4g} (core {sys.argv[4]}), after {after:.4g} (core {sys.argv[5]}),"
      f" after / before {after / before:.3f}, series identical: {sys.argv[6]}")
print(repr(after / before), file=open(sys.argv[7], "a"))
' "$work/before" "$work/after" "$round" "$core_before" "$core_after" "$same" "$work/ratios"
  round=$((round + 1))
done
python3 -c '
import math, statistics, sys
ratios = [float(line) for line in open(sys.argv[1])]
pairs = [math.sqrt(ratios[i] * ratios[i + 1]) for i in range(0, len(ratios) - 1, 2)]
if pairs:
    print("pairs (geometric means of rounds 1-2, 3-4, ...): " + ", ".join(f"{p:.3f}" for p in pairs))
    print(f"after / before, median of {len(pairs)} pairs: {statistics.median(pairs):.3f}"
          f" (range {min(pairs):.3f}-{max(pairs):.3f})")
' "$work/ratios"
