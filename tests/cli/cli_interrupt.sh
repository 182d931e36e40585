#!/bin/sh
# A run stopped by SIGINT or SIGTERM exits 130 or 143 with its outputs
# whole, summary.json saying "interrupted" and a checkpoint; resuming it
# gives the series of the run that never stopped, byte for byte, with the
# linear law and with Burger's contacts (whose element state the checkpoint
# must carry), by the command its message gives; a resume with another
# deck or on another build is refused; a comparison says it cannot be
# resumed; a signal while the figures are drawn exits 143 with the
# results whole and the summary saying which part was stopped; a signal
# while a sample is prepared ends the preparation (and the test waiting for
# it) with exit 143 and an honest summary.
# Usage: cli_interrupt.sh DEMVV CASES_DIR
set -u
demvv=$1
cases=$2
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
deck=$cases/s01_box_six_planes/case.prm
fail() { echo "FAIL: $*"; exit 1; }
# The box for 0.3 s of simulated time on one thread: long enough that the
# signal, sent once a few rows are written, arrives well before the end.
duration=0.3
run_box() { "$demvv" run "$deck" --set run/duration=$duration --set "contact law/law=$law" --threads 1 --quiet "$@"; }
# In the background the function's subshell becomes demvv itself, so that $!
# is the process the signal must reach.
run_box_in_background() { exec "$demvv" run "$deck" --set run/duration=$duration --set "contact law/law=$law" --threads 1 --quiet "$@"; }

passed=0
for law in linear burgers; do
  run_box --out "$work/whole_$law" 2>/dev/null || fail "$law: the uninterrupted run failed"
  for signal in INT TERM; do
    dir=$work/stopped_${law}_$signal
    run_box_in_background --out "$dir" 2>"$work/err" &
    pid=$!
    tries=0
    while [ "$(grep -vc '^#' "$dir/series.csv" 2>/dev/null || echo 0)" -lt 5 ]; do
      tries=$((tries + 1))
      [ $tries -gt 600 ] && fail "$law $signal: the run wrote no rows within a minute"
      sleep 0.1
    done
    kill -s $signal $pid
    wait $pid
    code=$?
    [ "$signal" = INT ] && expected=130 || expected=143
    [ $code -eq 0 ] && fail "$law $signal: the run finished before the signal arrived: lengthen run/duration"
    [ $code -eq $expected ] || fail "$law $signal: exit code $code, expected $expected ($(cat "$work/err"))"
    grep -q '"state": "interrupted"' "$dir/summary.json" || fail "$law $signal: summary.json does not say interrupted"
    [ -f "$dir/checkpoint/driver.json" ] || fail "$law $signal: no checkpoint"
    # The command the message gives, run as given (it must repeat the
    # deck's --set values: a resume with others is refused); summary.json
    # gives the same.
    continue_with=$(sed -n 's/.*; continue with: demvv //p' "$work/err")
    [ -n "$continue_with" ] || fail "$law $signal: the message does not say how to resume: $(cat "$work/err")"
    python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["status"]["resume"])' "$dir/summary.json" \
      >"$work/resume_in_summary"
    [ "$(cat "$work/resume_in_summary")" = "demvv $continue_with" ] ||
      fail "$law $signal: summary.json resumes with '$(cat "$work/resume_in_summary")', the message with 'demvv $continue_with'"
    duration=0.4
    run_box --resume "$dir" 2>"$work/err_other"
    code=$?
    duration=0.3
    [ $code -eq 2 ] || fail "$law $signal: a resume with another deck was not refused with exit code 2"
    grep -q "another deck" "$work/err_other" || fail "$law $signal: the refusal does not say why: $(cat "$work/err_other")"
    if [ "$law$signal" = linearINT ]; then
      cp -r "$dir" "$work/other_build"
      python3 - "$work/other_build/checkpoint/driver.json" <<'EOF'
import json, sys
doc = json.load(open(sys.argv[1]))
doc["build"] = "another build"
json.dump(doc, open(sys.argv[1], "w"))
EOF
      run_box --resume "$work/other_build" 2>"$work/err_build"
      [ $? -eq 2 ] && [ "$(wc -l < "$work/err_build")" -eq 1 ] && grep -q "another build" "$work/err_build" ||
        fail "a resume on another build was not refused in one line: $(cat "$work/err_build")"
    fi
    eval "\"\$demvv\" $continue_with --quiet" 2>"$work/err_resume" ||
      fail "$law $signal: the resume the message gives failed: demvv $continue_with: $(cat "$work/err_resume")"
    grep -q '"state": "completed"' "$dir/summary.json" || fail "$law $signal: the resumed run did not complete"
    cmp -s "$dir/series.csv" "$work/whole_$law/series.csv" ||
      fail "$law $signal: resumed series.csv differs from the uninterrupted run"
    passed=$((passed + 1))
  done
done
run_box --resume "$work/stopped_linear_INT" 2>/dev/null
[ $? -eq 2 ] || fail "a finished run (its checkpoint removed) was resumed"

# A comparison cannot be resumed: its message says so, and none of its
# parts offers a resume command of its own.
dir=$work/compare
"$demvv" run "$cases/c14_compare_modified_burgers/case.prm" --out "$dir" --threads 1 --quiet 2>"$work/err_compare" &
pid=$!
tries=0
while [ "$(grep -vc '^#' "$dir/calibration/series.csv" 2>/dev/null || echo 0)" -lt 5 ]; do
  tries=$((tries + 1))
  [ $tries -gt 3000 ] && fail "the comparison wrote no rows within five minutes"
  sleep 0.1
