#!/bin/sh
# demvv sweep: members are the product of the --vary values and the seeds,
# one run directory each; a value the deck refuses is a row, not the end of
# the sweep; sweep.csv and stats.csv agree with the members' summaries (the
# 95 % half-width by Student t); a rerun keeps the completed members and
# runs only the missing one, to the same table; a directory holding
# something else, another sweep or a bad --vary is refused (exit 2, one
# line); under MPI two ranks give the members the same results, byte for
# byte, as one process; --threads is each member's ceiling.
# Usage: sweep.sh DEMVV WORK_DIR [MPIRUN]
set -u
. "$(dirname "$0")/multi_run_support.sh"

# A small lattice with random bond strengths, so that seeds matter.
cp "$(dirname "$0")/../data/small_lattice.prm" "$work/base.prm"
sweep() { "$demvv" sweep "$work/base.prm" --vary balls/friction=0.2,-1,0.5 --seeds 2 "$@"; }

sweep --out "$work/a" --threads 2 2>"$work/err_a" || fail "the sweep failed: $(cat "$work/err_a")"
[ "$(ls "$work/a/members" | wc -l)" -eq 6 ] || fail "not six member directories: $(ls "$work/a/members")"
grep -q "6 members: 0 kept from an earlier run, 6 to run" "$work/err_a" || fail "opening line: $(cat "$work/err_a")"
grep -q '"completed"' "$work/a/sweep.json" && grep -q '"balls/friction"' "$work/a/sweep.json" ||
  fail "sweep.json lacks its status or varied key"

# The tables against the members' own summaries.
python3 - "$work/a" <<'EOF' || fail "sweep.csv or stats.csv disagree with the members"
import csv, json, math, os, sys
d = sys.argv[1]
rows = list(csv.DictReader(l for l in open(d + "/sweep.csv") if not l.startswith("#")))
assert len(rows) == 6, rows
assert [r["balls/friction"] for r in rows] == ["0.2", "0.2", "-1", "-1", "0.5", "0.5"], rows
assert [r["seed"] for r in rows] == ["1", "2"] * 3, rows
assert [r["status"] for r in rows] == ["completed"] * 2 + ["refused"] * 2 + ["completed"] * 2, rows
assert "friction" in rows[2]["message"], rows[2]
members = sorted(os.listdir(d + "/members"))
for r, m in zip(rows, members):
    assert m.startswith(r["member"] + "_"), (m, r["member"])
    if r["status"] != "completed":
        continue
    s = json.load(open(d + "/members/" + m + "/summary.json"))
    threads = s["status"]["threads"]  # --threads 2: at most two, governed
    assert threads["governed"] and threads["most"] == 2 and 1 <= threads["at_end"] <= 2, threads
    for key in ("peak_stress_pa", "strain_at_peak", "initial_modulus_pa", "poisson_ratio"):
        assert math.isclose(float(r[key]), s[key], rel_tol=1e-10), (key, r[key], s[key])
    assert 0 <= float(r["bonds_broken_fraction_at_peak"]) <= 1, r
    assert int(float(r["particles"])) == s["sample"]["particles"], (r["particles"], s["sample"])
    assert float(r["run_time_s"]) > 0, r
peaks = [float(rows[i]["peak_stress_pa"]) for i in (0, 1)]
assert peaks[0] != peaks[1], "two seeds gave the same peak stress"
stats = list(csv.DictReader(l for l in open(d + "/stats.csv") if not l.startswith("#")))
assert [s["n"] for s in stats] == ["2", "0", "2"], stats
mean = sum(peaks) / 2
sd = abs(peaks[0] - peaks[1]) / math.sqrt(2)
t = 12.706204736174698  # Student t, 0.975 quantile, one degree of freedom
assert math.isclose(float(stats[0]["peak_stress_mean_pa"]), mean, rel_tol=1e-10), stats[0]
assert math.isclose(float(stats[0]["peak_stress_sd_pa"]), sd, rel_tol=1e-10), stats[0]
assert math.isclose(float(stats[0]["peak_stress_ci95_pa"]), t * sd / math.sqrt(2), rel_tol=1e-9), stats[0]
assert stats[1]["peak_stress_mean_pa"] == "", stats[1]
# The budget of each mean: u_seed its standard error, u_num as the members'
# summaries state it (empty where no time-step study applies).
assert math.isclose(float(stats[0]["peak_stress_u_seed_pa"]), sd / math.sqrt(2), rel_tol=1e-9), stats[0]
first = json.load(open(d + "/members/" + members[0] + "/summary.json"))["uncertainty"]["numerical_time_step"]
if first["estimated"]:
    expected = mean * first["peak_stress_pa"]["u_num_relative"]
    assert math.isclose(float(stats[0]["peak_stress_u_num_pa"]), expected, rel_tol=1e-9), stats[0]
