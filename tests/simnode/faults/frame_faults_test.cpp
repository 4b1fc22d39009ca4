// The frame faults: alias-conflict-ignored, burst-drops and answers-standard-frames, as stack
// hooks installed by ActiveFaults on a NodeStack of their own (frames as GridConnect strings) and
// on a whole SimNode against the good node.
#include <gtest/gtest.h>

#include "openlcb/node_test_util.hpp"
#include "simnode/faults/fault_hooks.hpp"
#include "simnode/faults/fault_test_util.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using namespace std::chrono_literals;
using Strings = std::vector<std::string>;

const std::string kVerified = ":X19170343N050101012200;";

class FrameFaultsTest : public olcb::test::StackFixture {
protected:
    void attach(const std::string& names) { ActiveFaults(test::faults_of({names})).attach(stack_); }
};

TEST_F(FrameFaultsTest, AliasConflictIgnoredIgnoresCidAndConflictOnItsActiveAlias) {
    attach("alias-conflict-ignored");
    boot();
    inject(":X17050343N;", 10ms);
    EXPECT_TRUE(take().empty());
    inject(":X19170343N020000000001;", 1s);
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(stack_.alias(), 0x343);
    EXPECT_TRUE(stack_.initialized());
    inject(":X19490AAAN;", 10ms);  // still answers
    EXPECT_EQ(take(), (Strings{kVerified}));
}

TEST_F(FrameFaultsTest, AliasConflictIgnoredStillRestartsReservationOnTentativeConflict) {
    attach("alias-conflict-ignored");
    stack_.start(net_.now());
    inject(":X17050343N;", 10ms);  // during reservation the fault changes nothing
    net_.run_for(1s);
    EXPECT_NE(stack_.alias(), 0x343);
    EXPECT_TRUE(stack_.initialized());
}

TEST_F(FrameFaultsTest, BurstDropsAddressedMessagesWhileMoreThan16OtherFramesIn10Ms) {
    attach("burst-drops");
    boot();
    net_.run_for(20ms);
    for (int i = 0; i < 16; ++i) port_.send(olcb::test::gc(":X198F4456N0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified}) << "16 frames of another source: no burst";
    port_.send(olcb::test::gc(":X198F4456N0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_TRUE(take().empty()) << "17 frames of another source within 10 ms";
    inject(":X19490456N;");
    EXPECT_EQ(take(), Strings{kVerified}) << "global messages still answered";
    net_.run_for(10ms);
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified}) << "10 ms later the burst is over";
}

TEST_F(FrameFaultsTest, BurstDropsCountsNotTheRequestersOwnQuickTraffic) {
    attach("burst-drops");
    boot();
    net_.run_for(20ms);
    for (int i = 0; i < 40; ++i) port_.send(olcb::test::gc(":X198F412CN0909090909090909;"));
    inject(":X1948812CN0343;");
    EXPECT_EQ(take(), Strings{kVerified});
}

TEST_F(FrameFaultsTest, AnswersStandardFramesWithVerifiedNodeId) {
    attach("answers-standard-frames");
    boot();
    inject(":S123N0102;");
    inject(":S7FFN;");
    EXPECT_EQ(take(), (Strings{kVerified, kVerified}));
    inject(":S123R;");
    EXPECT_TRUE(take().empty()) << "remote frames stay ignored";
}

TEST_F(FrameFaultsTest, NoFaultInstallsNoHook) {
    attach("snip-mismatch");
    boot();
    inject(":X17050343N;");
    EXPECT_EQ(take(), Strings{":X10700343N;"}) << "the alias is defended";
    inject(":S123N0102;");
    EXPECT_TRUE(take().empty());
}

}  // namespace
}  // namespace olcb::simnode

namespace olcb::simnode::test {
namespace {

TEST_F(FaultTest, GoodNodeDefendsItsAlias) {
    start(default_config());
    take();
    send_text(":X17050343N;");  // someone checks our alias
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X10700343N;"});
    send_text(":X19170343N020000000001;");  // someone uses it
    net_.run_for(10ms);
    const auto frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames[0], ":X10703343N050101012200;");
}

TEST_F(FaultTest, AliasConflictIgnored) {
    start_with({"alias-conflict-ignored"});
    take();
    send_text(":X17050343N;");
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    send_text(":X19170343N020000000001;");
    net_.run_for(1s);
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(alias(), 0x343);
    EXPECT_TRUE(node_->stack().initialized());
}

TEST_F(SimNodeRulesTest, AnswersStandardFramesWithVerifiedNodeId) {
    start_with({"answers-standard-frames"});
    take();
    send_text(":S123N0102;");
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
}

TEST_F(SimNodeRulesTest, BurstDropsLosesAddressedMessagesInABurst) {
    start_with({"burst-drops"});
    take();
    // Frames from a third party (another alias than the Verify's): what fills a receive buffer.
    auto noise = [&] {
        port_.send(can::make_frame(can::message_header(0x8F4, 0x456),
                                   std::vector<std::uint8_t>{9, 9, 9, 9, 9, 9, 9, 9}));
    };
    verify_in_burst(300, [&](std::size_t) { noise(); });
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    net_.run_for(20ms);
    // 16 frames of another source within 10 ms: not a burst yet.
    for (int i = 0; i < 16; ++i) noise();
    send_addressed(0x488);
    net_.run_for(20ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
    // 17 of them: dropped.
    for (int i = 0; i < 17; ++i) noise();
    send_addressed(0x488);
    net_.run_for(20ms);
    EXPECT_TRUE(take().empty());
    send_addressed(0x488);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"}) << "quiet again";
    // The requester's own quick traffic is no burst.
    for (int i = 0; i < 40; ++i) send_global(0x8F4, {9, 9, 9, 9, 9, 9, 9, 9});
    send_addressed(0x488);
    net_.run_for(20ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
}

}  // namespace
}  // namespace olcb::simnode::test
