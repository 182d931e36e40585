#!/usr/bin/env python3
"""Identical work for demvv and LIGGGHTS: the files of one scene, and one table.

  identical_work.py write SAMPLE_JSON DIR STEPS
      From a demvv sample file (the prepared 6000-ball cylinder), writes into
      DIR the same compression for both engines:
        balls.csv      the balls (x_m,y_m,z_m,radius_m) in a shuffled order
                       (seed 1), as a user's file in generation order would
                       be: no engine gets a head start from the file's order;
        scene.prm      the demvv scene deck;
        packing.data, top.stl, liggghts.in   the LIGGGHTS input, with the
                       neighbour skin of the peers' scripts (0.2 mm);
        liggghts_narrow.in   the same with a skin as narrow as demvv's
                       adaptive one at rest (1 % of the largest radius): on
                       this slow compression LIGGGHTS is faster with it, and
                       demvv is measured against the faster of the two.
      The scene: unbonded balls (kn 1.2e7, ks 1.2e6 N/m per ball, pair 6e6 /
      6e5 N/m in series; friction 0.5; density 2650 kg/m^3) in the sample's
      cylinder (frictionless, kn 1.2e7 N/m per wall, pair 6e6 N/m) on a fixed
      bottom plane, pressed by a frictionless top plane at 0.01 m/s; no
      damping of any kind, no gravity, a fixed step of 5e-7 s, STEPS steps.
  identical_work.py demvv RUN_DIR LABEL
  identical_work.py liggghts LOG LABEL
      Prints one result line: label, particle-steps/s, threads or ranks, and
      the physics at the end (ball-ball contacts, top-plane stress [Pa]).
  identical_work.py build RUN_DIR
      Prints the build that made a demvv run directory (git SHA, engine flags).
  identical_work.py table RESULTS
      Prints the table of a results file (lines the two commands above wrote)
      and each round's demvv / LIGGGHTS ratios (against each skin, and
      against the faster LIGGGHTS run of the round); then, over the rounds of
      each load, the median of each ratio (demvv against the faster LIGGGHTS,
      demvv's 2 threads and default against its 1 thread) with a
      distribution-free interval for it (order statistics; its coverage is
      printed: 94 % with five rounds, 96 % with nine); and checks that every
      run did the same work: contacts and top stress within 0.5 % of the
      first run's.  Lines "LOAD round_trip ROUND ns=T" (identical_work.sh
      writes them from demvv_core_round_trip) add each round's time for a
      cache line between two cores and back, and its median per load: two
      threads' speed follows it.
SI units; stress positive in compression.
"""
import json
import math
import random
import re
import statistics
import sys

KN_BALL, KS_BALL, KN_WALL = 1.2e7, 1.2e6, 1.2e7
FRICTION, DENSITY, SPEED, DT = 0.5, 2650.0, 0.01, 5e-7


