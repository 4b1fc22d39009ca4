// acdi.version-write-refused (conformance/checks/acdi_writes.cpp, OlcbChecker cd40) against the
// simulated node: refused on the well-behaved node, caught when the version byte takes writes,
// and the byte is the same afterwards either way.
#include <gtest/gtest.h>

#include "conformance/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::dump;
using testing::SimBench;

std::vector<CheckResult> run_acdi_writes(SimBench& b, const ProtocolOptions& options = {}) {
    auto node = b.start();
    if (!node) return {};
    CheckContext ctx;
    CheckRun run(*b.session, *node, options, ctx);
    for (const CheckSpec& spec : checks::acdi_write_checks()) run.run(spec);
    return run.take();
}

std::uint8_t version_byte(SimBench& b) {
    return b.dut->memory().read(0xFB, 0, 1).at(0);
}

TEST(AcdiWritesTest, DefaultNodeRefusesWith0x1083) {
    SimBench b;
    const auto results = run_acdi_writes(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].id, "acdi.version-write-refused");
    EXPECT_EQ(results[0].category, Category::kAcdi);
    EXPECT_EQ(results[0].status, Status::kPass) << dump(results);
    EXPECT_NE(results[0].message.find("refused with 0x1083"), std::string::npos);
    EXPECT_EQ(results[0].message.find("the standard gives"), std::string::npos);
    EXPECT_EQ(version_byte(b), 2);
}

TEST(AcdiWritesTest, WritableVersionByteFailsAndStaysTheSame) {
    SimBench b({"acdi-version-writable"});
    const auto results = run_acdi_writes(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kFail) << dump(results);
    EXPECT_EQ(results[0].seen, "accepted");
    EXPECT_NE(results[0].message.find("the byte is unchanged"), std::string::npos)
        << results[0].message;
    EXPECT_EQ(version_byte(b), 2);
}

TEST(AcdiWritesTest, AnotherRefusalCodePassesQuotingIt) {
    SimBench b({"readonly-0x1041"});
    const auto results = run_acdi_writes(b);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kPass) << dump(results);
    EXPECT_NE(results[0].message.find("refused with 0x1041 (the standard gives 0x1083)"),
              std::string::npos)
        << results[0].message;
}

TEST(AcdiWritesTest, ReadOnlySkips) {
    SimBench b({"acdi-version-writable"});
    ProtocolOptions o;
    o.read_only = true;
    const auto results = run_acdi_writes(b, o);
    ASSERT_EQ(results.size(), 1u) << dump(results);
    EXPECT_EQ(results[0].status, Status::kSkip);
    EXPECT_EQ(results[0].message, "--read-only");
}

}  // namespace
}  // namespace olcb::conform
