#include "tests/fuzz/fuzz_support.h"

#include "app/decks/deck.h"
#include "app/kinds/deck_kinds.h"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <new>
#include <stdexcept>

#include <unistd.h>

namespace fuzz
{
namespace
{
/// The scratch folder's path: a plain array, so that nothing destroys it
/// before the exit handler that removes the folder runs.
char scratch_path[4096];

void remove_scratch()
{
  std::error_code ec;
  std::filesystem::remove_all(scratch_path, ec);
}
} // namespace

std::string scratch()
{
  static const bool made = []
  {
    const std::string pattern = (std::filesystem::temp_directory_path() / "demvv_fuzz_XXXXXX").string();
    if (pattern.size() >= sizeof scratch_path)
      std::abort();
    pattern.copy(scratch_path, pattern.size());
    if (!mkdtemp(scratch_path))
    {
      std::perror("demvv fuzz: mkdtemp");
      std::abort();
    }
    std::atexit(remove_scratch);
    return true;
  }();
  return made ? scratch_path : "";
}

std::string write_input(const std::string &name, const std::uint8_t *data, std::size_t size)
{
  const std::string path = scratch() + "/" + name;
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char *>(data), static_cast<std::streamsize>(size));
  if (!out)
  {
    std::perror(("demvv fuzz: " + path).c_str());
    std::abort();
  }
  return path;
}

std::string write_input(const std::string &name, const std::string &text)
{
  return write_input(name, reinterpret_cast<const std::uint8_t *>(text.data()), text.size());
}

bool refused(const std::function<void()> &load)
{
  try
  {
    load();
    return false;
  }
  catch (const std::runtime_error &)
  {
    return true; // DeckError, OutputError and the rest: exit 2 or 4
  }
  catch (const std::bad_alloc &)
  {
    return true;
  }
  catch (const std::length_error &)
  {
    return true;
  }
}

void read_and_parse(const std::string &path, const std::vector<std::string> &overrides)
{
  const demvv::Deck deck = demvv::Deck::from_file(demvv::dem_deck_kinds(), path, overrides);
  deck.kind_row().parse(deck);
}
} // namespace fuzz