def write(sample_path, out, steps):
    doc = json.load(open(sample_path))
    cols = doc["balls"]["columns"]
    ix, iy, iz, ir = (cols.index(c) for c in ("x_m", "y_m", "z_m", "radius_m"))
    balls = [(r[ix], r[iy], r[iz], r[ir]) for r in doc["balls"]["rows"]]
    random.Random(1).shuffle(balls)
    # The cell's walls where the preparation left them (the servo moved them).
    walls, cell = doc["walls"], doc["cell"]
    bottom, top = walls[cell["bottom"]]["point_m"][2], walls[cell["top"]]["point_m"][2]
    radius = walls[cell["lateral"]]["radius_m"]
    balls = [(x, y, z - bottom, r) for x, y, z, r in balls]
    height = top - bottom
    duration = steps * DT
    with open(out + "/balls.csv", "w") as f:
        f.write("x_m,y_m,z_m,radius_m\n")
        for b in balls:
            f.write("%.17g,%.17g,%.17g,%.17g\n" % b)
    with open(out + "/scene.prm", "w") as f:
        f.write(f"""# Identical work (bench/identical_work.py): {len(balls)} unbonded balls in a
# frictionless cylinder pressed by the top plane at {SPEED} m/s, {steps} steps of {DT} s.
set kind = scene
set title = Identical-work benchmark
subsection particles
  set file = balls.csv
end
subsection balls
  set density = {DENSITY}
  set normal stiffness = {KN_BALL}
  set shear stiffness = {KS_BALL}
  set friction = {FRICTION}
end
subsection walls
  set resting overlap = 0.1
  subsection plane bottom
    set point = 0, 0, 0
    set normal = 0, 0, 1
    set normal stiffness = {KN_WALL}
  end
  subsection plane top
    set point = 0, 0, {height!r}
    set normal = 0, 0, -1
    set velocity = 0, 0, -{SPEED}
    set normal stiffness = {KN_WALL}
  end
  subsection cylinder lateral
    set radius = {radius!r}
    set normal stiffness = {KN_WALL}
  end
end
subsection motion
  set local damping = 0
  set fixed time step = {DT}
  set unstable fixed step = run
end
subsection run
  set duration = {duration!r}
end
subsection output
  set interval = {duration / 10!r}
end
""")
    pad = 2e-3
    with open(out + "/packing.data", "w") as f:
        f.write("LIGGGHTS data file: bench/identical_work.py\n\n%d atoms\n2 atom types\n\n" % len(balls))
        f.write("%.17g %.17g xlo xhi\n%.17g %.17g ylo yhi\n%.17g %.17g zlo zhi\n\nAtoms\n\n" %
                (-radius - pad, radius + pad, -radius - pad, radius + pad, -pad, height + pad))
        for k, (x, y, z, r) in enumerate(balls):
            f.write("%d 1 %.17g %g %.17g %.17g %.17g\n" % (k + 1, 2 * r, DENSITY, x, y, z))
    a = radius + pad / 2
    with open(out + "/top.stl", "w") as f:
        f.write("solid top\n")
        for tri in (((-a, -a), (a, -a), (a, a)), ((-a, -a), (a, a), (-a, a))):
            f.write(" facet normal 0 0 1\n  outer loop\n")
            for x, y in tri:
                f.write("   vertex %.17g %.17g %.17g\n" % (x, y, height))
            f.write("  endloop\n endfacet\n")
        f.write("endsolid top\n")
    pair_kn, pair_ks = KN_BALL * KN_WALL / (KN_BALL + KN_WALL), KS_BALL / 2
    for name, skin in (("liggghts.in", 2e-4), ("liggghts_narrow.in", 0.01 * max(b[3] for b in balls))):
        liggghts_input(out + "/" + name, skin, steps, radius, pair_kn, pair_ks)
    print("wrote %s: %d balls, cylinder D = %.6g m, H = %.6g m, %d steps of %g s" %
          (out, len(balls), 2 * radius, height, steps, DT))


def liggghts_input(path, skin, steps, radius, pair_kn, pair_ks):
    with open(path, "w") as f:
        f.write(f"""# Identical work (bench/identical_work.py) in LIGGGHTS 3.8: hooke/stiffness
# contacts kn {pair_kn:g} / kt {pair_ks:g} N/m (the per-ball stiffnesses in series), no damping
# (gamman = gammat = 0), friction {FRICTION} between balls, 0 at walls; {steps} steps of {DT} s;
# neighbour skin {skin!r} m.
atom_style granular
atom_modify map array
boundary f f f
newton off
communicate single vel yes
units si
read_data packing.data
neighbor {skin!r} bin
neigh_modify delay 0
fix m1 all property/global youngsModulus peratomtype 6.78e9 6.78e9
fix m2 all property/global poissonsRatio peratomtype 0.25 0.25
fix m3 all property/global coefficientRestitution peratomtypepair 2 1 1 1 1
fix m4 all property/global coefficientFriction peratomtypepair 2 {FRICTION} 0 0 0
fix m5 all property/global kn peratomtypepair 2 {pair_kn} {pair_kn} {pair_kn} {pair_kn}
fix m6 all property/global kt peratomtypepair 2 {pair_ks} {pair_ks} {pair_ks} {pair_ks}
fix m7 all property/global gamman peratomtypepair 2 0 0 0 0
fix m8 all property/global gammat peratomtypepair 2 0 0 0 0
pair_style gran model hooke/stiffness tangential history
pair_coeff * *
timestep {DT}
fix bottom all wall/gran model hooke/stiffness tangential history primitive type 2 zplane 0.0
fix side all wall/gran model hooke/stiffness tangential history primitive type 2 zcylinder {radius!r} 0 0
fix top all mesh/surface/stress file top.stl type 2
fix topw all wall/gran model hooke/stiffness tangential history mesh n_meshes 1 meshes top
fix mv all move/mesh mesh top linear 0. 0. -{SPEED}
fix integr all nve/sphere
compute cc all contact/atom
compute ncont all reduce sum c_cc
variable contacts equal c_ncont/2
variable stress equal abs(f_top[3])/({math.pi!r}*{radius!r}^2)
thermo_style custom step atoms v_contacts v_stress
thermo_modify norm no lost error
thermo {steps}
run {steps}
print "RESULT contacts=${{contacts}} stress_pa=${{stress}}"
""")


