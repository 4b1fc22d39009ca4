#include "openlcb/in_process_bus.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>
#include <vector>

#include "openlcb/asio.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;

CanFrame make_frame(std::uint32_t id, std::uint8_t len) {
    CanFrame f;
    f.id = id;
    f.len = len;
    for (std::uint8_t i = 0; i < len; ++i) f.data[i] = static_cast<std::uint8_t>(0x10 + i);
    return f;
}

struct Recorder {
    std::vector<CanFrame> frames;
    std::vector<InProcessBus::Duration> times;
};

TEST(InProcessBus, FramesReachEveryOtherPortButNotTheSender) {
    InProcessBus bus;
    std::vector<CanFrame> got[3];
    Transport* ports[3];
    for (int i = 0; i < 3; ++i) {
        ports[i] = &bus.add_endpoint([&got, i](const CanFrame& f) { got[i].push_back(f); });
    }
    const CanFrame a = make_frame(0x19490343, 0);
    const CanFrame b = make_frame(0x19170343, 6);
    ports[0]->send(a);
    ports[2]->send(b);
    EXPECT_EQ(bus.pending(), 2u);
    EXPECT_TRUE(got[1].empty());  // nothing delivered before the owner drives the bus
    EXPECT_EQ(bus.deliver(), 2u);
    EXPECT_EQ(got[0], std::vector<CanFrame>{b});
    EXPECT_EQ(got[1], (std::vector<CanFrame>{a, b}));
    EXPECT_EQ(got[2], std::vector<CanFrame>{a});
    EXPECT_EQ(bus.frames_delivered(), 2u);
    EXPECT_EQ(bus.pending(), 0u);
}

TEST(InProcessBus, RepliesSentFromHandlersAreDeliveredInOrderWithoutRecursion) {
    InProcessBus bus;
    std::vector<std::uint32_t> seen_by_a;
    Transport* b_port = nullptr;
    Transport& a = bus.add_endpoint([&](const CanFrame& f) { seen_by_a.push_back(f.id); });
    int depth = 0;
    b_port = &bus.add_endpoint([&](const CanFrame& f) {
        ++depth;
        EXPECT_EQ(depth, 1);
        if (f.id < 0x105) b_port->send(make_frame(f.id + 0x100, 0));
        --depth;
    });
    a.send(make_frame(0x101, 0));
    a.send(make_frame(0x102, 0));
    EXPECT_EQ(bus.deliver(), 4u);
    EXPECT_EQ(seen_by_a, (std::vector<std::uint32_t>{0x201, 0x202}));
}

TEST(InProcessBus, AHandlerMayReplaceItselfWhileRunning) {
    InProcessBus bus;
    Transport& a = bus.add_endpoint();
    Transport* b = nullptr;
    std::vector<std::string> calls;
    b = &bus.add_endpoint([&](const CanFrame&) {
        calls.push_back("first");
        b->set_handler([&](const CanFrame&) { calls.push_back("second"); });
        calls.push_back("first still alive");
    });
    a.send(make_frame(0x100, 0));
    a.send(make_frame(0x100, 0));
    EXPECT_EQ(bus.deliver(), 2u);
    EXPECT_EQ(calls, (std::vector<std::string>{"first", "first still alive", "second"}));
}

TEST(InProcessBus, DeliverHonoursTheFrameLimit) {
    InProcessBus bus;
    int received = 0;
    Transport& a = bus.add_endpoint();
    bus.add_endpoint([&](const CanFrame&) { ++received; });
    for (int i = 0; i < 5; ++i) a.send(make_frame(0x100, 0));
    EXPECT_EQ(bus.deliver(2), 2u);
    EXPECT_EQ(received, 2);
    EXPECT_EQ(bus.pending(), 3u);
}

TEST(CanBitTiming, WorstCaseBitCountsOfExtendedDataFrames) {
    // 54 + 8n stuffable bits, floor((53 + 8n) / 4) stuff bits, 13 fixed tail bits.
    EXPECT_EQ(can_frame_bits(0), 80u);   // 54 + 13 + 13
    EXPECT_EQ(can_frame_bits(1), 90u);   // 62 + 13 + 15
    EXPECT_EQ(can_frame_bits(2), 100u);  // 70 + 13 + 17
    EXPECT_EQ(can_frame_bits(6), 140u);  // 102 + 13 + 25
    EXPECT_EQ(can_frame_bits(8), 160u);  // 118 + 13 + 29
    EXPECT_EQ(can_frame_bits(200), 160u);
    EXPECT_EQ(can_frame_time(8, 125000), 1280us);  // 160 bits * 8 us
    EXPECT_EQ(can_frame_time(0, 125000), 640us);
    EXPECT_EQ(can_frame_time(8, 1000000), 160us);
}

