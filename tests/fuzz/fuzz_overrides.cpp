// Fuzz target: `--set SECTION/KEY=VALUE` overrides.  The first byte picks a
// valid deck (a scene with a particle file, a lattice uniaxial test, a
// prepare deck); every further line of the input is one --set value.
#include "tests/fuzz/fuzz_support.h"

#include <array>

namespace
{
const std::array<const char *, 3> decks = {
  "set kind = scene\nsubsection particles\n  set file = balls.csv\nend\nsubsection run\n  set duration = 1e-4\nend\n",
  "set kind = uniaxial\nsubsection sample\n  set source = lattice\n  set diameter = 0.01\n  set height = 0.01\nend\n",
  "set kind = prepare\nsubsection sample\n  set particles = 200\nend\n"};
} // namespace

extern "C" int LLVMFuzzerInitialize(int *, char ***)
{
  fuzz::write_input("balls.csv", "x_m,y_m,z_m,radius_m\n0,0,0,0.001\n0.0021,0,0,0.001\n");
  for (std::size_t k = 0; k < decks.size(); ++k)
    fuzz::write_input("base" + std::to_string(k) + ".prm", decks[k]);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  if (size == 0)
    return 0;
  const std::string base = fuzz::scratch() + "/base" + std::to_string(data[0] % decks.size()) + ".prm";
  std::vector<std::string> overrides;
  std::string line;
  for (std::size_t k = 1; k < size; ++k)
  {
    if (data[k] == '\n')
    {
      overrides.push_back(line);
      line.clear();
    }
    else
      line.push_back(static_cast<char>(data[k]));
  }
  if (!line.empty())
    overrides.push_back(line);
  fuzz::refused([&] { fuzz::read_and_parse(base, overrides); });
  return 0;
}
