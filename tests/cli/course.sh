#!/bin/sh
# The V&V course (cases/course/README.md) runs as written: every `sh` block of
# it, in order, in a fresh folder laid out like the repository's root (build/
# is this build, cases/ a copy of the source tree's), then the outcomes each
# exercise tells the student to look at, and every number its answer key
# quotes, within the range that cases/course/answer_ranges.csv gives and
# argues for it.  `text` blocks are the long runs and are not run here.
#
# usage: course.sh BUILD_DIR SOURCE_DIR WORK_DIR
set -eu
build=$1
source=$2
work=$3
rm -rf "$work"
mkdir -p "$work"
ln -s "$build" "$work/build"
cp -r "$source/cases" "$work/cases"
awk '/^```sh$/ {on = 1; next} /^```/ {on = 0} on' "$source/cases/course/README.md" > "$work/course.sh"
(cd "$work" && sh -eu course.sh) > "$work/course.log" 2>&1 || {
  echo "FAIL: a command of the course failed:"; tail -20 "$work/course.log"; exit 1; }

fail=0
# Exercise 7's mutants are patches to the engine's sources: each must still
# apply to this tree, or the exercise would plant nothing.
for patch in "$source"/cases/course/mutants/*.patch; do
  git -C "$source" apply --check "$patch" 2>/dev/null || {
    echo "FAIL: exercise 7: the mutant $(basename "$patch") no longer applies to the sources (remake it)"; fail=1; }
done
expect() { # FILE PATTERN WHAT
  if ! grep -q -- "$2" "$work/$1" 2>/dev/null; then
    echo "FAIL: $3 ($1 lacks '$2')"; fail=1
  fi
}
expect course.log "demvv exit code: 1" "exercise 1: the broken copy's verify exits 1"
expect runs/course/e1-broken/report.md "0 of 1 checks pass" "exercise 1: V01 fails on the broken copy"
expect runs/course/e1-integrator/report.md "1 of 1 checks pass" "exercise 1: V07 passes"
expect runs/course/e1-burgers/report.md "1 of 1 checks pass" "exercise 1: V14 passes"
for f in e1-integrator/report.html e2-tension/plots/contact_forces.svg e3-gci/plots/gci_peak_stress_pa.svg \
         e3-gci/plots/levels.svg e3-step-0.2/plots/stress_strain.svg e4-scaling/report.html \
         e6-rate-0.5/plots/stress_strain.svg e8-space-q2/plots/convergence.svg e8-space-q1/own_order_stress_l2.svg \
         e8-time/own_order_displacement_l2.svg e9-seeds/stats.csv; do
  [ -s "$work/runs/course/$f" ] || { echo "FAIL: runs/course/$f was not written"; fail=1; }
done
expect runs/course/e2-report/report.md "1 of 1 checks pass" "exercise 2: V02 passes"
expect runs/course/e4-scaling/report.md "1 of 1 checks pass" "exercise 4: V16 passes"
expect runs/course/e5-identity/report.md "1 of 1 checks pass" "exercise 5: V19 passes"
expect runs/course/e5-compare/summary.json "non_affine_ratio" "exercise 5: the compare run reports the non-affine ratio"
expect runs/course/e5-modified/summary.json "difference_calibrated" "exercise 5: the modified-law comparison ran"
expect course.log "PASS V24" "exercise 6: the calibration converges and meets its target"
expect runs/course/e6-validation/report.md "| V25 |" "exercise 6: the validation check reports its verdict"

# Every number the answer key quotes, read from the runs and held in the range
# that cases/course/answer_ranges.csv gives and argues for it.
python3 - "$work/runs/course" "$source/cases/course/answer_ranges.csv" "$source/cases/course/README.md" <<'PY' || fail=1
import csv, json, math, os, re, sys

runs, table, readme = sys.argv[1:4]
key = open(readme, encoding="utf-8").read()
cache = {}


def load(path):
    if path not in cache:
        with open(os.path.join(runs, path), encoding="utf-8") as f:
            if path.endswith(".json"):
                cache[path] = json.load(f)
            else:
                cache[path] = list(csv.DictReader(line for line in f if not line.startswith("#")))
    return cache[path]


def j(path, keys):
    d = load(path)
    for k in keys.split("/"):
        d = d[int(k)] if isinstance(d, list) else d[k]
    return d


def one(items, what):
    if len(items) != 1:
        raise LookupError("%d matches for %s" % (len(items), what))
    return items[0]


def check(path, cid):
    return one([c for c in load(path)["checks"] if c["id"] == cid], "check " + cid)


def metric(path, cid, start, parts):
    found = [x for x in check(path, cid)["metrics"]
             if x["metric"].startswith(start) and all(p in x["metric"] for p in parts)]
    exact = [x for x in found if x["metric"] == start]
    return one(exact or found, "metric '%s' of %s" % (start, cid))


def m(path, cid, start, *parts):
    return metric(path, cid, start, parts)["value"]


def tol(path, cid, start, *parts):
    return metric(path, cid, start, parts)["tolerance"]


def note(path, cid, start):
    return one([n for n in check(path, cid)["notes"] if n.startswith(start)], "note '%s' of %s" % (start, cid))


def after(text, label):
    rest = text[text.index(label) + len(label):]
    return float(re.match(r"\s*([-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?)", rest).group(1))


def col(path, column, row):
    return float(load(path)[row][column])


readers = {"j": j, "m": m, "tol": tol, "note": note, "after": after, "col": col,
           "min": min, "max": max, "abs": abs, "__builtins__": {}}
rows = list(csv.DictReader(line for line in open(table, encoding="utf-8") if not line.startswith("#")))
bad = 0
for r in rows:
    what = "exercise %s: %s" % (r["exercise"], r["quantity"])
    low, high = float(r["low"]), float(r["high"])
    try:
        value = float(eval(r["value"], readers))
    except Exception as e:
        print("FAIL: %s could not be read (%s: %s)" % (what, type(e).__name__, e))
        bad += 1
        continue
    if math.isnan(value) or not low <= value <= high:
        print("FAIL: %s = %.6g, outside its range [%g, %g]" % (what, value, low, high))
        bad += 1
    if r["printed"] and r["printed"] not in key:
        print("FAIL: %s: the answer key no longer prints '%s'" % (what, r["printed"]))
        bad += 1
if not bad:
    print("the answer key's %d quantities lie within their ranges" % len(rows))
sys.exit(1 if bad else 0)
PY
[ "$fail" -eq 0 ] && echo "the course's commands ran and gave what its text describes"
exit "$fail"
