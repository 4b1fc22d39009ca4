// The hub under attack, on loopback with bounded loops: a flooding client is slowed (its reads
// paused) instead of its readers being dropped; limits per address and in total; idle clients
// and slow readers are closed, each with a log line.
#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using std::chrono::milliseconds;
using test::frame_seq;
using test::numbered_frame;
using test::run_until;

using Raw = test::RawClient;

class TcpHubLimitsTest : public test::HubFixture {};

// A reader that takes at most 4 KiB per millisecond: slower than a flood, but it keeps up.
struct PacedReader {
    PacedReader(boost::asio::io_context& io, std::uint16_t port) : raw(io, port), timer(io) {}
    void start() {
        raw.socket.async_read_some(boost::asio::buffer(buf),
                                   [this](const boost::system::error_code& ec, std::size_t n) {
                                       if (ec) {
                                           raw.closed = true;
                                           return;
                                       }
                                       received += n;
                                       timer.expires_after(milliseconds(1));
                                       timer.async_wait([this](auto) { start(); });
                                   });
    }
    Raw raw;
    boost::asio::steady_timer timer;
    std::array<char, 4096> buf{};
    std::size_t received = 0;
};

TEST_F(TcpHubLimitsTest, AFloodIsSlowedAndNoReaderIsDropped) {
    options.socket_send_buffer_bytes = std::size_t{16} * 1024;
    options.max_client_frames_per_second = 0;  // the queues alone must slow it
    start();
    constexpr int kReaders = 4;
    std::vector<std::unique_ptr<PacedReader>> readers;
    for (int i = 0; i < kReaders; ++i) {
        readers.push_back(std::make_unique<PacedReader>(io, hub->port()));
        readers.back()->start();
    }
    Raw flooder(io, hub->port());
    ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == kReaders + 1; }));

    // ~3 MB of valid frames, written as fast as the hub takes them.
    const std::string text = test::numbered_lines(0x100, 100'000);
    bool written = false;
    boost::asio::async_write(flooder.socket, boost::asio::buffer(text),
                             [&](const boost::system::error_code& ec, std::size_t) {
                                 EXPECT_FALSE(ec);
                                 written = true;
                             });
    ASSERT_TRUE(run_until(
        io,
        [&] {
            return written && std::all_of(readers.begin(), readers.end(), [&](const auto& r) {
                       return r->received == text.size() || r->raw.closed;
                   });
        },
        std::chrono::seconds(60)));
    const auto stats = hub->stats();
    EXPECT_EQ(stats.clients_dropped_slow, 0u) << (log.empty() ? "" : log.front());
    EXPECT_GT(stats.read_pauses, 0u) << "the flood was never slowed";
    EXPECT_LE(stats.peak_client_queue_bytes, 2 * options.pause_above_bytes);
    for (const auto& r : readers) {
        EXPECT_FALSE(r->raw.closed);
        EXPECT_EQ(r->received, text.size());
    }
}

TEST_F(TcpHubLimitsTest, ConnectionsPerAddressAndInTotalAreLimited) {
    options.max_clients_per_address = 2;
    options.max_clients = 3;
    start();
    Raw a(io, hub->port()), b(io, hub->port()), c(io, hub->port());
    c.start_reading();
    b.start_reading();
    a.start_reading();
    ASSERT_TRUE(run_until(io, [&] { return a.closed || b.closed || c.closed; }));
    EXPECT_EQ(hub->stats().clients_rejected_per_address, 1u);
    EXPECT_EQ(hub->client_count(), 2u);
    EXPECT_TRUE(logged("(max-clients-per-address 2)")) << (log.empty() ? "" : log.front());
    EXPECT_TRUE(logged("refused client 127.0.0.1:"));
}

std::unique_ptr<Raw> raw_from(boost::asio::io_context& io, std::uint16_t port, const char* from) {
    auto raw = std::make_unique<Raw>(io, port, from);
    raw->start_reading();
    return raw;
}

// Idle connections from three addresses, each below the per-address limit, fill the hub.
class TcpHubEvictionTest : public TcpHubLimitsTest {
protected:
    std::vector<std::unique_ptr<Raw>> fill_with_idle_flood(milliseconds evict_idle_after) {
        options.max_clients = 6;
        options.max_clients_per_address = 2;
        options.evict_idle_after = evict_idle_after;
        start();
        std::vector<std::unique_ptr<Raw>> flood;
        for (const char* from : {"127.0.0.2", "127.0.0.3", "127.0.0.4"}) {
            for (int i = 0; i < 2; ++i) flood.push_back(raw_from(io, hub->port(), from));
        }
        run_until(io, [&] { return hub->client_count() == 6; });
        return flood;
    }
};

