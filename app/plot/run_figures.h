// The figures of a run directory: its summary.json names its kind, whose
// row in the table of kinds (DeckKind::figures) draws them:
//
//   uniaxial   stress-strain (with each platen's stress), stress and bonds
//              broken against strain (the pair of thesis Fig. 6.1), radial
//              strain, bonds broken by mode, energy ledger, time step,
//              quasi-static indicators, the sample's section at the end
//              with the bonds broken near it
//   scene      energy ledger, time step, contacts and bonds, wall forces
//   burgers_ode force and displacement with their closed form, internal
//              displacements
//   cylinder   stress against strain and time with the closed form, radial
//              strain, the mesh; a GCI study: every level's curve and the
//              GCI figure of each quantity
//   mms        errors against the refined size on log-log axes, with the
//              theoretical orders
//   prepare    mean stress against the reduction of the radii (thesis Fig.
//              5.5); the packing's section after the first, second and last
//              stage (Figs. 5.2-5.3); ParaView frames in paraview/ show the
//              sample in 3-D
//
// Figures read the run's own CSV files (scripts in RUN_DIR/plots refer to
// ../series.csv), so a figure of an older run is drawn from its data as it
// is; a column the run did not write is left out of its figure.
#pragma once

#include "app/decks/deck.h"
#include "app/plot/figure.h"
#include "app/plot/gnuplot.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace demvv
{
/// The figures of a run directory, drawn by its kind's row of `kinds`
/// (none for a kind the table does not know); DeckError when it is not a
/// run directory.
std::vector<Figure> run_figures(const std::string &run_dir, const DeckKinds &kinds);

/// Draws them into RUN_DIR/plots.
std::vector<DrawnFigure> plot_run(const std::string &run_dir, const DeckKinds &kinds);

/// Each kind's figures (DeckKind::figures): read from the run directory's
/// files and its summary.json.
void uniaxial_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void scene_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void burgers_ode_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void cylinder_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void mms_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void prepare_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
void compare_run_figures(const std::string &dir, const nlohmann::json &summary, std::vector<Figure> &out);
} // namespace demvv