done
kill -s INT $pid
wait $pid
code=$?
[ $code -eq 130 ] || fail "the comparison: exit code $code, expected 130 ($(cat "$work/err_compare"))"
grep -q "cannot be resumed" "$work/err_compare" || fail "the comparison's message offers a resume: $(cat "$work/err_compare")"
grep -rq '"resume"' "$dir" --include=summary.json && fail "a part of the comparison offers a resume command"

# A signal while the figures are drawn: a gnuplot that waits (a script on
# the PATH, in front of the real one; later figures fail at once) holds the
# run there; SIGTERM to demvv and that gnuplot, as a terminal sends it to
# the whole process group, then gives exit 143, results whole, and a
# summary that keeps "completed" and says the figures were interrupted and
# how to draw them.
mkdir -p "$work/slow_gnuplot"
cat > "$work/slow_gnuplot/gnuplot" <<EOF
#!/bin/sh
[ -e "$work/drawing" ] && exit 1
echo \$\$ > "$work/drawing.tmp" && mv "$work/drawing.tmp" "$work/drawing"
exec sleep 30
EOF
chmod +x "$work/slow_gnuplot/gnuplot"
dir=$work/drawing_run
law=linear
duration=0.02
PATH="$work/slow_gnuplot:$PATH" run_box_in_background --out "$dir" 2>"$work/err_drawing" &
pid=$!
tries=0
while [ ! -e "$work/drawing" ]; do
  tries=$((tries + 1))
  [ $tries -gt 600 ] && fail "the run did not start drawing its figures within a minute"
  sleep 0.1
done
kill -s TERM $pid "$(cat "$work/drawing")"
wait $pid
code=$?
[ $code -eq 143 ] || fail "a signal while drawing: exit code $code, expected 143 ($(cat "$work/err_drawing"))"
grep -q "while drawing the figures" "$work/err_drawing" || fail "the message does not say the drawing was stopped"
python3 - "$dir/summary.json" <<'EOF' || fail "the summary does not say the figures were interrupted"
import json, sys
s = json.load(open(sys.argv[1]))
sys.exit(0 if s["status"]["state"] == "completed" and s["figures"]["interrupted_by"] == "SIGTERM" else 1)
EOF
# Drawn again whole by the command the message gives, the summary no longer
# says the drawing was interrupted.
"$demvv" plot "$dir" 2>"$work/err_replot" || fail "the figures could not be drawn again: $(cat "$work/err_replot")"
python3 - "$dir/summary.json" <<'EOF' || fail "the summary still says the figures were interrupted"
import json, sys
sys.exit(0 if "interrupted_by" not in json.load(open(sys.argv[1])).get("figures", {}) else 1)
EOF
passed=$((passed + 1))
# A signal while a sample is prepared (a preparation has no checkpoint): a
# prepare run exits 143 with summary.json saying "interrupted" and that it
# must run again; a test whose sample deck is being prepared for it (an
# empty cache) exits 143 too, saying what was stopped, with no summary that
# says "running" (it stopped before its first step, so it wrote none), the
# cache's preparation saying "interrupted" and no sample in the cache.  The
# preparations take tens of seconds (4000 balls) and a minute or more (6000)
# on two cores; the signal goes a second after one has begun (its run
# directory's summary.json exists).
signal_during_preparation() { # NAME, FOLDER of the preparation, then demvv's arguments
  name=$1
  folder=$2
  shift 2
  ( exec "$demvv" "$@" 2>"$work/err_$name" ) &
  pid=$!
  tries=0
  while [ -z "$(find "$folder" -name summary.json 2>/dev/null)" ]; do
    tries=$((tries + 1))
    [ $tries -gt 600 ] && fail "$name: the preparation did not begin within a minute ($(cat "$work/err_$name"))"
    sleep 0.1
  done
  sleep 1
  kill -s TERM $pid
  wait $pid
  code=$?
  [ $code -eq 143 ] || fail "$name: exit code $code, expected 143 ($(cat "$work/err_$name"))"
}
signal_during_preparation prepare "$work/prepare_run" run "$cases/p05_sample_4000/case.prm" --out "$work/prepare_run" --threads 1
python3 - "$work/prepare_run/summary.json" <<'EOF' || fail "the prepare run's summary does not say it was interrupted"
import json, sys
s = json.load(open(sys.argv[1]))["status"]
sys.exit(0 if s["state"] == "interrupted" and s["signal"] == "SIGTERM" and "run it again" in s["message"] else 1)
EOF
export DEMVV_CACHE="$work/cache"
signal_during_preparation test "$work/cache" run "$cases/t61_damage/case.prm" --out "$work/test_run" --threads 1
unset DEMVV_CACHE
grep -q "while preparing the sample" "$work/err_test" || fail "the test's message does not say what was stopped: $(cat "$work/err_test")"
python3 - "$work/test_run/summary.json" <<'EOF' || fail "the test's summary says it is running"
import json, os, sys
if not os.path.exists(sys.argv[1]):
    sys.exit(0)  # stopped before its first step: no summary yet
s = json.load(open(sys.argv[1]))["status"]
sys.exit(0 if s["state"] == "interrupted" and s["signal"] == "SIGTERM" else 1)
EOF
python3 - "$work/cache" <<'EOF' || fail "the cache's preparation does not say it was interrupted"
import glob, json, sys
s = [json.load(open(f))["status"] for f in glob.glob(sys.argv[1] + "/*/summary.json")]
sys.exit(0 if len(s) == 1 and s[0]["state"] == "interrupted" else 1)
EOF
[ -z "$(find "$work/cache" -name sample.json)" ] || fail "an interrupted preparation left a sample in the cache"
passed=$((passed + 1))
echo "$passed passed, 0 failed"
