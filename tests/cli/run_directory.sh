#!/bin/sh
# Run directories: `demvv run` refuses a non-empty --out (exit 2, the files
# there untouched) unless --replace, which replaces a run directory whole
# (its stale outputs gone, a user's own files kept) and only once the deck
# has passed its checks; --resume
# still continues in its own directory; a run directory's deck.prm runs
# again from any folder with the same results; a prepare deck's sample is
# cached beside the deck whatever the current folder (or in $DEMVV_CACHE);
# --threads is a ceiling, OMP_NUM_THREADS an exact count;
# under MPI every rank takes rank 0's verdict (no hang, no rank left behind).
# Usage: run_directory.sh DEMVV CASES_DIR [MPIRUN]
set -u
demvv=$1
cases=$2
mpirun=${3:-}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*"; exit 1; }
impact=$cases/v01_linear_impact/case.prm
run() { "$demvv" run "$@" --quiet --threads 1; }
# Two completed runs whose summaries hold the same numbers (provenance and
# timings aside; texts may name a file as the deck wrote it).
same_results() {
  python3 - "$1" "$2" <<'EOF'
import json, sys
def numbers(j):
    if isinstance(j, dict):
        return {k: numbers(v) for k, v in j.items()
                if k not in ("provenance", "wall_seconds", "particle_steps_per_second", "threads")}
    if isinstance(j, list):
        return [numbers(v) for v in j]
    return None if isinstance(j, str) else j
a, b = (json.load(open(p)) for p in sys.argv[1:3])
done = a["status"]["state"] == b["status"]["state"] == "completed"
sys.exit(0 if done and numbers(a) == numbers(b) else 1)
EOF
}
one_line() { [ "$(wc -l < "$1")" -eq 1 ] || fail "$2: the error is not one line: $(cat "$1")"; }

# A non-empty --out is refused, and what is there stays as it was.
run "$impact" --out "$work/r" 2>/dev/null || fail "the first run failed"
cp "$work/r/summary.json" "$work/summary_before"
echo keep > "$work/r/stray.txt"
run "$impact" --out "$work/r" 2>"$work/err"
[ $? -eq 2 ] || fail "a run into a non-empty directory was not refused with exit code 2"
one_line "$work/err" "non-empty directory"
grep -q "run directory '$work/r' is not empty" "$work/err" && grep -q -- "--replace" "$work/err" ||
  fail "the refusal does not name the directory and --replace: $(cat "$work/err")"
[ -f "$work/r/stray.txt" ] && cmp -s "$work/r/summary.json" "$work/summary_before" || fail "the refusal touched the old run"

# --replace empties only a run directory (one holding demvv's marker), never
# an ordinary folder, and never a path that is not a directory.
mkdir "$work/notes" && echo keep > "$work/notes/keep.txt"
run "$impact" --out "$work/notes" --replace 2>"$work/err"
[ $? -eq 2 ] && grep -q "lacks demvv's marker" "$work/err" || fail "--replace of a folder that is no run directory: $(cat "$work/err")"
[ -f "$work/notes/keep.txt" ] || fail "--replace removed files of a folder that is no run directory"
echo text > "$work/file"
run "$impact" --out "$work/file" 2>"$work/err"
[ $? -eq 2 ] && grep -q "not a directory" "$work/err" || fail "--out naming a file: $(cat "$work/err")"

# --replace with a deck that fails its checks (a missing particle file,
# found only when the scene is parsed) loses nothing.
run "$impact" --out "$work/r" --replace --set particles/file=missing.csv 2>"$work/err"
[ $? -eq 2 ] && grep -q "missing.csv" "$work/err" || fail "a bad deck with --replace: $(cat "$work/err")"
[ -f "$work/r/stray.txt" ] && cmp -s "$work/r/summary.json" "$work/summary_before" || fail "a bad deck's --replace touched the old run"