def demvv_line(run_dir, label):
    s = json.load(open(run_dir + "/summary.json"))
    rows = [l for l in open(run_dir + "/series.csv") if l[0] not in "#" and l.strip()]
    head = rows[0].strip().split(",")
    last = [float(v) for v in rows[-1].split(",")]
    governor = s["status"]["threads"]
    sim = "%d%s" % (governor["at_end"], "" if not governor["changes"] else "(%d_changes)" % governor["changes"])
    top = last[head.index("top_force_z_n")]
    radius = float(re.search(r"set radius *= *([0-9.e+-]+)", open(run_dir + "/deck.prm").read()).group(1))
    print("%s rate=%.4g threads=%s contacts=%d stress_pa=%.6g" %
          (label, s["particle_steps_per_second"], sim, int(last[head.index("contacts")]),
           abs(top) / (math.pi * radius * radius)))


def build_line(run_dir):
    p = json.load(open(run_dir + "/summary.json"))["provenance"]
    print("demvv %s (%s)" % (p["git_sha"], p["dem_flags"]))


def liggghts_line(log, label):
    text = open(log).read()
    loop = re.findall(r"Loop time of ([0-9.e+-]+) on (\d+) procs for (\d+) steps with (\d+) atoms", text)
    res = re.findall(r"RESULT contacts=([0-9.e+-]+) stress_pa=([0-9.e+-]+)", text)
    if not loop or not res:
        print("%s FAILED (see %s)" % (label, log))
        return
    t, procs, steps, atoms = loop[-1]
    print("%s rate=%.4g threads=%s contacts=%d stress_pa=%.6g" %
          (label, int(atoms) * int(steps) / float(t), procs, round(float(res[-1][0])), float(res[-1][1])))


