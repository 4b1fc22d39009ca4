// The simnode program over TCP, as a tool sees it: discovery, PIP, SNIP, the CDI, memory
// configuration reads/writes and their error paths, persistence across restarts and reboot.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

#include "e2e/e2e_util.hpp"
#include "memory/snip.hpp"
#include "openlcb/pip.hpp"

namespace olcb::e2e {
namespace {

using memory::Space;

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
// Address of the 16-byte "Label" string in space 253 of scenarios/default.xml.
constexpr std::uint32_t kLabelAddress = 30;

std::string read_file(const std::filesystem::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<std::uint8_t> text_field(std::string_view text, std::size_t size) {
    std::vector<std::uint8_t> v(size, 0);
    std::copy_n(text.begin(), std::min(text.size(), size), v.begin());
    return v;
}

// simnode on the default scenario, on a free port, with its images in a fresh directory.
class SimnodeTest : public ::testing::Test {
protected:
    void SetUp() override {
#ifndef SIMNODE_PATH
        GTEST_SKIP() << "simnode is not built";
#else
        start();
#endif
    }

    void start(std::vector<std::string> extra = {}) {
#ifdef SIMNODE_PATH
        std::vector<std::string> args{"--scenario",  source_path("scenarios/default.ini").string(),
                                      "--listen",    "127.0.0.1:0",
                                      "--image-dir", images_.str()};
        args.insert(args.end(), extra.begin(), extra.end());
        child_ = Child::spawn(SIMNODE_PATH, args);
        ASSERT_TRUE(child_);
        const auto port = child_->wait_listening();
        ASSERT_TRUE(port) << child_->output();
        tool_ = std::make_unique<ToolNode>(*port);
        ASSERT_TRUE(tool_->wait_ready());
        const auto alias = tool_->find(kDefaultNode);
        ASSERT_TRUE(alias) << "no Verified Node ID from the default node";
        node_ = *alias;
#endif
    }

    void stop_gracefully() {
        tool_.reset();
        child_->signal(SIGTERM);
        ASSERT_TRUE(child_->wait_for(milliseconds(5000)));
        EXPECT_EQ(child_->wait(), 0);
    }

    TempDir images_{"simnode-e2e"};
    std::unique_ptr<Child> child_;
    std::unique_ptr<ToolNode> tool_;
    std::uint16_t node_ = 0;
};

TEST_F(SimnodeTest, AnswersVerifyNodeIdGlobalAndAddressed) {
    const auto id = kDefaultNode.to_bytes();
    tool_->send(Mti::kVerifyNodeIdAddressed, {}, node_);
    const auto m = tool_->take(
        [&](const Message& m) { return m.mti == Mti::kVerifiedNodeId && m.source.alias == node_; },
        milliseconds(750));
    ASSERT_TRUE(m);
    EXPECT_EQ(m->payload, std::vector<std::uint8_t>(id.begin(), id.end()));
}

TEST_F(SimnodeTest, ProtocolSupportReplyNamesWhatItServes) {
    tool_->send(Mti::kProtocolSupportInquiry, {}, node_);
    const auto m = tool_->take(
        [&](const Message& m) { return m.mti == Mti::kProtocolSupportReply; }, milliseconds(750));
    ASSERT_TRUE(m);
    const auto set = ProtocolSet::decode(m->payload);
    for (const auto p :
         {Protocol::kDatagram, Protocol::kStream, Protocol::kMemoryConfiguration,
          Protocol::kEventExchange, Protocol::kAcdi, Protocol::kSnip, Protocol::kCdi}) {
        EXPECT_TRUE(set.has(p)) << std::hex << static_cast<std::uint64_t>(p);
    }
    EXPECT_FALSE(set.has(Protocol::kTractionControl));
}

TEST_F(SimnodeTest, SnipMatchesTheCdiAndTheScenario) {
    tool_->send(Mti::kSnipRequest, {}, node_);
    const auto m =
        tool_->take([&](const Message& m) { return m.mti == Mti::kSnipReply; }, milliseconds(750));
    ASSERT_TRUE(m);
    const auto snip = memory::decode_snip(m->payload);
    EXPECT_EQ(snip.manufacturer_version, 4);
    EXPECT_EQ(snip.user_version, 2);
    EXPECT_EQ(snip.manufacturer, "OpenLCB Tools");
    EXPECT_EQ(snip.model, "simnode default");
    EXPECT_EQ(snip.hardware_version, "1.0");
    EXPECT_EQ(snip.software_version, "0.1.0");
    EXPECT_EQ(snip.user_name, "simnode default");
    EXPECT_EQ(snip.user_description, "A simulated node with every variable type");
}

TEST_F(SimnodeTest, WholeCdiReadEqualsTheFilePlusOneNul) {
    auto expected = read_file(source_path("scenarios/default.xml"));
    std::vector<std::uint8_t> want(expected.begin(), expected.end());
    want.push_back(0);
    const auto got = tool_->read_space(node_, Space::kCdi);
    ASSERT_TRUE(got);
    EXPECT_EQ(*got, want);

    memory::GetSpaceInfo info{Space::kCdi};
    const auto reply = tool_->memcfg(node_, info);
    ASSERT_TRUE(reply);
    const auto* present = std::get_if<memory::SpaceInfoReply>(&*reply);
    ASSERT_TRUE(present);
    EXPECT_EQ(present->highest_address, expected.size());
    EXPECT_TRUE(present->read_only);
}

TEST_F(SimnodeTest, ConfigOptionsAndAcdiSpaces) {
    const auto reply = tool_->memcfg(node_, memory::GetConfigOptions{});
    ASSERT_TRUE(reply);
    const auto* options = std::get_if<memory::ConfigOptionsReply>(&*reply);
    ASSERT_TRUE(options);
    EXPECT_EQ(options->write_lengths, 0xE2);
    EXPECT_EQ(options->available_commands & 0x0E00, 0x0E00);
    for (const auto& [space, highest, ro] : {std::tuple{Space::kAcdiManufacturer, 124u, true},
                                             std::tuple{Space::kAcdiUser, 127u, false}}) {
        const auto r = tool_->memcfg(node_, memory::GetSpaceInfo{space});
        ASSERT_TRUE(r);
        const auto* info = std::get_if<memory::SpaceInfoReply>(&*r);
        ASSERT_TRUE(info);
        EXPECT_EQ(info->highest_address, highest);
        EXPECT_EQ(info->read_only, ro);
    }
    const auto fixed = tool_->read(node_, Space::kAcdiManufacturer, 0, 14);
    ASSERT_TRUE(fixed);
    EXPECT_EQ((*fixed)[0], 4);
    EXPECT_EQ(std::string(fixed->begin() + 1, fixed->end()), "OpenLCB Tools");
}

TEST_F(SimnodeTest, WriteThenReadBackInBothForms) {
    const auto label = text_field("yard lead", 16);
    ASSERT_TRUE(tool_->write(node_, Space::kConfig, kLabelAddress, label));
    EXPECT_EQ(tool_->read(node_, Space::kConfig, kLabelAddress, 16), label);

    // The byte-6 form of the same read is answered in the byte-6 form.
    memory::Read r{Space::kConfig, kLabelAddress, 16, memory::SpaceForm::kByte6};
    Exchange ex;
    tool_->memcfg(node_, r, &ex);
    ASSERT_TRUE(ex.reply);
    ASSERT_GE(ex.reply->size(), 2u);
    EXPECT_EQ((*ex.reply)[1], 0x50);
    const auto decoded = memory::decode(*ex.reply);
    ASSERT_TRUE(decoded.ok());
    EXPECT_EQ(std::get<memory::ReadReply>(decoded.message).data, label);
}

TEST_F(SimnodeTest, ErrorPaths) {
    // Past the end: Write Reply Fail 0x1082, nothing written.
    memory::Write w{Space::kConfig, 100000, {1, 2, 3}};
    const auto fail = tool_->memcfg(node_, w);
    ASSERT_TRUE(fail);
    const auto* wf = std::get_if<memory::WriteReplyFail>(&*fail);
    ASSERT_TRUE(wf);
    EXPECT_EQ(wf->error, memory::ErrorCode::kOutOfBounds);

    // Read at the end: Read Reply Fail 0x1082.
    const auto rf = tool_->memcfg(node_, memory::Read{Space::kConfig, 100000, 8});
    ASSERT_TRUE(rf);
    ASSERT_TRUE(std::holds_alternative<memory::ReadReplyFail>(*rf));
    EXPECT_EQ(std::get<memory::ReadReplyFail>(*rf).error, memory::ErrorCode::kOutOfBounds);

    // Unknown space: Datagram Rejected 0x1081.
    Exchange ex;
    tool_->memcfg(node_, memory::Read{static_cast<Space>(0x42), 0, 8}, &ex);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->status, DatagramOutcome::Status::kRejected);
    EXPECT_EQ(ex.outcome->error_code, 0x1081);

    // Read-only space: rejected 0x1083.
    tool_->memcfg(node_, memory::Write{Space::kCdi, 0, {'x'}}, &ex);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->status, DatagramOutcome::Status::kRejected);
    EXPECT_EQ(ex.outcome->error_code, 0x1083);

