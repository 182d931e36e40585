// Figures: gnuplot scripts that read the run's own columns, SVG pictures
// drawn by gnuplot, the figures a run directory gets, and a GCI figure whose
// Richardson curve passes through the levels it was computed from.
#include "app/decks/deck.h"
#include "app/io/output.h"
#include "app/io/section.h"
#include "app/kinds/continuum_gci.h"
#include "app/kinds/deck_kinds.h"
#include "app/kinds/uniaxial.h"
#include "app/plot/gnuplot.h"
#include "app/plot/run_figures.h"
#include "app/plot/studies.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <set>
#include <sstream>
#include <vector>

namespace
{
namespace fs = std::filesystem;

bool contains(const std::string &text, const std::string &part) { return text.find(part) != std::string::npos; }
} // namespace

TEST_CASE("a figure script reads named columns with their display scale and a right axis", "[plot]")
{
  demvv::Figure f;
  f.name = "damage";
  f.title = "Stress and bonds broken";
  f.x_label = "axial strain [%]";
  f.y_label = "axial stress [MPa]";
  f.y2_label = "bonds broken [%]";
  f.curves.push_back(demvv::column_curve("stress", "../series.csv", "axial_strain", "axial_stress_pa", 100, 1e-6));
  f.curves.push_back(demvv::column_curve("it's broken", "../series.csv", "axial_strain", "bonds_broken_fraction", 100,
                                         100, demvv::CurveStyle::dashed));
  f.curves.back().right_axis = true;
  const std::string s = demvv::gnuplot_script(f);
  CHECK(contains(s, "set output 'damage.svg'"));
  CHECK(contains(
    s, "'../series.csv' using (column('axial_strain')*100):(column('axial_stress_pa')*9.9999999999999995e-07)"));
  CHECK(contains(s, "axes x1y2"));
  CHECK(contains(s, "set y2label 'bonds broken [%]'"));
  CHECK(contains(s, "title 'it''s broken'")); // a quote inside a title is doubled
}

TEST_CASE("a key goes below the frame in as many columns as fit, the picture growing by its rows", "[plot]")
{
  // gnuplot's entry is 8.4 px a character and 60 px more; 640 px are free.
  const auto figure = [](std::size_t entries, std::size_t title_length)
  {
    demvv::Figure f;
    f.name = "keys";
    for (std::size_t k = 0; k < entries; ++k)
      f.curves.push_back(demvv::curve(std::string(title_length, 'a' + char(k)), {0, 1}, {0, 1}));
    return f;
  };
  const std::string two_short = demvv::gnuplot_script(figure(2, 10)); // 144 px each: both in one row
  CHECK(contains(two_short, "set key below box opaque maxcols 2\nset bmargin 5"));
  CHECK(contains(two_short, "svg size 760,456 "));
  const std::string six_long = demvv::gnuplot_script(figure(6, 60)); // 564 px: one column, six rows
  CHECK(contains(six_long, "maxcols 1\nset bmargin 10"));
  CHECK(contains(six_long, "svg size 760,546 "));
  demvv::Figure none = figure(2, 10);
  none.key = demvv::KeyPlace::none;
  CHECK(contains(demvv::gnuplot_script(none), "set key off"));
  CHECK(contains(demvv::gnuplot_script(none), "svg size 760,460 "));
  demvv::Figure nameless = figure(3, 0); // untitled curves make no key rows
  CHECK(contains(demvv::gnuplot_script(nameless), "svg size 760,460 "));
}