def median_interval(values):
    """The median of `values` and a distribution-free interval for the
    median of the population they were drawn from: the order statistics
    x_(k), x_(n+1-k) with the largest k whose coverage, 1 - 2 P(B <= k-1)
    for B ~ Binomial(n, 1/2), is still at least 95 % (k = 1, the whole
    range, when no k reaches it; the coverage is then below 95 % and is
    returned with the interval: 75 % for three rounds, 94 % for five)."""
    x = sorted(values)
    n = len(x)
    def coverage(k):
        return 1 - 2 * sum(math.comb(n, i) for i in range(k)) / 2 ** n
    k = 1
    while k + 1 <= (n + 1) // 2 and coverage(k + 1) >= 0.95:
        k += 1
    mid = (x[(n - 1) // 2] + x[n // 2]) / 2
    return mid, x[k - 1], x[n - k], coverage(k)


PEERS = ("liggghts", "liggghts_narrow")


def peer_ranks(asked):
    """The LIGGGHTS ranks a demvv thread count is set against: its own
    count; demvv's default against 2 ranks."""
    return "2" if asked == "default" else asked


def faster_peer(rate, load, asked, rnd):
    """The faster of the LIGGGHTS runs (both skins) that demvv's `asked`
    threads are set against in round `rnd`; None when neither ran."""
    return max((p for p in (rate.get((load, e, peer_ranks(asked), rnd)) for e in PEERS) if p), default=None)


def summary(rate):
    """Over the rounds of each load: demvv against the faster LIGGGHTS run
    of the same round (1 thread against 1 rank, 2 threads and the default
    against 2 ranks) and demvv's 2 threads and default against its own
    1 thread in the same round, each as the median ratio and its interval."""
    loads = sorted({k[0] for k in rate}, key=["idle", "half", "full"].index)
    rounds = sorted({k[3] for k in rate}, key=int)
    against = [("demvv %s / LIGGGHTS %s (the faster)" % (a, peer_ranks(a)), a,
                lambda l, r, a=a: faster_peer(rate, l, a, r)) for a in ("1", "2", "default")]
    against += [("demvv %s / demvv 1" % a, a, lambda l, r: rate.get((l, "demvv", "1", r))) for a in ("2", "default")]
    print("| load | ratio | rounds | median | interval of the median | its coverage |")
    print("|---|---|---|---|---|---|")
    for load in loads:
        for name, asked, reference in against:
            ratios = [d / ref for d, ref in ((rate.get((load, "demvv", asked, r)), reference(load, r)) for r in rounds)
                      if d and ref]
            if ratios:
                mid, lo, hi, cover = median_interval(ratios)
                print("| %s | %s | %d | %.2f | %.2f-%.2f | %.0f %% |" % (load, name, len(ratios), mid, lo, hi,
                                                                         100 * cover))


def table(path):
    runs, trips = [], {}
    for line in open(path):
        m = re.match(r"(\S+) (\S+) (\S+) (\d+) rate=(\S+) threads=(\S+) contacts=(\d+) stress_pa=(\S+)", line)
        if m:
            runs.append(m.groups())
        m = re.match(r"(\S+) round_trip (\d+) ns=(\S+)", line)
        if m:
            trips[(m.group(1), m.group(2))] = float(m.group(3))
    if not runs:
        sys.exit("no results in " + path)
    print("| load | round | engine | threads asked | threads used | particle-steps/s | contacts | top stress [Pa] |")
    print("|---|---|---|---|---|---|---|---|")
    for load, engine, asked, rnd, rate, used, contacts, stress in runs:
        print("| %s | %s | %s | %s | %s | %.3e | %s | %.5g |" % (load, rnd, engine, asked, used, float(rate),
                                                                 contacts, float(stress)))
    rate = {(r[0], r[1], r[2], r[3]): float(r[4]) for r in runs}
    print()
    for load, _, asked, rnd in sorted({(r[0], "", r[2], r[3]) for r in runs}):
        if asked == "1" and (load, rnd) in trips:
            print("%s, round %s: core round trip %.0f ns" % (load, rnd, trips[(load, rnd)]))
        d = rate.get((load, "demvv", asked, rnd))
        ranks = peer_ranks(asked)
        peers = {e: rate.get((load, e, ranks, rnd)) for e in PEERS}
        ratios = ["against %s %.2f" % (e, d / l) for e, l in peers.items() if d and l]
        if ratios:
            print("%s, demvv %s thread(s) against LIGGGHTS %s rank(s), round %s: demvv / LIGGGHTS %s; "
                  "against the faster %.2f" % (load, asked, ranks, rnd, ", ".join(ratios),
                                               d / faster_peer(rate, load, asked, rnd)))
    print()
    summary(rate)
    for load in sorted({k[0] for k in trips}, key=["idle", "half", "full"].index):
        ns = sorted(v for k, v in trips.items() if k[0] == load)
        print("%s: core round trip %.0f ns in median over %d rounds (%.0f-%.0f ns)" %
              (load, statistics.median(ns), len(ns), ns[0], ns[-1]))
    c0, s0 = float(runs[0][6]), float(runs[0][7])
    worst = max(max(abs(float(r[6]) / c0 - 1), abs(float(r[7]) / s0 - 1)) for r in runs)
    print("\nsame work: contacts and top stress within %.3f %% of the first run's (limit 0.5 %%): %s" %
          (100 * worst, "yes" if worst <= 0.005 else "NO"))


if __name__ == "__main__":
    cmd = sys.argv[1] if len(sys.argv) > 1 else ""
    if cmd == "write" and len(sys.argv) == 5:
        write(sys.argv[2], sys.argv[3], int(sys.argv[4]))
    elif cmd == "demvv" and len(sys.argv) == 4:
        demvv_line(sys.argv[2], sys.argv[3])
    elif cmd == "build" and len(sys.argv) == 3:
        build_line(sys.argv[2])
    elif cmd == "liggghts" and len(sys.argv) == 4:
        liggghts_line(sys.argv[2], sys.argv[3])
    elif cmd == "table" and len(sys.argv) == 3:
        table(sys.argv[2])
    else:
        sys.exit(__doc__)
