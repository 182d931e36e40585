// Input files (app/io/input.h): what is not a regular file, too large,
// nested too deep or not UTF-8 is refused with the one-line error, and
// outputs never abort on text they cannot hold.  The bad-input corpus
// (tests/data/bad, tests/cli/bad_inputs.sh) runs the same through the command.
#include "app/decks/deck.h"
#include "app/io/input.h"
#include "app/io/output.h"
#include "app/io/sample_file.h"
#include "app/kinds/deck_kinds.h"

#include "tests/test_folder.h"

#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <functional>

namespace
{
namespace fs = std::filesystem;

std::string error_of(const std::function<void()> &f)
{
  try
  {
    f();
  }
  catch (const demvv::DeckError &e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST_CASE("only regular files within their size limit are read", "[inputs]")
{
  const std::string dir = fs::temp_directory_path().string();
  CHECK_THAT(error_of([&] { demvv::read_input(dir, "deck file", demvv::max_deck_bytes); }),
             Catch::Contains("not a regular file") && Catch::Contains(dir));
  CHECK_THAT(error_of([] { demvv::read_input("/dev/zero", "CSV file", demvv::max_table_bytes); }),
             Catch::Contains("/dev/zero: is not a regular file"));
  CHECK_THAT(error_of([] { demvv::read_input("/no/such/deck.prm", "deck file", demvv::max_deck_bytes); }),
             Catch::Contains("cannot open the deck file"));
  // One byte over the limit is refused before it is read; at the limit it is read.
  const std::string big = demvv_tests::test_file("test_inputs", "big.prm");
  std::ofstream(big) << std::string(demvv::max_deck_bytes + 1, '#');
  const std::string message = error_of([&] { demvv::Deck::from_file(demvv::deck_kinds(), big); });
  CHECK_THAT(message, Catch::Contains(big) && Catch::Contains("expected at most 1 MiB"));
  CHECK(message.find('\n') == std::string::npos);
  fs::resize_file(big, demvv::max_deck_bytes);
  CHECK(demvv::read_input(big, "deck file", demvv::max_deck_bytes).size() == demvv::max_deck_bytes);
}

TEST_CASE("JSON nested deeper than the limit is refused before it is parsed", "[inputs]")
{
  const auto nested = [](int depth) { return std::string(depth, '[') + std::string(depth, ']'); };
  CHECK(demvv::parse_json_input(nested(demvv::max_json_depth), "ok.json", "sample file").is_array());
  CHECK_THAT(error_of([&] { demvv::parse_json_input(nested(100000), "deep.json", "sample file"); }),
             Catch::Contains("deep.json") && Catch::Contains("nested more than 64 levels"));
  // Brackets inside strings are text, not nesting.
  CHECK(demvv::parse_json_input("{\"a\": \"" + std::string(1000, '[') + "\"}", "s.json", "deck").is_object());
  CHECK_THAT(error_of([] { demvv::parse_json_input("{\"a\": ", "cut.json", "deck"); }),
             Catch::Contains("cut.json: not valid JSON"));
}

TEST_CASE("UTF-8 is told from other encodings, and outputs replace what is not UTF-8", "[inputs]")
{
  CHECK(demvv::valid_utf8("plain ASCII"));
  CHECK(demvv::valid_utf8("caract\xc3\xa9ristique, \xe2\x82\xac, \xf0\x9f\x98\x80"));
  CHECK_FALSE(demvv::valid_utf8("caract\xe9ristique")); // Latin-1
  CHECK_FALSE(demvv::valid_utf8("\xc0\xaf"));           // overlong '/'
  CHECK_FALSE(demvv::valid_utf8("\xed\xa0\x80"));       // a UTF-16 surrogate
  CHECK_FALSE(demvv::valid_utf8("\xe2\x82"));           // cut short
  CHECK(demvv::escaped("a\xe9\n") == "a\\xE9\\x0A");
  // A path in Latin-1 reaches a summary: written with U+FFFD, not thrown.
  const nlohmann::json doc = {{"deck_file", "runs/caract\xe9ristique.prm"}};
  CHECK(demvv::json_text(doc) == "{\"deck_file\":\"runs/caract\xef\xbf\xbdristique.prm\"}");
}

TEST_CASE("an error that echoes a huge value stays readable and keeps what was expected", "[inputs]")
{
  const std::string word(100000, 'a'), tail = "': expected a file name";
  const std::string message = "deck.prm:3: key 'particles/file' has value '" + word + tail;
  const std::string shown = demvv::readable_length(message);
  CHECK(shown.size() < 400);
  CHECK(shown.rfind("deck.prm:3: key 'particles/file' has value '", 0) == 0);
  CHECK(shown.find("(99863 characters left out)") != std::string::npos);
  CHECK(shown.size() >= tail.size());
  CHECK(shown.compare(shown.size() - tail.size(), tail.size(), tail) == 0);
  // Short messages pass unchanged; a cut never splits a UTF-8 character.
  CHECK(demvv::readable_length("key 'a' has value 'b': expected c") == "key 'a' has value 'b': expected c");
  std::string euros;
  for (int k = 0; k < 100; ++k)
    euros += "\xe2\x82\xac"; // 300 bytes, 3 per character
  CHECK(demvv::valid_utf8(demvv::readable_length(euros)));
  // Many short words: the whole is kept to its first 1400 and last 400.
  std::string many;
  for (int k = 0; k < 2000; ++k)
    many += "word ";
  many += "expected this";
  const std::string clipped = demvv::readable_length(many);
  CHECK(clipped.size() < 1900);
  CHECK(clipped.compare(clipped.size() - 13, 13, "expected this") == 0);
}

TEST_CASE("a deck's text must be UTF-8 and name one kind", "[inputs][deck]")
{
  const std::string latin1 = demvv_tests::test_file("test_inputs", "latin1.prm");
  std::ofstream(latin1) << "set kind = scene\nset title = caract\xe9ristique\n";
  CHECK_THAT(error_of([&] { demvv::Deck::from_file(demvv::deck_kinds(), latin1); }),
             Catch::Contains(latin1 + ":2") && Catch::Contains("'title'") && Catch::Contains("caract\\xE9ristique") &&
               Catch::Contains("expected UTF-8"));
  CHECK_THAT(error_of(
               [&]
               {
                 demvv::Deck::from_file(demvv::deck_kinds(), demvv_tests::test_file("test_inputs", "latin1.prm"),
                                        {"title=\xe9t\xe9"});
               }),
             Catch::Contains("latin1.prm:2"));
  const std::string twice = demvv_tests::test_file("test_inputs", "twice.prm");
  std::ofstream(twice) << "set kind = scene\nset kind = prepare\n";
  CHECK_THAT(error_of([&] { demvv::Deck::from_file(demvv::deck_kinds(), twice); }),
             Catch::Contains(twice + ":2") && Catch::Contains("'prepare'") && Catch::Contains("one 'set kind'"));
}

TEST_CASE("a sample without platens loads, and a test refuses it", "[inputs][sample]")
{
  // A checkpoint's sample file names no platens: it is read, but a uniaxial
  // test cannot start from it.
  const demvv::SampleFile sample = demvv::read_sample(DEMVV_TEST_DATA "/bad/sample_no_platens.json");
  CHECK(sample.snapshot.particles.size() == 2);
  CHECK_THAT(error_of([&] { demvv::check_test_cell(sample, "no_platens.json"); }),
             Catch::Contains("no_platens.json: key 'cell.bottom' has value '-1'"));
  const demvv::SampleFile ok = demvv::read_sample(DEMVV_TEST_DATA "/bad/sample_ok.json");
  CHECK_NOTHROW(demvv::check_test_cell(ok, "ok.json"));
}
