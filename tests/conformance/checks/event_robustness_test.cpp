// The event robustness checks: PCERs with payload and Learn Event never upset the node.
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
using testing::SimBench;

TEST(EventRobustnessTest, DefaultAndIoBoardNodesTolerateBoth) {
    for (const char* file : {"default.xml", "io-board.xml"}) {
        SimBench b({}, read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / file));
        auto node = b.start();
        ASSERT_TRUE(node) << file;
        CheckContext ctx;
        ProtocolOptions o;
        o.selection.thorough = true;  // Learn Event only then: a node in learn mode keeps it
        o.selection.only = {"events.*"};
        const auto results = run_protocol_checks(*b.session, *node, o, ctx);
        for (const char* id : {"events.pcer-payload-tolerated", "events.learn-tolerated"}) {
            const CheckResult& c = expect_status(results, id, Status::kPass);
            EXPECT_EQ(c.category, Category::kEvents) << file;
        }
    }
}

TEST(EventRobustnessTest, LearnEventIsSentOnlyWithThorough) {
    const auto results = testing::protocol_results();
    expect_status(results, "events.pcer-payload-tolerated", Status::kPass);
    EXPECT_EQ(testing::find_check(results, "events.learn-tolerated"), nullptr);
}

}  // namespace
}  // namespace olcb::conform
