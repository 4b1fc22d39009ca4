// The TCP hub with Options::bitrate, on loopback with bounded loops and the steady clock: frames
// between clients and to and from local endpoints reach the others no sooner than their CAN frame
// time on one shared bus, in order; a flooding client waits in TCP, not in the hub's memory.
#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/can_timing.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using std::chrono::steady_clock;
using test::frame_seq;
using test::numbered_frame;
using test::run_until;

// Arrival times (steady clock) and sequence numbers of the numbered frames one port receives.
struct Arrivals {
    std::vector<std::uint32_t> seq;
    std::vector<steady_clock::time_point> at;
    void take(const CanFrame& f) {
        if ((f.id & 0x1FFFF000u) != 0x195B4000u) return;
        seq.push_back(frame_seq(f));
        at.push_back(steady_clock::now());
    }
};

class TcpHubPacingTest : public test::HubFixture {
protected:
    void start(std::uint32_t bitrate) {
        options.bitrate = bitrate;
        HubFixture::start();
    }
    std::unique_ptr<TcpClient> client(Arrivals& into) {
        return connect_client([&into](const CanFrame& f) { into.take(f); });
    }
};

TEST_F(TcpHubPacingTest, ABurstReachesAnotherClientNoSoonerThanItsFrameTime) {
    start(125000);
    Arrivals at_a, at_b;
    auto a = client(at_a);
    auto b = client(at_b);
    ASSERT_TRUE(run_until(io, [&] { return a->connected() && b->connected(); }));
    ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == 2; }));
    constexpr std::uint32_t kFrames = 40;
    const auto sent = steady_clock::now();
    for (std::uint32_t i = 0; i < kFrames; ++i) a->send(numbered_frame(0x100, i));
    ASSERT_TRUE(run_until(io, [&] { return at_b.seq.size() == kFrames; }));
    EXPECT_EQ(at_b.seq, test::sequence(kFrames));
    const auto frame = can_frame_time(8, 125000);  // 1.28 ms
    EXPECT_GE(at_b.at.back() - sent, kFrames * frame);
    EXPECT_GE(at_b.at.front() - sent, frame);
    EXPECT_TRUE(at_a.seq.empty());  // never back to the sender
    const auto stats = hub->stats();
    EXPECT_EQ(stats.bus_busy_time, kFrames * frame);
    EXPECT_EQ(stats.bus_bits, kFrames * 160u);
    EXPECT_EQ(stats.bus_frames_waiting, 0u);
}

TEST_F(TcpHubPacingTest, LocalEndpointsAndClientsShareOneBus) {
    start(125000);
    Arrivals at_client, at_local;
    Transport* local = nullptr;
    // A node that answers every frame with one frame of its own.
    local = &hub->add_local_endpoint([&](const CanFrame& f) {
        at_local.take(f);
        CanFrame answer = numbered_frame(0x200, frame_seq(f));
        local->send(answer);
    });
    auto a = client(at_client);
    ASSERT_TRUE(run_until(io, [&] { return a->connected() && hub->client_count() == 1; }));
    constexpr std::uint32_t kFrames = 10;
    const auto sent = steady_clock::now();
    for (std::uint32_t i = 0; i < kFrames; ++i) a->send(numbered_frame(0x100, i));
    ASSERT_TRUE(run_until(io, [&] { return at_client.seq.size() == kFrames; }));
    EXPECT_EQ(at_client.seq, test::sequence(kFrames));
    EXPECT_EQ(at_local.seq, test::sequence(kFrames));
    const auto frame = can_frame_time(8, 125000);
    // Requests and answers take turns on one bus: 2 x 10 frames have gone over it.
    EXPECT_GE(at_client.at.back() - sent, 2 * kFrames * frame);
    EXPECT_GE(at_local.at.front() - sent, frame);
    EXPECT_EQ(hub->stats().bus_busy_time, 2 * kFrames * frame);
}

TEST_F(TcpHubPacingTest, AFloodWaitsInTcpNotInTheHub) {
    options.max_client_frames_per_second = 0;  // the bus alone must slow it
    start(1'000'000);                          // 160 us per frame keeps the test short
    Arrivals at_reader;
    auto reader = client(at_reader);
    test::RawClient flooder(io, hub->port());
    ASSERT_TRUE(run_until(io, [&] { return reader->connected() && hub->client_count() == 2; }));
    constexpr std::uint32_t kFrames = 3000;
    const std::string text = test::numbered_lines(0x100, kFrames);
    bool written = false;
    boost::asio::async_write(flooder.socket, boost::asio::buffer(text),
                             [&](const boost::system::error_code& ec, std::size_t) {
                                 EXPECT_FALSE(ec);
                                 written = true;
                             });
    const auto sent = steady_clock::now();
    std::size_t peak = 0;
    ASSERT_TRUE(run_until(io, [&] {
        peak = std::max(peak, hub->stats().bus_frames_waiting);
        return written && at_reader.seq.size() == kFrames;
    }));
    EXPECT_EQ(at_reader.seq, test::sequence(kFrames));
    EXPECT_GE(at_reader.at.back() - sent, kFrames * can_frame_time(8, 1'000'000));
    // At most the backlog limit plus one read's worth of frames (4 KiB / 29 bytes) wait.
    EXPECT_LE(peak, options.max_client_bus_frames + 4096 / 29 + 1);
    EXPECT_GT(hub->stats().read_pauses, 0u);
}

TEST_F(TcpHubPacingTest, FramesOfAClientThatLeftStillGoOutAndStopDropsTheRest) {
    start(125000);
    Arrivals at_reader;
    auto reader = client(at_reader);
    {
        test::RawClient gone(io, hub->port());
        ASSERT_TRUE(run_until(io, [&] { return reader->connected() && hub->client_count() == 2; }));
        boost::asio::write(gone.socket, boost::asio::buffer(test::numbered_lines(0x100, 20)));
        ASSERT_TRUE(run_until(io, [&] { return hub->stats().frames_received == 20; }));
    }  // closed while its frames wait for the bus
    ASSERT_TRUE(run_until(io, [&] { return at_reader.seq.size() == 20; }));
    EXPECT_EQ(at_reader.seq, test::sequence(20));
    EXPECT_EQ(hub->client_count(), 1u);

    // Frames still waiting when the hub stops are never delivered, and nothing runs late.
    Arrivals at_local;
    Transport& local = hub->add_local_endpoint();
    hub->add_local_endpoint([&](const CanFrame& f) { at_local.take(f); });
    for (std::uint32_t i = 0; i < 10; ++i) local.send(numbered_frame(0x200, i));
    hub->stop();
    run_until(
        io, [] { return false; }, std::chrono::milliseconds(30));
    EXPECT_TRUE(at_local.seq.empty());
}

}  // namespace
}  // namespace olcb
