#include "openlcb/tcp_client.hpp"

#include <gtest/gtest.h>

#include <array>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/tcp_test_util.hpp"

namespace olcb {
namespace {

using namespace std::chrono_literals;
using test::numbered_frame;
using test::run_until;

TEST(ReconnectDelay, GrowsGeometricallyUpToTheCap) {
    TcpClientOptions o;
    o.initial_backoff = 100ms;
    o.max_backoff = 5000ms;
    o.backoff_factor = 2;
    EXPECT_EQ(reconnect_delay(o, 0), 100ms);
    EXPECT_EQ(reconnect_delay(o, 1), 200ms);
    EXPECT_EQ(reconnect_delay(o, 5), 3200ms);
    EXPECT_EQ(reconnect_delay(o, 6), 5000ms);
    EXPECT_EQ(reconnect_delay(o, 1000), 5000ms);
    o.backoff_factor = 1;
    EXPECT_EQ(reconnect_delay(o, 10), 100ms);
}

TEST(TcpClient, ReconnectsWithBackoffAfterTheHubRestarts) {
    boost::asio::io_context io;
    auto hub = std::make_unique<TcpHubServer>(io);
    ASSERT_FALSE(hub->listen("127.0.0.1", 0));
    const std::uint16_t port = hub->port();

    TcpClientOptions options;
    options.initial_backoff = 5ms;
    options.max_backoff = 40ms;
    TcpClient client(io, "127.0.0.1", port, options);
    std::vector<bool> transitions;
    client.set_connection_handler([&](bool up) { transitions.push_back(up); });
    std::vector<CanFrame> received;
    client.set_handler([&](const CanFrame& f) { received.push_back(f); });
    client.start();
    ASSERT_TRUE(run_until(io, [&] { return client.connected() && hub->client_count() == 1; }));

    hub.reset();  // the hub goes away
    ASSERT_TRUE(run_until(io, [&] { return !client.connected(); }));
    client.send(numbered_frame(0x100, 1));  // off the bus: dropped
    EXPECT_EQ(client.stats().frames_dropped, 1u);
    // Some attempts fail while nobody listens.
    ASSERT_TRUE(run_until(io, [&] { return client.stats().connect_attempts >= 4; }));
    EXPECT_FALSE(client.connected());

    hub = std::make_unique<TcpHubServer>(io);
    ASSERT_FALSE(hub->listen("127.0.0.1", port));
    std::vector<CanFrame> local_received;
    Transport& local =
        hub->add_local_endpoint([&](const CanFrame& f) { local_received.push_back(f); });
    ASSERT_TRUE(run_until(io, [&] { return client.connected() && hub->client_count() == 1; }));
    EXPECT_EQ(transitions, (std::vector<bool>{true, false, true}));
    EXPECT_EQ(client.stats().connects, 2u);

    client.send(numbered_frame(0x100, 2));
    local.send(numbered_frame(0x101, 3));
    ASSERT_TRUE(run_until(io, [&] { return !local_received.empty() && !received.empty(); }));
    EXPECT_EQ(local_received.front(), numbered_frame(0x100, 2));
    EXPECT_EQ(received.front(), numbered_frame(0x101, 3));
}

TEST(TcpClient, GivesUpAfterMaxAttempts) {
    boost::asio::io_context io;
    std::uint16_t port = 0;
    {
        TcpHubServer probe(io);  // find a port nobody listens on afterwards
        ASSERT_FALSE(probe.listen("127.0.0.1", 0));
        port = probe.port();
    }
    TcpClientOptions options;
    options.initial_backoff = 1ms;
    options.max_attempts = 3;
    TcpClient client(io, "127.0.0.1", port, options);
    client.start();
    ASSERT_TRUE(run_until(io, [&] { return client.gave_up(); }));
    EXPECT_EQ(client.stats().connect_attempts, 3u);
    EXPECT_EQ(client.stats().connects, 0u);
}

TEST(TcpClient, DestructionWithPendingWorkClosesTheConnectionSafely) {
    boost::asio::io_context io;
    TcpHubServer hub(io);
    ASSERT_FALSE(hub.listen("127.0.0.1", 0));
    bool called = false;
    {
        TcpClient client(io, "127.0.0.1", hub.port());
        client.set_handler([&](const CanFrame&) { called = true; });
        client.set_connection_handler([&](bool) { called = true; });
        client.start();
        ASSERT_TRUE(run_until(io, [&] { return client.connected() && hub.client_count() == 1; }));
        called = false;
        client.send(numbered_frame(0x100, 1));
        hub.add_local_endpoint().send(numbered_frame(0x101, 2));
    }  // destroyed with a write and a read pending
    ASSERT_TRUE(run_until(io, [&] { return hub.client_count() == 0; }));
    EXPECT_FALSE(called);  // no callback after destruction
}

TEST(TcpClient, StopEndsReconnecting) {
    boost::asio::io_context io;
    auto hub = std::make_unique<TcpHubServer>(io);
    ASSERT_FALSE(hub->listen("127.0.0.1", 0));
    TcpClientOptions options;
    options.initial_backoff = 1ms;
    TcpClient client(io, "127.0.0.1", hub->port(), options);
    client.start();
    ASSERT_TRUE(run_until(io, [&] { return client.connected(); }));
    hub.reset();
    ASSERT_TRUE(run_until(io, [&] { return client.stats().connect_attempts >= 3; }));
    client.stop();
    const auto attempts = client.stats().connect_attempts;
    run_until(
        io, [] { return false; }, 30ms);
    EXPECT_EQ(client.stats().connect_attempts, attempts);
    EXPECT_FALSE(client.connected());
}

// A hub that echoes: writes back everything a client sends, and one frame of its own after the
// first bytes.
class EchoingServer {
public:
    EchoingServer(boost::asio::io_context& io, CanFrame foreign)
        : acceptor_(io, {boost::asio::ip::make_address("127.0.0.1"), 0}),
          socket_(io),
          foreign_(foreign) {
        acceptor_.async_accept(socket_, [this](const boost::system::error_code& ec) {
            if (!ec) read();
        });
    }
    std::uint16_t port() const { return acceptor_.local_endpoint().port(); }

private:
    void read() {
        socket_.async_read_some(boost::asio::buffer(buf_),
                                [this](const boost::system::error_code& ec, std::size_t n) {
                                    if (ec) return;
                                    std::string out(buf_.data(), n);
                                    if (!foreign_sent_) {
                                        out += gridconnect::format(foreign_) + "\n";
                                        foreign_sent_ = true;
                                    }
                                    queue_.push_back(std::move(out));
                                    if (queue_.size() == 1) write();
                                    read();
                                });
    }
    void write() {
        boost::asio::async_write(socket_, boost::asio::buffer(queue_.front()),
                                 [this](const boost::system::error_code& ec, std::size_t) {
                                     if (ec) return;
                                     queue_.pop_front();
                                     if (!queue_.empty()) write();
                                 });
    }

