// Shared helpers of the TCP transport tests: bounded event-loop driving, raw loopback sockets,
// the hub on a free loopback port.
#pragma once

#include <gtest/gtest.h>

#include <array>
#include <chrono>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "openlcb/asio.hpp"
#include "openlcb/can_frame.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_client.hpp"
#include "openlcb/tcp_hub_server.hpp"

namespace olcb::test {

/// Runs `io` until `done()` holds or `limit` passes; returns done().
inline bool run_until(boost::asio::io_context& io, const std::function<bool()>& done,
                      std::chrono::milliseconds limit = std::chrono::seconds(20)) {
    const auto deadline = std::chrono::steady_clock::now() + limit;
    while (!done() && std::chrono::steady_clock::now() < deadline) {
        if (io.stopped()) io.restart();
        io.run_one_for(std::chrono::milliseconds(20));
    }
    return done();
}

/// An extended frame whose ID carries `alias` and whose data carries `seq`.
inline CanFrame numbered_frame(std::uint16_t alias, std::uint32_t seq) {
    CanFrame f;
    f.id = 0x195B4000u | alias;
    f.len = 8;
    f.data = {0x05,
              0x01,
              0x01,
              0x01,
              static_cast<std::uint8_t>(seq >> 24),
              static_cast<std::uint8_t>(seq >> 16),
              static_cast<std::uint8_t>(seq >> 8),
              static_cast<std::uint8_t>(seq)};
    return f;
}

/// The sequence number numbered_frame() put into `f`.
inline std::uint32_t frame_seq(const CanFrame& f) {
    return std::uint32_t{f.data[4]} << 24 | std::uint32_t{f.data[5]} << 16 |
           std::uint32_t{f.data[6]} << 8 | f.data[7];
}

/// GridConnect lines of numbered_frame(alias, 0) to numbered_frame(alias, n - 1), as a client
/// writes them.
inline std::string numbered_lines(std::uint16_t alias, std::uint32_t n) {
    std::string text;
    for (std::uint32_t seq = 0; seq < n; ++seq) {
        text += gridconnect::format(numbered_frame(alias, seq));
        text += '\n';
    }
    return text;
}

/// 0, 1, ..., n - 1: the sequence numbers of n numbered frames sent in order.
inline std::vector<std::uint32_t> sequence(std::uint32_t n) {
    std::vector<std::uint32_t> v(n);
    for (std::uint32_t i = 0; i < n; ++i) v[i] = i;
    return v;
}

/// A raw loopback socket: what a foreign or misbehaving client does on the wire.
struct RawClient {
    RawClient(boost::asio::io_context& io, std::uint16_t port) : socket(io) {
        socket.connect(
            boost::asio::ip::tcp::endpoint(boost::asio::ip::address_v4::loopback(), port));
    }
    /// Connects from another loopback address (`from`, e.g. "127.0.0.2"), as a second host.
    RawClient(boost::asio::io_context& io, std::uint16_t port, const char* from) : socket(io) {
        namespace ip = boost::asio::ip;
        socket.open(ip::tcp::v4());
        socket.bind(ip::tcp::endpoint(ip::make_address_v4(from), 0));
        socket.connect(ip::tcp::endpoint(ip::address_v4::loopback(), port));
    }
    /// Reads until the peer closes, appending to text; closed is set then.
    void start_reading() {
        socket.async_read_some(boost::asio::buffer(buf),
                               [this](const boost::system::error_code& ec, std::size_t n) {
                                   if (ec) {
                                       closed = true;
                                       return;
                                   }
                                   text.append(buf.data(), n);
                                   start_reading();
                               });
    }
    boost::asio::ip::tcp::socket socket;
    std::array<char, 4096> buf{};
    std::string text;
    bool closed = false;
};

/// A TcpHubServer with `options` on a free loopback port once start() ran; its log lines kept.
class HubFixture : public ::testing::Test {
protected:
    void start() {
        hub = std::make_unique<TcpHubServer>(io, options);
        hub->set_log_handler([this](const std::string& line) { log.push_back(line); });
        ASSERT_FALSE(hub->listen("127.0.0.1", 0));
        ASSERT_NE(hub->port(), 0);
    }
    /// A started TcpClient of the hub that hands what it receives to `handler`.
    std::unique_ptr<TcpClient> connect_client(std::function<void(const CanFrame&)> handler) {
        auto client = std::make_unique<TcpClient>(io, "127.0.0.1", hub->port());
        client->set_handler(std::move(handler));
        client->start();
        return client;
    }
    /// Whether a log line contains `part`.
    bool logged(std::string_view part) const {
        for (const auto& l : log) {
            if (l.find(part) != std::string::npos) return true;
        }
        return false;
    }
    boost::asio::io_context io;
    TcpHubServer::Options options;
    std::unique_ptr<TcpHubServer> hub;
    std::vector<std::string> log;
};

}  // namespace olcb::test