TEST_F(TcpHubEvictionTest, AFullHubClosesItsLongestIdleClientForANewcomer) {
    auto flood = fill_with_idle_flood(milliseconds(100));
    ASSERT_EQ(hub->client_count(), 6u);
    io.run_for(milliseconds(150));
    auto good = raw_from(io, hub->port(), "127.0.0.1");
    ASSERT_TRUE(run_until(io, [&] { return hub->stats().clients_evicted_idle == 1; }));
    io.run_for(milliseconds(50));
    EXPECT_FALSE(good->closed);
    EXPECT_TRUE(flood.front()->closed) << "the first of the flood has been idle the longest";
    EXPECT_EQ(std::count_if(flood.begin(), flood.end(), [](const auto& r) { return r->closed; }),
              1);
    EXPECT_EQ(hub->client_count(), 6u);
    EXPECT_TRUE(logged("ms, the longest, to admit 127.0.0.1:")) << (log.empty() ? "" : log.back());
}

TEST_F(TcpHubEvictionTest, AFullHubOfRecentClientsRefusesTheNewcomer) {
    auto flood = fill_with_idle_flood(milliseconds(60000));
    ASSERT_EQ(hub->client_count(), 6u);
    auto late = raw_from(io, hub->port(), "127.0.0.1");
    ASSERT_TRUE(run_until(io, [&] { return late->closed; }));
    EXPECT_EQ(hub->stats().clients_rejected, 1u);
    EXPECT_EQ(hub->stats().clients_evicted_idle, 0u);
    EXPECT_TRUE(logged("6 clients connected (max-clients 6)"));
}

// While it lives, the process may open no descriptor more (every new one fails with EMFILE).
class NoMoreDescriptors {
public:
    NoMoreDescriptors() {
        getrlimit(RLIMIT_NOFILE, &saved_);
        const int lowest_free = ::dup(0);
        ::close(lowest_free);
        rlimit none = saved_;
        none.rlim_cur = static_cast<rlim_t>(lowest_free);
        setrlimit(RLIMIT_NOFILE, &none);
    }
    ~NoMoreDescriptors() { setrlimit(RLIMIT_NOFILE, &saved_); }
    NoMoreDescriptors(const NoMoreDescriptors&) = delete;
    NoMoreDescriptors& operator=(const NoMoreDescriptors&) = delete;

private:
    rlimit saved_{};
};

TEST_F(TcpHubLimitsTest, OutOfDescriptorsTheHubRestsAndAcceptsLater) {
    start();
    boost::asio::ip::tcp::socket waiting(io);
    waiting.open(boost::asio::ip::tcp::v4());  // its descriptor exists before the limit
    {
        const NoMoreDescriptors none;
        waiting.connect({boost::asio::ip::address_v4::loopback(), hub->port()});
        io.run_for(milliseconds(300));
        EXPECT_EQ(hub->client_count(), 0u);
        EXPECT_GE(hub->stats().accept_errors, 1u);
        EXPECT_LE(hub->stats().accept_errors, 4u) << "accept() retried in a busy loop";
    }
    ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == 1; }));
    EXPECT_EQ(std::count_if(log.begin(), log.end(),
                            [](const std::string& l) {
                                return l.find("cannot accept a client") != std::string::npos;
                            }),
              1);
}

TEST_F(TcpHubLimitsTest, IdleClientsAreClosedTalkersStay) {
    options.idle_timeout = milliseconds(300);
    start();
    Raw idle(io, hub->port());
    Raw talker(io, hub->port());
    idle.start_reading();
    talker.start_reading();
    const std::string frame = gridconnect::format(numbered_frame(0x101, 1)) + "\n";
    const auto t0 = std::chrono::steady_clock::now();
    ASSERT_TRUE(run_until(io, [&] {
        boost::asio::write(talker.socket, boost::asio::buffer(frame));
        io.run_for(milliseconds(50));
        return idle.closed;
    }));
    EXPECT_GE(std::chrono::steady_clock::now() - t0, milliseconds(300));
    EXPECT_FALSE(talker.closed);
    EXPECT_EQ(hub->stats().clients_dropped_idle, 1u);
    EXPECT_TRUE(logged("idle for 300 ms (idle-timeout)"));
}

TEST_F(TcpHubLimitsTest, ASlowReaderIsDroppedNotItsPeers) {
    options.max_client_queue_bytes = 64 << 20;  // never overflows: the timeout must act
    options.slow_reader_timeout = milliseconds(600);
    start();
    Raw stalled(io, hub->port());  // never reads
    stalled.socket.set_option(boost::asio::socket_base::receive_buffer_size(4096));
    Raw reader(io, hub->port());
    reader.start_reading();
    TcpClient sender(io, "127.0.0.1", hub->port());
    sender.start();
    ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == 3 && sender.connected(); }));
    std::uint32_t seq = 0;
    ASSERT_TRUE(run_until(io, [&] {
        for (int i = 0; i < 2000; ++i) sender.send(numbered_frame(0x100, seq++));
        io.run_for(milliseconds(5));
        return hub->stats().clients_dropped_slow == 1;
    }));
    EXPECT_TRUE(logged("has not read its traffic for 600 ms"));
    EXPECT_FALSE(reader.closed);
    EXPECT_EQ(sender.stats().disconnects, 0u);
    EXPECT_EQ(hub->client_count(), 2u);
}

}  // namespace
}  // namespace olcb
