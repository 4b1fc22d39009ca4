#include "openlcb/tcp_hub_server.hpp"

#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/in_process_bus.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using test::frame_seq;
using test::numbered_frame;
using test::run_until;

// Per-sender received sequence numbers.
struct Inbox {
    std::vector<std::vector<std::uint32_t>> from;  // index: alias - 0x100
    explicit Inbox(std::size_t senders) : from(senders) {}
    void take(const CanFrame& f) {
        const std::uint32_t alias = f.id & 0xFFF;
        if ((f.id & 0x1FFFF000u) == 0x195B4000u && alias >= 0x100 && alias < 0x100 + from.size())
            from[alias - 0x100].push_back(frame_seq(f));
    }
};

class TcpHubTest : public test::HubFixture {
protected:
    void SetUp() override { start(); }
    std::unique_ptr<TcpClient> connect_client(Inbox& inbox) {
        return HubFixture::connect_client([&inbox](const CanFrame& f) { inbox.take(f); });
    }
};

// Whether every client (inboxes[i] is client i, sender 3 the local endpoint) has the frames of
// every other sender and the local endpoint those of every client, `frames` of each at least.
bool all_arrived(const std::vector<Inbox>& inboxes, const Inbox& local_inbox, std::size_t frames) {
    for (std::size_t r = 0; r < 3; ++r)
        for (std::size_t s = 0; s < 4; ++s)
            if (r != s && inboxes[r].from[s].size() < frames) return false;
    for (std::size_t s = 0; s < 3; ++s)
        if (local_inbox.from[s].size() < frames) return false;
    return true;
}

void expect_clients_got_all_but_their_own(const std::vector<Inbox>& inboxes,
                                          const std::vector<std::uint32_t>& expected) {
    for (std::size_t r = 0; r < 3; ++r) {
        for (std::size_t s = 0; s < 4; ++s) {
            if (r == s) {
                EXPECT_TRUE(inboxes[r].from[s].empty()) << "client " << r << " got its own frames";
            } else {
                EXPECT_EQ(inboxes[r].from[s], expected) << "client " << r << " from " << s;
            }
        }
    }
}

TEST_F(TcpHubTest, ThreeClientsSeeEachOthersFramesNeverTheirOwn) {
    std::vector<Inbox> inboxes(3, Inbox(4));
    std::vector<std::unique_ptr<TcpClient>> clients;
    clients.reserve(inboxes.size());
    for (auto& inbox : inboxes) clients.push_back(connect_client(inbox));
    Inbox local_inbox(4);
    Transport& local = hub->add_local_endpoint([&](const CanFrame& f) { local_inbox.take(f); });
    ASSERT_TRUE(run_until(io, [&] {
        return hub->client_count() == 3 && clients[0]->connected() && clients[1]->connected() &&
               clients[2]->connected();
    }));
    constexpr std::uint32_t kFrames = 50;
    for (std::uint32_t seq = 0; seq < kFrames; ++seq) {
        for (std::uint16_t i = 0; i < 3; ++i) clients[i]->send(numbered_frame(0x100 + i, seq));
        local.send(numbered_frame(0x103, seq));
    }
    const auto expected = test::sequence(kFrames);
    ASSERT_TRUE(run_until(io, [&] { return all_arrived(inboxes, local_inbox, kFrames); }));
    // Let any stray echo arrive before checking that none came.
    run_until(
        io, [] { return false; }, std::chrono::milliseconds(50));
    expect_clients_got_all_but_their_own(inboxes, expected);
    EXPECT_TRUE(local_inbox.from[3].empty());
    EXPECT_EQ(hub->stats().frames_received, 4 * kFrames);
}

TEST_F(TcpHubTest, LocalEndpointRepliesFromItsHandlerReachTheClients) {
    Inbox inbox_a(3), inbox_b(3);
    auto a = connect_client(inbox_a);
    auto b = connect_client(inbox_b);
    Transport* responder = nullptr;
    int seen_by_observer = 0;
    responder = &hub->add_local_endpoint([&](const CanFrame& f) {
        if ((f.id & 0xFFF) == 0x100) responder->send(numbered_frame(0x102, frame_seq(f)));
    });
    hub->add_local_endpoint([&](const CanFrame&) { ++seen_by_observer; });
    ASSERT_TRUE(run_until(
        io, [&] { return hub->client_count() == 2 && a->connected() && b->connected(); }));
    for (std::uint32_t seq = 0; seq < 10; ++seq) a->send(numbered_frame(0x100, seq));
    ASSERT_TRUE(run_until(io, [&] {
        return inbox_a.from[2].size() == 10 && inbox_b.from[2].size() == 10 &&
               inbox_b.from[0].size() == 10;
    }));
    EXPECT_EQ(seen_by_observer, 20);  // the requests and the replies
    EXPECT_EQ(inbox_a.from[2].back(), 9u);
}

