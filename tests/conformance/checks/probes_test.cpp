// The probes the checks share: the CDI download judges the NUL (cdi.nul-terminated,
// cdi.nul-at-highest).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;

TEST(ProbesTest, TheCdiDownloadFindsTheNulAtTheHighestAddress) {
    const auto results = testing::protocol_results();
    expect_status(results, "cdi.nul-terminated", Status::kPass);
    expect_status(results, "cdi.nul-at-highest", Status::kPass);
}

TEST(ProbesTest, AnUnterminatedCdiFailsNulTerminated) {
    const auto results = testing::protocol_results({"cdi-unterminated"});
    expect_status(results, "cdi.nul-terminated", Status::kFail);
}

}  // namespace
}  // namespace olcb::conform
