// The datagram checks: every datagram answered before its reply, Reply Pending on reads, and temporary rejects counted.
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

TEST(DatagramChecksTest, DefaultNodePassesEach) {
    SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    for (const char* id : {"datagram.ok-before-reply", "datagram.reply-pending"}) {
        expect_status(results, id, Status::kPass);
    }
}

TEST(DatagramChecksTest, ANodeThatNeverAcksWarnsOnlyTheOrderOfTheTechnicalNote) {
    SimBench b({"no-datagram-ack"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    const CheckResult& c = expect_status(results, "datagram.ok-before-reply", Status::kWarn);
    EXPECT_NE(c.message.find("before its Datagram Received OK"), std::string::npos) << c.message;
}

}  // namespace
}  // namespace olcb::conform
