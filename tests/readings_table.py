#!/usr/bin/env python3
"""ctest `readings_table`: cases/readings/readings.csv, the verdicts of the
thesis figures whose parameters the thesis does not give, under each reading.

- the header is the agreed one; every row names a figure of
  cases/thesis_figures.csv whose conditions the thesis does not give
  (at_thesis_conditions "cannot"), the case that figure's row names, a
  reading, what was measured, a verdict that begins with agrees, differs or
  not comparable, and the build and date of the measurement (YYYY-MM-DD);
- each of the figures the study covers has at least two readings, so a
  reader sees whether its verdict holds whatever the reading;
- cases/readings/run.sh runs every case the table names, and summarise.py
  (which wrote the table) names every figure the table holds.
Usage: readings_table.py SOURCE_DIR
"""
import csv
import os
import re
import sys

src = sys.argv[1]
bad = []
figures = {r["figure"]: r for r in csv.DictReader(open(os.path.join(src, "cases", "thesis_figures.csv")))}
path = os.path.join(src, "cases", "readings", "readings.csv")
with open(path, newline="") as f:
    reader = csv.reader(f)
    header = next(reader)
    rows = [dict(zip(header, r)) for r in reader]
if header != ["figure", "case", "reading", "measured", "verdict", "build", "date"]:
    bad.append(f"the header is {header}")
readings = {}
for k, r in enumerate(rows, 2):
    where = f"line {k} (figure {r.get('figure')})"
    if len(r) != 7 or not all(r.values()):
        bad.append(f"{where}: an empty field or not 7 fields: {r}")
        continue
    thesis = figures.get(r["figure"])
    if thesis is None:
        bad.append(f"{where}: no such figure in cases/thesis_figures.csv")
        continue
    if thesis["at_thesis_conditions"] != "cannot":
        bad.append(f"{where}: the thesis gives this figure's conditions (at_thesis_conditions {thesis['at_thesis_conditions']})")
    if r["case"] != thesis["case"] or not os.path.exists(os.path.join(src, "cases", r["case"], "case.prm")):
        bad.append(f"{where}: case {r['case']} is not the figure's case ({thesis['case']}) or has no deck")
    if not re.match(r"^(agrees|differs|not comparable)\b", r["verdict"]):
        bad.append(f"{where}: verdict '{r['verdict']}' begins with none of agrees, differs, not comparable")
    if not re.match(r"^\d{4}-\d{2}-\d{2}$", r["date"]):
        bad.append(f"{where}: date '{r['date']}' is not YYYY-MM-DD")
    readings.setdefault(r["figure"], set()).add(r["reading"])
for figure, seen in readings.items():
    if len(seen) < 2:
        bad.append(f"figure {figure}: one reading only ({seen}): expected at least two")
script = open(os.path.join(src, "cases", "readings", "run.sh")).read()
summarise = open(os.path.join(src, "cases", "readings", "summarise.py")).read()
for case in {r["case"] for r in rows}:
    if f"cases/{case}/case.prm" not in script:
        bad.append(f"run.sh does not run cases/{case}/case.prm")
for figure in readings:
    if f'"{figure}"' not in summarise:
        bad.append(f"summarise.py does not write figure {figure}")
if bad:
    print("readings table broken:\n" + "\n".join(bad))
    sys.exit(1)
print(f"readings table: {len(rows)} rows, {len(readings)} figures")
