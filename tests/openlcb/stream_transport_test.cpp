// Stream transport as frame scripts: the node under test (alias 0x343) on a simulated bus, a raw
// GridConnect port (alias 0x12C) playing the other end.
#include <gtest/gtest.h>

#include <chrono>
#include <numeric>
#include <string>
#include <vector>

#include "base/timings.hpp"
#include "openlcb/node_test_util.hpp"
#include "openlcb/stream_defs.hpp"
#include "openlcb/stream_transport.hpp"

namespace olcb::test {
namespace {

using namespace std::chrono_literals;
using namespace test;

NodeStackConfig stream_config(bool unsolicited = true) {
    NodeStackConfig c = stack_config();
    c.protocols.set(Protocol::kStream);
    c.streams = true;
    c.stream.accept_unsolicited = unsolicited;
    return c;
}

class StreamFixture : public StackFixture {
protected:
    explicit StreamFixture(NodeStackConfig c = stream_config()) : StackFixture(c) {
        stack_.set_stream_handler([this](const StreamEvent& e) { events_.push_back(e); });
        boot();
    }
    std::vector<StreamEvent> of_kind(StreamEvent::Kind k) const {
        std::vector<StreamEvent> out;
        for (const auto& e : events_) {
            if (e.kind == k) out.push_back(e);
        }
        return out;
    }
    std::vector<std::uint8_t> data_received() const {
        std::vector<std::uint8_t> out;
        for (const auto& e : of_kind(StreamEvent::Kind::kData)) {
            out.insert(out.end(), e.data.begin(), e.data.end());
        }
        return out;
    }
    // Opens a stream from the node to the port with buffer 16 and accepts it with DID 07.
    std::uint32_t open_accepted(std::uint16_t granted = 16) {
        auto id = stack_.open_stream(NodeHandle{NodeId{}, 0x12C}, 16, 0x07);
        EXPECT_TRUE(id.has_value());
        const unsigned sid = stack_.streams().info(id.value_or(0))->source_id;
        net_.run_for(0ms);
        char request[64];
        std::snprintf(request, sizeof request, ":X19CC8343N012C00100000%02X07;", sid);
        EXPECT_EQ(take(), Strings{request});
        char reply[64];
        std::snprintf(reply, sizeof reply, ":X1986812CN0343%04X8000%02X07;", unsigned{granted},
                      sid);
        inject(reply);
        return id.value_or(0);
    }
    std::vector<StreamEvent> events_;
};

class StreamSinkTest : public StreamFixture {};

TEST_F(StreamSinkTest, AcceptsNegotiatesReassemblesProceedsAndCompletes) {
    stack_.streams().config().sink_max_buffer = 16;
    inject(":X19CC812CN03430100000005FF;");  // proposes 256, SID 05, no suggested DID
    EXPECT_EQ(take(), Strings{":X19868343N012C001080000500;"});  // granted 16, DID 00
    ASSERT_EQ(of_kind(StreamEvent::Kind::kOpened).size(), 1u);
    inject(":X1F34312CN0001020304050607;");
    inject(":X1F34312CN0008090A0B0C0D0E;");
    EXPECT_EQ(take(), Strings{});  // 14 of 16: no Proceed yet
    inject(":X1F34312CN000F10;");
    EXPECT_EQ(take(), Strings{":X19888343N012C0500;"});
    inject(":X1F34312CN001112;");
    inject(":X198A812CN0343050000000012;");  // Complete, 18 bytes
    EXPECT_EQ(take(), Strings{});
    std::vector<std::uint8_t> want(18);
    std::iota(want.begin(), want.end(), std::uint8_t{1});
    EXPECT_EQ(data_received(), want);
    auto done = of_kind(StreamEvent::Kind::kCompleted);
    ASSERT_EQ(done.size(), 1u);
    EXPECT_EQ(done[0].count, 18u);
    EXPECT_EQ(done[0].bytes, 18u);
    EXPECT_EQ(stack_.streams().open_streams(), 0u);
}

TEST_F(StreamSinkTest, HonoursSuggestedDidAndRejectsZeroBufferAndFullTable) {
    inject(":X19CC812CN0343004000000642;");  // suggests DID 42
    EXPECT_EQ(take(), Strings{":X19868343N012C004080000642;"});
    inject(":X19CC812CN0343000000000742;");  // buffer 0: invalid
    EXPECT_EQ(take(), Strings{":X19868343N012C000010800700;"});
    stack_.streams().config().max_streams = 1;
    inject(":X19CC812CN03430040000008FF;");
    EXPECT_EQ(take(), Strings{":X19868343N012C000020200800;"});
}

TEST_F(StreamSinkTest, ZeroPayloadFlushDoesNotCountAndTerminateEndsTheStream) {
    stack_.streams().config().sink_max_buffer = 8;
    inject(":X19CC812CN03430008000009FF;");
    EXPECT_EQ(take(), Strings{":X19868343N012C000880000900;"});
    inject(":X1F34312CN0001020304;");
    inject(":X1F34312CN00;");  // zero payload
    inject(":X1F34312CN0005060708;");
    EXPECT_EQ(take(), Strings{":X19888343N012C0900;"});
    inject(":X190A812CN034320000000;");  // TDE
    EXPECT_EQ(of_kind(StreamEvent::Kind::kTerminated).size(), 1u);
    EXPECT_EQ(stack_.streams().open_streams(), 0u);
}

TEST_F(StreamSinkTest, IdleStreamTimesOut) {
    inject(":X19CC812CN0343004000000AFF;");
    take();
    net_.run_for(base::kStreamIdleTimeout + 1ms);
    EXPECT_EQ(of_kind(StreamEvent::Kind::kTimedOut).size(), 1u);
    EXPECT_EQ(stack_.streams().open_streams(), 0u);
}

class StreamSinkExpectTest : public StreamFixture {
protected:
    StreamSinkExpectTest() : StreamFixture(stream_config(false)) {}
};

TEST_F(StreamSinkExpectTest, UnannouncedIsRejectedAnnouncedIsAcceptedManualProceed) {
    inject(":X19CC812CN03430100000005FF;");
    EXPECT_EQ(take(), Strings{":X19868343N012C000010430500;"});
    stack_.expect_stream(0x12C, 0x33, 8, false);
    inject(":X19CC812CN0343FFFF00000533;");
    EXPECT_EQ(take(), Strings{":X19868343N012C000880000533;"});
    inject(":X1F34312CN3301020304050607;");
    inject(":X1F34312CN3308;");
    EXPECT_EQ(take(), Strings{});  // manual: the owner proceeds
    ASSERT_EQ(of_kind(StreamEvent::Kind::kWindowFull).size(), 1u);
    inject(":X1F34312CN3309;");  // beyond the window before Proceed: counted
    EXPECT_EQ(stack_.streams().info(events_[0].id)->max_in_window, 9u);
    EXPECT_TRUE(stack_.proceed_stream(events_[0].id));
    net_.run_for(0ms);
    EXPECT_EQ(take(), Strings{":X19888343N012C0533;"});
}

class StreamOffTest : public StackFixture {};

TEST_F(StreamOffTest, InitiateRequestWithoutStreamsGetsOir) {
    boot();
    inject(":X19CC812CN03430100000005FF;");
    EXPECT_EQ(take(), Strings{":X19068343N012C10430CC8;"});
}

class StreamSourceTest : public StreamFixture {};

TEST_F(StreamSourceTest, SendsUpToTheBufferWaitsForProceedThenCompletes) {
    const std::uint32_t id = open_accepted();
    ASSERT_EQ(of_kind(StreamEvent::Kind::kOpened).size(), 1u);
    std::vector<std::uint8_t> data(20);
    std::iota(data.begin(), data.end(), std::uint8_t{1});
    ASSERT_TRUE(stack_.write_stream(id, data));
    ASSERT_TRUE(stack_.close_stream(id));
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X1F12C343N0701020304050607;", ":X1F12C343N0708090A0B0C0D0E;",
                               ":X1F12C343N070F10;"}));
    net_.run_for(1s);
    EXPECT_EQ(take(), Strings{});  // waits for Proceed
    inject(":X1988812CN03430107;");
    EXPECT_EQ(take(), (Strings{":X1F12C343N0711121314;", ":X198A8343N012C010700000014;"}));
    EXPECT_EQ(of_kind(StreamEvent::Kind::kCompleted).size(), 1u);
    EXPECT_EQ(stack_.streams().info(id)->proceeds, 1u);
}

