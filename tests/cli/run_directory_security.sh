#!/bin/sh
# Run directories are untrusted input: a folder from a colleague, a CI
# artefact or a tarball must never make demvv run code or touch a file
# outside it, and demvv never mixes two writers in one directory.
#   - demvv plot on a hostile summary.json (keys holding newlines, gnuplot
#     commands, ../): no command runs, every file lands in RUN_DIR/plots
#     under a name of a fixed alphabet; a plots/ that is a symbolic link and
#     a link planted as a figure's log are refused or replaced, never
#     followed;
#   - an output file named by the user: a pipe is written through (never
#     replaced by a regular file), a symbolic link is refused, `-` is
#     standard output;
#   - --replace empties only a directory holding demvv's marker, and there
#     only the entries runs write (a user's notes stay); a working folder
#     holding a copied deck.prm and its CSV loses nothing;
#   - a second process on a directory in use (a run, a resume, a sweep) is
#     refused with exit 2, and the first one finishes undisturbed;
#   - text with control characters or '#' in a deck value, and a wall name
#     that would break a CSV header, are refused with the one-line error;
#   - a file-size limit ends a run with exit 4 (not SIGXFSZ), SIGHUP as
#     SIGTERM does (exit 143, checkpoint);
#   - a resume refuses a series cut since the pause and an input file
#     changed since the run began, and leaves the paused summary as it was.
# Each of these failed before the ownership marker, the locks and the
# sanitised script writer.
# Usage: run_directory_security.sh DEMVV CASES_DIR
set -u
demvv=$(cd "$(dirname "$1")" && pwd)/$(basename "$1")
cases=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'kill $long 2>/dev/null; rm -rf "$work"' EXIT
long=""
fail() { echo "FAIL: $*"; exit 1; }
impact=$cases/v01_linear_impact/case.prm
run() { "$demvv" run "$@" --quiet --threads 1; }
one_line() { [ "$(wc -l < "$1")" -eq 1 ] || fail "$2: the error is not one line: $(cat "$1")"; }
# Starts a run of about 30 s in the background (its pid in $long) and waits
# until it has begun writing its series.
start_long_run() {
  "$demvv" run "$impact" --out "$1" --set run/duration=2e-3 --quiet --threads 1 2>/dev/null &
  long=$!
  for _ in 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15 16 17 18 19 20; do
    [ -f "$1/series.csv" ] && break
    sleep 0.2
  done
}

# 1. A hostile summary.json: a key that would inject gnuplot lines (and
# run a shell command through system()), a key that would leave the folder.
mkdir -p "$work/hostile"
python3 - "$work/hostile/summary.json" "$work/pwned" <<'EOF'
import json, sys
level = {"cell_sizes_m_fine_to_coarse": [1, 2, 4], "values_fine_to_coarse": [1, 2, 3],
         "extrapolated": 0.5, "observed_order": 1, "gci_fine": 0.1}
