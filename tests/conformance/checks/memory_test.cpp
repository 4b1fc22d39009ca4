// The memory-configuration checks: both read forms, the reply form, unknown spaces' error codes.
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

TEST(MemoryChecksTest, DefaultNodePassesEach) {
    SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    for (const char* id : {"memory.read-short-form", "memory.read-byte6-form", "memory.reply-form",
                           "memory.unknown-space", "memory.config-options"}) {
        expect_status(results, id, Status::kPass);
    }
}

TEST(MemoryChecksTest, AnotherCodeForAnUnknownSpaceWarnsQuotingIt) {
    SimBench b({"unknown-space-0x1041"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    const CheckResult& c = expect_status(results, "memory.unknown-space", Status::kWarn);
    EXPECT_NE((c.message + c.seen).find("1041"), std::string::npos) << c.message << " " << c.seen;
}

TEST(MemoryChecksTest, AWrongReplyFormWarns) {
    SimBench b({"reply-form"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "memory.reply-form", Status::kWarn);
}

}  // namespace
}  // namespace olcb::conform