TEST_CASE("gnuplot draws a figure held in memory as SVG and reports a figure without data, not failing", "[plot]")
{
  REQUIRE(demvv::gnuplot_available()); // README and CI install gnuplot-nox
  const fs::path dir = demvv_tests::test_folder("test_plot");
  fs::remove_all(dir);
  demvv::Figure f;
  f.name = "parabola";
  f.title = "A parabola and its tangent";
  f.x_label = "x [m]";
  f.y_label = "y [m]";
  f.curves.push_back(demvv::curve("y = x^2", {0, 1, 2, 3}, {0, 1, 4, 9}));
  demvv::Figure empty;
  empty.name = "empty";
  empty.curves.push_back(demvv::curve("nothing", {}, {}));
  const auto drawn = demvv::draw_figures({f, empty}, dir.string());
  REQUIRE(drawn.size() == 2);
  REQUIRE(drawn[0].drawn());
  const std::string svg = demvv::read_file(drawn[0].svg);
  CHECK(contains(svg, "<svg"));
  CHECK(contains(svg, "A parabola and its tangent"));
  CHECK(fs::exists(dir / "parabola.gp"));
  CHECK(fs::exists(dir / "parabola.csv"));
  CHECK_FALSE(drawn[1].drawn());
  CHECK(contains(drawn[1].problem, "no data"));
}

TEST_CASE("a section cuts the balls the plane y = 0 meets, each in the circle of radius sqrt(R^2 - y^2)", "[plot]")
{
  dem::ParticleStore balls;
  const double r = 1e-3;
  for (const double y : {0.0, 0.6e-3, -0.8e-3, 1e-3, 1.5e-3})
  {
    dem::BallSpec b;
    b.position = dem::Vec3(2e-3, y, 5e-3);
    b.radius = r;
    balls.add(b);
  }
  const auto cut = demvv::vertical_section(balls);
  // |y| < R cuts (a ball that only touches the plane leaves no circle).
  REQUIRE(cut.size() == 3);
  CHECK(cut[0].radius == Approx(1e-3));
  CHECK(cut[1].radius == Approx(0.8e-3)); // a 3-4-5 triangle
  CHECK(cut[2].radius == Approx(0.6e-3));
  for (const auto &c : cut)
  {
    CHECK(c.x == 2e-3);
    CHECK(c.z == 5e-3);
  }
}

TEST_CASE("circles are drawn about their points with their radii, scaled as x is", "[plot]")
{
  REQUIRE(demvv::gnuplot_available());
  const fs::path dir = demvv_tests::test_folder("test_plot_circles");
  fs::remove_all(dir);
  demvv::Figure f = demvv::make_figure("discs", "Two discs", "x [mm]", "z [mm]", {});
  f.curves.push_back(demvv::curve("balls", {1e-3, 3e-3}, {1e-3, 1e-3}, demvv::CurveStyle::circles));
  f.curves.back().radius = {1e-3, 0.5e-3};
  f.curves.back().x_scale = f.curves.back().y_scale = 1e3;
  const auto drawn = demvv::draw_figures({f}, dir.string());
  REQUIRE(drawn.at(0).drawn());
  const std::string script = demvv::read_file((dir / "discs.gp").string());
  CHECK(contains(script, "using ($1*1000):($2*1000):($3*1000) with circles"));
  // The second disc's row: x, z and its radius, each read back bit for bit.
  std::istringstream data(demvv::read_file((dir / "discs.csv").string()));
  std::string row, last;
  while (std::getline(data, row))
    last = row.empty() ? last : row;
  std::istringstream fields(last);
  std::vector<double> values;
  for (std::string field; std::getline(fields, field, ',');)
    values.push_back(std::stod(field));
  CHECK(values == std::vector<double>{3e-3, 1e-3, 0.5e-3});
}