keys = ['x\nsystem("touch %s")\n' % sys.argv[2], "../../../escaped", "`touch %s`" % sys.argv[2]]
json.dump({"kind": "cylinder", "gci": [{k: level for k in keys}]}, open(sys.argv[1], "w"))
EOF
"$demvv" plot "$work/hostile" 2>"$work/err" || fail "plot of the hostile folder failed: $(cat "$work/err")"
[ ! -e "$work/pwned" ] || fail "plot ran a command named in summary.json"
[ -z "$(find "$work" -name 'escaped*' ! -path "$work/hostile/plots/*")" ] || fail "plot wrote outside RUN_DIR/plots"
for f in "$work/hostile/plots"/*; do
  case "$(basename "$f")" in
    *[!A-Za-z0-9_.-]*) fail "a figure file name outside the fixed alphabet: $f" ;;
  esac
done
if command -v gnuplot >/dev/null 2>&1; then
  for gp in "$work/hostile/plots"/*.gp; do (cd "$work/hostile/plots" && gnuplot "$gp" >/dev/null 2>&1); done
  [ ! -e "$work/pwned" ] || fail "a figure's script, run by gnuplot, ran a command"
fi

# A plots/ that is a symbolic link is refused, its target untouched.
mkdir -p "$work/linked" "$work/outside"
cp "$work/hostile/summary.json" "$work/linked/"
ln -s "$work/outside" "$work/linked/plots"
"$demvv" plot "$work/linked" 2>"$work/err"
[ $? -ne 0 ] && grep -q "is not a directory" "$work/err" || fail "a linked plots/ was not refused: $(cat "$work/err")"
one_line "$work/err" "linked plots/"
[ -z "$(ls "$work/outside")" ] || fail "plot wrote through a linked plots/: $(ls "$work/outside")"

# A link planted where a figure's gnuplot log goes is removed, not followed.
run "$impact" --out "$work/r" 2>/dev/null || fail "the impact run failed"
echo precious > "$work/precious"
ln -s "$work/precious" "$work/r/plots/energy.log"
"$demvv" plot "$work/r" 2>/dev/null || fail "plot of a run with a planted link failed"
[ "$(cat "$work/precious")" = precious ] || fail "plot wrote through a planted link"
# Figures an earlier drawing made that the data no longer give (the
# summary's kind edited) are removed and said; a user's file stays, and so
# does what a planted link points at.
cp -a "$work/r" "$work/stale"
echo notes > "$work/stale/plots/notes.svg"
ln -sf "$work/precious" "$work/stale/plots/linked.gp"
python3 -c "import json,sys; d=json.load(open(sys.argv[1])); d['kind']='mms'; json.dump(d,open(sys.argv[1],'w'))" \
  "$work/stale/summary.json"
"$demvv" plot "$work/stale" 2>"$work/err" || fail "plot of a run with another kind failed: $(cat "$work/err")"
grep -q "energy: removed, a figure of an earlier drawing" "$work/err" && [ ! -e "$work/stale/plots/energy.svg" ] &&
  [ ! -e "$work/stale/plots/energy.gp" ] && [ -f "$work/stale/plots/notes.svg" ] &&
  [ "$(cat "$work/precious")" = precious ] || fail "stale figures: $(cat "$work/err"); $(ls "$work/stale/plots")"

# 2. Outputs the user names: a pipe written through, a link refused, - is stdout.
mkfifo "$work/pipe"
cat "$work/pipe" > "$work/from_pipe" &
reader=$!
"$demvv" catalogue --out "$work/pipe" || fail "catalogue into a pipe failed"
wait $reader
[ -p "$work/pipe" ] || fail "catalogue replaced a pipe by a regular file"
grep -q "verification catalogue" "$work/from_pipe" || fail "catalogue did not write through the pipe"
# A pipe nobody reads is refused after a few seconds, not waited on forever.
mkfifo "$work/unread_pipe"
timeout 30 "$demvv" catalogue --out "$work/unread_pipe" 2>"$work/err"
[ $? -eq 4 ] && grep -q "no process opened for reading" "$work/err" || fail "a pipe nobody reads: $(cat "$work/err")"
one_line "$work/err" "a pipe nobody reads"
echo precious > "$work/target.md"
ln -s "$work/target.md" "$work/link.md"
"$demvv" catalogue --out "$work/link.md" 2>"$work/err"
[ $? -eq 4 ] && grep -q "symbolic link" "$work/err" || fail "catalogue onto a link: $(cat "$work/err")"
[ -L "$work/link.md" ] && [ "$(cat "$work/target.md")" = precious ] || fail "catalogue replaced or followed a link"
"$demvv" catalogue --out - | grep -q "verification catalogue" || fail "catalogue --out - did not write standard output"
[ ! -e ./- ] || fail "catalogue --out - made a file named -"

# 3. --replace: a working folder with a copied deck.prm and the CSV it names
# is no run directory; a run directory keeps its user's files.
mkdir "$work/mine"
cp "$cases/v01_linear_impact/balls.csv" "$work/mine/"
sed "s|set file = .*balls.csv|set file = balls.csv|" "$work/r/deck.prm" > "$work/mine/deck.prm"
echo notes > "$work/mine/notes.txt"
(cd "$work/mine" && "$demvv" run deck.prm --out . --replace --quiet --threads 1) 2>"$work/err"
[ $? -eq 2 ] && grep -q "lacks demvv's marker" "$work/err" || fail "--replace of a working folder: $(cat "$work/err")"
one_line "$work/err" "--replace of a working folder"
[ -f "$work/mine/deck.prm" ] && [ -f "$work/mine/balls.csv" ] && [ -f "$work/mine/notes.txt" ] ||
  fail "--replace of a working folder removed files: $(ls "$work/mine")"
[ ! -e "$work/mine/.demvv.lock" ] || fail "a refused run left its lock file in a foreign folder"
# A marker of another kind, or one that cannot be read, is said to be so.
for marker in '{"made_by": "demvv", "holds": "sweep"}' 'not json'; do
  mkdir -p "$work/marked" && echo notes > "$work/marked/notes.txt" && printf '%s' "$marker" > "$work/marked/.demvv"
  run "$impact" --out "$work/marked" --replace 2>"$work/err"
  [ $? -eq 2 ] && grep -Eq "says it holds a sweep, not a run|cannot be read" "$work/err" &&
    [ -f "$work/marked/notes.txt" ] || fail "--replace over the marker '$marker': $(cat "$work/err")"
  rm -rf "$work/marked"
done
# Through a link too: a refused --out leaves the folder it points at as it was.
mkdir "$work/victim" && echo notes > "$work/victim/notes.txt" && ln -s "$work/victim" "$work/link"
run "$impact" --out "$work/link" 2>"$work/err"
[ $? -eq 2 ] || fail "a run into a linked non-empty folder was not refused: $(cat "$work/err")"
[ "$(ls -A "$work/victim")" = notes.txt ] || fail "a refused run wrote into a linked folder: $(ls -A "$work/victim")"
echo notes > "$work/r/notes.txt"
run "$impact" --out "$work/r" --replace 2>/dev/null || fail "--replace of a run directory failed"
[ -f "$work/r/notes.txt" ] || fail "--replace removed a file no run writes"
# A forged marker proves nothing about what to remove: only run outputs go.
python3 -c 'import json,sys; json.dump({"made_by":"demvv","holds":"run","outputs":["*"]}, open(sys.argv[1],"w"))' "$work/mine/.demvv"
(cd "$work/mine" && "$demvv" run deck.prm --out . --replace --quiet --threads 1) 2>"$work/err"
[ -f "$work/mine/notes.txt" ] && [ -f "$work/mine/balls.csv" ] || fail "a forged marker's list was obeyed, or an input removed"

# 4. One writer at a time: a second run, resume or sweep on a directory in
# use is refused (exit 2) and the first finishes as if alone.
start_long_run "$work/long"
run "$impact" --out "$work/long" --replace 2>"$work/err"
[ $? -eq 2 ] && grep -q "in use by another demvv process" "$work/err" || fail "a second --replace: $(cat "$work/err")"
one_line "$work/err" "directory in use"
run "$impact" --resume "$work/long" 2>"$work/err"
[ $? -eq 2 ] && grep -q "in use" "$work/err" || fail "a --resume of a run in progress: $(cat "$work/err")"
"$demvv" sweep "$impact" --seeds 2 --out "$work/long" --quiet 2>"$work/err"
[ $? -eq 2 ] && grep -q "in use" "$work/err" || fail "a sweep into a run in progress: $(cat "$work/err")"
kill -TERM $long 2>/dev/null
wait $long
long=""
grep -q '"interrupted"' "$work/long/summary.json" || fail "the first run's summary is not its own: $(head -c 300 "$work/long/summary.json")"

# 5. Text that would rewrite the run's own records is refused.
run "$impact" --out "$work/t1" --set "title=line one
set kind = prepare" 2>"$work/err"
[ $? -eq 2 ] && grep -q "control character" "$work/err" || fail "a title with a newline: $(cat "$work/err")"
one_line "$work/err" "a title with a newline"
run "$impact" --out "$work/t2" --set "title=a # b" 2>"$work/err"
[ $? -eq 2 ] && grep -q "'#'" "$work/err" || fail "a title with '#': $(cat "$work/err")"
printf 'set kind = scene\nsubsection walls\n  subsection plane a,b\n    set point = 0,0,0\n  end\nend\n' > "$work/comma.prm"
run "$work/comma.prm" --out "$work/t3" 2>"$work/err"
[ $? -eq 2 ] && grep -q "a,b" "$work/err" && grep -q "series.csv" "$work/err" || fail "a wall named a,b: $(cat "$work/err")"
# 6. Limits end a run through its own paths: a file-size limit (ulimit -f)
# is an output error (exit 4, the summary says so), not SIGXFSZ; SIGHUP
# stops a run as SIGTERM does (exit 143, checkpoint written).
(ulimit -f 16; exec "$demvv" run "$impact" --out "$work/limited" --set run/duration=4e-4 --quiet --threads 1) 2>"$work/err"
[ $? -eq 4 ] || fail "a file-size limit did not end in exit 4: $(cat "$work/err")"
grep -q '"output failed"' "$work/limited/summary.json" || fail "the summary does not say the output failed"
start_long_run "$work/hup"
sleep 0.3
kill -HUP $long
wait $long
code=$?
long=""
[ $code -eq 143 ] && [ -f "$work/hup/checkpoint/driver.json" ] || fail "SIGHUP ended the run with $code, expected 143 and a checkpoint"
# 7. Checkpoints that cannot lie: a series cut after the pause is refused
# (never padded with NUL bytes), an input file changed after the pause is
# refused, a checkpoint sample edited by hand is refused, and a refused
# resume leaves the paused run's summary as it was.
mkdir "$work/own"
cp "$cases/v01_linear_impact/balls.csv" "$work/own/"
sed "s|set file = .*balls.csv|set file = balls.csv|" "$work/r/deck.prm" > "$work/own/deck.prm"
run "$work/own/deck.prm" --out "$work/cut" --pause-after 500 2>/dev/null || fail "the paused run failed"
cp "$work/cut/summary.json" "$work/paused_summary"
size=$(wc -c < "$work/cut/series.csv")
head -c $((size - 200)) "$work/cut/series.csv" > "$work/short" && cp "$work/short" "$work/cut/series.csv"
run "$work/own/deck.prm" --resume "$work/cut" 2>"$work/err"
[ $? -eq 2 ] && grep -q "shorter than" "$work/err" || fail "a resume on a cut series: $(cat "$work/err")"
one_line "$work/err" "a cut series"
! tr -d '\n' < "$work/cut/series.csv" | od -An -c | grep -q '\\0' || fail "the series was padded with NUL bytes"
cmp -s "$work/cut/summary.json" "$work/paused_summary" || fail "a refused resume rewrote the paused run's summary"
run "$work/own/deck.prm" --out "$work/changed" --pause-after 500 2>/dev/null || fail "the second paused run failed"
sed -i '$ s/^\(.\)/9\1/' "$work/own/balls.csv"
run "$work/own/deck.prm" --resume "$work/changed" 2>"$work/err"
[ $? -eq 2 ] && grep -q "balls.csv changed since the run began" "$work/err" || fail "a resume on a changed input: $(cat "$work/err")"
grep -q '"paused"' "$work/changed/summary.json" || fail "a refused resume lost the paused state"
# A checkpoint is its state file and the sample file of the step it names:
# a run killed after writing a newer sample file (here one cut short),
# before the state that names it, resumes from the checkpoint before.
run "$work/own/deck.prm" --out "$work/killed" --pause-after 500 2>/dev/null || fail "the paused run to kill failed"
[ "$(ls "$work/killed/checkpoint" | grep -c '^state_')" -eq 1 ] || fail "not one sample file: $(ls "$work/killed/checkpoint")"
head -c 200 "$work/killed/checkpoint/"state_*.json > "$work/killed/checkpoint/state_99999999.json"
run "$work/own/deck.prm" --resume "$work/killed" 2>"$work/err" || fail "a resume beside a newer sample cut short: $(cat "$work/err")"
grep -q '"completed"' "$work/killed/summary.json" || fail "the resumed run did not complete"
# A checkpoint whose sample was edited by hand (a ball moved) is refused.
run "$work/own/deck.prm" --out "$work/moved" --pause-after 500 2>/dev/null || fail "the paused run to edit failed"
python3 - "$work/moved/checkpoint/"state_*.json <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["balls"]["rows"][0][0] += 1e-6
json.dump(d, open(sys.argv[1], "w"))
EOF
run "$work/own/deck.prm" --resume "$work/moved" 2>"$work/err"
[ $? -eq 2 ] && grep -q "the checkpoint recorded" "$work/err" || fail "a resume on an edited checkpoint: $(cat "$work/err")"
one_line "$work/err" "an edited checkpoint"

# 8. A resumed series is the run's own regular file and the checkpoint's
# size ends a row after its header: a series replaced by a link to a file
# outside the run is refused and that file untouched; a checkpoint whose
# recorded size was edited to cut into the header is refused, the series
# left whole.
run "$work/own/deck.prm" --out "$work/linked_series" --pause-after 500 2>/dev/null || fail "the third paused run failed"
# (larger than the series, so that only the link, not the size, refuses it)
python3 -c 'print("outside\n" * 50000, end="")' > "$work/outside_file"
cp "$work/outside_file" "$work/outside_before"
rm "$work/linked_series/series.csv"
ln -s "$work/outside_file" "$work/linked_series/series.csv"
run "$work/own/deck.prm" --resume "$work/linked_series" 2>"$work/err"
[ $? -eq 2 ] && grep -q "a link or a special file" "$work/err" || fail "a resume through a linked series: $(cat "$work/err")"
cmp -s "$work/outside_file" "$work/outside_before" || fail "a resume wrote through a link to a file outside the run"
run "$work/own/deck.prm" --out "$work/edited" --pause-after 500 2>/dev/null || fail "the fourth paused run failed"
cp "$work/edited/series.csv" "$work/series_before"
python3 - "$work/edited/checkpoint/driver.json" <<'EOF'
import json, sys
d = json.load(open(sys.argv[1]))
d["series"][0]["bytes"] = 9
json.dump(d, open(sys.argv[1], "w"))
EOF
run "$work/own/deck.prm" --resume "$work/edited" 2>"$work/err"
[ $? -eq 2 ] && grep -q "does not end a row after the header" "$work/err" || fail "a checkpoint cutting the header: $(cat "$work/err")"
cmp -s "$work/edited/series.csv" "$work/series_before" || fail "a refused resume changed the series"

# 9. Names that would break a line: a deck whose file name holds a newline
# runs, its series' comment stays one line and its figures are drawn; a
# run directory whose series is a link is not plotted (exit 2, nothing of
# the linked file printed).
nl_deck="$work/own/$(printf 'nl\nset output x')deck.prm"
cp "$work/own/deck.prm" "$nl_deck"
run "$nl_deck" --out "$work/newline_name" 2>"$work/err" || fail "a deck named with a newline: $(cat "$work/err")"
[ "$(grep -c '^#' "$work/newline_name/series.csv")" -eq 1 ] || fail "the series' comment is not one line"
"$demvv" plot "$work/newline_name" 2>"$work/err" || fail "the figures of a deck named with a newline: $(cat "$work/err")"
rm "$work/newline_name/series.csv"
printf 'secret line one\nsecret line two\n' > "$work/secret"
ln -s "$work/secret" "$work/newline_name/series.csv"
"$demvv" plot "$work/newline_name" 2>"$work/err"
[ $? -eq 2 ] && ! grep -q secret "$work/err" || fail "plot followed a linked series: $(cat "$work/err")"

# 10. OMP_NUM_THREADS far above the cores is clamped (it crashed the runtime).
OMP_NUM_THREADS=100000 "$demvv" run "$impact" --out "$work/many_threads" --quiet 2>"$work/err" ||
  fail "OMP_NUM_THREADS=100000: $(cat "$work/err")"

# 11. A figure cut short by a file-size limit (gnuplot exits 0 on it) is an
# output failure, exit 4, and the picture drawn before is kept whole.
ls "$work/many_threads/plots/"*.svg >/dev/null 2>&1 || fail "the run drew no figures to redraw"
cp -r "$work/many_threads/plots" "$work/plots_before"
(ulimit -f 8; "$demvv" plot "$work/many_threads" 2>"$work/err")
[ $? -eq 4 ] && grep -q "cut short" "$work/err" || fail "a figure cut by a file-size limit: $(cat "$work/err")"
for f in "$work/plots_before/"*.svg; do
  cmp -s "$f" "$work/many_threads/plots/$(basename "$f")" || fail "$(basename "$f") was not kept whole"
done

# 12. A summary of no known kind is refused (it drew "0 figures", exit 0);
# verify --cases on a folder that does not exist is bad input (exit 2).
mkdir "$work/foreign_kind"
printf '{"kind": "../../etc"}\n' > "$work/foreign_kind/summary.json"
"$demvv" plot "$work/foreign_kind" 2>"$work/err"
[ $? -eq 2 ] && grep -q "no deck kind" "$work/err" || fail "a summary of an unknown kind: $(cat "$work/err")"
"$demvv" verify --only V05 --cases "$work/nowhere" --out "$work/verify_nowhere" 2>"$work/err"
[ $? -eq 2 ] && grep -q "not a directory" "$work/err" || fail "verify --cases on no folder: $(cat "$work/err")"
echo "run directory security: ok"
