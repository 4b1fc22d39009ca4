// Linux SocketCAN transport: a raw AF_CAN socket on one interface (vcan0, can0).
#pragma once

#include <linux/can.h>

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "openlcb/asio.hpp"
#include "openlcb/transport.hpp"

namespace olcb::socketcan {

/// The kernel frame for `frame`: CAN_EFF_FLAG always set, ID masked to 29 bits, length clamped
/// to 8.
::can_frame to_kernel(const CanFrame& frame);

/// The OpenLCB frame in `frame`, or nullopt for standard, remote (RTR) and error frames.
std::optional<CanFrame> from_kernel(const ::can_frame& frame);

/// Why opening an interface failed.
struct OpenError {
    int errno_value = 0;  ///< the failing call's errno (97 = EAFNOSUPPORT: no CAN in the kernel)
    std::string message;  ///< readable reason naming the interface and the failing step
};

/// A port on the CAN bus behind a SocketCAN interface; the kernel loops frames to other sockets.
class SocketCanPort final : public Transport {
public:
    /// Counters since open.
    struct Stats {
        std::uint64_t frames_sent = 0;
        std::uint64_t frames_received = 0;
        std::uint64_t frames_ignored = 0;  ///< standard, RTR or error frames (either direction)
        std::uint64_t frames_dropped = 0;  ///< send queue full, not open, link down, send error
        std::uint64_t send_retries = 0;    ///< sends put off because the interface was full
        std::uint64_t link_losses = 0;     ///< times the interface went down
    };

    /// Maximum frames waiting for the socket; more are dropped (counted).
    static constexpr std::size_t kMaxQueuedFrames = 1024;

    /// A closed port whose I/O will run on `io`.
    explicit SocketCanPort(boost::asio::io_context& io);
    /// Closes the socket.
    ~SocketCanPort() override;
    SocketCanPort(const SocketCanPort&) = delete;
    SocketCanPort& operator=(const SocketCanPort&) = delete;

    /// Opens a raw CAN socket bound to `interface` and starts reading; the error if it fails,
    /// an interface that is down included (errno ENETDOWN).
    std::optional<OpenError> open(const std::string& interface);
    /// Closes the socket; nothing is delivered afterwards.
    void close();
    /// True while the socket is open.
    bool is_open() const;
    /// False from the interface going down (`ip link set IF down`, an adapter unplugged) until
    /// it is up again; frames sent meanwhile are dropped, as on a bus without the node. The
    /// socket stays bound and reads again once the interface is up.
    bool link_up() const;
    /// Called with false and the reason when the interface goes down, true when it is back.
    void set_connection_handler(std::function<void(bool up, const std::string& reason)> handler);
    /// Counters.
    Stats stats() const;

    /// Queues an extended data frame for the bus; standard and remote frames are not sent.
    void send(const CanFrame& frame) override;
    /// Receives extended data frames other sockets put on the bus.
    void set_handler(FrameHandler handler) override;

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace olcb::socketcan
