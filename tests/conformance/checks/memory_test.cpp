// The memory-configuration checks: both read forms, the reply form, unknown spaces' error codes.
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

TEST(MemoryChecksTest, DefaultNodePassesEach) {
    const auto results = testing::protocol_results();
    testing::expect_each(results,
                         {"memory.read-short-form", "memory.read-byte6-form", "memory.reply-form",
                          "memory.unknown-space", "memory.config-options"},
                         Status::kPass);
}

TEST(MemoryChecksTest, AnotherCodeForAnUnknownSpaceWarnsQuotingIt) {
    const auto results = testing::protocol_results({"unknown-space-0x1041"});
    const CheckResult& c = expect_status(results, "memory.unknown-space", Status::kWarn);
    EXPECT_NE((c.message + c.seen).find("1041"), std::string::npos) << c.message << " " << c.seen;
}

TEST(MemoryChecksTest, AWrongReplyFormWarns) {
    const auto results = testing::protocol_results({"reply-form"});
    expect_status(results, "memory.reply-form", Status::kWarn);
}

}  // namespace
}  // namespace olcb::conform
