// The datagram checks: every datagram answered before its reply, Reply Pending on reads, and
// temporary rejects counted.
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

TEST(DatagramChecksTest, DefaultNodePassesEach) {
    const auto results = testing::protocol_results();
    testing::expect_each(results, {"datagram.ok-before-reply", "datagram.reply-pending"},
                         Status::kPass);
}

TEST(DatagramChecksTest, AnOkAfterTheReplyWarnsOnlyTheOrderOfTheTechnicalNote) {
    const auto results = testing::protocol_results({"no-datagram-ack"});
    const CheckResult& c = expect_status(results, "datagram.ok-before-reply", Status::kWarn);
    EXPECT_NE(c.message.find("before its Datagram Received OK"), std::string::npos) << c.message;
}

TEST(DatagramChecksTest, ANodeThatNeverSendsAnOkFails) {
    const auto results = testing::protocol_results({"reply-without-ack"});
    const CheckResult& c = expect_status(results, "datagram.ok-before-reply", Status::kFail);
    EXPECT_NE(c.message.find("no Datagram Received OK or Rejected for"), std::string::npos)
        << c.message;
    expect_status(results, "datagram.reply-pending", Status::kSkip);
    // Update Complete has no reply: unanswerable by such a node, so it is the same cause.
    const CheckResult& u = expect_status(results, "memory.update-complete", Status::kSkip);
    EXPECT_NE(u.message.find("depends on datagram.ok-before-reply"), std::string::npos)
        << u.message;
}

}  // namespace
}  // namespace olcb::conform
