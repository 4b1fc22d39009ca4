// A run of the protocol checks: each result's ID is in the registry once, in its category, and a
// selection runs only its checks (which still ask for what they need).
#include "conformance/checks/check_run.hpp"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "conformance/checks/check_registry.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

TEST(CheckRunTest, IdsAreUniqueInADefaultNodesProtocolChecks) {
    testing::SimBench b;
    CheckContext ctx;
    auto results = b.run(ctx);
    ASSERT_FALSE(results.empty());
    std::set<std::string> ids;
    for (const CheckResult& r : results) {
        EXPECT_TRUE(ids.insert(r.id).second) << "duplicate " << r.id;
        const CheckSpec* spec = find_check(r.id);
        ASSERT_NE(spec, nullptr) << r.id << " is not in the registry";
        EXPECT_EQ(r.category, spec->category) << r.id;
    }
}

TEST(CheckRunTest, OnlyRunsTheSelectedChecks) {
    testing::SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    CheckContext ctx;
    ProtocolOptions o;
    o.selection.only = {"pip.*"};
    const std::size_t frames = b.session->frame_mark();
    auto results = run_protocol_checks(*b.session, *node, o, ctx);
    ASSERT_FALSE(results.empty());
    for (const CheckResult& r : results) EXPECT_TRUE(r.id.starts_with("pip.")) << r.id;
    // The PIP checks still judge: they asked what they needed (SNIP, Options, the CDI).
    for (const CheckResult& r : results) EXPECT_EQ(r.status, Status::kPass) << r.id << r.message;
    EXPECT_GT(b.session->frame_mark(), frames);
}

}  // namespace
}  // namespace olcb::conform
