// The ACDI checks: space 251's user name must be valid UTF-8, its bytes shown when it is not.
#include <gtest/gtest.h>

#include <string>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/report_test_util.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::expect_status;
using testing::kFffd;

TEST(AcdiUtf8, AnInvalidUserNameInSpace251Fails) {
    // What `simnode --user-name $'bad\xff\xfename'` serves: the bytes in 251 and in SNIP.
    simnode::NodeConfig cfg;
    cfg.node_id = kDut;
    cfg.cdi = testing::default_cdi();
    cfg.user_name = "bad\xff\xfename";
    std::string error;
    auto bench = testing::SimBench::serve(cfg, error);
    ASSERT_TRUE(bench) << error;
    CheckContext ctx;
    const auto results = bench->run(ctx);
    const CheckResult& acdi = expect_status(results, "acdi.utf8", Status::kFail);
    EXPECT_EQ(acdi.seen, std::string("space 251 @1 user name \"bad") + kFffd + kFffd +
                             "name\" (bytes 62 61 64 FF FE 6E 61 6D 65)");
    const CheckResult& snip = expect_status(results, "snip.utf8", Status::kWarn);
    EXPECT_NE(snip.seen.find("(bytes 62 61 64 FF FE 6E 61 6D 65)"), std::string::npos);
    // The same bytes on both sides: the strings still match.
    expect_status(results, "snip.matches-acdi", Status::kPass);
}

}  // namespace
}  // namespace olcb::conform