TEST_F(StreamSourceTest, GrantAboveProposalIsCappedAndRejectIsReported) {
    const std::uint32_t id = open_accepted(0x0100);
    EXPECT_EQ(stack_.streams().info(id)->buffer, 16);
    auto second = stack_.open_stream(NodeHandle{NodeId{}, 0x12C}, 16, 0xFF);
    net_.run_for(0ms);
    EXPECT_EQ(take(), Strings{":X19CC8343N012C0010000002FF;"});
    inject(":X1986812CN03430000202002FF;");
    auto rejected = of_kind(StreamEvent::Kind::kRejected);
    ASSERT_EQ(rejected.size(), 1u);
    EXPECT_EQ(rejected[0].id, second.value_or(0));
    EXPECT_EQ(rejected[0].code, 0x2020);
}

TEST_F(StreamSourceTest, OirAndMissingReplyAndMissingProceedEndTheStream) {
    auto a = stack_.open_stream(NodeHandle{NodeId{}, 0x12C}, 16, 0xFF);
    net_.run_for(0ms);
    take();
    inject(":X1906812CN034310430CC8;");
    ASSERT_EQ(of_kind(StreamEvent::Kind::kRejected).size(), 1u);
    EXPECT_EQ(of_kind(StreamEvent::Kind::kRejected)[0].code, 0x1043);
    auto b = stack_.open_stream(NodeHandle{NodeId{}, 0x12C}, 16, 0xFF);
    ASSERT_TRUE(a && b);
    net_.run_for(base::kStreamInitiateTimeout + 1ms);
    EXPECT_EQ(of_kind(StreamEvent::Kind::kTimedOut).size(), 1u);
    take();
    const std::uint32_t id = open_accepted();
    std::vector<std::uint8_t> data(40, 0xAA);
    stack_.write_stream(id, data);
    net_.run_for(base::kStreamProceedTimeout + 1ms);
    EXPECT_EQ(of_kind(StreamEvent::Kind::kTimedOut).size(), 2u);
}

