// DatagramWatch (the datagram and request/reply rules of the client audit), as frame scripts on
// a simulated clock: frame sequences, one datagram at a time, resends, reply acknowledgements,
// requests before replies (memory configuration, SNIP).
#include <gtest/gtest.h>

#include "audit_script.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

class DatagramRules : public AuditScript {
protected:
    DatagramRules() { login(); }

    // The CDI read of the fact sheet: 64 bytes of 0xFF at 0.
    void read_cdi() { client(":X1A34312CN20430000000040;"); }
    // The node's reply to it (fewer bytes: the audit does not look into them).
    void cdi_reply() { node_datagram({0x20, 0x53, 0, 0, 0, 0, '<', '?', 'x', 'm', 'l'}); }
    // A datagram of no known protocol (lcc-conform's datagram.unknown-protocol).
    const std::vector<std::uint8_t> odd_ = {0x5A, 1, 2, 3};
};

TEST_F(DatagramRules, AReadAnsweredRepliedAndAcknowledgedIsClean) {
    read_cdi();
    advance(2ms);
    node_ok();
    cdi_reply();
    advance(2ms);
    client_ok();
    read_cdi();  // the next one after the reply
    node_ok();
    cdi_reply();
    client_ok();
    advance(5s);
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, AMiddleOrLastFrameWithoutAFirstIsAFinding) {
    client(":X1D34312CN01;");  // a lone last frame
    client(":X1C34312CN02;");  // a lone middle frame
    const auto f = found(RuleId::kDatagramFrameSequence);
    ASSERT_EQ(f.size(), 1u);  // one finding, counted twice
    EXPECT_EQ(f[0].count, 2u);
    EXPECT_THAT(f[0].frames, ElementsAre(":X1D34312CN01;"));
}

TEST_F(DatagramRules, AFirstFrameCuttingOffAnotherDatagramIsAFinding) {
    client(":X1B34312CN2043000000000000;");  // a first frame, never finished
    client(":X1B34312CN5A01020304050607;");  // a whole 2-frame datagram cuts in
    client(":X1D34312CN08;");
    const auto f = found(RuleId::kDatagramFrameSequence);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_THAT(f[0].frames,
                ElementsAre(":X1B34312CN2043000000000000;", ":X1B34312CN5A01020304050607;"));
    // The node may drop the datagram that cut in: the next one is no overlap.
    node(":X19A48343N012C2042;");
    client_datagram(odd_);
    EXPECT_THAT(rules_found(), ElementsAre("datagram.frame-sequence"));
}

TEST_F(DatagramRules, AnEmptyMiddleFrameAndMoreThan72BytesAreFindings) {
    client(":X1B34312CN2043000000000000;");
    client(":X1C34312CN;");
    EXPECT_THAT(rules_found(), ElementsAre("datagram.frame-sequence"));
    client(":X1B34312CN0000000000000000;");
    for (int i = 0; i < 9; ++i) client(":X1C34312CN0000000000000000;");  // 80 bytes
    const auto f = found(RuleId::kDatagramFrameSequence);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 2u);
}

TEST_F(DatagramRules, ASecondDatagramBeforeTheFirstIsAnsweredIsAnOverlap) {
    read_cdi();
    advance(10ms);
    client_datagram(odd_);
    const auto f = found(RuleId::kDatagramOverlap);
    ASSERT_EQ(f.size(), 1u);
    ASSERT_TRUE(f[0].node);
    EXPECT_EQ(f[0].node->node_id, kNodeId);
    EXPECT_THAT(f[0].frames, ElementsAre(":X1A34312CN20430000000040;", ":X1A34312CN5A010203;"));
}

TEST_F(DatagramRules, AfterTheRequesterTimeoutTheClientMayGoOn) {
    read_cdi();
    advance(3s);
    client_datagram(odd_);
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, TheSameDatagramBeforeAnyAnswerIsAResendWithoutReject) {
    read_cdi();
    advance(100ms);
    read_cdi();
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-without-reject"));
}

TEST_F(DatagramRules, AResendAfterATemporaryRejectIsAllowed) {
    read_cdi();
    node(":X19A48343N012C2020;");  // buffer unavailable: resend OK
    advance(100ms);
    read_cdi();
    node_ok();
    cdi_reply();
    client_ok();
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, AResendAfterAPermanentRejectIsAFinding) {
    client_datagram(read_cmd(0x50, 0, 8));  // an unknown space
    node(":X19A48343N012C1081;");
    client_datagram(read_cmd(0x50, 0, 8));
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-after-permanent"));
}

TEST_F(DatagramRules, ARejectWithoutATypeFlagForbidsNothing) {
    client_datagram(odd_);
    node(":X19A48343N012C;");  // no error code: its bits read as 0, neither flag set
    client_datagram(odd_);
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, SixResendsWithinASecondAreARetryStorm) {
    read_cdi();
    for (int i = 0; i < 6; ++i) {
        node(":X19A48343N012C2020;");
        advance(50ms);
        read_cdi();
    }
    const auto f = found(RuleId::kDatagramRetryStorm);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("6 resends"), std::string::npos) << f[0].message;
}

TEST_F(DatagramRules, ResendsThatPauseForTheNodeAreNoStorm) {
    read_cdi();
    for (int i = 0; i < 10; ++i) {
        node(":X19A48343N012C2020;");
        advance(250ms);
        read_cdi();
    }
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, TheSameRequestAfterReplyPendingBeforeTheReplyIsAResendAfterOk) {
    read_cdi();
    node_ok();
    advance(500ms);
    read_cdi();
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-after-ok"));
}

