#!/bin/sh
# Course exercise 7: plant a real bug in the engine, build it, run the
# verification, and see which checks catch it.
#
# Each NAME.patch beside this script is one mutant: a one-line change to an
# engine source that a programmer could plausibly make.  The mutants live
# only here, as patches; no build option of demvv itself carries them, so
# no release can contain one.  The script clones this repository's HEAD into
# WORK_DIR/tree, builds `demvv` there (Release, the build CI makes), and for
# the unmutated baseline and each mutant: resets the clone, applies the
# patch (only the files it touches recompile), runs `demvv verify --quick`
# into WORK_DIR/NAME/ and reads report.json.  A mutant is caught by a check
# that fails with it and passes on the baseline (V25's validation finding
# fails on both: it is about the model, not the code).
#
# usage: cases/course/mutants/run_mutants.sh WORK_DIR [NAME ...]
#   WORK_DIR  a new folder, or one this script made before (it keeps the
#             build: a second call rebuilds only what changed); any other
#             non-empty folder is refused
#   NAME      the mutants to run (default: every *.patch here)
# writes WORK_DIR/mutants.md (the table the course's answer key shows) and
# WORK_DIR/mutants.csv (mutant, checks that catch it, failing metrics).
# Cost on 2 cores: the first build about 10 minutes, then per mutant a
# rebuild of the touched files (1-6 minutes: contact.h is included by most
# of the engine) and a quick verification (about 2 minutes).
set -eu
if [ $# -lt 1 ]; then
  echo "usage: $0 WORK_DIR [NAME ...]" >&2
  exit 2
fi
here=$(cd "$(dirname "$0")" && pwd)
src=$(git -C "$here" rev-parse --show-toplevel)
work=$1
shift
if [ -e "$work" ] && [ ! -f "$work/.demvv-mutants" ] && [ -n "$(ls -A "$work" 2>/dev/null)" ]; then
  echo "$0: WORK_DIR '$work' is not empty and was not made by this script: expected a new folder" >&2
  exit 2
fi
mkdir -p "$work"
work=$(cd "$work" && pwd)
touch "$work/.demvv-mutants"
if [ $# -eq 0 ]; then
  set -- $(cd "$here" && ls ./*.patch | sed 's|^\./||; s|\.patch$||')
fi
for name in "$@"; do
  if [ ! -f "$here/$name.patch" ]; then
    echo "$0: no mutant '$name' (expected one of: $(cd "$here" && ls ./*.patch | sed 's|^\./||; s|\.patch$||' | tr '\n' ' '))" >&2
    exit 2
  fi
done

tree=$work/tree
build=$work/build
[ -d "$tree/.git" ] || git clone -q "$src" "$tree"
git -C "$tree" fetch -q "$src" HEAD
head=$(git -C "$tree" rev-parse FETCH_HEAD)
jobs=$(nproc 2>/dev/null || echo 2)

for name in baseline "$@"; do
  git -C "$tree" reset -q --hard "$head"
  if [ "$name" != baseline ]; then
    git -C "$tree" apply "$here/$name.patch"
  fi
  echo "== $name: building"
  [ -f "$build/CMakeCache.txt" ] || cmake -S "$tree" -B "$build" -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
  cmake --build "$build" -j "$jobs" --target demvv > "$work/$name.build.log" 2>&1 || {
    echo "$0: the $name build failed (see $work/$name.build.log)" >&2
    exit 1
  }
  echo "== $name: demvv verify --quick"
  rm -rf "${work:?}/$name"
  # Exit 1 means a check failed: for a mutant, that is the point.
  "$build/demvv" verify --quick --out "$work/$name" > "$work/$name.verify.log" 2>&1 || true
  [ -f "$work/$name/report.json" ] || {
    echo "$0: $name wrote no report (see $work/$name.verify.log)" >&2
    exit 1
  }
done
git -C "$tree" reset -q --hard "$head"

python3 - "$work" "$head" "$here" "$@" <<'EOF'
import csv, json, sys

work, head, here, names = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4:]

def failing(name):
    report = json.load(open("%s/%s/report.json" % (work, name), encoding="utf-8"))
    out = {}
    for c in report["checks"]:
        if not c["pass"]:
            bad = [m["metric"] for m in c["metrics"] if not m["pass"]]
            out[c["id"]] = bad or ["stopped: " + c["error"]]
    return out

def first_line(name):
    for line in open("%s/%s.patch" % (here, name), encoding="utf-8"):
        if line.startswith("+") and not line.startswith("+++"):
            return line[1:].strip()
    return ""

base = failing("baseline")
rows = []
for name in names:
    caught = {k: v for k, v in failing(name).items() if k not in base}
    rows.append((name, first_line(name), caught))
with open(work + "/mutants.csv", "w", newline="", encoding="utf-8") as f:
    w = csv.writer(f)
    w.writerow(["mutant", "changed_line", "caught_by", "failing_metrics"])
    for name, line, caught in rows:
        w.writerow([name, line, " ".join(sorted(caught)),
                    " | ".join("%s: %s" % (k, "; ".join(v)) for k, v in sorted(caught.items()))])
with open(work + "/mutants.md", "w", encoding="utf-8") as f:
    f.write("Mutants against `demvv verify --quick` (clone of %s; the baseline fails %s)\n\n"
            % (head[:12], ", ".join(sorted(base)) or "nothing"))
    f.write("| mutant | the planted line | caught by | failing metrics |\n|---|---|---|---|\n")
    for name, line, caught in rows:
        f.write("| %s | `%s` | %s | %s |\n" % (
            name, line, ", ".join(sorted(caught)) or "**no check**",
            "; ".join("%s: %s" % (k, ", ".join(v)) for k, v in sorted(caught.items())) or "-"))
print(open(work + "/mutants.md", encoding="utf-8").read())
EOF