TEST_CASE("a thinned curve keeps at most its share of points, the first and the last, in order", "[plot]")
{
  for (const std::size_t n : {1u, 2u, 999u, 1000u, 1001u, 1002u, 100000u, 123457u})
  {
    std::vector<double> x, y, e;
    for (std::size_t k = 0; k < n; ++k)
    {
      x.push_back(double(k));
      y.push_back(2.0 * double(k));
      e.push_back(0.5);
    }
    demvv::Curve c = demvv::curve("c", x, y);
    c.y_error = e;
    const demvv::Curve t = demvv::thinned(c, 1000);
    INFO("n = " << n);
    if (n <= 1000)
      CHECK(t.x.size() == n); // nothing to thin
    else
    {
      CHECK(t.x.size() <= 1000);
      CHECK(t.x.size() > 500); // every k-th with k = ceil((n - 1) / 999): at least half the share
    }
    REQUIRE(t.y.size() == t.x.size());
    CHECK(t.y_error.size() == t.x.size());
    CHECK(t.x.front() == 0);
    CHECK(t.x.back() == double(n - 1));
    for (std::size_t k = 0; k < t.x.size(); ++k)
      CHECK(t.y[k] == 2 * t.x[k]); // each point is one of the curve's own
    CHECK(std::is_sorted(t.x.begin(), t.x.end()));
    CHECK(t.title == "c");
  }
}

TEST_CASE("the Richardson curve of a GCI figure passes through the three levels and the extrapolated value", "[plot]")
{
  // f(h) = 5 + 2 h^1.7 on h = 1, 2, 4 (ratio 2): the GCI procedure recovers
  // p = 1.7 and f_ext = 5 up to round-off, and the figure's curve must pass
  // through every level it was computed from (not merely near them).
  const double h[3] = {1e-3, 2e-3, 4e-3};
  double phi[3];
  for (int k = 0; k < 3; ++k)
    phi[k] = 5 + 2 * std::pow(h[k] / 1e-3, 1.7);
  const demvv::GciResult g = demvv::grid_convergence_index(h, phi);
  REQUIRE(g.order == Approx(1.7).epsilon(1e-9));
  const demvv::GciLevels levels{{h[0], h[1], h[2]}, {phi[0], phi[1], phi[2]}, g.extrapolated, g.order, g.gci_fine};
  for (int k = 0; k < 3; ++k)
    CHECK(demvv::richardson_value(levels, h[k]) == Approx(phi[k]).epsilon(1e-12));
  CHECK(demvv::richardson_value(levels, 0) == Approx(5).epsilon(1e-9));
  const demvv::Figure f = demvv::gci_figure("gci", "peak stress", levels, 1e3, 1, "cell size [mm]", "value");
  REQUIRE(f.curves.size() == 5);
  CHECK(f.curves[1].x.front() == 0);
  CHECK(f.curves[1].y.front() == Approx(g.extrapolated).epsilon(1e-12));
  CHECK(f.curves[3].y.front() == Approx(phi[0] * (1 + g.gci_fine)).epsilon(1e-12));
}

TEST_CASE("a uniaxial run directory gets the Fig. 6.1 pair and its other figures, plot refuses a non-run", "[plot]")
{
  const fs::path dir = demvv_tests::test_folder("test_plot_run");
  fs::remove_all(dir);
  demvv::Deck d = demvv::Deck::defaults(demvv::deck_kinds(), "uniaxial");
  d.set("sample/diameter", "0.008");
  d.set("sample/height", "0.008");
  d.set("loading/final strain", "0.002");
  d.set("output/strain interval", "0.0005");
  demvv::run_uniaxial(d, {dir.string(), 1, false});
  std::set<std::string> names;
  for (const demvv::DrawnFigure &f : demvv::plot_run(dir.string(), demvv::deck_kinds()))
  {
    CHECK(f.drawn());
    names.insert(f.name);
  }
  for (const char *n : {"stress_strain", "damage", "radial_strain", "bonds_broken_by_mode", "energy", "time_step",
                        "quasi_static", "section"})
  {
    CHECK(names.count(n) == 1);
    CHECK(fs::exists(dir / "plots" / (std::string(n) + ".svg")));
  }
  CHECK(contains(demvv::read_file((dir / "plots" / "damage.gp").string()), "'../series.csv'"));
  CHECK_THROWS_AS(demvv::run_figures((dir / "plots").string(), demvv::deck_kinds()), demvv::DeckError);
}