TEST_F(TcpHubTest, TheFrameObserverNamesEachSenderAndEndedConnectionsAreReported) {
    std::vector<std::pair<std::uint64_t, std::string>> seen;
    hub->set_frame_observer([&](const CanFrame&, const TcpHubServer::FrameSource& source) {
        seen.emplace_back(source.connection, std::string(source.remote));
    });
    std::vector<std::uint64_t> ended;
    hub->set_disconnect_handler(
        [&](std::uint64_t connection, const std::string&) { ended.push_back(connection); });
    Transport& local = hub->add_local_endpoint();
    const auto local_connection = hub->connection_of(local);
    ASSERT_TRUE(local_connection);
    {
        test::RawClient raw(io, hub->port());
        ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == 1; }));
        boost::asio::write(raw.socket, boost::asio::buffer(std::string(":X19490123N;\n")));
        ASSERT_TRUE(run_until(io, [&] { return seen.size() == 1; }));
        EXPECT_NE(seen[0].first, *local_connection);
        EXPECT_TRUE(seen[0].second.starts_with("127.0.0.1:")) << seen[0].second;
        local.send(numbered_frame(0x100, 1));
        ASSERT_EQ(seen.size(), 2u);
        EXPECT_EQ(seen[1], std::make_pair(*local_connection, std::string()));
    }
    ASSERT_TRUE(run_until(io, [&] { return ended.size() == 1; }));
    EXPECT_EQ(ended[0], seen[0].first);
    InProcessBus other;
    EXPECT_FALSE(hub->connection_of(other.add_endpoint()));
}

TEST_F(TcpHubTest, LowercaseAndShortIdFramesAreRelayedReformatted) {
    test::RawClient writer(io, hub->port());
    test::RawClient reader(io, hub->port());
    reader.start_reading();
    ASSERT_TRUE(run_until(io, [&] { return hub->client_count() == 2; }));
    const std::string input = "garbage\r\n:x19490343n;\n  :X1a2N0a0B;:X19170343N050101012200;";
    boost::asio::write(writer.socket, boost::asio::buffer(input));
    const std::string expected = ":X19490343N;\n:X000001A2N0A0B;\n:X19170343N050101012200;\n";
    ASSERT_TRUE(run_until(io, [&] { return reader.text.size() >= expected.size(); }));
    EXPECT_EQ(reader.text, expected);
    EXPECT_EQ(hub->stats().frames_received, 3u);
}

TEST_F(TcpHubTest, StalledClientIsDroppedWhileOthersKeepReceiving) {
    hub.reset();
    options.max_client_queue_bytes = std::size_t{64} * 1024;
    options.max_client_frames_per_second = 0;  // 10 MB from one client: no rate limit here
    SetUp();
    test::RawClient stalled(io, hub->port());  // connects, never reads
    stalled.socket.set_option(boost::asio::socket_base::receive_buffer_size(4096));
    Inbox inbox_a(2), inbox_b(2);
    auto a = connect_client(inbox_a);
    auto b = connect_client(inbox_b);
    ASSERT_TRUE(run_until(
        io, [&] { return hub->client_count() == 3 && a->connected() && b->connected(); }));

    // 10 MB of GridConnect text from a, paced by b's progress (b must keep up throughout).
    const std::size_t line = gridconnect::format(numbered_frame(0x100, 0)).size() + 1;
    const std::uint32_t total = static_cast<std::uint32_t>(std::size_t{10} * 1024 * 1024 / line);
    constexpr std::uint32_t kBatch = 2000;
    std::size_t peak_queue = 0;
    for (std::uint32_t sent = 0; sent < total;) {
        const std::uint32_t end = std::min(total, sent + kBatch);
        for (; sent < end; ++sent) a->send(numbered_frame(0x100, sent));
        ASSERT_TRUE(run_until(io, [&] { return inbox_b.from[0].size() == sent; }))
            << "b stalled at " << inbox_b.from[0].size() << " of " << sent;
        peak_queue = std::max(peak_queue, hub->stats().queued_bytes);
    }
    const auto stats = hub->stats();
    EXPECT_EQ(stats.clients_dropped_slow, 1u);
    EXPECT_EQ(hub->client_count(), 2u);
    EXPECT_LE(stats.peak_client_queue_bytes, 2 * options.max_client_queue_bytes);
    EXPECT_LE(peak_queue, 2 * options.max_client_queue_bytes);
    EXPECT_EQ(a->stats().disconnects, 0u);
    EXPECT_EQ(inbox_b.from[0].front(), 0u);
    EXPECT_EQ(inbox_b.from[0].back(), total - 1);
}

