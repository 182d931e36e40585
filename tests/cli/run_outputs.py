"""Every file a run writes reads back, and demvv draws its figures from them:
each JSON parses (strict JSON: no NaN or Infinity), each CSV has its header
and whole rows of numbers (nan where the run has no value), and
each figure passes figure_lint.py (its key inside the picture, off the data
and the labels), each ParaView file opens in VTK's own XML readers (python3-vtk9) with the
point counts and arrays demvv says it wrote: one point per ball (summary.json,
sample.json), the arrays paraview.h documents with one tuple per point or
line, the ids 0..N-1, the radii of the sample, and as many broken bonds at
each frame as bond_breaks.csv has rows up to that frame's time.  deal.II's
cylinder frames have one cell per mesh cell of their level.

usage: run_outputs.py DEMVV CASES_DIR WORK_DIR
"""
import csv
import fnmatch
import glob
import json
import math
import os
import subprocess
import sys
import xml.etree.ElementTree as ElementTree

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import figure_lint  # noqa: E402  (beside this file)
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkIOXML import (vtkXMLPolyDataReader, vtkXMLPUnstructuredGridReader,
                                 vtkXMLUnstructuredGridReader)

demvv, cases, work = sys.argv[1:4]
problems = []


def fail(what):
    problems.append(what)


def run(name, deck, *sets):
    args = [demvv, "run", deck, "--out", os.path.join(work, name), "--replace", "--quiet", "--threads", "1"]
    for s in sets:
        args += ["--set", s]
    result = subprocess.run(args, stderr=subprocess.PIPE, text=True)
    if result.returncode != 0:
        fail(f"{name}: demvv exited with {result.returncode}: {result.stderr.strip()}")
    check_owned(os.path.join(work, name))
    return os.path.join(work, name)


def check_owned(run_dir):
    """Every entry a run writes is one that --replace knows to remove (the
    marker lists them, as demvv's own table does), so a replaced run leaves
    nothing of its own behind and touches nothing else."""
    try:
        marker = read_json(os.path.join(run_dir, ".demvv"))
    except (OSError, ValueError) as e:
        fail(f"{run_dir}: no readable ownership marker .demvv: {e}")
        return
    if marker.get("made_by") != "demvv" or marker.get("holds") != "run":
        fail(f"{run_dir}/.demvv: not a run's marker: {marker}")
    for entry in os.listdir(run_dir):
        if entry == ".demvv.lock":
            continue
        if not any(fnmatch.fnmatchcase(entry, p) for p in marker.get("outputs", [])):
            fail(f"{run_dir}: the run wrote '{entry}', which --replace would not remove (add it to output_entries)")


def reject_constant(text):
    raise ValueError(f"{text} is not JSON")


def read_json(path):
    with open(path, encoding="utf-8") as f:
        return json.load(f, parse_constant=reject_constant)


def numbers(row, path, line):
    """The values of a row: numbers, nan where the run had none (never inf)."""
    try:
        values = [float(v) for v in row]
    except ValueError:
        fail(f"{path}:{line}: a value is not a number: {row}")
        return []
    if any(math.isinf(v) for v in values):
        fail(f"{path}:{line}: a value is infinite: {row}")
    return values


def check_csv(path):
    """A series or table: comment lines, a header of distinct names, rows of
    as many numbers.  A gnuplot data file (plots/*.csv, mesh.csv)
    has its columns named in its comment and blank lines between blocks,
    each block of one width."""
    gnuplot = os.path.basename(os.path.dirname(path)) == "plots" or os.path.basename(path) == "mesh.csv"
    with open(path, encoding="utf-8", newline="") as f:
        lines = f.read().split("\n")
    if lines and lines[-1] == "":
        lines.pop()
    header, rows, block_width = None, [], None
    for k, text in enumerate(lines, 1):
        if gnuplot and text == "":
            block_width = None  # each block its own width (circles have a radius, points not)
            continue
        if text.startswith("#"):
            continue
        row = next(csv.reader([text]))
        if header is None and not gnuplot:
            header = row
            if len(set(header)) != len(header) or not all(header):
                fail(f"{path}:{k}: the header has empty or repeated names: {header}")
            try:
                [float(v) for v in header]
                fail(f"{path}:{k}: the header is numbers, not names")
            except ValueError:
                pass
            continue
        width = len(header) if header else (block_width or len(row))
        block_width = width
        if len(row) != width:
            fail(f"{path}:{k}: {len(row)} values for {width} columns")
        rows.append(numbers(row, path, k))
    if not gnuplot and header is None:
        fail(f"{path}: no header")
    if not rows and os.path.basename(path) not in ("bond_breaks.csv",):
        fail(f"{path}: no rows")
    return header, rows


def read_vtk(reader_class, path):
    """The dataset VTK's reader makes of `path`; a reader error is a problem."""
    reader = reader_class()
    errors = []
    for event in (vtkCommand.ErrorEvent, vtkCommand.WarningEvent):
        reader.AddObserver(event, lambda obj, ev: errors.append(ev))
    reader.SetFileName(path)
    reader.Update()
    if errors or reader.GetErrorCode() != 0:
        fail(f"{path}: VTK's reader reported {errors or reader.GetErrorCode()}")
    return reader.GetOutput()


