// Fuzz target: the sample-file loader.  The input is a sample file (JSON),
// loaded and checked as a test cell as a uniaxial run loads it.
#include "tests/fuzz/fuzz_support.h"

#include "app/io/sample_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t *data, std::size_t size)
{
  const std::string path = fuzz::write_input("sample.json", data, size);
  fuzz::refused([&] { demvv::check_test_cell(demvv::read_sample(path), path); });
  return 0;
}
