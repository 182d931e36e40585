// Fuzz target: the CSV particle reader.  The input is the particle file of a
// scene deck (its balls, and the overlap check run on them), read as
// `demvv run` reads it before a run.  The deck is read once; each input
// runs the scene's parse, which reads the particle file.
#include "app/kinds/deck_kinds.h"
#include "tests/fuzz/fuzz_support.h"

#include "app/decks/deck.h"

#include <optional>

namespace
{
std::optional<demvv::Deck> deck;
} // namespace

extern "C" int LLVMFuzzerInitialize(int *, char ***)
{
  const std::string path =
    fuzz::write_input("scene.prm", "set kind = scene\nsubsection particles\n  set file = particles.csv\nend\n"
                                   "subsection walls\n  subsection plane floor\n    set point = 0, 0, -1\n"
                                   "    set normal = 0, 0, 1\n  end\nend\n");
  deck = demvv::Deck::from_file(demvv::dem_deck_kinds(), path);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  fuzz::write_input("particles.csv", data, size);
  fuzz::refused([] { deck->kind_row().parse(*deck); });
  return 0;
}
