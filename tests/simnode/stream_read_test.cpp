// Memory-config stream reads served by simnode, read by a second NodeStack with the stream
// transport on (the way lcc-conform reads), on the simulated bus.
#include <gtest/gtest.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "openlcb/node_stack.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

constexpr NodeId kReaderId{0x02'01'0D'00'00'02ull};
constexpr std::uint8_t kDid = 0x21;

class StreamReadTest : public SimNodeTest {
protected:
    StreamReadTest() : reader_(reader_config()) {
        reader_.set_datagram_handler([this](const ReceivedDatagram& d) {
            replies_.push_back(d.payload);
            reader_.accept_datagram(d.source_alias);
        });
        reader_.set_outcome_handler([this](const DatagramOutcome& o) { outcomes_.push_back(o); });
        reader_.set_stream_handler([this](const StreamEvent& e) {
            if (e.kind == StreamEvent::Kind::kData) {
                data_.insert(data_.end(), e.data.begin(), e.data.end());
            }
            if (e.kind == StreamEvent::Kind::kOpened) stream_ = e.id;
            if (e.kind == StreamEvent::Kind::kCompleted) completed_ = e;
        });
    }
    static NodeStackConfig reader_config() {
        NodeStackConfig c;
        c.node_id = kReaderId;
        c.protocols = {Protocol::kDatagram, Protocol::kStream};
        c.streams = true;
        return c;
    }
    void boot(NodeConfig config) {
        start(std::move(config));
        net_.add_stack(reader_);
        reader_.start(net_.now());
        ASSERT_TRUE(net_.run_until([this] { return reader_.initialized(); }, 1s));
    }
    // Reads the CDI by stream (count 0 = to the end) with our buffer `buffer`.
    void read_cdi(std::uint16_t buffer, Duration max = 5s) {
        reader_.expect_stream(alias(), kDid, buffer);
        const std::vector<std::uint8_t> cmd{0x20, 0x63, 0, 0, 0, 0, 0xFF, kDid, 0, 0, 0, 0};
        ASSERT_TRUE(reader_.send_datagram(alias(), cmd, net_.now()));
        net_.run_until([this] { return completed_.has_value(); }, max);
    }
    std::vector<std::uint8_t> cdi_bytes() {
        memory::MemorySpace* s = node_->memory().space(0xFF);
        std::vector<std::uint8_t> out(s->size());
        out.resize(s->read(0, out));
        return out;
    }
    std::optional<StreamInfo> info() { return reader_.streams().info(stream_); }

    NodeStack reader_;
    std::vector<std::vector<std::uint8_t>> replies_;
    std::vector<DatagramOutcome> outcomes_;
    std::vector<std::uint8_t> data_;
    std::uint32_t stream_ = 0;
    std::optional<StreamEvent> completed_;
};

TEST_F(StreamReadTest, CdiByStreamMatchesTheSpaceAndHonoursTheBuffer) {
    boot(default_config());
    EXPECT_TRUE(node_->stack().protocols().has(Protocol::kStream));
    read_cdi(256);
    ASSERT_TRUE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
    EXPECT_EQ(completed_->count, data_.size());
    ASSERT_EQ(outcomes_.size(), 1u);
    EXPECT_EQ(outcomes_[0].flags & 0x80, 0x80);  // Reply Pending
    ASSERT_EQ(replies_.size(), 1u);
    EXPECT_EQ(replies_[0][1], 0x73);  // Read Stream Reply OK, short form
    EXPECT_EQ(replies_[0][7], kDid);
    ASSERT_TRUE(info());
    EXPECT_EQ(info()->buffer, 256);  // node proposes 0xFFFF; ours is smaller
    EXPECT_LE(info()->max_in_window, 256u);
    EXPECT_EQ(info()->proceeds, data_.size() / 256);
}

TEST_F(StreamReadTest, ReadAtTheEndFails1082AndDatagramOnlyNodeRejects1041) {
    boot(default_config());
    const std::uint32_t end = static_cast<std::uint32_t>(cdi_bytes().size());
    const std::vector<std::uint8_t> cmd{0x20,
                                        0x63,
                                        static_cast<std::uint8_t>(end >> 24),
                                        static_cast<std::uint8_t>(end >> 16),
                                        static_cast<std::uint8_t>(end >> 8),
                                        static_cast<std::uint8_t>(end),
                                        0xFF,
                                        kDid,
                                        0,
                                        0,
                                        0,
                                        0};
    auto a = exchange(cmd);
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x7B);
    EXPECT_EQ((*a.reply)[6], 0x10);
    EXPECT_EQ((*a.reply)[7], 0x82);
}

TEST_F(StreamReadTest, StreamsOffIsADatagramOnlyNode) {
    NodeConfig c = default_config();
    c.streams = false;
    boot(std::move(c));
    EXPECT_FALSE(node_->stack().protocols().has(Protocol::kStream));
    auto a = exchange({0x20, 0x63, 0, 0, 0, 0, 0xFF, kDid, 0, 0, 0, 0});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1041);
    auto options = exchange({0x20, 0x80});
    ASSERT_TRUE(options.reply);
    EXPECT_EQ((*options.reply)[2] & 0x10, 0);  // no "stream reads"
}

TEST_F(StreamReadTest, WrongCountFaultMisstatesTheTotal) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-wrong-count"});
    boot(std::move(c));
    read_cdi(256);
    ASSERT_TRUE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
    EXPECT_EQ(completed_->count, data_.size() + 1);
}

TEST_F(StreamReadTest, NoCompleteFaultNeverEnds) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-no-complete"});
    boot(std::move(c));
    read_cdi(256, 2s);
    EXPECT_FALSE(completed_);
    EXPECT_EQ(data_, cdi_bytes());
}

TEST_F(StreamReadTest, IgnoreProceedAndExceedBufferOverrunTheWindow) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-ignore-proceed"});
    boot(std::move(c));
    read_cdi(64);
    ASSERT_TRUE(completed_);
    EXPECT_GT(info()->max_in_window, 64u);
}

TEST_F(StreamReadTest, ExceedBufferSendsTwiceTheGrant) {
    NodeConfig c = default_config();
    c.faults = test::faults_of({"stream-exceed-buffer"});
    boot(std::move(c));
    read_cdi(64);
    ASSERT_TRUE(completed_);
    EXPECT_GT(info()->max_in_window, 64u);  // our auto Proceed at 64 hides part of the 128
    EXPECT_EQ(data_, cdi_bytes());
}

}  // namespace
}  // namespace olcb::simnode::test