# verify writes its report only into a new or empty folder, or a report
# folder it made (replaced there); a user's folder is refused untouched.
mkdir -p "$work/user_report" && echo notes > "$work/user_report/report.md"
"$demvv" verify --only V05 --out "$work/user_report" --threads 1 2>"$work/err"
[ $? -eq 2 ] && [ "$(cat "$work/user_report/report.md")" = notes ] && grep -q "no report directory demvv made" "$work/err" ||
  fail "verify into a user's folder: $(cat "$work/err")"
one_line "$work/err" "verify into a user's folder"
for k in 1 2; do
  "$demvv" verify --only V05 --out "$work/own_report" --threads 1 2>"$work/err" || fail "verify $k into its own folder: $(cat "$work/err")"
done

# --replace replaces the run whole: old ParaView frames go, a file no run
# writes (the user's) stays.
run "$impact" --out "$work/pv" --set output/paraview=true 2>/dev/null || fail "the ParaView run failed"
[ -d "$work/pv/paraview" ] || fail "the ParaView run wrote no paraview/"
echo keep > "$work/pv/stray.txt"
# The user's files named like another kind's outputs or like demvv's
# temporary files stay too: a scene's --replace removes what a scene writes.
echo keep > "$work/pv/my_results.tmp" && echo keep > "$work/pv/sample.json"
mkdir "$work/pv/level_notes" "$work/pv/calibration" "$work/pv/dem"
demvv_tmp="$work/pv/summary.json.Ab12Cd.tmp" && echo stale > "$demvv_tmp"
run "$impact" --out "$work/pv" --replace 2>/dev/null || fail "the run with --replace failed"
[ ! -e "$work/pv/paraview" ] && [ ! -e "$demvv_tmp" ] || fail "--replace left old files: $(ls "$work/pv")"
for f in stray.txt my_results.tmp sample.json level_notes calibration dem; do
  [ -e "$work/pv/$f" ] || fail "--replace removed $f, which no scene writes"
done
same_results "$work/pv/summary.json" "$work/r/summary.json" || fail "the replacing run's results differ"

# A paused run resumes in its own directory, to the uninterrupted results.
run "$impact" --out "$work/paused" --pause-after 500 2>/dev/null || fail "the paused run failed"
grep -q '"paused"' "$work/paused/summary.json" || fail "the run did not pause"
run "$impact" --resume "$work/paused" --replace 2>"$work/err"
[ $? -eq 2 ] && grep -q -- "--replace" "$work/err" || fail "--resume with --replace: $(cat "$work/err")"
run "$impact" --resume "$work/paused" 2>/dev/null || fail "the resumed run failed"
cmp -s "$work/paused/series.csv" "$work/r/series.csv" || fail "the resumed series differs from the uninterrupted one"

# deck.prm runs again from another folder (its particle file named
# absolute), to the same results.
mkdir "$work/elsewhere"
grep -q "set file = /" "$work/r/deck.prm" || fail "deck.prm does not name its particle file absolute"
(cd "$work/elsewhere" && run ../r/deck.prm --out ../again 2>/dev/null) || fail "deck.prm did not run from another folder"
same_results "$work/again/summary.json" "$work/r/summary.json" || fail "deck.prm rerun gave other results"

# A prepare deck's sample is cached beside it: runs from two folders (and
# the rerun of a run's deck.prm) prepare it once.
mkdir -p "$work/decks" "$work/a" "$work/b"
printf 'set kind = prepare\nsubsection sample\n  set particles = 200\n  set seed = 5\nend\n' > "$work/decks/small.prm"
printf 'set kind = uniaxial\nsubsection sample\n  set source = file\n  set file = small.prm\nend\nsubsection loading\n  set final strain = 0.002\nend\nsubsection output\n  set strain interval = 0.0005\nend\n' > "$work/decks/test.prm"
(cd "$work/a" && "$demvv" run ../decks/test.prm --out u --threads 1 2>"$work/err_a") || fail "the uniaxial run from a/ failed"
grep -q "^prepare small" "$work/err_a" || fail "the first run did not prepare the sample"
(cd "$work/b" && "$demvv" run "$work/decks/test.prm" --out u --threads 1 2>"$work/err_b") || fail "the run from b/ failed"
(cd "$work/elsewhere" && "$demvv" run ../a/u/deck.prm --out u --threads 1 2>"$work/err_c") || fail "the deck.prm rerun failed"
! grep -q "^prepare" "$work/err_b" "$work/err_c" || fail "a run from another folder prepared the sample again"
[ "$(ls "$work/decks/samples")" = "$(ls "$work/decks/samples" | head -1)" ] && [ -f "$work/decks/samples"/small-*/sample.json ] ||
  fail "not one cache entry beside the deck: $(ls "$work/decks/samples")"
