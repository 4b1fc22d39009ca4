#include "openlcb/tcp_client.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "openlcb/tcp_hub_server.hpp"
#include "openlcb/transport/tcp_test_util.hpp"

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

}  // namespace
}  // namespace olcb
