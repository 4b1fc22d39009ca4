// The node and link entries of the registry: produced by the node run's phases, never by a check.
#include <gtest/gtest.h>

#include <vector>

#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/checks_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

TEST(NodeChecksTest, EntriesAreRunPhasesInTheRegistryOfTheirCategory) {
    const std::vector<CheckSpec> specs = checks::node_checks();
    ASSERT_EQ(specs.size(), 3u);
    for (const CheckSpec& s : specs) {
        EXPECT_EQ(s.run, nullptr) << s.id;  // a phase of the run reports it
        const CheckSpec* found = find_check(s.id);
        ASSERT_NE(found, nullptr) << s.id;
        EXPECT_EQ(found->order, s.order) << s.id;
    }
    EXPECT_EQ(find_check("node.rebooted")->category, Category::kNode);
    EXPECT_EQ(find_check("node.stopped-answering")->strength, Strength::kShall);
    EXPECT_EQ(find_check("link.lost")->strength, Strength::kRun);  // the run, not the node
}

TEST(NodeChecksTest, AProtocolRunOnAHealthyNodeReportsNoneOfThem) {
    const auto results = testing::protocol_results();
    ASSERT_FALSE(results.empty());
    for (const char* id : {"node.rebooted", "node.stopped-answering", "link.lost"}) {
        EXPECT_EQ(testing::find_check(results, id), nullptr) << id;
    }
}

}  // namespace
}  // namespace olcb::conform
