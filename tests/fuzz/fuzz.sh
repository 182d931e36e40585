#!/bin/sh
# Runs the fuzz targets: first over their regression corpus
# (regressions/<target>/, every input that ever crashed one), then, when
# SECONDS > 0, fuzzes each for SECONDS from a seed corpus built from the
# cases' decks, tests/data and the sample files, one target after the other.
# A crash, sanitizer report, timeout (10 s per input) or escaped exception
# fails: the input is kept in ARTIFACTS (default: a folder in /tmp) to be
# added to regressions/<target>/ once fixed.  Prints a line per target:
# executions, executions per second, new coverage.
#
# usage: fuzz.sh FUZZ_BUILD_DIR SOURCE_DIR SECONDS [TARGET...]
#   FUZZ_BUILD_DIR  the build folder's tests/fuzz (it holds fuzz_deck, ...)
#   TARGET          deck, overrides, particles, sample, plot (default: all five)
set -u
bin=$1
src=$2
seconds=$3
shift 3
targets=${*:-deck overrides particles sample plot}
here=$src/tests/fuzz
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
artifacts=${ARTIFACTS:-$(mktemp -d /tmp/demvv_fuzz_artifacts.XXXXXX)}
mkdir -p "$artifacts"

# Copies the seed inputs of a target into a folder, one file each.
seeds() { # TARGET DIR
  case $1 in
    deck) set -- "$2" "$src"/cases/*/case.prm "$src"/tests/data/*.prm "$src"/tests/data/bad/*.prm \
            "$src"/tests/data/bad/deck_*.json ;;
    overrides) set -- "$2" "$here"/seeds/overrides/* ;;
    particles) set -- "$2" "$src"/cases/*/*.csv "$src"/tests/data/*.csv "$src"/tests/data/bad/*.csv ;;
    sample) set -- "$2" "$src"/tests/data/*.json "$src"/tests/data/bad/sample_*.json ;;
    plot) set -- "$2" "$here"/seeds/plot/* ;;
  esac
  dir=$1
  shift
  n=0
  for f in "$@"; do
    n=$((n + 1))
    cp "$f" "$dir/seed_$n"
  done
}

failed=0
for target in $targets; do
  exe=$bin/fuzz_$target
  [ -x "$exe" ] || { echo "FAIL: no fuzz target $exe"; exit 1; }
  log=$work/$target.log
  # The regression corpus: each input once.
  set -- "$here"/regressions/"$target"/*
  if [ -e "$1" ]; then
    if ! "$exe" -timeout=10 -rss_limit_mb=4096 "$@" > "$log" 2>&1; then
      echo "FAIL: fuzz_$target: an input of regressions/$target fails again:"
      grep -E "Running:|ERROR|SUMMARY|runtime error|terminate|what\(\)" "$log" | tail -6
      failed=1
      continue
    fi
    echo "fuzz_$target: $# regression inputs pass"
  fi
  [ "$seconds" -gt 0 ] || continue
  corpus=$work/corpus_$target
  mkdir -p "$corpus"
  seeds "$target" "$corpus"
  cp "$here"/regressions/"$target"/* "$corpus"/ 2>/dev/null
  if "$exe" -max_total_time="$seconds" -timeout=10 -rss_limit_mb=4096 -print_final_stats=1 \
       -artifact_prefix="$artifacts/${target}_" "$corpus" > "$log" 2>&1; then
    runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log")
    rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log")
    added=$(sed -n 's/^stat::new_units_added: *//p' "$log")
    echo "fuzz_$target: $runs runs in $seconds s ($rate/s), $added new inputs, no finding"
  else
    echo "FAIL: fuzz_$target found an input that fails (kept in $artifacts):"
    grep -E "ERROR|SUMMARY|runtime error|terminate|what\(\)|Test unit written" "$log" | tail -6
    failed=1
  fi
done
exit "$failed"