def declared(path, element):
    """The counts a VTK XML file declares for its Piece (or the element)."""
    piece = ElementTree.parse(path).getroot().find(f".//{element}")
    return {k: int(v) for k, v in piece.attrib.items() if k.startswith("NumberOf")}


def arrays(data):
    return {data.GetArrayName(k): data.GetArray(k) for k in range(data.GetNumberOfArrays())}


def values(array):
    return [array.GetTuple(k) for k in range(array.GetNumberOfTuples())]


def collection(path):
    """(time, file) of every data set of a .pvd, each file present."""
    out = []
    for d in ElementTree.parse(path).getroot().iter("DataSet"):
        file = os.path.join(os.path.dirname(path), d.get("file"))
        if not os.path.isfile(file):
            fail(f"{path}: names {d.get('file')}, which is not there")
        out.append((float(d.get("timestep")), file))
    times = [t for t, _ in out]
    if not out or times != sorted(times):
        fail(f"{path}: no data sets, or times out of order: {times}")
    return out


def check_dem_paraview(run_dir, balls, radii=None):
    """The three collections of a DEM run against what the run says."""
    pv = os.path.join(run_dir, "paraview")
    frames = {stem: collection(os.path.join(pv, stem + ".pvd")) for stem in ("particles", "contacts", "breaks")}
    counts = {stem: len(glob.glob(os.path.join(pv, stem + "_*.vtp"))) for stem in frames}
    if len({len(f) for f in frames.values()} | set(counts.values())) != 1:
        fail(f"{pv}: frames in the collections {[len(f) for f in frames.values()]}, files {counts}")
    breaks_csv = os.path.join(run_dir, "bond_breaks.csv")
    _, broken = check_csv(breaks_csv) if os.path.exists(breaks_csv) else (None, [])
    for k, (time, file) in enumerate(frames["particles"]):
        p = read_vtk(vtkXMLPolyDataReader, file)
        if p.GetNumberOfPoints() != balls or declared(file, "Piece")["NumberOfPoints"] != balls:
            fail(f"{file}: {p.GetNumberOfPoints()} points, expected one per ball ({balls})")
        a = arrays(p.GetPointData())
        for name, components in (("radius", 1), ("id", 1), ("velocity", 3), ("spin", 3), ("force", 3)):
            if name not in a or a[name].GetNumberOfComponents() != components or \
                    a[name].GetNumberOfTuples() != balls:
                fail(f"{file}: no array {name} of {components} components and {balls} tuples")
        if "id" in a and [v[0] for v in values(a["id"])] != list(range(balls)):
            fail(f"{file}: ids are not 0..{balls - 1}")
        if radii is not None and "radius" in a and \
                any(abs(r[0] - s) > 1e-9 * s for r, s in zip(values(a["radius"]), radii)):
            fail(f"{file}: radii differ from the sample's")

        cfile = frames["contacts"][k][1]
        c = read_vtk(vtkXMLPolyDataReader, cfile)
        lines = c.GetNumberOfLines()
        if c.GetNumberOfPoints() != balls or declared(cfile, "Piece")["NumberOfLines"] != lines:
            fail(f"{cfile}: {c.GetNumberOfPoints()} points (expected {balls}) or line count not as declared")
        a = arrays(c.GetCellData())
        for name in ("normal_force_n", "shear_force_n", "state", "bonded"):
            if name not in a or a[name].GetNumberOfTuples() != lines:
                fail(f"{cfile}: no cell array {name} with one value per contact ({lines})")
        if lines and all(n in a for n in ("normal_force_n", "state")):
            for (fn,), (state,) in zip(values(a["normal_force_n"]), values(a["state"])):
                if state != (1.0 if fn >= 0 else -1.0):
                    fail(f"{cfile}: state {state} for normal force {fn}")
                    break

        bfile = frames["breaks"][k][1]
        b = read_vtk(vtkXMLPolyDataReader, bfile)
        so_far = [row for row in broken if row[0] <= time]
        if b.GetNumberOfPoints() != len(so_far):
            fail(f"{bfile}: {b.GetNumberOfPoints()} broken bonds at t = {time} s, "
                 f"bond_breaks.csv has {len(so_far)} up to then")
        a = arrays(b.GetPointData())
        if "time_s" not in a or "mode" not in a:
            fail(f"{bfile}: no time_s or mode array")
        elif [round(v[0], 9) for v in values(a["time_s"])] != [round(r[0], 9) for r in so_far] or \
                [v[0] for v in values(a["mode"])] != [r[3] for r in so_far]:
            fail(f"{bfile}: times or modes differ from bond_breaks.csv")
    return len(frames["particles"])


