// simnode's live-control listener: TCP connections carrying one JSON request per line and one
// JSON response per line (docs/control.md), answered by ControlCommands on the io_context the
// nodes run on, so a request never races the node stacks.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "openlcb/asio.hpp"
#include "simnode/control_commands.hpp"

namespace olcb::simnode {

/// Longest request line taken; a longer one is refused and its connection closed.
inline constexpr std::size_t kMaxControlLineBytes = std::size_t{64} * 1024;
/// Control connections open at once; one more closes the connection silent longest if it has
/// been silent kControlEvictIdleAfter, else it is refused with an error line.
inline constexpr std::size_t kMaxControlClients = 16;
/// Answers a connection may have waiting to be written before it is answered no further (and
/// not read from) until they are: a client that pipelines requests and never reads costs this
/// much memory, plus one answer (one `list` may be longer).
inline constexpr std::size_t kMaxControlQueuedBytes = std::size_t{256} * 1024;
/// Requests of one connection answered in one turn of the io thread, whatever their answers'
/// size: between turns the hub and the nodes run.
inline constexpr std::size_t kMaxControlBatch = 64;
/// A connection whose answers wait this long without a byte of them read is closed.
inline constexpr std::chrono::milliseconds kControlWriteTimeout{30'000};
/// How long a connection must have been silent (sent nothing, nothing left to write) before a
/// newcomer to a full server closes it.
inline constexpr std::chrono::milliseconds kControlEvictIdleAfter{1000};

/// Accepts control connections and answers their requests in order, one at a time.
class ControlServer {
public:
    /// Told a line on every refused or dropped connection, for simnode's output.
    using LogHandler = std::function<void(const std::string&)>;

    /// A server answering with commands (which must outlive it) on io.
    ControlServer(boost::asio::io_context& io, ControlCommands& commands);
    /// Closes the listener and every connection.
    ~ControlServer();
    ControlServer(const ControlServer&) = delete;
    ControlServer& operator=(const ControlServer&) = delete;

    /// Listens on a numeric address (port 0: any free port); an error when it cannot.
    boost::system::error_code listen(const std::string& address, std::uint16_t port);
    /// The port listened on (0 when not listening).
    std::uint16_t port() const;
    /// Sets who is told of refused and dropped connections.
    void set_log_handler(LogHandler handler);
    /// Sets how long answers may wait unread before their connection is closed (default
    /// kControlWriteTimeout); for connections accepted from now on.
    void set_write_timeout(std::chrono::milliseconds timeout);
    /// Sets how long a connection must be silent before a newcomer to a full server closes it
    /// (default kControlEvictIdleAfter).
    void set_evict_idle_after(std::chrono::milliseconds silence);
    /// Bytes of answers not yet written, over every connection: what the clients cost.
    std::size_t queued_bytes() const;
    /// Connections open now (refused ones not counted).
    std::size_t connections() const;
    /// Stops accepting and closes every connection.
    void stop();

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace olcb::simnode
