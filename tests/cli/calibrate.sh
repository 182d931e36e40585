#!/bin/sh
# demvv calibrate:
# 1. an exactly proportional model: the initial modulus of an elastic bonded
#    lattice whose contact stiffnesses all take one value k is c k (linear
#    elasticity; a run at 1e7 and one at 2e7 N/m differ from proportional
#    by 3e-5, the platens' inertia).  Fitted from a start 43 % below the
#    answer, k must equal k_ref E_target / E(k_ref) from one plain run
#    within 3e-4 (the stop tolerance 1e-4 plus that departure, with margin).
# 2. a noisy model: the peak stress of a lattice with random bond strengths
#    (CoV 0.3), fitted from a start 50 % below the answer on seeds 1-3, then
#    on seeds 4-6: converged, the target met within its standard error or
#    the tolerance, a positive standard error, and the two fits within 2.5
#    combined standard errors of each other: a test of the stated error
#    (two honest fits, normally distributed, lie further apart about once
#    in 80 seed sets; the seed sets are fixed, so the test is
#    deterministic).
# 3. the same command again resumes: nothing runs, the same calibration.json.
# 4. bad input: an entry the deck lacks, an unknown quantity, too few seeds
#    (exit 2, one line); an evaluation that faults (exit 3, one line, the
#    evaluations kept, no fitted deck); an unreachable target (30 MPa at 0.4 % strain; exit 3,
#    "not converged"); a target beyond every value the deck accepts (exit 3, not converged);
#    a parameter no target moves (exit 3, "not determined", no standard error).
# 5. the fitted deck names its calibration: its runs and sweeps state the
#    fit's input uncertainty u_input; a changed fitted entry is refused.
# 6. under MPI two ranks give the same fit, byte for byte, as one process.
# Usage: calibrate.sh DEMVV WORK_DIR [MPIRUN]
set -u
. "$(dirname "$0")/multi_run_support.sh"
same_fit() { # DIR_A DIR_B: the same fitted parameters and targets
  python3 - "$work/$1/calibration.json" "$work/$2/calibration.json" <<'EOF'
import json, sys
a, b = (json.load(open(f)) for f in sys.argv[1:3])
assert a["parameters"] == b["parameters"] and a["targets"] == b["targets"]
EOF
}
field() { python3 -c "import json,sys; d=json.load(open(sys.argv[1])); print(eval(sys.argv[2]))" "$1" "$2"; }

lattice="$(dirname "$0")/../data/small_lattice.prm"
stiffness="balls/normal stiffness+balls/shear stiffness+platens/normal stiffness"
strength="bonds/normal strength+bonds/shear strength"
elastic="bonds/strength cov=0"
short="loading/final strain=0.002"

# 1. Proportional model against its closed form.
"$demvv" run "$lattice" --set "$elastic" --set "$short" --set "balls/normal stiffness=1e7" \
  --set "balls/shear stiffness=1e7" --set "platens/normal stiffness=1e7" --out "$work/reference" --quiet \
  --threads 1 2>/dev/null || fail "reference run"
"$demvv" calibrate "$lattice" --fit "$stiffness=0.75e7" --target initial_modulus_pa=3e9 --at "$elastic" \
  --at "$short" --tolerance 1e-4 --seeds 2 --out "$work/elastic" --threads 1 --quiet 2>"$work/err_elastic" ||
  fail "elastic calibration: $(tail -1 "$work/err_elastic")"
python3 - "$work" <<'EOF' || fail "the proportional model's fit is off its closed form"
import json, sys
w = sys.argv[1]
e_ref = json.load(open(w + "/reference/summary.json"))["initial_modulus_pa"]
c = json.load(open(w + "/elastic/calibration.json"))
k = c["parameters"][0]["value"]
expected = 1e7 * 3e9 / e_ref
print("fitted k", k, "closed form", expected, "relative", abs(k / expected - 1))
assert c["status"] == "converged", c["status"]
assert abs(k / expected - 1) <= 3e-4
assert abs(c["targets"][0]["relative_residual"]) <= 1e-4
EOF
grep -q "^ *set normal stiffness *= *13250" "$work/elastic/fitted.prm" || fail "fitted.prm lacks the fitted stiffness"

# 2. Noisy model, two seed sets.
calibrate_noisy() { # OUT FIRST_SEED [launcher]
  $3 "$demvv" calibrate "$lattice" --fit "$strength=11" --target peak_stress_pa=1e7 \
    --at "loading/final strain=0.02" --seeds 3 --first-seed "$2" --out "$work/$1" --threads 1 --quiet
}
calibrate_noisy noisy_a 1 "" 2>"$work/err_a" || fail "noisy calibration, seeds 1-3: $(tail -1 "$work/err_a")"
calibrate_noisy noisy_b 4 "" 2>"$work/err_b" || fail "noisy calibration, seeds 4-6: $(tail -1 "$work/err_b")"
python3 - "$work" <<'EOF' || fail "the noisy fits disagree beyond their stated errors"
import json, math, sys
w = sys.argv[1]
a, b = (json.load(open(w + "/" + d + "/calibration.json")) for d in ("noisy_a", "noisy_b"))
for c in (a, b):
    assert c["status"] == "converged", c["status"]
    t = c["targets"][0]
    assert abs(t["residual"]) <= max(t["standard_error_of_mean"], 0.005 * t["value"]), t
    assert c["parameters"][0]["standard_error"] > 0
