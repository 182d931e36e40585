// Fuzz target: the deck reader.  The input is a deck file (.prm syntax, or
// JSON when it starts with '{'), read and parsed by its kind as `demvv run`
// does before a run.
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  const bool json = size > 0 && data[0] == '{';
  const std::string path = fuzz::write_input(json ? "deck.json" : "deck.prm", data, size);
  fuzz::refused([&] { fuzz::read_and_parse(path); });
  return 0;
}
