// AliasWatch (the alias rules of the client audit: alias.unreserved, alias.rid-too-early, and
// message.before-init-complete), as frame scripts on a simulated clock.
#include <gtest/gtest.h>

#include "audit_script.hpp"

namespace olcb::simnode::audit::test {
namespace {

using ::testing::ElementsAre;
using ::testing::IsEmpty;

TEST_F(AliasRules, AReservedAndMappedClientIsClean) {
    login();
    client(":X1949012CN;");                // Verify Node ID global
    client(":X1982812CN0343;");            // Protocol Support Inquiry
    node(":X19668343N012C545800000000;");  // its reply
    client(":X1A34312CN20430000000040;");  // a CDI read
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(AliasRules, AMessageFromAnAliasNeverReservedIsAFinding) {
    client(":X1949012CN;");
    client(":X1949012CN;");
    const auto f = found(RuleId::kAliasUnreserved);
    ASSERT_EQ(f.size(), 1u);  // the same violation again only counts
    EXPECT_EQ(f[0].count, 2u);
    EXPECT_EQ(f[0].client.alias, kClientAlias);
    EXPECT_EQ(f[0].client.remote, "127.0.0.1:50000");
    EXPECT_THAT(f[0].frames, ElementsAre(":X1949012CN;"));
    EXPECT_NE(f[0].message.find("never reserved"), std::string::npos) << f[0].message;
}

TEST_F(AliasRules, AddressedTrafficNamesTheNodeItWentTo) {
    client(":X1982812CN0343;");
    const auto f = found(RuleId::kAliasUnreserved);
    ASSERT_EQ(f.size(), 1u);
    ASSERT_TRUE(f[0].node);
    EXPECT_EQ(f[0].node->node_id, kNodeId);
    EXPECT_EQ(f[0].node->alias, kNodeAlias);
}

TEST_F(AliasRules, MessagesBeforeRidOrAmdAndAfterAmrAreFindings) {
    for (int n = 7; n >= 4; --n)
        audit_.on_frame(can::make_cid(n, kClientId, kClientAlias), Direction::kFromClient,
                        kConnection, now_);
    client(":X1949012CN;");  // before RID
    advance(250ms);
    client(":X1070012CN;");  // RID
    client(":X1949012CN;");  // before AMD
    client(":X1070112CN02010D000001;");
    client(":X1910012CN02010D000001;");  // Initialization Complete
    client(":X1949012CN;");              // Permitted: fine
    client(":X1070312CN02010D000001;");  // AMR
    client(":X1949012CN;");              // after AMR
    const auto f = found(RuleId::kAliasUnreserved);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 3u);
    // The CID frames told the client's node ID.
    ASSERT_TRUE(f[0].client.node_id);
    EXPECT_EQ(*f[0].client.node_id, kClientId);
}

TEST_F(AliasRules, AnAmdForAnAliasNeverReservedIsAFinding) {
    // lcc-conform's frame.collision: an AMD from the node's alias with another node ID.
    client(":X10701343N050101013FFF;");
    EXPECT_THAT(rules_found(), ElementsAre("alias.unreserved"));
}

TEST_F(AliasRules, ACidForTheNodesAliasIsNoFindingAndTheNodesRidEndsIt) {
    // lcc-conform's frame.cid-defended: a CID7 with the node's alias; the node defends it.
    client(":X17050343N;");
    node(":X10700343N;");
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(AliasRules, ATakeoverOfADefendedAliasIsAFinding) {
    for (int n = 7; n >= 4; --n)
        audit_.on_frame(can::make_cid(n, kClientId, kNodeAlias), Direction::kFromClient,
                        kConnection, now_);
    node(":X10700343N;");  // the node holds 0x343: the reservation failed
    advance(250ms);
    client(":X10700343N;");
    client(":X10701343N02010D000001;");
    EXPECT_THAT(rules_found(), ElementsAre("alias.unreserved"));
}

TEST_F(AliasRules, ABridgedBusIsAssumedToHaveReservedItsAliasesBefore) {
    constexpr std::uint64_t kBridge = 7;  // never named: a bridge
    client(":X19490ABCN;", kBridge);
    client(":X10703ABCN050101010101;", kBridge);  // AMR: the bridged node leaves
    finish();
    EXPECT_THAT(found(RuleId::kAliasUnreserved), IsEmpty());
}

TEST_F(AliasRules, AnAliasIsFreeAgainOnceItsConnectionEnded) {
    login();
    audit_.on_disconnect(kConnection, now_);
    advance(3s);
    audit_.name_connection(2, "127.0.0.1:50001", ConnectionKind::kHubClient);
    client(":X1949012CN;", 2);  // another client taking the alias must reserve it itself
    EXPECT_THAT(rules_found(), ElementsAre("alias.unreserved"));
}

TEST_F(AliasRules, RidSoonerThan200msAfterTheLastCidIsAFinding) {
    for (int n = 7; n >= 4; --n)
        audit_.on_frame(can::make_cid(n, kClientId, kClientAlias), Direction::kFromClient,
                        kConnection, now_);
    advance(20ms);
    client(":X1070012CN;");  // python-openlcb sends RID at once
    client(":X1070112CN02010D000001;");
    client(":X1949012CN;");
    const auto f = found(RuleId::kAliasRidTooEarly);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_NE(f[0].message.find("20 ms"), std::string::npos) << f[0].message;
    // The reservation still counts: no unreserved traffic on top.
    EXPECT_THAT(found(RuleId::kAliasUnreserved), IsEmpty());
}

// A CID the hub read late makes a correct client's wait look short: within kArrivalJitter of
// 200 ms the audit gives the client the benefit of the doubt.
TEST_F(AliasRules, ARidThatLooksUpTo100msEarlyIsNoFinding) {
    for (int n = 7; n >= 4; --n)
        audit_.on_frame(can::make_cid(n, kClientId, kClientAlias), Direction::kFromClient,
                        kConnection, now_);
    advance(110ms);
    client(":X1070012CN;");
    client(":X1070112CN02010D000001;");
    EXPECT_THAT(found(RuleId::kAliasRidTooEarly), IsEmpty());
}

TEST_F(AliasRules, RidAfter200msIsClean) {
    login();
    EXPECT_THAT(rules_found(), IsEmpty());
}

// OpenLCB_Java: Verify Node ID Global between its AMD and its Initialization Complete.
TEST_F(AliasRules, AMessageBeforeTheClientsInitializationCompleteIsAFinding) {
    reserve();
    client(":X1949012CN;");  // Verify Node ID Global
    initialized();
    client(":X1949012CN;");
    client(":X1A34312CN20430000000040;");
    finish();
    EXPECT_THAT(rules_found(), ElementsAre("message.before-init-complete"));
    const auto f = found(RuleId::kMessageBeforeInitComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 1u);
    EXPECT_FALSE(f[0].node);  // a global message
    EXPECT_NE(f[0].message.find("Verify Node ID Global"), std::string::npos) << f[0].message;
    EXPECT_NE(f[0].message.find("02.01.0D.00.00.01"), std::string::npos) << f[0].message;
    EXPECT_EQ(rule(f[0].rule).level, Level::kError);
}

// python-openlcb's examples: datagrams, never an Initialization Complete. Counted per message,
// not per frame, and named with the node they went to.
TEST_F(AliasRules, DatagramsFromAClientThatNeverInitializedAreAFinding) {
    reserve();
    client_datagram(read_cmd(0xFF, 0, 64));
    node_ok();
    node_datagram({0x20, 0x53, 0, 0, 0, 0, '<', '?', 'x', 'm', 'l'});
    client_ok();                                                 // a message too
    client_datagram({0x5A, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11});  // two frames, one message
    node_ok(0);
    EXPECT_THAT(rules_found(), ElementsAre("message.before-init-complete"));
    const auto f = found(RuleId::kMessageBeforeInitComplete);
    ASSERT_EQ(f.size(), 1u);
    EXPECT_EQ(f[0].count, 3u);
    ASSERT_TRUE(f[0].node);
    EXPECT_EQ(f[0].node->node_id, kNodeId);
    EXPECT_NE(f[0].message.find("a datagram"), std::string::npos) << f[0].message;
}

TEST_F(AliasRules, ANewAliasOfAnInitializedClientNeedsNoSecondInitializationComplete) {
    login();
    client(":X1070312CN02010D000001;");  // AMR: gives 0x12C up
    reserve(0x12D);
    client(":X1949012DN;");
    finish();
    EXPECT_THAT(rules_found(), IsEmpty());
}

TEST_F(AliasRules, AClientThatConnectsAgainStartsUninitialized) {
    login();
    audit_.on_disconnect(kConnection, now_);
    advance(3s);
    audit_.name_connection(2, "127.0.0.1:50001", ConnectionKind::kHubClient);
    reserve(kClientAlias, kClientId, 2);
    client(":X1949012CN;", 2);
    EXPECT_THAT(rules_found(), ElementsAre("message.before-init-complete"));
}

TEST_F(AliasRules, UnreservedOrBridgedAliasesAreNotJudgedForInitialization) {
    client(":X1949012CN;");  // never reserved: alias.unreserved only
    constexpr std::uint64_t kBridge = 7;
    client(":X19490ABCN;", kBridge);  // on the bus before simnode joined it
    finish();
    EXPECT_THAT(rules_found(), ElementsAre("alias.unreserved"));
}

TEST_F(AliasRules, ABridgedNodeSeenReservingIsJudgedToo) {
    constexpr std::uint64_t kBridge = 7;
    reserve(0xABC, NodeId(0x05'01'01'01'01'01ull), kBridge);
    client(":X19490ABCN;", kBridge);
    EXPECT_THAT(rules_found(), ElementsAre("message.before-init-complete"));
}

}  // namespace
}  // namespace olcb::simnode::audit::test