pa, pb = a["parameters"][0], b["parameters"][0]
combined = math.hypot(pa["standard_error"], pb["standard_error"])
print("seeds 1-3:", pa["value"], "+-", pa["standard_error"], " seeds 4-6:", pb["value"], "+-", pb["standard_error"])
assert abs(pa["value"] - pb["value"]) <= 2.5 * combined
# The start was 50 % below the answer (within its error).
assert abs(11 / pa["value"] - 0.5) < 0.1
EOF

# 3. Resume: nothing runs again, the same result; refused on another build.
mkdir -p "$work/before"
cp "$work/noisy_a/calibration.json" "$work/before/calibration.json"
calibrate_noisy noisy_a 1 "" 2>"$work/err_resume" || fail "resume: $(tail -1 "$work/err_resume")"
same_fit before noisy_a || fail "resumed calibration differs"
[ -z "$(find "$work/noisy_a/evaluations" -path '*/members/*/summary.json' -newer "$work/before/calibration.json")" ] ||
  fail "resume ran members again"
# ... but not on another build: its fit's path is not this build's.
cp -r "$work/noisy_a" "$work/other_build"
python3 - "$work/other_build/calibration.json" <<'EOF'
import json, sys
c = json.load(open(sys.argv[1]))
c["provenance"]["sources_sha256"] = "0" * 64
json.dump(c, open(sys.argv[1], "w"))
EOF
calibrate_noisy other_build 1 "" 2>"$work/err_other_build"
[ $? -eq 2 ] && grep -q "another build" "$work/err_other_build" ||
  fail "a calibration begun by another build was not refused: $(cat "$work/err_other_build")"
one_line "$work/err_other_build" "another build"

# 4. Bad input.
expect() { # CODE WORDS NAME -- command...
  code=$1 words=$2 name=$3
  shift 4
  "$@" >/dev/null 2>"$work/err_$name"
  got=$?
  [ "$got" -eq "$code" ] || fail "$name: exit $got, expected $code: $(cat "$work/err_$name")"
  tail -1 "$work/err_$name" | grep -q "$words" || fail "$name: the error does not say '$words': $(cat "$work/err_$name")"
}
expect 2 "has no entry 'bonds/strength'" no_entry -- "$demvv" calibrate "$lattice" --fit "bonds/strength=10" \
  --target peak_stress_pa=1e7 --out "$work/bad1"
one_line "$work/err_no_entry" "unknown entry"
expect 2 "QUANTITY one of" no_quantity -- "$demvv" calibrate "$lattice" --fit "$strength=10" \
  --target peak=1e7 --out "$work/bad2"
one_line "$work/err_no_quantity" "unknown quantity"
expect 2 "expected a positive value" negative_start -- "$demvv" calibrate "$lattice" --fit "$strength=-3" \
  --target peak_stress_pa=1e7 --out "$work/bad3"
[ ! -e "$work/bad1" ] && [ ! -e "$work/bad2" ] && [ ! -e "$work/bad3" ] || fail "refused input left a directory"
expect 3 "calibration failed: evaluation 000 (centre), seed 1: fault" fault -- "$demvv" calibrate "$lattice" \
  --fit "$strength=10" --target peak_stress_pa=1e7 --seeds 2 --at "motion/fixed time step=1e-4" \
  --at "motion/unstable fixed step=run" --out "$work/fault" --threads 1 --quiet
[ "$(field "$work/fault/calibration.json" 'd["status"]')" = failed ] || fail "a faulted fit is not recorded as failed"
[ -f "$work/fault/evaluations/000/sweep.csv" ] && [ ! -e "$work/fault/fitted.prm" ] ||
  fail "a faulted fit lost its evaluation or wrote a fitted deck"
expect 3 "not converged" unreachable -- "$demvv" calibrate "$lattice" --fit "$strength=10" \
  --target peak_stress_pa=3e7 --seeds 2 --max-iterations 2 --out "$work/unreachable" --threads 1 --quiet
[ "$(field "$work/unreachable/calibration.json" 'd["status"]')" = "not converged" ] ||
  fail "an unreachable target is not recorded as not converged"
# A target so far off that the fit steps beyond what the deck accepts (a
# strength of inf) is not reached: said so, not called bad input.
expect 3 "the fit stepped to values the deck refuses" beyond -- "$demvv" calibrate "$lattice" \
  --fit "$strength=10" --target peak_stress_pa=1e12 --seeds 2 --max-iterations 4 --out "$work/beyond" --threads 1 --quiet
