#!/bin/sh
# The demvv command's exit codes: 0 success, 2 bad input or usage,
# 3 numerical fault (with outputs kept), and one-line errors.
demvv="$1"; data="$2"; out=$(mktemp -d)
fail() { echo "FAIL: $*"; exit 1; }

"$demvv" defaults scene > "$out/scene.prm" || fail "defaults scene"
"$demvv" defaults soup > /dev/null 2> "$out/err"; [ $? -eq 2 ] || fail "defaults of an unknown kind must exit 2"
[ "$(wc -l < "$out/err")" -eq 1 ] || fail "the error must be one line"

"$demvv" run "$data/nowhere.prm" 2> "$out/err"; [ $? -eq 2 ] || fail "a missing deck must exit 2"
grep -q "nowhere.prm" "$out/err" || fail "the error must name the file"
"$demvv" run "$data/unstable.prm" --set "run/duratio=1" 2> "$out/err"; [ $? -eq 2 ] || fail "bad --set must exit 2"
"$demvv" run --bogus 2> /dev/null; [ $? -eq 2 ] || fail "a bad option must exit 2"

"$demvv" run "$data/unstable.prm" --out "$out/fault" 2> "$out/err"; [ $? -eq 3 ] || fail "a blow-up must exit 3"
grep -q "step" "$out/err" && grep -q "particle" "$out/err" || fail "the fault diagnostic names step and particle"
[ -s "$out/fault/series.csv" ] && [ -s "$out/fault/summary.json" ] || fail "outputs kept after a fault"

"$demvv" run "$data/unstable.prm" --out "$out/stop" --set "motion/unstable fixed step=stop" 2> "$out/err"
[ $? -eq 3 ] || fail "a fixed step above the bound must stop with exit 3"
grep -q "exceeds the critical step bound" "$out/err" || fail "the diagnostic says the step is too large"

# --quiet silences the preparation of a sample prepared on first use too
# (it printed its 22 stage lines): one line, the final one, on stderr.
DEMVV_CACHE="$out/cache" "$demvv" run "$data/../../cases/t61_damage/case.prm" --out "$out/quiet" --threads 1 --quiet \
  --set "sample/file=$data/prepare_200.prm" --set "loading/final strain=0.002" 2> "$out/err" ||
  fail "a run on a 200-ball prepared sample must succeed"
[ "$(wc -l < "$out/err")" -eq 1 ] || fail "--quiet must leave one line on stderr, not $(wc -l < "$out/err")"
grep -q "^demvv: done" "$out/err" || fail "the line --quiet leaves is the final one"
# A DEMVV_CACHE that is a file is named as the cause.
DEMVV_CACHE="$out/err" "$demvv" run "$data/../../cases/t61_damage/case.prm" --out "$out/cache_file" --threads 1 \
  --quiet --set "sample/file=$data/prepare_200.prm" 2> "$out/err_cache"
[ $? -eq 2 ] && grep -q "DEMVV_CACHE='$out/err': not a directory" "$out/err_cache" ||
  fail "a DEMVV_CACHE that is a file: $(cat "$out/err_cache")"

# A test meant to be quasi-static that is not (a platen at 300 m/s crushes
# the lattice in four steps) ends with exit 0 and a warning naming the
# inertial number, no longer silently.
"$demvv" run "$data/bad/uniaxial_lattice.prm" --out "$out/fast" --threads 1 --quiet \
  --set "loading/platen speed=300" --set "loading/final strain=0.1" 2> "$out/err" || fail "a fast platen still runs"
grep -q "^demvv: warning: not quasi-static: the inertial number reached" "$out/err" ||
  fail "a test far from quasi-static must say so"
grep -q '"not quasi-static' "$out/fast/summary.json" || fail "the warning is in summary.json too"

# A thread count beyond the machine is clamped to its cores (not an abort
# in libgomp, not a run thousands of times slower).
"$demvv" run "$data/../../cases/v01_linear_impact/case.prm" --out "$out/threads" --threads 1024 --quiet 2> "$out/err" ||
  fail "--threads 1024 must run (clamped to the cores)"
python3 -c "import json, os, sys; t = json.load(open(sys.argv[1]))['status']['threads']
sys.exit(0 if max(t.get('most', 0), t['at_end']) <= os.cpu_count() else 1)" "$out/threads/summary.json" ||
  fail "--threads 1024 must use at most the machine's cores"

# A run that can end, but only in hours or days, says so before its first step (a
# pause after ten steps ends this one at once).
"$demvv" run "$data/bad/uniaxial_lattice.prm" --set "loading/platen speed=1e-11" --out "$out/long" --pause-after 10 \
  --quiet 2> "$out/err" ||
  fail "a long run paused after ten steps: $(cat "$out/err")"
grep -q "note: this run needs at least .* hours" "$out/err" || fail "a run of days does not say so: $(cat "$out/err")"

"$demvv" verify --only V05 --out "$out/verify" 2> /dev/null || fail "verify V05 must pass"
[ -s "$out/verify/report.md" ] && [ -s "$out/verify/report.json" ] || fail "verify writes report.md and report.json"
"$demvv" bench --particles 300 --steps 20 --repeat 1 | grep -q "particle-steps/s" || fail "bench prints its line"
# Standard output that cannot be written is no success: exit 4 with one line.
if [ -w /dev/full ]; then
  "$demvv" catalogue > /dev/full 2> "$out/err"
  [ $? -eq 4 ] && grep -q "standard output cannot be written" "$out/err" ||
    fail "a catalogue written to a full device must exit 4: $(cat "$out/err")"
fi
rm -rf "$out"
echo "cli exit codes: ok"
