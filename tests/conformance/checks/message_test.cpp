// The message checks: Verify Node ID answered, unknown addressed MTIs rejected, nothing
// unsolicited.
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

TEST(MessageChecksTest, DefaultNodePassesEach) {
    const auto results = testing::protocol_results();
    testing::expect_each(
        results,
        {"message.verify-global", "message.verify-addressed", "message.oir-unknown-mti",
         "message.unknown-global-ignored", "message.no-unsolicited", "message.pip-answered"},
        Status::kPass);
}

TEST(MessageChecksTest, UnsolicitedTrafficWarns) {
    const auto results = testing::protocol_results({"unsolicited-traffic"});
    expect_status(results, "message.no-unsolicited", Status::kWarn);
    expect_status(results, "message.verify-global", Status::kPass);  // only that one is judged
}

}  // namespace
}  // namespace olcb::conform
