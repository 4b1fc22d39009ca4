// BusPacer on a simulated clock: frames back to back at CAN bit timing, idle gaps, arbitration
// by lowest ID among the senders' oldest frames, each sender in order, late callers, and two
// request/response clients sharing one bus.
#include "openlcb/bus_pacer.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <vector>

namespace olcb {
namespace {

using namespace std::chrono_literals;
using Duration = BusPacer::Duration;

CanFrame frame(std::uint32_t id, std::uint8_t len) {
    CanFrame f;
    f.id = id;
    f.len = len;
    return f;
}

// Pops everything, one frame at a time at its completion; the ids in bus order.
std::vector<std::uint32_t> drain(BusPacer& bus, std::vector<Duration>* times = nullptr) {
    std::vector<std::uint32_t> ids;
    for (int guard = 0; guard < 1000; ++guard) {
        const auto next = bus.next_completion();
        if (!next) break;
        const auto done = bus.pop(*next);
        if (!done) break;
        ids.push_back(done->frame.id);
        if (times) times->push_back(done->completed_at);
    }
    return ids;
}

TEST(BusPacer, FramesOfOneSenderGoBackToBackAtTheFrameTime) {
    BusPacer bus(125000);
    bus.push(1, frame(0x19170001, 8), 0us);
    bus.push(1, frame(0x19170001, 0), 0us);
    bus.push(1, frame(0x19170001, 8), 0us);
    EXPECT_EQ(bus.pending(), 3u);
    EXPECT_EQ(bus.next_completion(), can_frame_time(8, 125000));
    EXPECT_FALSE(bus.pop(1279us));  // still on the wire
    const auto first = bus.pop(1280us);
    ASSERT_TRUE(first);
    EXPECT_EQ(first->source, 1u);
    EXPECT_EQ(first->completed_at, 1280us);
    std::vector<Duration> times;
    drain(bus, &times);
    EXPECT_EQ(times, (std::vector<Duration>{1920us, 3200us}));
    EXPECT_EQ(bus.busy_time(), 3200us);
    EXPECT_EQ(bus.bits_on_wire(), 160u + 80u + 160u);
    EXPECT_EQ(bus.pending(), 0u);
    EXPECT_FALSE(bus.next_completion());
}

TEST(BusPacer, AFrameSentToAnIdleBusStartsWhenItIsSent) {
    BusPacer bus(125000);
    bus.push(1, frame(0x100, 0), 0us);
    ASSERT_TRUE(bus.pop(10ms));
    bus.push(2, frame(0x100, 0), 10ms);
    EXPECT_EQ(bus.next_completion(), 10ms + 640us);
    EXPECT_EQ(bus.busy_time(), 1280us);
}

TEST(BusPacer, LowestIdWinsAndEachSenderKeepsItsOrder) {
    BusPacer bus(125000);
    bus.push(1, frame(0x19500000, 0), 0us);
    bus.push(1, frame(0x10000000, 0), 0us);  // high priority, but behind sender 1's first frame
    bus.push(2, frame(0x19400000, 0), 0us);
    bus.push(3, frame(0x19400000, 0), 0us);  // same ID as sender 2's: the lower key goes first
    std::vector<std::uint32_t> ids;
    std::vector<BusPacer::Source> sources;
    for (int i = 0; i < 4; ++i) {
        const auto done = bus.pop(1s);
        ASSERT_TRUE(done);
        ids.push_back(done->frame.id);
        sources.push_back(done->source);
    }
    EXPECT_EQ(ids, (std::vector<std::uint32_t>{0x19400000, 0x19400000, 0x19500000, 0x10000000}));
    EXPECT_EQ(sources, (std::vector<BusPacer::Source>{2, 3, 1, 1}));
}

TEST(BusPacer, AFrameOnTheWireIsNotPreemptedAndLateArrivalsWaitForTheNextArbitration) {
    BusPacer bus(125000);
    bus.push(1, frame(0x19500000, 0), 0us);
    EXPECT_EQ(bus.next_completion(), 640us);  // chosen: on the wire
    bus.push(2, frame(0x10000000, 0), 100us);
    bus.push(3, frame(0x19600000, 0), 200us);
    // At 640 us both later frames wait; the lower ID wins, then the other follows.
    EXPECT_EQ(drain(bus), (std::vector<std::uint32_t>{0x19500000, 0x10000000, 0x19600000}));

    // A frame ready after the bus fell free does not take part in that arbitration.
    BusPacer idle(125000);
    idle.push(1, frame(0x19500000, 0), 0us);
    idle.push(2, frame(0x10000000, 0), 1us);
    EXPECT_EQ(drain(idle), (std::vector<std::uint32_t>{0x19500000, 0x10000000}));
}

TEST(BusPacer, ALateCallerGetsWhatCompletedMeanwhileOnTheBusSchedule) {
    BusPacer bus(1'000'000);
    for (int i = 0; i < 5; ++i) bus.push(7, frame(0x100, 8), 0us);  // 160 us each
    EXPECT_EQ(bus.queued(7), 5u);  // none on the wire before a look
    std::vector<Duration> times;
    while (const auto done = bus.pop(500us)) times.push_back(done->completed_at);
    EXPECT_EQ(times, (std::vector<Duration>{160us, 320us, 480us}));
    EXPECT_EQ(bus.queued(7), 1u);  // one on the wire, one waiting
    EXPECT_EQ(bus.pending(), 2u);
    EXPECT_EQ(bus.next_completion(), 640us);  // no drift from the late look
    EXPECT_EQ(bus.queued(8), 0u);
}

// A caller stalled for a second (simnode building 1,000 nodes before its loop ran) gets only
// kMaxCatchUp (20 ms) of bus time at once, not a second's frames as one burst; the rest follow
// at the bit rate.
TEST(BusPacer, AStalledCallerGetsAtMostTheCatchUpAtOnce) {
    BusPacer bus(1'000'000);
    for (int i = 0; i < 1000; ++i) bus.push(7, frame(0x100, 8), 0us);  // 160 us each
    std::vector<Duration> times;
    while (const auto done = bus.pop(1'000'000us)) times.push_back(done->completed_at);
    ASSERT_EQ(times.size(), 125u);  // 20 ms / 160 us
    EXPECT_EQ(times.front(), 980'160us);
    EXPECT_EQ(times.back(), 1'000'000us);
    EXPECT_EQ(bus.next_completion(), 1'000'160us);
    EXPECT_EQ(bus.pending(), 875u);
}

// Tools reading 64 bytes at a time from one node, one read outstanding each: request (1 frame),
// the node's Datagram Received OK and 9 reply frames (the last one marked by its ID), the tool's
// Datagram Received OK. Returns the reads each tool completed within `span`.
std::vector<int> reads_within(int tools, Duration span) {
    constexpr BusPacer::Source kNode = 0;
    BusPacer bus(125000);
    std::vector<int> reads(static_cast<std::size_t>(tools), 0);
    for (int t = 0; t < tools; ++t) bus.push(1 + t, frame(0x1A000100u + t, 7), 0us);
    for (int guard = 0; guard < 1'000'000; ++guard) {
        const auto next = bus.next_completion();
        if (!next || *next > span) break;
        const auto done = bus.pop(*next);
        const Duration now = done->completed_at;
        const std::uint32_t tool = done->frame.id & 0xF;
        if (done->frame.id >> 24 == 0x1A) {  // a request reached the node
            bus.push(kNode, frame(0x19A28000u + tool, 2), now);
            for (int i = 0; i < 8; ++i) bus.push(kNode, frame(0x1C000200u + tool, 8), now);
            bus.push(kNode, frame(0x1D000200u + tool, 6), now);
        } else if (done->frame.id >> 24 == 0x1D) {  // the reply is complete
            ++reads[tool];
            bus.push(1 + tool, frame(0x19A28100u + tool, 2), now);
            bus.push(1 + tool, frame(0x1A000100u + tool, 7), now);
        }
    }
    return reads;
}

TEST(BusPacer, TwoDownloadsShareTheBusAboutEvenly) {
    const auto alone = reads_within(1, 10s);
    const auto both = reads_within(2, 10s);
    // 150 + 100 + 8 * 160 + 140 + 100 = 1,770 bits = 14.16 ms per read at 125 kbit/s.
    EXPECT_EQ(alone[0], 706);
    EXPECT_NEAR(both[0], alone[0] / 2.0, 2);
    EXPECT_NEAR(both[1], alone[0] / 2.0, 2);
}

}  // namespace
}  // namespace olcb