same_results "$work/b/u/summary.json" "$work/a/u/summary.json" && same_results "$work/elsewhere/u/summary.json" "$work/a/u/summary.json" ||
  fail "runs on the cached sample gave other results"
(cd "$work/b" && DEMVV_CACHE="$work/cache" "$demvv" run ../decks/test.prm --out v --threads 1 2>"$work/err_d") || fail "the DEMVV_CACHE run failed"
grep -q "^prepare small" "$work/err_d" && [ -f "$work/cache"/small-*/sample.json ] || fail "DEMVV_CACHE did not hold the cache"

# --threads N is the most a run may use, its count governed below it;
# OMP_NUM_THREADS alone fixes the count (summary.json says which).
"$demvv" run "$impact" --out "$work/t2" --quiet --threads 2 || fail "the --threads 2 run failed"
OMP_NUM_THREADS=2 "$demvv" run "$impact" --out "$work/e2" --quiet || fail "the OMP_NUM_THREADS=2 run failed"
python3 - "$work/t2/summary.json" "$work/e2/summary.json" <<'EOF' || fail "the thread counts are not as asked"
import json, sys
ceiling, exact = (json.load(open(p))["status"]["threads"] for p in sys.argv[1:3])
assert ceiling["governed"] and ceiling["most"] == 2 and 1 <= ceiling["at_end"] <= 2, ceiling
assert not exact["governed"] and exact["at_end"] == 2 and exact["changes"] == 0 and "most" not in exact, exact
EOF

# Under MPI rank 0 decides for every rank: a refusal ends every rank with
# exit code 2 (no hang), a failed check loses nothing, a replacement works.
if [ -n "$mpirun" ]; then
  launch="$mpirun --oversubscribe -np 2"
  [ "$(id -u)" -eq 0 ] && launch="$mpirun --allow-run-as-root --oversubscribe -np 2"
  cylinder() { timeout 120 $launch "$demvv" run "$cases/c04_cylinder_bonded_gci/case.prm" --out "$work/mpi" --quiet \
    --set "study/gci refinements=" --set discretisation/refinements=2 --set "discretisation/time steps=3" "$@"; }
  cylinder >/dev/null 2>&1 || fail "the MPI cylinder run failed"
  echo keep > "$work/mpi/stray.txt"
  cylinder >/dev/null 2>"$work/err"
  code=$?
  [ $code -eq 2 ] || fail "MPI: a non-empty directory ended with $code, expected 2 on every rank (124: a rank hung)"
  [ "$(grep -o "is not empty" "$work/err" | wc -l)" -eq 2 ] || fail "MPI: not both ranks refused: $(cat "$work/err")"
  cylinder --replace --set "measurement/fit window=0.5,0.1" >/dev/null 2>"$work/err"
  code=$?
  [ $code -eq 2 ] && [ "$(grep -o "fit window" "$work/err" | wc -l)" -eq 2 ] ||
    fail "MPI: a check failed on rank 0 ended with $code: $(cat "$work/err")"
  [ -f "$work/mpi/stray.txt" ] || fail "MPI: a failed --replace removed the old files"
  cylinder --replace >/dev/null 2>&1 || fail "MPI: the run with --replace failed"
  [ -f "$work/mpi/stray.txt" ] && grep -q '"completed"' "$work/mpi/summary.json" || fail "MPI: --replace did not replace"
fi
echo "run directories: ok"
