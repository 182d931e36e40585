#!/bin/sh
# Memory traffic of the engine's step: the bytes a step fetches from memory
# per ball (particle-step), from valgrind's cachegrind (Debian `valgrind`)
# simulating a last-level cache of LL_BYTES (default 32 MiB, 16-way, 64-byte
# lines) around demvv_dem_bench.  Two runs of STEPS and 3 STEPS timed steps
# differ by 8 STEPS steps (the bench warms up for min(200, STEPS) steps and
# times three rounds), so the start-up cancels; the lines missed in the
# last-level cache (reads and the write-allocate of writes) times 64 bytes,
# per step and ball, is what a step streams in when the data exceed that
# cache.  Write-backs of dirtied lines come on top; cachegrind does not
# count them.
#
# valgrind 3.19 (bookworm) cannot decode AVX-512: build the bench for
# x86-64-v3, e.g.
#   cmake -S . -B build-v3 -DCMAKE_BUILD_TYPE=Release -DDEMVV_NATIVE=OFF \
#         -DCMAKE_CXX_FLAGS=-march=x86-64-v3
#   cmake --build build-v3 --target demvv_dem_bench
#
# usage: bench/memory_traffic.sh [BENCH [BALLS [STEPS]]]
#   BENCH  default build-v3/bench/demvv_dem_bench
#   BALLS  default 300000 (data far beyond the simulated cache)
#   STEPS  default 2, at most 66 (so that each run's warm-up is as long as one
#          timed round)
set -eu
bench=${1:-build-v3/bench/demvv_dem_bench}
balls=${2:-300000}
steps=${3:-2}
ll=${LL_BYTES:-33554432}
[ "$steps" -ge 1 ] && [ "$steps" -le 66 ] || { echo "memory_traffic.sh: STEPS must be 1 to 66" >&2; exit 2; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
trap 'exit 130' INT
trap 'exit 143' TERM
fail() { echo "memory_traffic.sh: $*" >&2; exit 1; }
# Prints the last-level data-cache misses of a run of STEPS timed steps.
misses() {
  valgrind --tool=cachegrind --cache-sim=yes --I1=32768,8,64 --D1=32768,8,64 --LL="$ll",16,64 \
    --cachegrind-out-file="$work/out" "$bench" "$balls" 1 "$1" > "$work/log" 2>&1 ||
    { cat "$work/log" >&2; fail "valgrind or the bench failed (above)"; }
  grep 'demvv_dem_bench:' "$work/log" | sed -n 's/.*balls \([0-9]*\),.*/\1/p' > "$work/balls"
  sed -n 's/.*LLd misses: *\([0-9,]*\).*/\1/p' "$work/log" | tr -d ,
}
command -v valgrind > /dev/null || fail "valgrind not found (Debian: apt-get install valgrind)"
short=$(misses "$steps")
long=$(misses $((3 * steps)))
n=$(cat "$work/balls")
for value in "$short" "$long" "$n"; do
  case $value in '' | *[!0-9]*) fail "could not read cachegrind's LLd misses or the ball count" ;; esac
done
echo "# $(uname -n), $(date -u '+%Y-%m-%d %H:%M UTC'), $bench, simulated last-level cache $ll bytes"
awk -v a="$short" -v b="$long" -v n="$n" -v s="$steps" 'BEGIN {
  lines = (b - a) / (8 * s)
  printf "balls %d: %.0f lines missed per step, %.0f bytes fetched per particle-step\n", n, lines, 64 * lines / n
}'