TEST(StreamTransportTest, ConcurrentStreamsShareTheBusFrameByFrame) {
    StreamTransport t;
    const NodeHandle peer{NodeId{}, 0x12C};
    const TimePoint now{};
    auto a = t.open(peer, 16, 0xFF, now);
    auto b = t.open(peer, 16, 0xFF, now);
    ASSERT_TRUE(a && b);
    std::vector<std::uint8_t> sids;
    while (auto m = t.pop_message()) sids.push_back(m->payload[4]);
    ASSERT_EQ(sids.size(), 2u);
    EXPECT_NE(sids[0], sids[1]);
    for (std::uint8_t i = 0; i < 2; ++i) {
        Message reply{Mti::kStreamInitiateReply, peer, NodeHandle{NodeId{}, 0x343},
                      stream::encode(stream::InitiateReply{16, stream::kAccept, sids[i],
                                                           static_cast<std::uint8_t>(i + 1)})};
        EXPECT_TRUE(t.on_message(reply, now));
    }
    t.write(*a, std::vector<std::uint8_t>(14, 0x11));
    t.write(*b, std::vector<std::uint8_t>(14, 0x22));
    std::vector<std::uint8_t> dids;
    while (auto m = t.pop_message()) {
        if (m->mti == Mti::kStreamDataSend) dids.push_back(m->payload[0]);
    }
    EXPECT_EQ(dids, (std::vector<std::uint8_t>{1, 2, 1, 2}));
    // A Proceed naming the other stream's SID does not open this one's window.
    Message proceed{Mti::kStreamDataProceed, peer, NodeHandle{NodeId{}, 0x343},
                    stream::encode(stream::DataProceed{0x77, 1})};
    EXPECT_FALSE(t.on_message(proceed, now));
}

// The hooks an owner breaks the stream rules through (simnode's stream-* faults): the outbound
// filter sees Data Complete, the window policy sizes what one grant allows.
class StreamHookTest : public StreamFixture {};

TEST_F(StreamHookTest, OutboundFilterRewritesOrDropsDataComplete) {
    bool drop = false;
    stack_.set_outbound_filter([&drop](Message& m) {
        if (m.mti != Mti::kStreamDataComplete) return true;
        if (drop) return false;
        auto complete = stream::decode_data_complete(m.payload);
        ++*complete->total_bytes;
        m.payload = stream::encode(*complete);
        return true;
    });
    std::uint32_t id = open_accepted();
    stack_.write_stream(id, std::vector<std::uint8_t>(3, 1));
    stack_.close_stream(id);
    net_.run_for(0ms);
    EXPECT_EQ(take(), (Strings{":X1F12C343N07010101;", ":X198A8343N012C010700000004;"}));
    drop = true;
    id = open_accepted();
    stack_.write_stream(id, std::vector<std::uint8_t>(3, 1));
    stack_.close_stream(id);
    net_.run_for(0ms);
    EXPECT_EQ(take(), Strings{":X1F12C343N07010101;"});
}

TEST_F(StreamHookTest, WindowPolicySizesWhatOneGrantAllows) {
    stack_.streams().set_window_policy(
        [](std::uint16_t) { return StreamTransport::kUnlimitedWindow; });
    std::uint32_t id = open_accepted();
    stack_.write_stream(id, std::vector<std::uint8_t>(35, 2));
    net_.run_for(0ms);
    EXPECT_EQ(take().size(), 5u);  // all 35 bytes, past the 16-byte buffer
    stack_.streams().set_window_policy([](std::uint16_t buffer) { return 2ull * buffer; });
    id = open_accepted();
    stack_.write_stream(id, std::vector<std::uint8_t>(40, 3));
    net_.run_for(0ms);
    EXPECT_EQ(take().size(), 5u);  // 32 bytes = twice the buffer: 7+7+7+7+4
}

TEST_F(StreamSourceTest, LargeWindowIsFramedAsTheOutputDrains) {
    const std::uint32_t id = open_accepted(0xFFFF);
    (void)id;
    auto big = stack_.open_stream(NodeHandle{NodeId{}, 0x12C}, 0, 0x09);
    net_.run_for(0ms);
    take();
    inject(":X1986812CN0343FFFF80000209;");
    std::vector<std::uint8_t> data(std::size_t{7} * 5000,
                                   0x5A);  // more frames than max_output_frames
    stack_.write_stream(big.value_or(0), data);
    stack_.close_stream(big.value_or(0));
    net_.run_for(10ms);
    const Strings got = take();
    ASSERT_EQ(got.size(), 5001u);
    EXPECT_EQ(got.back(), ":X198A8343N012C0209000088B8;");
    EXPECT_EQ(stack_.dropped_frames(), 0u);
}

}  // namespace
}  // namespace olcb::test
