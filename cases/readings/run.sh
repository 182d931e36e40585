#!/bin/sh
# The readings study: the sweeps behind readings.csv, then the table.
# Each sweep resumes where it stopped; on two cores about 90 minutes in all
# (cases/readings/README.md).  Run from the repository's root:
#   cases/readings/run.sh [OUT_DIR]        (default runs/readings)
# DEMVV names the executable (default build/demvv); LAUNCH prefixes every
# sweep (e.g. LAUNCH="mpirun -np 2", with --threads 1 per member).
set -eu
demvv=${DEMVV:-build/demvv}
out=${1:-runs/readings}
launch=${LAUNCH:-}
sweep() { $launch "$demvv" sweep "$@" --quiet; }
strength="bonds/normal strength+bonds/shear strength"

# Figs. 7.5-7.7: the preliminary model's bond strength, 2 N (t73b's) to 31.3 N (chapter 6's).
sweep cases/t72_preliminary_modified_burgers/case.prm --out "$out/t72_strength" --vary "$strength=2,5,10,20,31.3"
# Fig. 7.12: viscosity scaling with breakage at three bond strengths, each against its slow reference.
sweep cases/t73b_viscosity_scaling_breakage/case.prm --out "$out/t73b_scaled" --vary "$strength=2,5,10"
sweep cases/t73b_viscosity_scaling_breakage/case.prm --out "$out/t73b_reference" --vary "$strength=2,5,10" \
  --vary "loading/strain rate=0.01" --vary "loading/ramp time=0.1" --vary "rate/physical strain rate=0"
# Figs. 7.13-7.15: frictional contacts with chapter 6's bond strength and twice it.
sweep cases/t713_frictional_contacts/case.prm --out "$out/t713_strength" --vary "$strength=31.3,62.6" \
  --vary balls/friction=0.1,0.5,0.9 --vary "bonds/removed fraction=0,0.1,0.2,0.3"
# Figs. A.2, A.4-A.6: the displacement criterion at three frictions, every stiffness ratio and rate, to 4 %.
for ks in 6e6 2e6 0.6e6; do
  sweep cases/tA2_displacement_criterion_bulk/case.prm --out "$out/tA_ks$ks" --vary "balls/friction=0.3,0.5,0.7" \
    --vary "rate/physical strain rate=0.02,0.1,0.5" --vary "loading/final strain=0.04" \
    --vary "contact law/shear maxwell stiffness+contact law/shear kelvin stiffness=$ks"
done
python3 "$(dirname "$0")/summarise.py" "$out" "$out/readings.csv"
echo "readings: table in $out/readings.csv"