else:
    assert first["why"] and stats[0]["peak_stress_u_num_pa"] == "", (first, stats[0])
# The figure's data: the means against the friction (the refused point left
# out), then every member, then the 95 % half-widths as error bars.
blocks = [[[float(x) for x in l.split(",")] for l in b.strip().splitlines() if not l.startswith("#")]
          for b in open(d + "/plots/peak_stress.csv").read().split("\n\n\n")]
assert [p[0] for p in blocks[0]] == [0.2, 0.5], blocks[0]
assert math.isclose(blocks[0][0][1], mean, rel_tol=1e-10), blocks[0]
assert all(math.isclose(a, b, rel_tol=1e-10) for a, b in zip(sorted(p[1] for p in blocks[1][:2]), sorted(peaks))), blocks[1]
assert math.isclose(blocks[2][0][2], t * sd / math.sqrt(2), rel_tol=1e-9), blocks[2]
# The budget figure's data: u_seed in per cent of the mean at each point
# with completed members (the refused point has none).
budget = [[[float(x) for x in l.split(",")] for l in b.strip().splitlines() if not l.startswith("#")]
          for b in open(d + "/plots/budget_peak_stress.csv").read().split("\n\n\n")]
assert [p[0] for p in budget[0]] == [0.2, 0.5], budget[0]
assert math.isclose(budget[0][0][1], 100 * sd / math.sqrt(2) / mean, rel_tol=1e-9), budget[0]
EOF
if command -v gnuplot >/dev/null; then
  for f in peak_stress strain_at_peak initial_modulus budget_peak_stress; do
    grep -q "<svg" "$work/a/plots/$f.svg" || fail "the sweep's figure $f.svg was not drawn"
  done
fi

