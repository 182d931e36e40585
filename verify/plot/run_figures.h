// The figures of a run directory, chosen by the kind its summary.json names.
//
//   uniaxial   stress-strain (with each platen's stress), stress and bonds
//              broken against strain (the pair of thesis Fig. 6.1), radial
//              strain, bonds broken by mode, energy ledger, time step,
//              quasi-static indicators
//   scene      energy ledger, time step, contacts and bonds, wall forces
//   burgers_ode force and displacement with their closed form, internal
//              displacements
//   cylinder   stress against strain and time with the closed form, radial
//              strain, the mesh; a GCI study: every level's curve and the
//              GCI figure of each quantity
//   mms        errors against the refined size on log-log axes, with the
//              theoretical orders
//   prepare    mean stress against the reduction of the radii (thesis Fig.
//              5.5); ParaView frames in paraview/ show the sample
//
// Figures read the run's own CSV files (scripts in RUN_DIR/plots refer to
// ../series.csv), so a figure of an older run is drawn from its data as it
// is; a column the run did not write is left out of its figure.
#pragma once

#include "verify/plot/figure.h"
#include "verify/plot/gnuplot.h"

#include <string>
#include <vector>

namespace verify
{
/// The figures of a run directory; DeckError when it is not one.
std::vector<Figure> run_figures(const std::string &run_dir);

/// Draws them into RUN_DIR/plots.
std::vector<DrawnFigure> plot_run(const std::string &run_dir);
} // namespace verify
