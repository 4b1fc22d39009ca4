// Start-up, Verify Node ID, PIP, SNIP, OIR and event identification of a SimNode, end to end over
// SimNetwork with GridConnect frames.
#include <gtest/gtest.h>

#include "memory/acdi.hpp"
#include "memory/snip.hpp"
#include "sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

class ProtocolTest : public SimNodeTest {};

// Default event IDs: node ID + 16-bit ordinal among eventid variables without a default.
std::string consumer_identified(std::uint16_t suffix) {
    char buf[64];
    std::snprintf(buf, sizeof buf, ":X194C7343N0501010122000%03X;", suffix);
    return buf;
}

TEST_F(ProtocolTest, StartUpAllocatesAliasThenInitializationCompleteThenEvents) {
    start(default_config());
    const auto frames = take();
    ASSERT_GE(frames.size(), 7u + 8u);
    EXPECT_EQ(frames[0], ":X17050343N;");
    EXPECT_EQ(frames[1], ":X16101343N;");
    EXPECT_EQ(frames[2], ":X15012343N;");
    EXPECT_EQ(frames[3], ":X14200343N;");
    EXPECT_EQ(frames[4], ":X10700343N;");
    EXPECT_EQ(frames[5], ":X10701343N050101012200;");
    EXPECT_EQ(frames[6], ":X19100343N050101012200;");
    // 4 ports x (On, Off): consumed (no role text in the default CDI), state Unknown.
    for (std::uint16_t i = 0; i < 8; ++i) EXPECT_EQ(frames[7 + i], consumer_identified(i));
    EXPECT_EQ(frames.size(), 15u);
    // RID only after the 200 ms wait.
    const auto& log = net_.log();
    TimePoint cid4{}, rid{};
    for (const auto& e : log) {
        const auto t = gridconnect::format(e.frame);
        if (t == ":X14200343N;") cid4 = e.at;
        if (t == ":X10700343N;") rid = e.at;
    }
    EXPECT_GE(rid - cid4, std::chrono::milliseconds(200));
}

TEST_F(ProtocolTest, NoTrafficAfterStartUpWhenNobodyAsks) {
    start(default_config());
    take();
    net_.run_for(30s);
    EXPECT_TRUE(take().empty());
}

TEST_F(ProtocolTest, VerifyNodeIdGlobalAndAddressed) {
    start(default_config());
    take();
    send_global(0x490);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
    send_global(0x490, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00});
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
    send_global(0x490, {0x05, 0x01, 0x01, 0x01, 0x22, 0x01});  // someone else
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    send_addressed(0x488);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19170343N050101012200;"});
}

TEST_F(ProtocolTest, PipWithAcdiAndEvents) {
    start(default_config());
    take();
    send_addressed(0x828);
    net_.run_for(10ms);
    // 0x20 = Stream: simnode serves stream reads by default, as an OpenMRN node.
    EXPECT_EQ(take(), std::vector<std::string>{":X19668343N012C745800000000;"});
}

TEST_F(ProtocolTest, PipWithoutAcdiOrEvents) {
    NodeConfig c = default_config();
    // Drop <acdi/> and every eventid: no ACDI bit, no Event Exchange bit.
    std::string cdi = c.cdi;
    cdi.erase(cdi.find("<acdi/>"), 7);
    for (auto p = cdi.find("<eventid>"); p != std::string::npos; p = cdi.find("<eventid>")) {
        cdi.erase(p, cdi.find("</eventid>", p) + 10 - p);
    }
    c.cdi = cdi;
    start(std::move(c));
    send_addressed(0x828);
    net_.run_for(10ms);
    const auto frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames.back(), ":X19668343N012C701800000000;");
    EXPECT_EQ(node_->memory().space(0xFC), nullptr);
    // The CDI still lays out space 251, so 251 is served as a configuration space.
    EXPECT_NE(node_->memory().space(0xFB), nullptr);
    EXPECT_TRUE(node_->events().empty());
}

TEST_F(ProtocolTest, SnipEqualsAcdiSpacesAndCdiIdentification) {
    start(default_config());
    const auto payload = request_snip();
    const memory::Snip snip = memory::decode_snip(payload);
    EXPECT_EQ(payload[0], 4);
    EXPECT_EQ(snip.manufacturer, "OpenLCB Tools");
    EXPECT_EQ(snip.model, "simnode default");
    EXPECT_EQ(snip.hardware_version, "1.0");
    EXPECT_EQ(snip.software_version, "0.1.0");
    EXPECT_EQ(snip.user_name, "Test node");
    EXPECT_EQ(snip.user_description, "Bench");
    EXPECT_EQ(payload, memory::encode_snip(snip));

    // The same strings over memory configuration (252 and 251 read in the byte-6 form).
    std::vector<std::uint8_t> fixed = read(0xFC, 0, 64);
    auto rest = read(0xFC, 64, 64);
    fixed.insert(fixed.end(), rest.begin(), rest.end());
    ASSERT_EQ(fixed.size(), 125u);
    std::vector<std::uint8_t> user = read(0xFB, 0, 64);
    rest = read(0xFB, 64, 64);
    user.insert(user.end(), rest.begin(), rest.end());
    ASSERT_EQ(user.size(), 128u);
    EXPECT_EQ(fixed[0], 4);
    EXPECT_EQ(user[0], 2);
    EXPECT_EQ(memory::snip_from_acdi(fixed, user), snip);
}

