// ClientAudit: frames judged by their direction (the message.unknown-mti rule is its own), what
// a client that left keeps open judged after the grace, the deadlines it reports, and nothing
// judged after the end of the run.
#include "simnode/audit/client_audit.hpp"

#include <gtest/gtest.h>

#include "audit_script.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST_F(AliasRules, AnUnallocatedMtiIsAFindingPerMti) {
    login();
    client(":X194F912CN0343;");  // addressed 0x04F9 (lcc-conform's message.oir-unknown-mti)
    client(":X194F912CN0343;");
    client(":X1993012CN;");  // global 0x0930 (message.unknown-global-ignored)
    const auto f = found(RuleId::kMessageUnknownMti);
    ASSERT_EQ(f.size(), 2u);
    EXPECT_EQ(f[0].count, 2u);
    EXPECT_NE(f[0].message.find("0x04F9"), std::string::npos) << f[0].message;
    ASSERT_TRUE(f[0].node);
    EXPECT_NE(f[1].message.find("0x0930"), std::string::npos) << f[1].message;
}

TEST_F(AliasRules, EventReportWithPayloadFramesAndReservedFormatsAreJudgedRight) {
    login();
    client(":X19F1612CN0101000000000001;");  // PCER with payload, first frame
    client(":X19F1512CN0102030405060708;");  // middle
    client(":X19F1412CN09;");                // last
    EXPECT_THAT(rules_found(), IsEmpty());
    client(":X1E34312CN00;");  // format 6 is reserved
    EXPECT_THAT(rules_found(), ElementsAre("message.unknown-mti"));
}

TEST_F(AliasRules, StandardAndRemoteFramesAreNotJudged) {
    client(":S123N0102;");
    client(":X1949012CR;");
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

class ClientAuditTest : public AuditScript {
protected:
    // A node datagram the client has not acknowledged (the CDI read's reply).
    void leave_reply_unacknowledged() {
        login();
        client_datagram(read_cmd(0xFF, 0, 64));
        node_ok();
        node_datagram({0x20, 0x53, 0, 0, 0, 0, '<', '?', 'x', 'm', 'l'});
    }
};

TEST_F(ClientAuditTest, ANodesOwnFramesAreNeverJudgedAsAClients) {
    node(":X194F9343N012C;");  // an unallocated MTI, from the node
    node(":X1949012CN;");      // the client's alias, but sent by a node: no client frame
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(ClientAuditTest, WhatALeavingClientKeptOpenIsJudgedAfterTheGraceOnly) {
    leave_reply_unacknowledged();
    audit_.on_disconnect(kConnection, now_);
    EXPECT_EQ(audit_.next_deadline(), now_ + kDisconnectGrace);
    advance(kDisconnectGrace - 1ms);
    EXPECT_THAT(found(RuleId::kDatagramReplyUnacknowledged), IsEmpty());
    advance(1ms);
    EXPECT_EQ(found(RuleId::kDatagramReplyUnacknowledged).size(), 1u);
}

TEST_F(ClientAuditTest, NothingIsJudgedAfterFinish) {
    EXPECT_FALSE(audit_.finished());
    finish();
    EXPECT_TRUE(audit_.finished());
    client(":X1949012CN;");  // from an alias never reserved
    audit_.on_disconnect(kConnection, now_);
    advance(kDisconnectGrace);
    EXPECT_THAT(rules_found(), IsEmpty());
    EXPECT_EQ(audit_.next_deadline(), std::nullopt);
}

TEST_F(ClientAuditTest, FinishJudgesALeavingClientWithoutWaitingForTheGrace) {
    leave_reply_unacknowledged();
    audit_.on_disconnect(kConnection, now_);
    EXPECT_THAT(rules_found(), IsEmpty());
    finish();
    EXPECT_EQ(found(RuleId::kDatagramReplyUnacknowledged).size(), 1u);
}

}  // namespace
}  // namespace olcb::simnode::audit::test
