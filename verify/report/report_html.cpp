#include "verify/report/report.h"

#include "app/io/output.h"
#include "app/plot/gnuplot.h"
#include "app/plot/studies.h"
#include "verify/checks/catalogue.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

namespace demvv
{
namespace
{
std::string html_escaped(std::string_view text)
{
  std::string out;
  for (char c : text)
    switch (c)
    {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    default:
      out += c;
    }
  return out;
}

std::string base64(const std::string &bytes)
{
  static const char digits[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t k = 0;
  for (; k + 2 < bytes.size(); k += 3)
  {
    const unsigned v = static_cast<unsigned char>(bytes[k]) << 16 | static_cast<unsigned char>(bytes[k + 1]) << 8 |
                       static_cast<unsigned char>(bytes[k + 2]);
    out += {digits[v >> 18], digits[v >> 12 & 63], digits[v >> 6 & 63], digits[v & 63]};
  }
  if (k + 1 == bytes.size())
  {
    const unsigned v = static_cast<unsigned char>(bytes[k]) << 16;
    out += {digits[v >> 18], digits[v >> 12 & 63], '=', '='};
  }
  else if (k + 2 == bytes.size())
  {
    const unsigned v = static_cast<unsigned char>(bytes[k]) << 16 | static_cast<unsigned char>(bytes[k + 1]) << 8;
    out += {digits[v >> 18], digits[v >> 12 & 63], digits[v >> 6 & 63], '='};
  }
  return out;
}

std::string lower(std::string_view s)
{
  std::string out(s);
  for (char &c : out)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

/// How far inside its tolerance a metric is: value / tolerance (tolerance /
/// value for a lower bound); below 1 passes.  An exact zero under an upper
/// bound stays 0 (a count that must match, tolerance 0 included; the
/// figure draws it apart); what no number can say (NaN, a lower bound of
/// 0) is 1e6, far above the line.
double margin(const Metric &m)
{
  const double v = std::abs(m.value), t = std::abs(m.tolerance);
  if (!m.at_least && v == 0)
    return 0;
  const double r = m.at_least ? t / v : v / t;
  return std::isfinite(r) ? std::min(r, 1e6) : 1e6;
}

const char *figure_check_script = R"(
window.addEventListener('load', function () {
  var closed = document.querySelectorAll('details:not([open])');
  closed.forEach(function (d) { d.open = true; });
  var figures = document.querySelectorAll('img.figure'), broken = 0;
  figures.forEach(function (img) {
    var box = img.getBoundingClientRect();
    var ok = img.complete && img.naturalWidth > 0 && box.width > 0 && box.height > 0;
    img.setAttribute('data-rendered', ok ? 'yes' : 'no');
    if (!ok) {
      broken++;
      var note = document.createElement('p');
      note.className = 'broken';
      note.textContent = 'This figure did not render in this browser.';
      img.parentNode.insertBefore(note, img.nextSibling);
    }
  });
  closed.forEach(function (d) { d.open = false; });
  document.body.setAttribute('data-figures', String(figures.length));
  document.body.setAttribute('data-figures-broken', String(broken));
});
)";

const char *style_sheet = R"(
body { font-family: sans-serif; max-width: 1000px; margin: 2em auto; padding: 0 1em; color: #222; line-height: 1.4; }
table { border-collapse: collapse; margin: 1em 0; font-size: 0.9em; }
th, td { border: 1px solid #ccc; padding: 0.25em 0.5em; text-align: left; vertical-align: top; }
th { background: #f2f2f2; }
.pass { color: #17663a; font-weight: bold; }
.fail { color: #b00020; font-weight: bold; }
figure { margin: 1em 0; }
img.figure { max-width: 100%; height: auto; border: 1px solid #ddd; }
figcaption, .missing, .broken { font-size: 0.9em; color: #555; }
.missing, .broken { color: #b00020; }
section.check { border-top: 2px solid #ddd; margin-top: 1em; }
summary { cursor: pointer; }
summary h3 { display: inline; }
table.signoff td { min-width: 10em; height: 2em; }
dl.facts dt { font-weight: bold; float: left; clear: left; width: 9em; }
dl.facts dd { margin-left: 10em; }
pre { background: #f7f7f7; padding: 0.5em; overflow-x: auto; font-size: 0.8em; }
)";

/// Convergence studies a check shows one by one; more are a family.
constexpr std::size_t family_unfolded = 4;

std::string convergence_family_table(const std::vector<ConvergenceTable> &tables)
{
  std::ostringstream o;
  o << "<table class=\"family\">\n<tr><th>study</th><th>levels</th><th>finest error</th><th>last observed "
       "order</th><th>reference</th></tr>\n";
  for (const ConvergenceTable &t : tables)
    o << "<tr><td>" << html_escaped(t.title) << "</td><td>" << t.rows.size() << "</td><td>"
      << (t.rows.empty()
            ? std::string("-")
            : report_number(std::min_element(t.rows.begin(), t.rows.end(),
                                             [](const ConvergenceRow &a, const ConvergenceRow &b) { return a.h < b.h; })
                              ->error))
      << "</td><td>"
      << (t.reference == ConvergenceTable::Reference::roundoff ? std::string("(round-off, none claimed)")
                                                               : report_number(t.last_order()))
      << "</td><td>" << html_escaped(reference_text(t)) << "</td></tr>\n";
  o << "</table>\n";
  return o.str();
}

std::string verdict(bool pass)
{
  return pass ? "<span class=\"pass\">PASS</span>" : "<span class=\"fail\">FAIL</span>";
}
} // namespace

std::vector<Figure> check_figures(const CheckRecord &r)
{
  const std::string id = lower(r.check->id);
  std::vector<Figure> out;
  for (std::size_t k = 0; k < r.outcome.tables.size(); ++k)
  {
    const ConvergenceTable &t = r.outcome.tables[k];
    Figure f;
    f.name = id + "_convergence_" + std::to_string(k + 1);
    f.title = t.title;
    f.x_label = t.h_name;
    f.y_label = t.error_name;
    std::vector<double> h, e;
    for (const ConvergenceRow &row : t.rows)
    {
      h.push_back(row.h);
      e.push_back(row.error);
    }
    using Reference = ConvergenceTable::Reference;
    if (t.reference == Reference::roundoff)
    {
      add_order_study(f, "error (round-off, no order)", h, e, 0);
      const auto [low, high] = std::minmax_element(h.begin(), h.end());
      if (low != h.end())
        f.curves.push_back(curve("round-off bound of the check", {*low, *high}, {t.roundoff_bound, t.roundoff_bound},
                                 CurveStyle::dashed));
      f.caption = "The scheme reproduces this quantity exactly, so what is left is round-off, not a truncation error: "
                  "the errors are drawn against the bound the check holds them to, and no order is claimed (an "
                  "observed order of round-off is noise). Exact zeros are not drawn.";
    }
    else
    {
      const bool theory = t.reference == Reference::theory;
      add_order_study(f, "observed (last order " + report_number(t.last_order()) + ")", h, e, t.expected_order,
                      theory ? "theory"
                             : (t.reference == Reference::fitted ? "fitted to these points" : "the least accepted"));
      if (!(t.expected_order > 0))
        f.caption = "Errors of the study on log-log axes; no order is claimed, so no reference line is drawn: the "
                    "check holds the errors themselves to its tolerance.";
      else
        f.caption = "Errors of the study on log-log axes; the dashed line is the " + reference_text(t) +
                    ", drawn through the finest level." +
                    (theory ? ""
                     : t.reference == Reference::fitted
                       ? " It is fitted to the points it passes, so it shows the fit, not a prediction."
                       : " Errors that fall faster than the line pass: it is a bound, not a prediction.");
    }
    out.push_back(std::move(f));
  }
  for (Figure f : r.outcome.figures)
  {
    f.name = id + "_" + f.name;
    out.push_back(std::move(f));
  }
  if (!r.outcome.metrics.empty())
  {
    Figure f;
    f.name = id + "_margins";
    f.title = std::string(r.check->id) + ": each metric against its tolerance";
    f.x_label = "metric (numbered as in the table)";
    f.y_label = "value / tolerance (tolerance / value for a lower bound)";
    f.log_y = true;
    // Exact zeros (a closed form met to the last bit) have no place on a
    // log axis: they are drawn apart, as open circles on a floor a hundred
    // times below the least non-zero margin, so that they neither vanish
    // nor stretch the axis over sixteen decades.
    std::vector<double> n, ratio, zero_n;
    double least = 1, most = 1;
    for (std::size_t k = 0; k < r.outcome.metrics.size(); ++k)
    {
      const double m = margin(r.outcome.metrics[k]);
      (m > 0 ? n : zero_n).push_back(static_cast<double>(k + 1));
      if (m > 0)
        ratio.push_back(m);
      least = m > 0 ? std::min(least, m) : least;
      most = std::max(most, m);
    }
    const double floor = least / 100;
    const double right = static_cast<double>(r.outcome.metrics.size()) + 0.5;
    f.curves.push_back(curve("metric", n, ratio, CurveStyle::points));
    f.curves.push_back(curve("tolerance (pass below)", {0.5, right}, {1.0, 1.0}, CurveStyle::dashed));
    if (!zero_n.empty())
    {
      f.curves.push_back(curve("exact zero (drawn at the floor)", zero_n, std::vector<double>(zero_n.size(), floor),
                               CurveStyle::points));
      f.curves.back().point_type = 6;
    }
    f.y_low = floor / 3;
    f.y_high = 10 * most;
    f.x_margins = true;
    f.caption = "How far inside its tolerance each metric lies: a point below the dashed line passes." +
                std::string(zero_n.empty() ? ""
                                           : " Open circles are exact zeros, drawn on a floor a hundred times below "
                                             "the least non-zero ratio (a log axis has no zero).");
    out.push_back(std::move(f));
  }
  return out;
}

std::string report_html(const std::vector<CheckRecord> &records, const std::vector<std::vector<Figure>> &figures,
                        const nlohmann::json &provenance, const std::map<std::string, DrawnFigure> &drawn)
{
  std::size_t missing = 0;
  std::ostringstream body;
  for (std::size_t n = 0; n < records.size(); ++n)
  {
    const CheckRecord &r = records[n];
    const Check &c = *r.check;
    body << "<section class=\"check\" id=\"" << html_escaped(c.id) << "\">\n<details" << (r.pass() ? "" : " open")
         << ">\n<summary><h3>" << html_escaped(c.id) << ": " << html_escaped(c.title) << " — " << verdict(r.pass())
         << "</h3></summary>\n<dl class=\"facts\">\n"
         << "<dt>Requirement</dt><dd>" << html_escaped(c.requirement) << "</dd>\n"
         << "<dt>Reference</dt><dd>" << html_escaped(c.reference) << "</dd>\n"
         << "<dt>Category</dt><dd>" << html_escaped(category_name(c.category)) << "</dd>\n"
         << "<dt>Tolerance classes</dt><dd>" << html_escaped(tolerance_class_list(c.tolerance_classes)) << "</dd>\n"
         << "<dt>Case decks</dt><dd>" << html_escaped(case_decks_text(r)) << "</dd>\n"
         << "<dt>Run time</dt><dd>" << report_number(r.seconds) << " s</dd>\n</dl>\n";
    if (!r.error.empty())
      body << "<p class=\"fail\">The check stopped: " << html_escaped(r.error) << "</p>\n";
    // A long family of convergence studies (V21 has two dozen) is one table
    // of its studies, with their figures folded under it.
    const std::size_t studies = r.outcome.tables.size();
    const bool family = studies > family_unfolded;
    if (family)
      body << convergence_family_table(r.outcome.tables) << "<details class=\"family\">\n<summary>The " << studies
           << " convergence figures</summary>\n";
    for (std::size_t k = 0; k < figures[n].size(); ++k)
    {
      const Figure &f = figures[n][k];
      const auto it = drawn.find(f.name);
      body << "<figure>\n";
      if (it != drawn.end() && it->second.drawn())
        body << "<img class=\"figure\" alt=\"" << html_escaped(f.title) << "\" src=\"data:image/svg+xml;base64,"
             << base64(read_file(it->second.svg)) << "\">\n";
      else
      {
        ++missing;
        body << "<p class=\"missing\">Figure '" << html_escaped(f.name) << "' was not drawn"
             << (it == drawn.end() ? std::string() : ": " + html_escaped(it->second.problem)) << ".</p>\n";
      }
      body << "<figcaption>" << html_escaped(f.title) << (f.caption.empty() ? "" : ". ") << html_escaped(f.caption)
           << "</figcaption>\n</figure>\n";
      if (family && k + 1 == studies)
        body << "</details>\n";
    }
    body << "<table>\n<tr><th>#</th><th>metric</th><th>class</th><th>value</th><th>tolerance</th><th>verdict</th>"
            "<th>why this tolerance</th></tr>\n";
    for (std::size_t k = 0; k < r.outcome.metrics.size(); ++k)
    {
      const Metric &m = r.outcome.metrics[k];
      body << "<tr><td>" << k + 1 << "</td><td>" << html_escaped(m.name) << "</td><td>"
           << tolerance_class_letter(m.tolerance_class) << "</td><td>" << report_number(m.value) << "</td><td>"
           << (m.at_least ? "&ge; " : "&le; ") << report_number(m.tolerance) << "</td><td>" << verdict(m.pass)
           << "</td><td>" << html_escaped(m.reason) << "</td></tr>\n";
    }
    body << "</table>\n";
    if (!r.outcome.notes.empty())
    {
      body << "<ul>\n";
      for (const std::string &n : r.outcome.notes)
        body << "<li>" << html_escaped(n) << "</li>\n";
      body << "</ul>\n";
    }
    body << "</details>\n</section>\n";
  }

  const Headline head = headline(records);
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
    << "<title>demvv verification report</title>\n<style>" << style_sheet << "</style>\n</head>\n"
    << "<body data-figures-missing=\"" << missing
    << "\">\n<h1>demvv verification report</h1>\n<p id=\"headline\" class=\"" << (head.code_failures ? "fail" : "pass")
    << "\"><b>" << html_escaped(head.text()) << "</b> (" << head.counts() << ").</p>\n"
    << "<p id=\"banner\">" << html_escaped(banner(provenance)) << "</p>\n"
    << "<h2>Scope and intended use</h2>\n";
  for (const std::string &paragraph : report_scope(provenance))
    o << "<p>" << html_escaped(paragraph) << "</p>\n";
  o << "<h2>Verdicts</h2>\n<table>\n<tr><th>id</th><th>check</th><th>category</th><th>classes</th><th>verdict</th>"
       "<th>run time [s]</th></tr>\n";
  for (const CheckRecord &r : records)
    o << "<tr><td><a href=\"#" << html_escaped(r.check->id) << "\">" << html_escaped(r.check->id) << "</a></td><td>"
      << html_escaped(r.check->title) << "</td><td>" << html_escaped(category_name(r.check->category)) << "</td><td>"
      << html_escaped(tolerance_class_list(r.check->tolerance_classes)) << "</td><td>" << verdict(r.pass())
      << "</td><td>" << report_number(r.seconds) << "</td></tr>\n";
  o << "</table>\n<h2>Categories and tolerance classes</h2>\n<dl>\n";
  for (Category c : all_categories)
    o << "<dt><b>" << html_escaped(category_name(c)) << "</b></dt><dd>" << html_escaped(category_definition(c))
      << "</dd>\n";
  for (ToleranceClass t : {ToleranceClass::A, ToleranceClass::B, ToleranceClass::C, ToleranceClass::D})
    o << "<dt><b>class " << tolerance_class_letter(t) << " (" << html_escaped(tolerance_class_name(t))
      << ")</b></dt><dd><i>What limits it:</i> " << html_escaped(tolerance_class_limit(t)) << ".<br><i>Rule:</i> "
      << html_escaped(tolerance_class_rule(t)) << ".<br><i>Why:</i> " << html_escaped(tolerance_class_reasoning(t))
      << "</dd>\n";
  o << "</dl>\n<h2>Checks</h2>\n<p>Each check folds: its title opens it. Checks that fail are open.</p>\n"
    << body.str() << "<h2 id=\"sign-off\">Sign-off</h2>\n<p>" << html_escaped(sign_off_statement) << "</p>\n"
    << "<table class=\"signoff\">\n<tr><th>role</th><th>name</th><th>date</th><th>signature</th></tr>\n";
  for (const char *role : sign_off_roles)
    o << "<tr><td>" << role << "</td><td></td><td></td><td></td></tr>\n";
  o << "</table>\n<h2>Provenance</h2>\n<pre>" << html_escaped(json_text(provenance, 2)) << "</pre>\n<script>"
    << figure_check_script << "</script>\n</body>\n</html>\n";
  return o.str();
}

void write_reports(const std::vector<CheckRecord> &records, const nlohmann::json &provenance,
                   const std::string &out_dir)
{
  make_directories(out_dir);
  write_atomically(out_dir + "/report.json", json_text(report_json(records, provenance), 2) + "\n");
  write_atomically(out_dir + "/report.md", report_markdown(records, provenance));
  std::vector<std::vector<Figure>> figures;
  std::vector<Figure> all;
  for (const CheckRecord &r : records)
  {
    figures.push_back(check_figures(r));
    all.insert(all.end(), figures.back().begin(), figures.back().end());
  }
  std::map<std::string, DrawnFigure> drawn;
  for (DrawnFigure &d : draw_figures(all, out_dir + "/figures"))
    drawn[d.name] = std::move(d);
  write_atomically(out_dir + "/report.html", report_html(records, figures, provenance, drawn));
}
} // namespace demvv
