// AuditContext: the nodes and the aliases they hold, connections and the client aliases seen on
// them, and findings that name the client's connection, node ID and the node they concern.
#include "simnode/audit/audit_context.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <vector>

#include "openlcb/gridconnect.hpp"

namespace olcb::simnode::audit {
namespace {

using ::testing::UnorderedElementsAre;

const TimePoint kStart{};
const NodeId kNode(0x050101012200);
const NodeId kOther(0x050101012201);
const NodeId kClient(0x02010D000001);

NodeProfile bare(NodeId id) {
    return NodeProfile(id, nullptr, {});
}

TEST(AuditContext, NodesAreFoundByIdAndByTheAliasTheyHoldUntilReleased) {
    AuditContext ctx(kStart);
    ctx.add_node(bare(kNode));
    ctx.add_node(bare(kOther));
    EXPECT_EQ(ctx.node_index(kOther), 1u);
    EXPECT_EQ(ctx.node_index(kClient), std::nullopt);
    EXPECT_EQ(ctx.node_at(0x343), nullptr);
    ctx.set_node_alias(0x343, 0);
    ctx.set_node_alias(0x344, 1);
    ASSERT_NE(ctx.node_at(0x344), nullptr);
    EXPECT_EQ(ctx.node_at(0x344)->node_id(), kOther);
    ctx.release_node_alias(0x344);
    EXPECT_EQ(ctx.node_at(0x344), nullptr);
    EXPECT_EQ(ctx.node_at(0x343)->node_id(), kNode);
}

TEST(AuditContext, AConnectionNeverNamedIsABridge) {
    AuditContext ctx(kStart);
    ctx.name_connection(1, "127.0.0.1:50000", ConnectionKind::kHubClient);
    EXPECT_EQ(ctx.kind(1), ConnectionKind::kHubClient);
    EXPECT_EQ(ctx.kind(2), ConnectionKind::kBridge);
}

TEST(AuditContext, ClientAliasesAreListedByTheConnectionTheyLastCameOn) {
    AuditContext ctx(kStart);
    ctx.note_client(0x12C, 1);
    ctx.note_client(0x12D, 1);
    ctx.note_client(0x12E, 2);
    ctx.note_client(0x12D, 2);  // moved
    EXPECT_THAT(ctx.clients_of(1), UnorderedElementsAre(0x12C));
    EXPECT_THAT(ctx.clients_of(2), UnorderedElementsAre(0x12D, 0x12E));
    ctx.forget_client(0x12E);
    EXPECT_THAT(ctx.clients_of(2), UnorderedElementsAre(0x12D));
}

TEST(AuditContext, AReportNamesTheClientsConnectionIdAndTheNodeItConcerns) {
    AuditContext ctx(kStart);
    ctx.add_node(bare(kNode));
    ctx.set_node_alias(0x343, 0);
    ctx.name_connection(1, "127.0.0.1:50000", ConnectionKind::kHubClient);
    ctx.note_client(0x12C, 1);
    ctx.set_client_node_id(0x12C, kClient);
    const std::vector<CanFrame> frames = {*gridconnect::parse_frame(":X1982812CN0343;")};
    ctx.report(RuleId::kAliasUnreserved, 0x12C, 0x343, "never reserved", frames, "", kStart);
    ctx.report(RuleId::kAliasUnreserved, 0x12D, 0x999, "unknown client", {}, "", kStart);
    ASSERT_EQ(ctx.log().findings().size(), 2u);
    const Finding& f = ctx.log().findings()[0];
    EXPECT_EQ(f.message, "never reserved");
    EXPECT_EQ(f.client.connection, 1u);
    EXPECT_EQ(f.client.remote, "127.0.0.1:50000");
    EXPECT_EQ(f.client.node_id, kClient);
    ASSERT_TRUE(f.node);
    EXPECT_EQ(f.node->node_id, kNode);
    EXPECT_EQ(f.node->alias, 0x343);
    EXPECT_EQ(f.frames, std::vector<std::string>{":X1982812CN0343;"});
    const Finding& g = ctx.log().findings()[1];
    EXPECT_EQ(g.client.connection, 0u) << "a client never noted is on no connection";
    EXPECT_EQ(g.client.remote, "");
    EXPECT_FALSE(g.node) << "0x999 is none of simnode's nodes";
}

TEST(AuditContext, PairKeysAndAliasTextRoundTrip) {
    const auto key = pair_key(0x12C, 0x343);
    EXPECT_EQ(pair_client(key), 0x12C);
    EXPECT_EQ(pair_node(key), 0x343);
    EXPECT_NE(pair_key(0x343, 0x12C), key);
    EXPECT_EQ(alias_text(0x12C), "0x12C");
    EXPECT_EQ(alias_text(0x5), "0x005");
}

}  // namespace
}  // namespace olcb::simnode::audit
