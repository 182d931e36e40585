#!/bin/sh
# A run stopped by SIGINT or SIGTERM exits 130 or 143 with its outputs
# whole, summary.json saying "interrupted" and a checkpoint; resuming it
# gives the series of the run that never stopped, byte for byte.
# Usage: cli_interrupt.sh DEMVV CASES_DIR
set -u
demvv=$1
cases=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
deck=$cases/s01_box_six_planes/case.prm
long="--set run/duration=0.3 --threads 1 --quiet"
fail() { echo "FAIL: $*"; exit 1; }

"$demvv" run "$deck" $long --out "$work/whole" 2>/dev/null || fail "the uninterrupted run failed"

for signal in INT TERM; do
  dir=$work/stopped_$signal
  "$demvv" run "$deck" $long --out "$dir" 2>"$work/err_$signal" &
  pid=$!
  # Stop it once it has written a few rows.
  tries=0
  while [ "$(grep -vc '^#' "$dir/series.csv" 2>/dev/null || echo 0)" -lt 5 ]; do
    tries=$((tries + 1))
    [ $tries -gt 600 ] && fail "$signal: the run wrote no rows within a minute"
    sleep 0.1
  done
  kill -s $signal $pid
  wait $pid
  code=$?
  [ "$signal" = INT ] && expected=130 || expected=143
  [ $code -eq 0 ] && fail "$signal: the run finished before the signal arrived: lengthen run/duration"
  [ $code -eq $expected ] || fail "$signal: exit code $code, expected $expected ($(cat "$work/err_$signal"))"
  grep -q '"state": "interrupted"' "$dir/summary.json" || fail "$signal: summary.json does not say interrupted"
  [ -f "$dir/checkpoint/driver.json" ] || fail "$signal: no checkpoint"
  grep -q -- "--resume" "$work/err_$signal" || fail "$signal: the message does not say how to resume"
  "$demvv" run "$deck" $long --set run/duration=0.4 --resume "$dir" 2>"$work/err_other"
  [ $? -eq 2 ] || fail "$signal: a resume with another deck was not refused with exit code 2"
  grep -q "another deck" "$work/err_other" || fail "$signal: the refusal does not say why: $(cat "$work/err_other")"
  "$demvv" run "$deck" $long --resume "$dir" 2>/dev/null || fail "$signal: the resumed run failed"
  grep -q '"state": "completed"' "$dir/summary.json" || fail "$signal: the resumed run did not complete"
  cmp -s "$dir/series.csv" "$work/whole/series.csv" || fail "$signal: resumed series.csv differs from the uninterrupted run"
done
"$demvv" run "$deck" $long --resume "$work/stopped_INT" 2>"$work/err_done"
[ $? -eq 2 ] || fail "a finished run (its checkpoint removed) was resumed"
echo "2 passed, 0 failed"
