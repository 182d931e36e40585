// Fuzz target: `demvv plot` on a hostile run directory.  The input is a
// run directory's summary.json, and after a line "---" its series.csv;
// run_figures() reads them as `demvv plot` does, and every figure's
// gnuplot script is written as draw_figures() writes it (gnuplot itself is
// not run: the script is what it would execute).  Beyond the refusals of
// fuzz_support.h, a finding is a figure whose name would leave its folder
// or whose script holds a line demvv did not mean to write: every line must
// be one of demvv's own commands (reset, set, plot, a continuation of the
// plot) or a comment without a line continuation or a backquote.
#include "app/kinds/deck_kinds.h"
#include "tests/fuzz/fuzz_support.h"

#include "app/plot/gnuplot.h"
#include "app/plot/run_figures.h"

#include <filesystem>
#include <sstream>
#include <string>

namespace
{
bool demvv_line(const std::string &line)
{
  for (const char *command : {"reset", "set ", "unset ", "plot ", "     "})
    if (line.rfind(command, 0) == 0)
      return true;
  return line.rfind("# ", 0) == 0 && line.find('`') == std::string::npos && line.back() != '\\';
}

void check_figure(const demvv::Figure &figure)
{
  const std::string name = demvv::figure_name(figure.name);
  if (name.empty() ||
      name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") != std::string::npos)
    __builtin_trap();
  demvv::Figure named = figure;
  named.name = name;
  std::istringstream script(demvv::gnuplot_script(named));
  std::string line;
  while (std::getline(script, line))
  {
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        __builtin_trap();
    if (!line.empty() && !demvv_line(line))
      __builtin_trap();
  }
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  const std::string input(reinterpret_cast<const char *>(data), size);
  const std::size_t cut = input.find("\n---\n");
  const std::string dir = fuzz::scratch() + "/run";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  fuzz::write_input("run/summary.json", input.substr(0, cut));
  if (cut != std::string::npos)
    fuzz::write_input("run/series.csv", input.substr(cut + 5));
  fuzz::refused(
    [&]
    {
      for (const demvv::Figure &f : demvv::run_figures(dir, demvv::dem_deck_kinds()))
        check_figure(f);
    });
  return 0;
}
