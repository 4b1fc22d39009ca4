// GridConnect over a serial port: the USB-CAN adapters most LCC users have (LCC Buffer-USB,
// SPROG, CANRS, CANable in GridConnect mode) show up as a tty that speaks GridConnect lines.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "openlcb/asio.hpp"
#include "openlcb/transport.hpp"

namespace olcb {

/// Line settings and reopen policy of a SerialPort.
struct SerialOptions {
    unsigned baud = 115200;   ///< bits per second (ignored by pseudo-terminals)
    bool rtscts = false;      ///< hardware flow control; none unless asked
    bool drop_echoes = true;  ///< drop frames that echo our own (EchoFilter)
    std::chrono::milliseconds initial_backoff{100};  ///< delay before the first reopen attempt
    std::chrono::milliseconds max_backoff{2000};     ///< the delay never grows past this
    std::size_t max_queue_bytes = 1 << 20;           ///< unsent output beyond this drops new frames
};

/// A port on the CAN segment behind a serial GridConnect adapter.
///
/// The device is opened raw (8N1, no echo, no line editing). Input may use CR, LF, CRLF or no
/// separator between frames, lowercase hex, and start with a partial line: the streaming
/// GridConnect parser resynchronises on ':'. When the device goes away (read or write error,
/// end of file: the adapter was unplugged) the port closes it, reports the loss, and tries to
/// reopen the same path with backoff until close(); frames sent meanwhile are dropped and counted.
class SerialPort final : public Transport {
public:
    /// Counters since construction.
    struct Stats {
        std::uint64_t opens = 0;   ///< successful opens, the first included
        std::uint64_t losses = 0;  ///< times the device went away
        std::uint64_t frames_sent = 0;
        std::uint64_t frames_received = 0;  ///< handed to the frame handler (echoes excluded)
        std::uint64_t frames_dropped = 0;   ///< sent while closed or with a full queue
        std::uint64_t echoes_dropped = 0;   ///< received frames recognised as our own echo
        std::uint64_t parse_errors = 0;
    };

    /// A port for `device` (e.g. /dev/ttyACM0) on `io`; call open().
    SerialPort(boost::asio::io_context& io, std::string device, SerialOptions options = {});
    /// Closes the port.
    ~SerialPort() override;
    SerialPort(const SerialPort&) = delete;
    SerialPort& operator=(const SerialPort&) = delete;

    /// Opens the device and starts reading; on failure returns a message naming the device and
    /// the reason (nothing is retried: a wrong path on the command line is a usage error).
    std::optional<std::string> open();
    /// Closes the device and stops reopening.
    void close();
    /// True while the device is open.
    bool connected() const;
    /// Called on each loss (false, with the reason) and each successful reopen (true, "").
    void set_connection_handler(std::function<void(bool up, const std::string& reason)> handler);
    /// The device path.
    const std::string& device() const;
    /// Counters.
    Stats stats() const;
    /// Output bytes not yet written to the device.
    std::size_t queued_bytes() const;

    /// Queues the frame as one GridConnect line ending in "\r\n".
    void send(const CanFrame& frame) override;
    /// Receives the frames the adapter delivers.
    void set_handler(FrameHandler handler) override;

private:
    struct Impl;
    std::shared_ptr<Impl> impl_;
};

}  // namespace olcb