TEST_F(TcpHubTest, GarbageFloodDoesNotHarmOtherClients) {
    Inbox inbox_a(2), inbox_b(2);
    auto a = connect_client(inbox_a);
    auto b = connect_client(inbox_b);
    test::RawClient noisy(io, hub->port());
    test::RawClient endless(io, hub->port());
    ASSERT_TRUE(run_until(
        io, [&] { return hub->client_count() == 4 && a->connected() && b->connected(); }));

    std::string noise(std::size_t{10} * 1024 * 1024, '\0');
    std::mt19937 rng(1234);
    for (char& c : noise) c = static_cast<char>(rng());
    std::string endless_frame = ":X19490343N" + std::string(std::size_t{10} * 1024 * 1024, 'A');
    std::size_t written = 0;
    auto write_all = [&](test::RawClient& c, const std::string& text) {
        boost::asio::async_write(c.socket, boost::asio::buffer(text),
                                 [&](const boost::system::error_code& ec, std::size_t n) {
                                     ASSERT_FALSE(ec);
                                     written += n;
                                 });
    };
    write_all(noisy, noise);
    write_all(endless, endless_frame);

    std::uint32_t seq = 0;
    // Keep exchanging valid frames until both floods are fully consumed by the hub.
    while (written < noise.size() + endless_frame.size() || seq < 100) {
        a->send(numbered_frame(0x100, seq));
        b->send(numbered_frame(0x101, seq));
        ++seq;
        ASSERT_TRUE(run_until(
            io, [&] { return inbox_b.from[0].size() == seq && inbox_a.from[1].size() == seq; }))
            << "exchange stalled at " << seq;
    }
    // The hub consumed the floods (the last bytes may still be in its read buffer).
    ASSERT_TRUE(run_until(io, [&] { return hub->stats().parse_errors > 0; }));
    for (std::uint32_t i = 0; i < seq; ++i) {
        ASSERT_EQ(inbox_b.from[0][i], i);
        ASSERT_EQ(inbox_a.from[1][i], i);
    }
    EXPECT_EQ(a->stats().disconnects, 0u);
    EXPECT_EQ(b->stats().disconnects, 0u);
    EXPECT_EQ(hub->stats().clients_dropped_slow, 0u);
}

TEST_F(TcpHubTest, ExtraClientsBeyondTheLimitAreRefused) {
    hub.reset();
    options.max_clients = 1;
    SetUp();
    test::RawClient first(io, hub->port());
    test::RawClient second(io, hub->port());
    second.start_reading();
    ASSERT_TRUE(run_until(io, [&] { return second.closed; }));
    EXPECT_EQ(hub->stats().clients_rejected, 1u);
    EXPECT_EQ(hub->client_count(), 1u);
}

TEST(TcpHubServer, ListenReportsBadAddressAndBusyPort) {
    boost::asio::io_context io;
    TcpHubServer a(io);
    EXPECT_TRUE(a.listen("not-an-address", 0));
    ASSERT_FALSE(a.listen("127.0.0.1", 0));
    TcpHubServer b(io);
    EXPECT_EQ(b.listen("127.0.0.1", a.port()), boost::asio::error::address_in_use);
    EXPECT_EQ(b.port(), 0);
    // The failed bind closed b's listener again, so it can listen elsewhere; a listening a says
    // so rather than opening a second listener.
    EXPECT_FALSE(b.listen("127.0.0.1", 0));
    EXPECT_NE(b.port(), 0);
    EXPECT_EQ(a.listen("127.0.0.1", 0), boost::asio::error::already_open);
    a.stop();
    EXPECT_EQ(a.port(), 0);
}

}  // namespace
}  // namespace olcb
