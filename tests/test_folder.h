#pragma once
// A folder of this test process's own for the files a test writes.
//
// ctest runs every test case as a process of its own, several at a time
// (README: ctest -j), so a fixed name under /tmp would be shared by test
// cases running side by side.  The folder is named by the process and
// removed when the process ends.

#include "verify/checks/checks_support.h"

#include <filesystem>
#include <string>

namespace demvv_tests
{
/// `name` inside this process's own folder under the temporary directory
/// (the folder exists; `name` itself is not created).
inline std::filesystem::path test_folder(const std::string &name)
{
  static const demvv::ScratchDirectory scratch;
  std::filesystem::create_directories(scratch.path());
  return std::filesystem::path(scratch.path()) / name;
}
} // namespace demvv_tests
