// The message checks: Verify Node ID answered, unknown addressed MTIs rejected, nothing unsolicited.
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

TEST(MessageChecksTest, DefaultNodePassesEach) {
    SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    for (const char* id : {"message.verify-global", "message.verify-addressed",
                           "message.oir-unknown-mti", "message.unknown-global-ignored",
                           "message.no-unsolicited", "message.pip-answered"}) {
        expect_status(results, id, Status::kPass);
    }
}

TEST(MessageChecksTest, UnsolicitedTrafficWarns) {
    SimBench b({"unsolicited-traffic"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "message.no-unsolicited", Status::kWarn);
    expect_status(results, "message.verify-global", Status::kPass);  // only that one is judged
}

}  // namespace
}  // namespace olcb::conform