[ "$(field "$work/beyond/calibration.json" 'd["status"]')" = "not converged" ] ||
  fail "a fit stepped beyond the deck is not recorded as not converged"
# A parameter no target moves (this lattice's friction: its bonds hold
# every contact by the peak) meets the target without determining anything.
expect 3 "no target moves with balls/friction" idle -- "$demvv" calibrate "$lattice" --fit "balls/friction=0.5" \
  --target peak_stress_pa=7e6 --seeds 2 --max-iterations 2 --out "$work/idle" --threads 1 --quiet
[ "$(field "$work/idle/calibration.json" 'd["status"]')" = "not determined" ] && [ ! -e "$work/idle/fitted.prm" ] &&
  [ "$(field "$work/idle/calibration.json" '"standard_error" in d["parameters"][0]')" = False ] ||
  fail "an undetermined parameter was recorded as fitted"

# 5. The fitted deck carries its calibration: a run of it states u_input,
#    the fitted strength's relative standard error r times the elasticity g
#    = slope / fitted mean that calibration.json records (one parameter:
#    u_input / |q| = |g| r, app/run/input_uncertainty.h), for the target
#    only; a sweep of it carries u_input x mean into stats.csv; a deck whose
#    fitted entry was changed, or whose record is not a converged
#    calibration, is refused (exit 2, one line); the fitted deck calibrates
#    again (its evaluations vary the fitted entries without the record, which
#    would refuse them).
"$demvv" sweep "$work/noisy_a/fitted.prm" --seeds 2 --out "$work/fitted_sweep" --threads 1 --quiet \
  2>"$work/err_fitted_sweep" || fail "sweep of the fitted deck: $(tail -1 "$work/err_fitted_sweep")"
python3 - "$work" <<'EOF' || fail "the fitted deck's runs do not state the calibration's u_input"
import csv, glob, json, math, sys
w = sys.argv[1]
c = json.load(open(w + "/noisy_a/calibration.json"))
t, p = c["targets"][0], c["parameters"][0]
expected = abs(t["slope_per_ln_parameter"][0] / t["fitted_mean"]) * p["relative_standard_error"]
assert expected > 0, expected
summaries = sorted(glob.glob(w + "/fitted_sweep/members/*/summary.json"))
assert len(summaries) == 2, summaries
for f in summaries:
    u = json.load(open(f))["uncertainty"]["input_calibration"]
    assert u["estimated"] and u["record"].endswith("/noisy_a/calibration.json"), u
    assert math.isclose(u["peak_stress_pa"]["u_input_relative"], expected, rel_tol=1e-12), (u, expected)
    assert u["strain_at_peak"]["u_input_relative"] is None and "not a target" in u["strain_at_peak"]["why"], u
rows = list(csv.DictReader(l for l in open(w + "/fitted_sweep/stats.csv") if not l.startswith("#")))
mean = float(rows[0]["peak_stress_mean_pa"])
assert math.isclose(float(rows[0]["peak_stress_u_input_pa"]), expected * mean, rel_tol=1e-9), rows[0]
assert rows[0]["strain_at_peak_u_input"] == "", rows[0]
print("u_input / peak", expected)
EOF
expect 2 "here: expected the fitted value" changed_fit -- "$demvv" run "$work/noisy_a/fitted.prm" \
  --set "bonds/normal strength=99" --out "$work/changed_fit" --quiet
one_line "$work/err_changed_fit" "a changed fitted entry"
sed 's/"status": "converged"/"status": "not converged"/' "$work/noisy_a/calibration.json" >"$work/unconverged.json"
expect 2 "did not converge" unconverged -- "$demvv" run "$work/noisy_a/fitted.prm" \
  --set "calibration/record=$work/unconverged.json" --out "$work/unconverged_run" --quiet
one_line "$work/err_unconverged" "an unconverged record"
# From the fitted value on the same seeds the target is met at once: one
# evaluation, converged, and its fitted deck names the new record.
fitted=$(field "$work/noisy_a/calibration.json" 'd["parameters"][0]["deck_value"]')
"$demvv" calibrate "$work/noisy_a/fitted.prm" --fit "$strength=$fitted" --target peak_stress_pa=1e7 --seeds 3 \
  --out "$work/again" --threads 1 --quiet 2>"$work/err_again" &&
  [ "$(ls "$work/again/evaluations")" = 000 ] && grep -q "set record *= *$work/again/calibration.json" "$work/again/fitted.prm" ||
  fail "the fitted deck does not calibrate again: $(tail -1 "$work/err_again")"

# 6. MPI: the same fit on two ranks.
if [ -n "$mpirun" ]; then
  calibrate_noisy noisy_mpi 1 "$launch_np2" 2>"$work/err_mpi" || fail "two ranks: $(tail -1 "$work/err_mpi")"
  same_fit noisy_a noisy_mpi || fail "two ranks give another fit than one process"
fi
echo "calibrate: all passed"
