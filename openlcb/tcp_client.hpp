// GridConnect-over-TCP client: joins a hub's segment and keeps reconnecting when it goes away.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "openlcb/asio.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// Reconnect and queue limits of a TcpClient.
struct TcpClientOptions {
    std::chrono::milliseconds initial_backoff{100};  ///< delay before the first retry
    std::chrono::milliseconds max_backoff{5000};     ///< the delay never grows past this
    unsigned backoff_factor = 2;                     ///< delay multiplier per failed attempt
    unsigned max_attempts = 0;  ///< consecutive failed connects before giving up; 0 = never
    std::size_t max_queue_bytes =
        std::size_t{256} * 1024;  ///< unsent output beyond this drops the connection
    bool drop_echoes = true;      ///< drop frames that echo our own (hubs that echo; EchoFilter)
};

/// Delay before reconnect attempt `failures` + 1: initial * factor^failures, capped at max_backoff.
std::chrono::milliseconds reconnect_delay(const TcpClientOptions& options, unsigned failures);

/// A port on a remote hub's segment (GridConnect lines over TCP).
///
/// While disconnected, sent frames are dropped and counted (a CAN port off the bus loses them
/// too). When the connection breaks, or its output queue overflows, it reconnects after
/// reconnect_delay(); a successful connect resets the delay.
class TcpClient final : public Transport {
public:
    /// Counters since construction.
    struct Stats {
        std::uint64_t connect_attempts = 0;
        std::uint64_t connects = 0;
        std::uint64_t disconnects = 0;
        std::uint64_t frames_sent = 0;
        std::uint64_t frames_received = 0;
        std::uint64_t frames_dropped = 0;  ///< sent while disconnected
        std::uint64_t parse_errors = 0;
        std::uint64_t echoes_dropped = 0;  ///< received frames recognised as our own echo
    };

    /// A client of host:port running on `io`; call start() to connect.
    TcpClient(boost::asio::io_context& io, std::string host, std::uint16_t port,
              TcpClientOptions options = {});
    /// Stops the client.
    ~TcpClient() override;
    TcpClient(const TcpClient&) = delete;
    TcpClient& operator=(const TcpClient&) = delete;

    /// Starts connecting (and reconnecting) in the background.
    void start();
    /// Closes the connection and stops reconnecting.
    void stop();
    /// True while connected to the hub.
    bool connected() const;
    /// True after max_attempts consecutive failures made the client give up.
    bool gave_up() const;
    /// Why the last connect attempt failed ("connection refused", "host X not found (...)",
    /// the system's text otherwise); "" while none has.
    std::string last_error() const;
    /// Called with true on each connect and false on each disconnect.
    void set_connection_handler(std::function<void(bool connected)> handler);
    /// Counters.
    Stats stats() const;
    /// Output bytes not yet handed to the socket (pacing for bulk senders).
    std::size_t queued_bytes() const;

    /// Queues the frame as one GridConnect line; dropped (counted) when not connected.
    void send(const CanFrame& frame) override;
    /// Receives the frames the hub relays from other ports.
    void set_handler(FrameHandler handler) override;

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace olcb