TEST_F(DatagramRules, TheSameRequestWithinThreeSecondsIsAResendAfterOkThereafterAllowed) {
    read_cdi();
    node_ok();
    advance(2999ms);
    read_cdi();
    node_ok();
    advance(3s);
    read_cdi();
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-after-ok"));
}

// OpenLCB_Java reads N = 1 as `1 << 1000` ms and resends after ~270 ms (real-world.md §7).
TEST_F(DatagramRules, TheSameRequestBeforeThePromisedTimeIsAResendBeforeTimeout) {
    read_cdi();
    advance(2ms);
    node_ok(0x81);  // the reply within 2^1 s
    advance(270ms);
    read_cdi();
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-before-timeout"));
    const auto f = found(RuleId::kDatagramResendBeforeTimeout);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("270 ms"), std::string::npos) << f[0].message;  // from the OK
    EXPECT_NE(f[0].message.find("flags 0x81"), std::string::npos) << f[0].message;
    EXPECT_NE(f[0].message.find("2^1 s = 2 s"), std::string::npos) << f[0].message;
    EXPECT_EQ(f[0].frames.size(), 2u);  // the read and its resend
    EXPECT_EQ(rule(f[0].rule).level, Level::kError);
}

// A promise longer than 3 s does not stretch the 3 s any requester may time out after.
TEST_F(DatagramRules, APromiseOfMoreThanThreeSecondsIsJudgedAtThreeSeconds) {
    read_cdi();
    node_ok(0x83);  // the reply within 2^3 s
    advance(2900ms);
    read_cdi();
    EXPECT_THAT(rules_found(), ElementsAre("datagram.resend-before-timeout"));
    node_ok(0x83);
    advance(3100ms);
    read_cdi();
    EXPECT_EQ(found(RuleId::kDatagramResendBeforeTimeout)[0].count, 1u);
}

TEST_F(DatagramRules, AResendAfterTheReplyCameIsNoResendBeforeTimeout) {
    read_cdi();
    node_ok(0x81);
    cdi_reply();
    client_ok();
    read_cdi();  // asked again on purpose, e.g. to compare
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, AnotherRequestAfterReplyPendingBeforeTheReplyIsANote) {
    read_cdi();
    node_ok();
    client_datagram(read_cmd(0xFD, 0, 8));
    const auto f = found(RuleId::kMemoryRequestBeforeReply);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].frames.size(), 2u);
    // No clause forbids it once the OK came (DatagramTransportS §6.1).
    EXPECT_EQ(rule(f[0].rule).level, Level::kNote);
}

TEST_F(DatagramRules, OnceTheAnnouncedTimeHasPassedTheClientMayAskAgain) {
    read_cdi();
    node_ok(0x81);  // the reply within 2^1 s
    advance(1900ms);
    EXPECT_TRUE(audit_.next_deadline().has_value());
    advance(200ms);
    read_cdi();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, AReplyThatCameBeforeItsOkLeavesNothingPending) {
    // simnode's no-datagram-ack fault: the reply first, then the OK with Reply Pending.
    read_cdi();
    cdi_reply();
    client_ok();
    node_ok();
    client_datagram(read_cmd(0xFD, 0, 8));
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, AReplyNotAcknowledgedWithin3sIsAFinding) {
    read_cdi();
    node_ok();
    cdi_reply();
    advance(2900ms);
    EXPECT_THAT(rules_found(), IsEmpty());
    advance(200ms);
    const auto f = found(RuleId::kDatagramReplyUnacknowledged);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].frames.size(), 2u);  // the reply's first and last frame
    EXPECT_NE(f[0].message.find("within 3 s"), std::string::npos) << f[0].message;
}

TEST_F(DatagramRules, AReplyLeftUnacknowledgedByAClientThatDisconnectsIsAFinding) {
    read_cdi();
    node_ok();
    cdi_reply();
    audit_.on_disconnect(kConnection, now_);
    advance(2100ms);  // the grace a paced bus needs
    const auto f = found(RuleId::kDatagramReplyUnacknowledged);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("connection ended"), std::string::npos) << f[0].message;
}

TEST_F(DatagramRules, AnAcknowledgementLaterThan750msIsLate) {
    read_cdi();
    node_ok();
    cdi_reply();
    advance(900ms);
    client_ok();
    advance(5s);
    EXPECT_THAT(rules_found(), ElementsAre("datagram.reply-ack-late"));
}

TEST_F(DatagramRules, ARejectOfTheReplyAnswersIt) {
    read_cdi();
    node_ok();
    cdi_reply();
    client(":X19A4812CN03432020;");  // the client is busy: the node resends
    advance(5s);
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, ANodeThatRestartsVoidsItsPendingExchanges) {
    read_cdi();
    node_ok();
    cdi_reply();
    node(":X19100343N050101012200;");  // Initialization Complete: the reply is dropped
    advance(5s);
    client_datagram(odd_);
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(DatagramRules, ASnipRequestBeforeTheWholeReplyCameIsAFinding) {
    client(":X19DE812CN0343;");
    node(":X19A08343N112C0441434D4520;");  // first frame of the reply
    client(":X19DE812CN0343;");
    EXPECT_THAT(rules_found(), ElementsAre("snip.request-before-reply"));
}

TEST_F(DatagramRules, ASnipRequestAfterTheLastFrameOrAfter3sIsClean) {
    client(":X19DE812CN0343;");
    node(":X19A08343N112C0441434D4520;");
    node(":X19A08343N212C6E636800;");  // last frame
    client(":X19DE812CN0343;");
    advance(3s);
    client(":X19DE812CN0343;");
    EXPECT_THAT(rules_found(), IsEmpty());
}

}  // namespace
}  // namespace olcb::simnode::audit::test
