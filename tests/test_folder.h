#pragma once
// A folder of this test process's own for the files a test writes.
//
// ctest runs every test case as a process of its own, several at a time
// (README: ctest -j), so a fixed name under /tmp would be shared by test
// cases running side by side.  The folder is named by the process and
// removed when the process ends.

#include "app/io/output.h"
#include "verify/checks/checks_support.h"

#include <nlohmann/json.hpp>

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

/// `name` inside the folder `folder` of this process's own folder (the
/// folder is created; `name` is not).
inline std::string test_file(const std::string &folder, const std::string &name)
{
  const std::filesystem::path dir = test_folder(folder);
  std::filesystem::create_directories(dir);
  return (dir / name).string();
}

/// A JSON file a run wrote, parsed.
inline nlohmann::json read_json(const std::filesystem::path &path)
{
  return nlohmann::json::parse(demvv::read_file(path.string()));
}
} // namespace demvv_tests