# Resume: one member's directory gone, another run by another build (its
# provenance says so); the rerun runs those two alone and leaves the same
# table (run times aside).
without_time() { python3 -c "
import csv, sys
rows = csv.reader(l for l in open(sys.argv[1]) if not l.startswith('#'))
for r in rows:
    del r[-2]
    print(r)" "$1"; }
cp -r "$work/a" "$work/a_before"
member=$(ls "$work/a/members" | sed -n 5p)
rm -rf "$work/a/members/$member"
older=$(ls "$work/a/members" | sed -n 1p)
python3 - "$work/a/members/$older/summary.json" <<'EOF'
import json, sys
s = json.load(open(sys.argv[1]))
s["provenance"]["sources_sha256"] = "0" * 64
json.dump(s, open(sys.argv[1], "w"))
EOF
sweep --out "$work/a" --threads 2 2>"$work/err_b" || fail "the resumed sweep failed: $(cat "$work/err_b")"
grep -q "6 members: 4 kept from an earlier run, 2 to run" "$work/err_b" || fail "resume did not keep four: $(cat "$work/err_b")"
for m in $(ls "$work/a/members"); do
  [ "$m" = "$member" ] || [ "$m" = "$older" ] && continue
  cmp -s "$work/a/members/$m/summary.json" "$work/a_before/members/$m/summary.json" || fail "resume reran $m"
done
[ "$(without_time "$work/a/sweep.csv")" = "$(without_time "$work/a_before/sweep.csv")" ] ||
  fail "the resumed sweep.csv differs from the uninterrupted one"
for m in "$member" "$older"; do
  cmp -s "$work/a/members/$m/series.csv" "$work/a_before/members/$m/series.csv" || fail "the rerun member $m differs"
done

# Refusals: another sweep into the same directory, a folder that holds no
# sweep (even with --replace), an unknown key.
"$demvv" sweep "$work/base.prm" --vary balls/friction=0.3 --out "$work/a" 2>"$work/err"
[ $? -eq 2 ] && grep -q "holds another sweep" "$work/err" || fail "another sweep into a sweep directory: $(cat "$work/err")"
one_line "$work/err" "another sweep"
mkdir -p "$work/other" && echo keep > "$work/other/notes.txt"
sweep --out "$work/other" --replace 2>"$work/err"
[ $? -eq 2 ] && [ -f "$work/other/notes.txt" ] || fail "a folder without sweep.json was not refused: $(cat "$work/err")"
one_line "$work/err" "folder without sweep.json"
"$demvv" sweep "$work/base.prm" --vary balls/fricton=0.3 --out "$work/c" 2>"$work/err"
[ $? -eq 2 ] && grep -q "fricton" "$work/err" && [ ! -e "$work/c" ] || fail "an unknown --vary key: $(cat "$work/err")"
one_line "$work/err" "unknown key"
"$demvv" sweep "$work/base.prm" --vary balls/friction=0.1,0.3,1e-1 --out "$work/d" 2>"$work/err"
[ $? -eq 2 ] && grep -q "given twice" "$work/err" && [ ! -e "$work/d" ] || fail "a value varied twice: $(cat "$work/err")"
one_line "$work/err" "value twice"
"$demvv" sweep "$work/base.prm" --vary "balls/friction+balls/friction=0.1" --out "$work/d" 2>"$work/err"
[ $? -eq 2 ] && grep -q "varied twice" "$work/err" && [ ! -e "$work/d" ] || fail "a key tied to itself: $(cat "$work/err")"
one_line "$work/err" "key tied to itself"
"$demvv" sweep "$work/base.prm" --vary "bonds/normal strength+=3" --out "$work/d" 2>"$work/err"
[ $? -eq 2 ] && grep -q "deck entries and their values" "$work/err" && [ ! -e "$work/d" ] || fail "an empty tied key: $(cat "$work/err")"
one_line "$work/err" "empty tied key"
# An entry no member's deck reads (another law's constant) would run
# identical members under different labels.
"$demvv" sweep "$work/base.prm" --vary "contact law/normal maxwell stiffness=1e5,2e5" --out "$work/d" 2>"$work/err"
[ $? -eq 2 ] && grep -q "no point's deck reads 'contact law/normal maxwell stiffness'" "$work/err" && [ ! -e "$work/d" ] ||
  fail "a key the deck ignores: $(cat "$work/err")"
one_line "$work/err" "key the deck ignores"
# A damaged sweep.json is said to be damaged, not another sweep's.
cp -a "$work/a" "$work/damaged" && echo '{' > "$work/damaged/sweep.json"
sweep --out "$work/damaged" 2>"$work/err"
[ $? -eq 2 ] && grep -q "sweep.json cannot be read" "$work/err" || fail "a damaged sweep.json: $(cat "$work/err")"
one_line "$work/err" "damaged sweep.json"
rm -rf "$work/damaged"
sweep --out "$work/a" --replace --quiet 2>"$work/err" || fail "--replace of a sweep directory failed: $(cat "$work/err")"
[ "$(without_time "$work/a/sweep.csv")" = "$(without_time "$work/a_before/sweep.csv")" ] || fail "--replace changed the table"

# A shared sweep directory may hold planted links: a members folder (or a
# member) that is a link is refused before anything is written through it.
mkdir -p "$work/elsewhere"
"$demvv" sweep "$work/base.prm" --vary balls/friction=0.1 --out "$work/linked" --quiet --threads 1 2>/dev/null ||
  fail "the sweep to plant a link in failed"
rm -rf "$work/linked/members" && ln -s ../elsewhere "$work/linked/members"
"$demvv" sweep "$work/base.prm" --vary balls/friction=0.1 --out "$work/linked" --quiet --threads 1 2>"$work/err"
[ $? -eq 2 ] && [ -z "$(ls "$work/elsewhere")" ] && grep -q "a link or a special file" "$work/err" ||
  fail "a members folder that is a link was followed: $(cat "$work/err"); elsewhere: $(ls "$work/elsewhere")"
one_line "$work/err" "members link"
# Values are text in sweep.csv, never a formula or a broken row; a control
# character is refused before anything runs.
"$demvv" sweep "$work/base.prm" --vary "sample/source=lattice,=HYPERLINK(\"x\")" --out "$work/formula" --quiet \
  --threads 1 2>/dev/null
grep -q "^1,\"'=HYPERLINK(\"\"x\"\")\"," "$work/formula/sweep.csv" || fail "a formula-like value: $(cat "$work/formula/sweep.csv")"
"$demvv" sweep "$work/base.prm" --vary "sample/source=lattice,$(printf 'a\nb')" --out "$work/newline" 2>"$work/err"
[ $? -eq 2 ] && [ ! -e "$work/newline" ] && grep -q "control character" "$work/err" ||
  fail "a value with a newline: $(cat "$work/err")"
one_line "$work/err" "control character"
# Alone (no mpirun) a sweep starts no MPI, so a small file-size limit ends
# it as it ends a run: exit 4, one line (Open MPI's start-up aborted).
(ulimit -f 20; "$demvv" sweep "$work/base.prm" --vary balls/friction=0.1,0.2 --out "$work/fsize" --quiet --threads 1) \
  2>"$work/err"
[ $? -eq 4 ] || fail "a sweep under a file-size limit: $(cat "$work/err")"
one_line "$work/err" "file-size limit"

# Entries tied by '+' take one value each point: one factor of the
# product, a column each, every member's deck setting both.
"$demvv" sweep "$work/base.prm" --vary "bonds/normal strength+bonds/shear strength=20,40" --vary balls/friction=0.2,0.4 \
  --out "$work/tied" --threads 2 --quiet 2>"$work/err" || fail "the sweep of tied entries failed: $(cat "$work/err")"
python3 - "$work/tied" <<'EOF' || fail "tied entries were not set together"
import csv, glob, re, sys
d = sys.argv[1]
rows = list(csv.DictReader(l for l in open(d + "/sweep.csv") if not l.startswith("#")))
assert [(r["bonds/normal strength"], r["bonds/shear strength"], r["balls/friction"]) for r in rows] == [
    ("20", "20", "0.2"), ("20", "20", "0.4"), ("40", "40", "0.2"), ("40", "40", "0.4")], rows
assert all(r["status"] == "completed" for r in rows), rows
for r in rows:
    deck = open(glob.glob(d + "/members/" + r["member"] + "_*/deck.prm")[0]).read()
    for key in ("normal strength", "shear strength"):
        assert re.search(r"set " + key + r" *= " + r["bonds/normal strength"] + r"\n", deck), (key, r["member"])
EOF
if command -v gnuplot >/dev/null; then
  grep -q "bonds/normal strength + bonds/shear strength" "$work/tied/plots/peak_stress.gp" &&
    grep -q "balls/friction = 0.4" "$work/tied/plots/peak_stress.gp" ||
    fail "the tied sweep's figure is not drawn against both entries, one series per friction"
fi

# Seeds of a sample from a prepare deck: each seed prepares its own
# packing (cached beside the deck), which its member's deck.prm names.
printf 'set kind = prepare\nsubsection sample\n  set particles = 200\n  set seed = 5\nend\n' > "$work/small.prm"
printf 'set kind = uniaxial\nsubsection sample\n  set source = file\n  set file = small.prm\nend\nsubsection loading\n  set final strain = 0.002\nend\nsubsection output\n  set strain interval = 0.0005\nend\n' > "$work/packed.prm"
"$demvv" sweep "$work/packed.prm" --seeds 2 --out "$work/p" --threads 2 --quiet 2>"$work/err" ||
  fail "the sweep over prepared samples failed: $(cat "$work/err")"
[ "$(ls "$work/samples" | wc -l)" -eq 2 ] || fail "not one cached sample per seed: $(ls "$work/samples")"
for s in 1 2; do
  sample=$(sed -n 's/^ *set file *= *//p' "$work/p/members/"*"_s$s/deck.prm")
  python3 -c "import json, sys; sys.exit(json.load(open(sys.argv[1]))['seed'] != $s)" "$sample" ||
    fail "seed $s: its sample '$sample' was not prepared with that seed"
done
[ "$(cut -d, -f4 "$work/p/sweep.csv" | sort -u | wc -l)" -eq 4 ] || fail "two seeds gave one peak stress: $(cat "$work/p/sweep.csv")"
# Another seed set (--first-seed 2: seeds 2 and 3): seed 2's member is the
# one above to the last digit, seed 3's sample is prepared with seed 3, and
# the first sweep's folder refuses it as another sweep.
"$demvv" sweep "$work/packed.prm" --seeds 2 --first-seed 2 --out "$work/p2" --threads 2 --quiet 2>"$work/err" ||
  fail "the sweep of seeds 2-3 failed: $(cat "$work/err")"
[ "$(sed -n 's/^1,2,completed,//p' "$work/p/sweep.csv" | cut -d, -f1)" = \
  "$(sed -n 's/^0,2,completed,//p' "$work/p2/sweep.csv" | cut -d, -f1)" ] ||
  fail "seed 2 gave another peak in the second seed set: $(cat "$work/p/sweep.csv" "$work/p2/sweep.csv")"
sample=$(sed -n 's/^ *set file *= *//p' "$work/p2/members/"*"_s3/deck.prm")
python3 -c "import json, sys; sys.exit(json.load(open(sys.argv[1]))['seed'] != 3)" "$sample" ||
  fail "seed 3: its sample '$sample' was not prepared with that seed"
if "$demvv" sweep "$work/packed.prm" --seeds 2 --first-seed 2 --out "$work/p" --quiet 2>"$work/err"; then
  fail "a sweep of seeds 2-3 resumed the folder of seeds 1-2"
fi
grep -q "another sweep" "$work/err" || fail "another seed set in a sweep's folder: $(cat "$work/err")"

# A sweep of a kind without a peak stress (a Burger's chain) draws no
# figure of the quantities its members do not have, and says nothing
# about them.
"$demvv" sweep "$(dirname "$0")/../../cases/c01_burgers_ode_constant_velocity/case.prm" --vary loading/rate=1,2 --out "$work/ode" \
  --quiet 2>"$work/err_ode" || fail "the sweep of a Burger's chain failed: $(cat "$work/err_ode")"
grep -q "not drawn" "$work/err_ode" && fail "a sweep drew figures of quantities its members lack: $(cat "$work/err_ode")"
[ -z "$(ls "$work/ode/plots" 2>/dev/null | grep peak_stress)" ] || fail "a Burger's chain sweep has a peak-stress figure"

# Two MPI ranks share the members: the same results as one process.
if [ -n "$mpirun" ]; then
  DEMVV_CACHE="$work/mpi_samples" timeout 300 $launch_np2 "$demvv" sweep "$work/packed.prm" --seeds 2 --out "$work/mpi_p" \
    --threads 1 --quiet 2>"$work/err_mpi" || fail "the 2-rank sweep over prepared samples failed: $(cat "$work/err_mpi")"
  [ "$(ls "$work/mpi_samples" | wc -l)" -eq 2 ] || fail "MPI: not one sample per seed: $(ls "$work/mpi_samples")"
  for m in $(ls "$work/p/members"); do # the header names the sample's folder
    [ "$(tail -n +2 "$work/p/members/$m/series.csv")" = "$(tail -n +2 "$work/mpi_p/members/$m/series.csv")" ] ||
      fail "MPI: $m has another series"
  done
  timeout 300 $launch_np2 "$demvv" sweep "$work/base.prm" --vary balls/friction=0.2,-1,0.5 --seeds 2 --out "$work/mpi" \
    --threads 1 --quiet 2>"$work/err_mpi" || fail "the 2-rank sweep failed: $(cat "$work/err_mpi")"
  for m in $(ls "$work/a/members"); do
    [ -f "$work/a/members/$m/series.csv" ] || continue
    cmp -s "$work/a/members/$m/series.csv" "$work/mpi/members/$m/series.csv" || fail "MPI: $m has another series"
  done
  [ "$(without_time "$work/mpi/sweep.csv")" = "$(without_time "$work/a/sweep.csv")" ] || fail "MPI: another sweep.csv"
  grep -q '"ranks": 2' "$work/mpi/sweep.json" || fail "MPI: sweep.json does not say two ranks"
  timeout 120 $launch_np2 "$demvv" sweep "$work/base.prm" --vary balls/friction=0.2,0.5 --out "$work/mpi" --quiet 2>"$work/err"
  [ $? -eq 2 ] || fail "MPI: another sweep into the directory was not refused with 2 on every rank"
fi
rm -rf "$work"
echo "sweep: ok"