    boost::asio::ip::tcp::acceptor acceptor_;
    boost::asio::ip::tcp::socket socket_;
    CanFrame foreign_;
    bool foreign_sent_ = false;
    std::array<char, 4096> buf_{};
    std::deque<std::string> queue_;
};

TEST(TcpClient, DropsEchoesOfItsOwnFramesFromAnEchoingHub) {
    boost::asio::io_context io;
    const auto ours = numbered_frame(0x100, 1);
    const auto theirs = numbered_frame(0x200, 1);
    EchoingServer server(io, theirs);
    TcpClient client(io, "127.0.0.1", server.port());
    std::vector<CanFrame> received;
    client.set_handler([&](const CanFrame& f) { received.push_back(f); });
    client.start();
    ASSERT_TRUE(run_until(io, [&] { return client.connected(); }));
    client.send(ours);
    ASSERT_TRUE(run_until(io, [&] { return !received.empty(); }));
    EXPECT_EQ(received, (std::vector<CanFrame>{theirs}));
    EXPECT_EQ(client.stats().echoes_dropped, 1u);
    EXPECT_EQ(client.stats().frames_received, 1u);
}

TEST(TcpClient, DeliversEchoesWhenAskedNotToDropThem) {
    boost::asio::io_context io;
    const auto ours = numbered_frame(0x100, 1);
    const auto theirs = numbered_frame(0x200, 1);
    EchoingServer server(io, theirs);
    TcpClientOptions options;
    options.drop_echoes = false;
    TcpClient client(io, "127.0.0.1", server.port(), options);
    std::vector<CanFrame> received;
    client.set_handler([&](const CanFrame& f) { received.push_back(f); });
    client.start();
    ASSERT_TRUE(run_until(io, [&] { return client.connected(); }));
    client.send(ours);
    ASSERT_TRUE(run_until(io, [&] { return received.size() == 2; }));
    EXPECT_EQ(received, (std::vector<CanFrame>{ours, theirs}));
    EXPECT_EQ(client.stats().echoes_dropped, 0u);
}

}  // namespace
}  // namespace olcb
