// The probes the checks share: the CDI download judges the NUL (cdi.nul-terminated, cdi.nul-at-highest).
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::SimBench;

TEST(ProbesTest, TheCdiDownloadFindsTheNulAtTheHighestAddress) {
    SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "cdi.nul-terminated", Status::kPass);
    expect_status(results, "cdi.nul-at-highest", Status::kPass);
}

TEST(ProbesTest, AnUnterminatedCdiFailsNulTerminated) {
    SimBench b({"cdi-unterminated"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "cdi.nul-terminated", Status::kFail);
}

}  // namespace
}  // namespace olcb::conform
