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

TEST(DatagramChecksTest, ANodeThatNeverAcksWarnsOnlyTheOrderOfTheTechnicalNote) {
    const auto results = testing::protocol_results({"no-datagram-ack"});
    const CheckResult& c = expect_status(results, "datagram.ok-before-reply", Status::kWarn);
    EXPECT_NE(c.message.find("before its Datagram Received OK"), std::string::npos) << c.message;
}

}  // namespace
}  // namespace olcb::conform
