// The SNIP checks: snip.utf8 on node text that is not valid UTF-8, the bytes shown in hex.
#include <gtest/gtest.h>

#include <string>

#include "conformance/report_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::kFffd;

// SimpleNodeInformationS names no encoding (only CommonInformationTN does): a WARN that still
// names the field and its bytes; the FAIL is snip.matches-acdi's (251 holds the valid name).
TEST(SnipUtf8, TheFaultWarnsNamingTheFieldAndItsBytes) {
    testing::SimBench b({"snip-invalid-utf8"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    const CheckResult& c = expect_status(results, "snip.utf8", Status::kWarn);
    EXPECT_EQ(c.message, "user name is not valid UTF-8");
    EXPECT_EQ(c.expected, "valid UTF-8");
    EXPECT_EQ(c.seen, std::string("user name \"simnode default") + kFffd + kFffd +
                          "\" (bytes 73 69 6D 6E 6F 64 65 20 64 65 66 61 75 6C 74 FF FE)");
    // Space 251 holds the valid name: ACDI is fine, and SNIP disagrees with it.
    expect_status(results, "acdi.utf8", Status::kPass);
    expect_status(results, "snip.matches-acdi", Status::kFail);
}

TEST(SnipUtf8, AGoodNodePasses) {
    testing::SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "snip.utf8", Status::kPass);
    expect_status(results, "acdi.utf8", Status::kPass);
}

}  // namespace
}  // namespace olcb::conform
