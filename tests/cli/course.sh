#!/bin/sh
# The V&V course (cases/course/README.md) runs as written: every `sh` block of
# it, in order, in a fresh folder laid out like the repository's root (build/
# is this build, cases/ a copy of the source tree's), then the outcomes each
# exercise tells the student to look at.  `text` blocks are the long runs and
# are not run here.
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
         e6-rate-0.5/plots/stress_strain.svg; do
  [ -s "$work/runs/course/$f" ] || { echo "FAIL: runs/course/$f was not written"; fail=1; }
done
expect runs/course/e2-report/report.md "1 of 1 checks pass" "exercise 2: V02 passes"
expect runs/course/e4-scaling/report.md "1 of 1 checks pass" "exercise 4: V16 passes"
expect runs/course/e5-identity/report.md "1 of 1 checks pass" "exercise 5: V19 passes"
expect runs/course/e5-compare/summary.json "non_affine_ratio" "exercise 5: the compare run reports the non-affine ratio"
expect runs/course/e5-modified/summary.json "difference_calibrated" "exercise 5: the modified-law comparison ran"
expect course.log "PASS V24" "exercise 6: the calibration converges and meets its target"
expect runs/course/e6-validation/report.md "| V25 |" "exercise 6: the validation check reports its verdict"
[ "$fail" -eq 0 ] && echo "the course's commands ran and gave what its text describes"
exit "$fail"