TEST_F(ProtocolTest, SnipReplyIsOneMultiFrameMessage) {
    start(default_config());
    take();
    request_snip();
    const auto frames = take();
    ASSERT_GE(frames.size(), 2u);
    EXPECT_EQ(frames.front().substr(0, 16), ":X19A08343N112C0");
    EXPECT_EQ(frames.back().substr(0, 15), ":X19A08343N212C");
    for (std::size_t i = 1; i + 1 < frames.size(); ++i) {
        EXPECT_EQ(frames[i].substr(0, 15), ":X19A08343N312C");
    }
}

TEST_F(ProtocolTest, IdentityOverridesCdiIdentification) {
    NodeConfig c = default_config();
    c.identity = Identity{"Maker", "Model X", "2", "3.4"};
    start(std::move(c));
    const memory::Snip snip = memory::decode_snip(request_snip());
    EXPECT_EQ(snip.manufacturer, "Maker");
    EXPECT_EQ(snip.model, "Model X");
    EXPECT_EQ(memory::decode_acdi_manufacturer(read(0xFC, 0, 64)).model, "Model X");
}

TEST_F(ProtocolTest, UnknownAddressedMtiGetsOir) {
    start(default_config());
    take();
    send_addressed(0x4F9);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19068343N012C104304F9;"});
    send_global(0x5B4, {1, 2, 3, 4, 5, 6, 7, 8});  // unsupported global: ignored
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
}

TEST_F(ProtocolTest, IdentifyEventsGlobalAndAddressed) {
    start(default_config());
    take();
    send_global(0x970);
    net_.run_for(10ms);
    auto frames = take();
    ASSERT_EQ(frames.size(), 8u);
    EXPECT_EQ(frames[0], consumer_identified(0));
    send_addressed(0x968);
    net_.run_for(10ms);
    frames = take();
    ASSERT_EQ(frames.size(), 8u);
    EXPECT_EQ(frames[7], consumer_identified(7));
}

TEST_F(ProtocolTest, IdentifyConsumerAndProducerAnswerOnlyForOwnEvents) {
    start(default_config());
    take();
    const std::vector<std::uint8_t> own{0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x03};
    const std::vector<std::uint8_t> foreign{0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x63};
    send_global(0x8F4, own);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{consumer_identified(3)});
    send_global(0x8F4, foreign);
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    send_global(0x914, own);  // we consume it, we do not produce it
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
}

TEST_F(ProtocolTest, ProducerEventsByRoleRule) {
    NodeConfig c = default_config();
    std::string cdi = c.cdi;
    // The Off event now sits under a name saying it is produced.
    const std::string off = "<eventid><name>Off event</name></eventid>";
    cdi.replace(cdi.find(off), off.size(), "<eventid><name>Produced event</name></eventid>");
    c.cdi = cdi;
    start(std::move(c));
    auto frames = take();
    EXPECT_EQ(count_prefix(frames, ":X19547343N"), 4u);
    EXPECT_EQ(count_prefix(frames, ":X194C7343N"), 4u);
    send_global(0x914, {0x05, 0x01, 0x01, 0x01, 0x22, 0x00, 0x00, 0x01});
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19547343N0501010122000001;"});
}

TEST_F(ProtocolTest, CreateRefusesBadConfig) {
    std::string error;
    NodeConfig c = default_config();
    c.node_id = NodeId{};
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_NE(error.find("zero"), std::string::npos);
    c = default_config();
    c.cdi = "<cdi><segment space='253'><int size='3'/></segment>";
    error.clear();
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_FALSE(error.empty());
    c.cdi = "";
    EXPECT_EQ(SimNode::create(c, error), nullptr);
}

TEST_F(ProtocolTest, HugeReplicationRefusedWithoutAllocating) {
    std::string error;
    NodeConfig c = default_config();
    c.cdi =
        "<?xml version=\"1.0\"?><cdi><segment space=\"253\"><group replication=\"100000000\">"
        "<int size=\"1\"><name>x</name></int></group></segment></cdi>";
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_FALSE(error.empty());
}

}  // namespace
}  // namespace olcb::simnode::test
