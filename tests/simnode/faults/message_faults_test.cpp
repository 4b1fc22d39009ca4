// The message faults: unsolicited-traffic and duplicate-id-silent.
#include <gtest/gtest.h>

#include "simnode/faults/fault_test_util.hpp"

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, UnsolicitedTraffic) {
    start_with({"unsolicited-traffic"});
    take();
    net_.run_for(3500ms);
    EXPECT_EQ(count_prefix(take(), ":X19490343N"), 3u);
}

TEST_F(SimNodeRulesTest, DuplicateIdSilentSendsNoPcer) {
    start_with({"duplicate-id-silent"});
    take();
    send_text(":X19170456N050101012200;");
    send_text(":X10701457N050101012200;");
    net_.run_for(2s);
    send_text(":X10701457N050101012200;");
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    send_addressed(0x488);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
}

}  // namespace
}  // namespace olcb::simnode::test
