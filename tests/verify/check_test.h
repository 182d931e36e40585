// The test of one check of the registry (test_verification.cpp), and the
// ids of the checks that have a generated test (check_tests.cmake writes
// one TEST_CASE per registry row, which calls require_check).
#pragma once

#include <string_view>
#include <vector>

namespace demvv_test
{
/// Runs the check `id` and asserts every metric: its verdict (a validation
/// metric only finite: validation may fail), a tolerance class its row
/// declares, and every declared class used.
void require_check(std::string_view id);

/// The ids of the generated tests, in registry order.
extern const std::vector<std::string_view> generated_check_ids;
} // namespace demvv_test