TEST(InProcessBus, TimingModelSerialisesFramesBackToBack) {
    InProcessBus bus;
    bus.enable_timing();  // 125 kbit/s
    Recorder rx;
    Transport& tx = bus.add_endpoint();
    bus.add_endpoint([&](const CanFrame& f) {
        rx.frames.push_back(f);
        rx.times.push_back(bus.now());
    });
    tx.send(make_frame(0x19170343, 8));
    tx.send(make_frame(0x19170343, 0));
    tx.send(make_frame(0x19170343, 8));
    EXPECT_EQ(bus.advance(1279us), 0u);  // first frame still on the wire
    EXPECT_EQ(bus.advance(1us), 1u);
    EXPECT_EQ(bus.now(), 1280us);
    EXPECT_EQ(bus.advance_to(10ms), 2u);
    ASSERT_EQ(rx.times.size(), 3u);
    EXPECT_EQ(rx.times[0], 1280us);
    EXPECT_EQ(rx.times[1], 1920us);  // + 640 us
    EXPECT_EQ(rx.times[2], 3200us);  // + 1280 us
    EXPECT_EQ(bus.busy_time(), 3200us);
    EXPECT_EQ(bus.bits_on_wire(), 400u);
    EXPECT_EQ(bus.now(), 10ms);

    // The bus was idle for a while: the next frame starts when it is sent.
    tx.send(make_frame(0x19490343, 0));
    EXPECT_EQ(bus.next_completion(), 10ms + 640us);
    EXPECT_EQ(bus.run_until_idle(), 1u);
    EXPECT_EQ(rx.times.back(), 10ms + 640us);
    EXPECT_EQ(bus.busy_time(), 3840us);
}

TEST(InProcessBus, TimingModelArbitratesByLowestIdAndKeepsEachPortInOrder) {
    InProcessBus bus;
    bus.enable_timing(125000);
    std::vector<std::uint32_t> order;
    Transport& a = bus.add_endpoint();
    Transport& b = bus.add_endpoint();
    bus.add_endpoint([&](const CanFrame& f) { order.push_back(f.id); });
    a.send(make_frame(0x19500000, 0));
    a.send(make_frame(0x10000000, 0));  // high priority but queued behind a's first frame
    b.send(make_frame(0x19400000, 0));
    EXPECT_EQ(bus.run_until_idle(), 3u);
    EXPECT_EQ(order, (std::vector<std::uint32_t>{0x19400000, 0x19500000, 0x10000000}));
    EXPECT_EQ(bus.now(), 3 * 640us);
}

TEST(InProcessBus, TimedRepliesQueueFromTheCompletionOfTheRequest) {
    InProcessBus bus;
    bus.enable_timing(125000);
    std::vector<InProcessBus::Duration> reply_times;
    Transport& requester =
        bus.add_endpoint([&](const CanFrame&) { reply_times.push_back(bus.now()); });
    Transport* responder = nullptr;
    responder =
        &bus.add_endpoint([&](const CanFrame& f) { responder->send(make_frame(f.id + 1, 8)); });
    requester.send(make_frame(0x19490001, 0));
    EXPECT_EQ(bus.run_until_idle(), 2u);
    EXPECT_EQ(reply_times, std::vector<InProcessBus::Duration>{640us + 1280us});
}

TEST(InProcessBus, IoContextModeDeliversAsPostedHandlers) {
    boost::asio::io_context io;
    InProcessBus bus(io);
    std::vector<CanFrame> got;
    Transport& a = bus.add_endpoint();
    bus.add_endpoint([&](const CanFrame& f) { got.push_back(f); });
    a.send(make_frame(0x19490343, 0));
    EXPECT_TRUE(got.empty());
    io.run_for(std::chrono::seconds(1));
    ASSERT_EQ(got.size(), 1u);
    EXPECT_EQ(got[0].id, 0x19490343u);
}

TEST(InProcessBus, IoContextModeWithTimingDeliversAfterTheFrameTime) {
    boost::asio::io_context io;
    InProcessBus bus(io);
    bus.enable_timing(1'000'000);
    std::vector<InProcessBus::Duration> times;
    Transport& a = bus.add_endpoint();
    bus.add_endpoint([&](const CanFrame&) { times.push_back(bus.now()); });
    a.send(make_frame(0x19490343, 8));
    a.send(make_frame(0x19490343, 8));
    for (int i = 0; i < 100 && times.size() < 2; ++i)
        io.run_one_for(std::chrono::milliseconds(100));
    ASSERT_EQ(times.size(), 2u);
    EXPECT_GE(times[0], 160us);
    EXPECT_GE(times[1], 320us);
    EXPECT_EQ(bus.busy_time(), 320us);
}

}  // namespace
}  // namespace olcb