def check_cylinder_paraview(level_dir):
    """deal.II draws each cell of degree p as p^dim patches."""
    level = read_json(os.path.join(level_dir, "summary.json"))
    dim = 2 if level["geometry"]["model"] == "axisymmetric" else 3
    cells = level["discretisation"]["cells"] * level["discretisation"]["degree"] ** dim
    frames = collection(os.path.join(level_dir, "paraview", "cylinder.pvd"))
    for _, file in frames:
        grid = read_vtk(vtkXMLPUnstructuredGridReader if file.endswith(".pvtu") else vtkXMLUnstructuredGridReader,
                        file)
        if grid.GetNumberOfCells() != cells:
            fail(f"{file}: {grid.GetNumberOfCells()} cells, the level's mesh gives {cells}")
        a = arrays(grid.GetPointData())
        for name in ("displacement_m", "axial_stress_compression_pa"):
            if name not in a or a[name].GetNumberOfTuples() != grid.GetNumberOfPoints():
                fail(f"{file}: no point array {name} with one tuple per point")
    return len(frames)


def check_files(run_dir):
    """Every file of a run directory read by the rule of its kind."""
    known = (".json", ".csv", ".txt", ".prm", ".svg", ".gp", ".vtp", ".vtu", ".pvtu", ".pvd")
    for root, _, files in os.walk(run_dir):
        for name in files:
            path = os.path.join(root, name)
            ext = os.path.splitext(name)[1]
            if name == ".demvv":
                read_json(path)  # the ownership marker (check_owned reads what it says)
                continue
            if name == ".demvv.lock":
                continue  # the lock file: a pid, or nothing
            if ext not in known:
                fail(f"{path}: a file this test does not know how to check")
            elif ext == ".json":
                try:
                    read_json(path)
                except ValueError as e:
                    fail(f"{path}: not JSON: {e}")
            elif ext == ".csv":
                check_csv(path)
            elif ext == ".txt" and not open(path, encoding="utf-8").read().strip():
                fail(f"{path}: empty")
            elif ext == ".vtu":
                read_vtk(vtkXMLUnstructuredGridReader, path)
            elif ext == ".vtp":
                read_vtk(vtkXMLPolyDataReader, path)
            elif ext == ".svg":
                for finding in figure_lint.findings(path, open(path, encoding="utf-8").read(), ""):
                    fail(finding)


os.makedirs(work, exist_ok=True)
uniaxial_deck = os.path.join(work, "uniaxial.prm")
with open(uniaxial_deck, "w") as f:
    f.write("set kind = uniaxial\n"
            "subsection sample\n  set diameter = 0.008\n  set height = 0.008\nend\n"
            "subsection bonds\n  set normal strength = 5\n  set shear strength = 5\n  set strength cov = 0.25\nend\n"
            "subsection loading\n  set final strain = 0.006\nend\n"
            "subsection measurement\n  set gauge study = 0.2, 0.5\nend\n"
            "subsection output\n  set strain interval = 0.0005\n  set paraview = true\n"
            "  set paraview strain interval = 0.002\nend\n")
prepare_deck = os.path.join(work, "small.prm")
with open(prepare_deck, "w") as f:
    f.write("set kind = prepare\nsubsection sample\n  set particles = 200\n  set seed = 5\nend\n")

runs = {
    "uniaxial": run("uniaxial", uniaxial_deck),
    "tension": run("tension", os.path.join(cases, "v02_bond_tension", "case.prm"), "output/paraview=true",
                   "output/paraview interval=2e-5"),
    "box": run("box", os.path.join(cases, "s01_box_six_planes", "case.prm"), "run/duration=0.02",
               "output/track particles=0,7", "output/track pairs=0-1"),
    "prepare": run("prepare", prepare_deck),
    "ode": run("ode", os.path.join(cases, "c01_burgers_ode_constant_velocity", "case.prm")),
    "cylinder": run("cylinder", os.path.join(cases, "c04_cylinder_bonded_gci", "case.prm"), "output/paraview=true",
                    "study/gci refinements=1,2,3", "discretisation/time steps=4", "output/paraview every=2"),
    "mms": run("mms", os.path.join(cases, "c05_mms_space", "case.prm"), "study/levels=1,2,3"),
}
if problems:
    print("FAIL: " + "\nFAIL: ".join(problems))
    sys.exit(1)
for run_dir in runs.values():
    check_files(run_dir)

summary = read_json(os.path.join(runs["uniaxial"], "summary.json"))
frames = check_dem_paraview(runs["uniaxial"], summary["sample"]["particles"])
if frames < 3 or len(check_csv(os.path.join(runs["uniaxial"], "bond_breaks.csv"))[1]) == 0:
    fail(f"the uniaxial run wrote {frames} frames and no broken bond: the test needs both")
summary = read_json(os.path.join(runs["tension"], "summary.json"))
check_dem_paraview(runs["tension"], summary["particles"])
sample = read_json(os.path.join(runs["prepare"], "sample.json"))
columns = sample["balls"]["columns"]
radii = [row[columns.index("radius_m")] for row in sample["balls"]["rows"]]
check_dem_paraview(runs["prepare"], len(radii), radii)
study = read_json(os.path.join(runs["cylinder"], "summary.json"))
for level in study["levels"]:
    check_cylinder_paraview(os.path.join(runs["cylinder"], f"level_{level['refinements']}"))

if problems:
    print("FAIL: " + "\nFAIL: ".join(problems))
    sys.exit(1)
print(f"run outputs: every file of {len(runs)} run directories reads back")
