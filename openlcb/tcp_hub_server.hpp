// GridConnect-over-TCP hub: every TCP client and every local endpoint form one CAN segment.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "openlcb/asio.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// Limits of one TcpHubServer.
struct TcpHubOptions {
    std::size_t max_client_queue_bytes =
        std::size_t{256} * 1024;               ///< output bytes waiting per client
    std::size_t max_clients = 64;              ///< connections beyond are closed
    std::size_t max_clients_per_address = 48;  ///< per remote address; beyond are closed
    /// A client's output queue above this pauses reading from every client until it drains
    /// (capped at half of max_client_queue_bytes).
    std::size_t pause_above_bytes = std::size_t{64} * 1024;
    /// A queue above the pause level this long marks its client a slow reader: it no longer
    /// pauses the others, and is dropped when its queue overflows.
    std::chrono::milliseconds slow_reader_grace{500};
    /// A slow reader whose queue stays above the pause level this long is dropped.
    std::chrono::milliseconds slow_reader_timeout{5000};
    /// SO_SNDBUF of each client socket (0 = the system's): a small one keeps a flood in the
    /// hub's queues, where backpressure sees it, instead of the kernel's.
    std::size_t socket_send_buffer_bytes = 0;
    /// Frames per second one client may send, with a burst of one second's worth (0 = no
    /// limit); beyond, its reads pause (simnode uses 20,000: far above what a CAN segment
    /// carries, ~8,000/s at 1 Mbit/s, low enough that every reader keeps up with a flooder).
    std::uint32_t max_client_frames_per_second = 0;
    /// A client that sent nothing this long is closed (0 = never).
    std::chrono::milliseconds idle_timeout{0};
    /// When max_clients are connected, a newcomer (from an address below its own limit) is
    /// admitted by closing the client that has sent nothing for the longest time, if that is at
    /// least this long (0 = never: the newcomer is refused).
    std::chrono::milliseconds evict_idle_after{1000};
    /// Paces the segment as one CAN bus at this many bit/s (0 = off): every frame, whoever sent
    /// it, occupies the bus for can_frame_time() and reaches the others when it completes
    /// (BusPacer: lowest ID wins when several wait, each sender in order).
    std::uint32_t bitrate = 0;
    /// With bitrate: a client with more frames than this waiting for the bus has its reads
    /// paused until half of them went out (as a CAN adapter's full transmit buffer stops its
    /// host), so a flood waits in TCP instead of the hub's memory.
    std::size_t max_client_bus_frames = 64;
};

/// A TCP server joining its clients (and local endpoints) into one virtual CAN segment.
///
/// Frames read from a client are parsed and re-formatted (uppercase, 8 ID digits, '\n' after
/// ';') before they go to every other client and local endpoint, never back to the sender.
/// Garbage and over-long frame text are skipped by the GridConnect parser (bounded, counted).
/// Backpressure: while a client's output queue is above Options::pause_above_bytes the hub stops
/// reading from every client (TCP then slows the senders, a flooding one first), so a fast
/// sender is slowed instead of its readers being dropped. A client that stays congested past
/// slow_reader_grace is a slow reader: it stops pausing the others, and is disconnected when its
/// queue would exceed max_client_queue_bytes or it stays congested past slow_reader_timeout
/// (dropping single frames would silently corrupt multi-frame messages; a dropped client
/// notices and can reconnect). Every refusal and drop is reported to the log handler.
/// With Options::bitrate the segment is paced like one real CAN bus (see there): a local
/// endpoint's send() then only queues its frame, and every delivery (to clients and to local
/// handlers) runs from the io_context once the frame's transmission has completed.
class TcpHubServer {
public:
    /// Limits of one hub.
    using Options = TcpHubOptions;

    /// Counters since construction.
    struct Stats {
        std::uint64_t clients_accepted = 0;
        std::uint64_t clients_rejected = 0;      ///< refused because max_clients were connected
        std::uint64_t clients_dropped_slow = 0;  ///< disconnected for an overflowing queue
        std::uint64_t clients_rejected_per_address = 0;  ///< refused: too many from one address
        std::uint64_t clients_dropped_idle = 0;          ///< closed after idle_timeout
        std::uint64_t clients_evicted_idle = 0;  ///< closed for a newcomer (evict_idle_after)
        std::uint64_t accept_errors = 0;         ///< accepts that failed (e.g. no descriptors)
        std::uint64_t read_pauses = 0;      ///< times a client's reading was paused (backpressure)
        std::uint64_t frames_received = 0;  ///< valid frames from clients and local endpoints
        std::uint64_t parse_errors = 0;     ///< invalid or over-long frame texts from clients
        std::size_t queued_bytes = 0;       ///< output bytes currently held for all clients
        std::size_t peak_client_queue_bytes = 0;
        std::size_t bus_frames_waiting = 0;         ///< with bitrate: frames not yet off the bus
        std::chrono::nanoseconds bus_busy_time{0};  ///< with bitrate: time the bus carried frames
        std::uint64_t bus_bits = 0;                 ///< with bitrate: worst-case bits sent
    };

    /// Called after a client was accepted, with its remote address as "HOST:PORT".
    using ConnectionHandler = std::function<void(const std::string& remote)>;
    /// Who put a frame on the segment.
    struct FrameSource {
        /// The sender's number (clients and local endpoints share one count, never reused).
        std::uint64_t connection = 0;
        /// A client's "HOST:PORT"; empty for a local endpoint.
        std::string_view remote;
    };
    /// Sees every frame the hub relays, with its sender, before any port receives it.
    using FrameObserver = std::function<void(const CanFrame& frame, const FrameSource& source)>;
    /// Called when a client's connection has ended, with its number and "HOST:PORT".
    using DisconnectHandler =
        std::function<void(std::uint64_t connection, const std::string& remote)>;
    /// Receives one line per refused or dropped client (without a trailing newline).
    using LogHandler = std::function<void(const std::string& line)>;

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
    /// Sets the handler called for every accepted client (replaces any previous one).
    void set_connection_handler(ConnectionHandler handler);
    /// Sets the handler of the hub's log lines (replaces any previous one).
    void set_log_handler(LogHandler handler);
    /// Sets the observer of every relayed frame (replaces any previous one; empty = none).
    void set_frame_observer(FrameObserver observer);
    /// Sets the handler called for every client whose connection ended (replaces any previous
    /// one).
    void set_disconnect_handler(DisconnectHandler handler);
    /// The FrameSource::connection of frames sent through `endpoint`, a local endpoint of this
    /// hub; nullopt for any other transport.
    std::optional<std::uint64_t> connection_of(const Transport& endpoint) const;
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
