// ClientAudit: frames judged by their direction (the message.unknown-mti rule is its own), what
// a client that left keeps open judged after the grace, the deadlines it reports, and nothing
// judged after the end of the run.
#include "simnode/audit/client_audit.hpp"

#include <gtest/gtest.h>

#include <map>

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

// OpenLCB_Java's RestoreConfig then BackupConfig, each on its own connection with alias 0xC22:
// the second takes up the alias within the first's grace.
TEST_F(ClientAuditTest, AnAliasTakenUpByANewConnectionIsAnotherClient) {
    constexpr std::uint64_t kSecond = 2;
    audit_.name_connection(kSecond, "127.0.0.1:50001", ConnectionKind::kHubClient);
    login();
    client_datagram(write_cmd(0xFD, 0, {1}));  // a write, and no Update Complete
    node_ok(0);
    audit_.on_disconnect(kConnection, now_);
    advance(500ms);
    EXPECT_THAT(rules_found(), IsEmpty());

    reserve(kClientAlias, kClientId, kSecond);
    // The restore's open write is judged now, under its own connection.
    const auto open = found(RuleId::kMemoryNoUpdateComplete);
    ASSERT_EQ(open.size(), 1u);
    EXPECT_EQ(open[0].client.connection, kConnection);
    // The new client starts Uninitialized: a message before its Initialization Complete counts.
    client(":X1949012CN;", kSecond);  // Verify Node ID Global
    const auto early = found(RuleId::kMessageBeforeInitComplete);
    ASSERT_EQ(early.size(), 1u);
    EXPECT_EQ(early[0].client.connection, kSecond);

    initialized(kClientAlias, kClientId, kSecond);
    client_datagram(read_cmd(0xFD, 0, 8), kClientAlias, kSecond);  // the backup only reads
    node_ok();
    node_datagram({0x20, 0x51, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0});
    client_ok();
    advance(kDisconnectGrace);
    audit_.on_disconnect(kSecond, now_);
    finish();
    EXPECT_EQ(found(RuleId::kMemoryNoUpdateComplete).size(), 1u);
    EXPECT_THAT(rules_found(),
                ElementsAre("memory.no-update-complete", "message.before-init-complete"));
}

TEST_F(ClientAuditTest, AnAliasAnotherLiveConnectionAlsoUsesKeepsItsState) {
    constexpr std::uint64_t kSecond = 2;
    audit_.name_connection(kSecond, "127.0.0.1:50001", ConnectionKind::kHubClient);
    login();
    client_datagram(write_cmd(0xFD, 0, {1}));
    node_ok(0);
    client(":X1949012CN;", kSecond);  // the same alias on a connection still open: no hand-over
    EXPECT_THAT(found(RuleId::kMemoryNoUpdateComplete), IsEmpty());
    EXPECT_THAT(found(RuleId::kMessageBeforeInitComplete), IsEmpty());
}

// `simnode ctl add`: a node the audit learns while it runs is audited as one of the start's.
class AddedNodeTest : public AuditScript {
protected:
    static constexpr NodeId kAddedId{0x05'01'01'01'22'20ull};
    static constexpr std::uint16_t kAddedAlias = 0x7A1;

    // The default node's CDI and spaces under another ID, as `ctl add` with its CDI makes it.
    static NodeProfile added_profile() {
        const NodeProfile& d = default_profile();
        std::map<std::uint8_t, SpaceShape> spaces;
        for (const std::uint8_t sp : {std::uint8_t{0xFD}, std::uint8_t{0xFF}})
            spaces[sp] = *d.space(sp);
        std::string error;
        return NodeProfile(kAddedId, load_cdi_model(simnode::test::default_cdi(), error),
                           std::move(spaces));
    }
    // The added node logs in (AMD, Initialization Complete) and the client reads from it.
    void start_added_and_read() {
        node(":X107017A1N050101012220;");
        node(":X191007A1N050101012220;");
        login();
        client(":X1A7A112CN20410000000008;");  // read 8 bytes of 0xFD
        node(":X19A287A1N012C80;");
        node(":X1A12C7A1N2051000000000000;");  // its reply
        advance(20ms);
        client(":X19A2812CN07A1;");  // acknowledged 20 ms later
    }
};

TEST_F(AddedNodeTest, ItsRepliesAreAcknowledgedAndItsWritesJudged) {
    audit_.add_node(added_profile());
    start_added_and_read();
    client_datagram(write_cmd(0xFD, 1, {0x07, 0xD0}));  // to 0x343, the scenario's node
    node_ok(0);
    client(":X1A7A112CN200100000001FC18;");  // Trim -1000 to the added node: in range
    node(":X19A287A1N012C;");
    client(":X1A7A112CN20010000000107D0;");  // Trim 2000 to the added node
    node(":X19A287A1N012C;");
    advance(5s);
    const auto f = found(RuleId::kCdiIntOutOfRange);
    ASSERT_EQ(f.size(), 2u) << ::testing::PrintToString(rules_found());
    ASSERT_TRUE(f[1].node);
    EXPECT_EQ(f[1].node->node_id, kAddedId);
    EXPECT_EQ(f[1].node->alias, kAddedAlias);
    EXPECT_THAT(found(RuleId::kDatagramReplyUnacknowledged), IsEmpty());
}

// Before the fix a node the audit did not know had its replies held against the client, whose
// acknowledgements went nowhere: none is judged now.
TEST_F(AddedNodeTest, ANodeTheAuditDoesNotKnowIsNotJudgedAtAll) {
    start_added_and_read();
    client(":X1A7A112CN20010000000107D0;");
    advance(5s);
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(AddedNodeTest, ANodeAddedAgainWithTheSameIdReplacesTheFirst) {
    audit_.add_node(added_profile());
    // Removed and added again: no CDI now, and 8 bytes of 0xFD.
    audit_.add_node(NodeProfile(kAddedId, nullptr, {{0xFD, SpaceShape{8, false}}}));
    start_added_and_read();
    client(":X1A7A112CN20010000000107D0;");  // Trim 2000: no CDI says what byte 1 is now
    node(":X19A287A1N012C;");
    client(":X1A7A112CN2001000000070102;");  // 2 bytes at 7: past the end of the 8
    node(":X19A487A1N012C1082;");
    EXPECT_THAT(found(RuleId::kCdiIntOutOfRange), IsEmpty());
    const auto f = found(RuleId::kMemoryWritePastEnd);
    ASSERT_EQ(f.size(), 1u);
    ASSERT_TRUE(f[0].node);
    EXPECT_EQ(f[0].node->node_id, kAddedId);
}

}  // namespace
}  // namespace olcb::simnode::audit::test