    // An addressed MTI the node does not know: Optional Interaction Rejected.
    tool_->send(static_cast<Mti>(0x0CE8), {}, node_);
    EXPECT_TRUE(
        tool_->take([&](const Message& m) { return m.mti == Mti::kOptionalInteractionRejected; },
                    milliseconds(750)));
}

TEST_F(SimnodeTest, UserNameWriteChangesSnipAndReinitializes) {
    tool_->messages().clear();
    ASSERT_TRUE(tool_->write(node_, Space::kAcdiUser, 1, text_field("Renamed", 63)));
    EXPECT_TRUE(tool_->take(
        [&](const Message& m) {
            return m.mti == Mti::kInitializationComplete && m.source.alias == node_;
        },
        milliseconds(2000)));
    tool_->send(Mti::kSnipRequest, {}, node_);
    const auto m =
        tool_->take([&](const Message& m) { return m.mti == Mti::kSnipReply; }, milliseconds(750));
    ASSERT_TRUE(m);
    EXPECT_EQ(memory::decode_snip(m->payload).user_name, "Renamed");
}

TEST_F(SimnodeTest, WritesPersistAcrossRestart) {
    const auto label = text_field("kept", 16);
    ASSERT_TRUE(tool_->write(node_, Space::kConfig, kLabelAddress, label));
    ASSERT_TRUE(tool_->write(node_, Space::kAcdiUser, 1, text_field("Persisted", 63)));
    stop_gracefully();
    start();
    EXPECT_EQ(tool_->read(node_, Space::kConfig, kLabelAddress, 16), label);
    EXPECT_EQ(tool_->read(node_, Space::kAcdiUser, 1, 10), text_field("Persisted", 10));
}

TEST_F(SimnodeTest, RebootKeepsTheTcpClientConnected) {
    tool_->messages().clear();
    const auto disconnects = tool_->client().stats().disconnects;
    Exchange ex;
    tool_->memcfg(node_, memory::ResetReboot{}, &ex, milliseconds(1000));
    const auto init = tool_->take(
        [&](const Message& m) {
            return m.mti == Mti::kInitializationComplete &&
                   m.payload == std::vector<std::uint8_t>{0x05, 0x01, 0x01, 0x01, 0x22, 0x00};
        },
        milliseconds(3000));
    ASSERT_TRUE(init) << "no Initialization Complete after 20 A9";
    EXPECT_EQ(tool_->client().stats().disconnects, disconnects);
    EXPECT_TRUE(tool_->client().connected());
    const auto alias = tool_->find(kDefaultNode, milliseconds(3000));
    ASSERT_TRUE(alias);
    EXPECT_TRUE(tool_->read(*alias, Space::kConfig, 0, 1));
}

TEST_F(SimnodeTest, FactoryResetOnlyWithOwnNodeId) {
    ASSERT_TRUE(tool_->write(node_, Space::kConfig, kLabelAddress, text_field("changed", 16)));
    Exchange ex;
    tool_->memcfg(node_, memory::FactoryReset{0x020102030405}, &ex);
    ASSERT_TRUE(ex.outcome);
    EXPECT_EQ(ex.outcome->status, DatagramOutcome::Status::kRejected);
    EXPECT_EQ(tool_->read(node_, Space::kConfig, kLabelAddress, 16), text_field("changed", 16));

    tool_->messages().clear();
    tool_->memcfg(node_, memory::FactoryReset{kDefaultNode.value()}, &ex, milliseconds(1000));
    ASSERT_TRUE(tool_->take([&](const Message& m) { return m.mti == Mti::kInitializationComplete; },
                            milliseconds(3000)));
    const auto alias = tool_->find(kDefaultNode, milliseconds(3000));
    ASSERT_TRUE(alias);
    EXPECT_EQ(tool_->read(*alias, Space::kConfig, kLabelAddress, 16), text_field("", 16));
}

TEST_F(SimnodeTest, TraceAndCandumpLogTheTraffic) {
    TempDir logs("simnode-logs");
    const auto trace = logs.path() / "trace.txt";
    const auto candump = logs.path() / "candump.log";
    tool_.reset();
    child_.reset();
    start({"--trace", trace.string(), "--candump", candump.string()});
    ASSERT_TRUE(tool_->read(node_, Space::kCdi, 0, 16));
    stop_gracefully();
    const auto t = read_file(trace);
    EXPECT_NE(t.find("read"), std::string::npos) << t.substr(0, 2000);
    EXPECT_NE(t.find(":X19170"), std::string::npos);
    const auto c = read_file(candump);
    EXPECT_NE(c.find(" vcan0 19170"), std::string::npos) << c.substr(0, 2000);
}

}  // namespace
}  // namespace olcb::e2e
