// What the protocol check suites share (checks/): every check's results on a simnode with some
// faults, and one status expected of several checks.
#pragma once

#include <gtest/gtest.h>

#include <initializer_list>
#include <string>
#include <vector>

#include "conformance/sim_bench.hpp"

namespace olcb::conform::testing {

/// Every protocol check against the default scenario's simnode with these faults.
inline std::vector<CheckResult> protocol_results(const std::vector<std::string>& faults = {}) {
    SimBench b(faults);
    CheckContext ctx;
    return b.run(ctx);
}

/// Expects status of each check in ids.
inline void expect_each(const std::vector<CheckResult>& results,
                        std::initializer_list<const char*> ids, Status status) {
    for (const char* id : ids) expect_status(results, id, status);
}

}  // namespace olcb::conform::testing
