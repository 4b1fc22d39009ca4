// GridConnect-over-TCP hub: every TCP client and every local endpoint form one CAN segment.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include "openlcb/asio.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// Limits of one TcpHubServer.
struct TcpHubOptions {
    std::size_t max_client_queue_bytes = 256 * 1024;  ///< output bytes waiting per client
    std::size_t max_clients = 64;                     ///< connections beyond are closed
};

/// A TCP server joining its clients (and local endpoints) into one virtual CAN segment.
///
/// Frames read from a client are parsed and re-formatted (uppercase, 8 ID digits, '\n' after
/// ';') before they go to every other client and local endpoint, never back to the sender.
/// Garbage and over-long frame text are skipped by the GridConnect parser (bounded, counted).
/// Slow clients: each client has a bounded output queue; a client whose queue would exceed
/// Options::max_client_queue_bytes is disconnected at once (dropping single frames would
/// silently corrupt multi-frame messages; a dropped client notices and can reconnect).
class TcpHubServer {
public:
    /// Limits of one hub.
    using Options = TcpHubOptions;

    /// Counters since construction.
    struct Stats {
        std::uint64_t clients_accepted = 0;
        std::uint64_t clients_rejected = 0;      ///< refused because max_clients were connected
        std::uint64_t clients_dropped_slow = 0;  ///< disconnected for an overflowing queue
        std::uint64_t frames_received = 0;       ///< valid frames from clients and local endpoints
        std::uint64_t parse_errors = 0;          ///< invalid or over-long frame texts from clients
        std::size_t queued_bytes = 0;            ///< output bytes currently held for all clients
        std::size_t peak_client_queue_bytes = 0;
    };

    /// A hub that runs its I/O on `io`.
    explicit TcpHubServer(boost::asio::io_context& io, Options options = {});
    /// Stops the hub (closing every connection).
    ~TcpHubServer();
    TcpHubServer(const TcpHubServer&) = delete;
    TcpHubServer& operator=(const TcpHubServer&) = delete;

    /// Listens on address:port (port 0 picks a free one, see port()); returns the error if any.
    boost::system::error_code listen(const std::string& address, std::uint16_t port);
    /// The bound port once listening, else 0.
    std::uint16_t port() const;
    /// Adds an in-process port on the segment; it lives as long as the hub.
    Transport& add_local_endpoint(FrameHandler handler = {});
    /// Closes the listener and every client; local endpoints stop receiving.
    void stop();
    /// Number of connected clients.
    std::size_t client_count() const;
    /// Counters and queue sizes.
    Stats stats() const;

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace olcb
