#include "openlcb/serial_port.hpp"

#include <termios.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <deque>
#include <string_view>
#include <utility>

#include "openlcb/echo_filter.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb {

namespace {

using boost::asio::serial_port_base;

// Frames are recorded for echo detection when handed to the device, in batches of at most
// kMaxBatchFrames; the filter must hold every frame between that moment and its echo: a batch
// plus what the kernel and the adapter buffer (a few KiB, about 30 bytes per frame).
constexpr std::size_t kMaxBatchFrames = 64;
constexpr std::size_t kEchoCapacity = 1024;
// A zero backoff would turn a device that keeps failing into a busy loop.
constexpr std::chrono::milliseconds kMinBackoff{1};

bool is_pseudo_terminal(int fd) {
    std::array<char, 128> name{};
    return ::ttyname_r(fd, name.data(), name.size()) == 0 &&
           std::string_view(name.data()).starts_with("/dev/pts/");
}

}  // namespace

struct SerialPort::Impl : std::enable_shared_from_this<SerialPort::Impl> {
    Impl(boost::asio::io_context& io, std::string d, SerialOptions o)
        : port(io), timer(io), device(std::move(d)), options(o), echo(kEchoCapacity) {
        options.initial_backoff = std::max(options.initial_backoff, kMinBackoff);
        options.max_backoff = std::max(options.max_backoff, options.initial_backoff);
        backoff = options.initial_backoff;
    }

    std::string error_text(const std::string& what) const {
        return "serial " + device + ": " + what;
    }

    // Opens the device with the configured line settings and starts reading.
    std::optional<std::string> open_device() {
        boost::system::error_code ec;
        termios probe{};
        serial_port_base::baud_rate(options.baud).store(probe, ec);
        if (ec) return error_text("unsupported baud rate " + std::to_string(options.baud));
        port.open(device, ec);
        if (ec) return error_text(ec.message());
        if (auto error = configure()) {
            boost::system::error_code ignored;
            port.close(ignored);
            return error;
        }
        is_open = true;
        ++generation;
        ++stats.opens;
        backoff = options.initial_backoff;
        parser.reset();
        echo.clear();
        read(generation);
        return std::nullopt;
    }

    std::optional<std::string> configure() {
        // A pseudo-terminal has no line: a kernel may refuse settings that mean nothing there
        // (ENOTTY, EINVAL) and bytes still flow, so such a refusal is no reason to fail. Tests
        // and socat-style bridges use ptys; a real adapter refusing a setting is an error.
        const bool pty = is_pseudo_terminal(port.native_handle());
        std::optional<std::string> error;
        const auto set = [&](const auto& option) {
            if (error) return;
            boost::system::error_code ec;
            port.set_option(option, ec);
            if (!ec) return;
            if (pty && (ec == boost::system::errc::inappropriate_io_control_operation ||
                        ec == boost::system::errc::invalid_argument)) {
                return;
            }
            error = error_text(ec.message());
        };
        set(serial_port_base::baud_rate(options.baud));
        set(serial_port_base::character_size(8));
        set(serial_port_base::parity(serial_port_base::parity::none));
        set(serial_port_base::stop_bits(serial_port_base::stop_bits::one));
        set(serial_port_base::flow_control(options.rtscts ? serial_port_base::flow_control::hardware
                                                          : serial_port_base::flow_control::none));
        return error;
    }

    void read(std::uint64_t gen) {
        port.async_read_some(
            boost::asio::buffer(read_buf),
            [self = shared_from_this(), gen](const boost::system::error_code& ec, std::size_t n) {
                if (self->stopped || gen != self->generation) return;
                if (ec) {
                    self->lose(ec.message());
                    return;
                }
                self->receive(std::string_view(self->read_buf.data(), n), gen);
                if (!self->stopped && gen == self->generation) self->read(gen);
            });
    }

    void receive(std::string_view bytes, std::uint64_t gen) {
        const auto now = Clock::now();
        const auto errors_before = parser.errors();
        parser.feed(bytes, [&](const CanFrame& frame) {
            // The handler may have closed the port.
            if (stopped || gen != generation) return;
            if (options.drop_echoes && echo.is_echo(frame, now)) {
                ++stats.echoes_dropped;
                return;
            }
            ++stats.frames_received;
            handler(frame);
        });
        stats.parse_errors += parser.errors() - errors_before;
    }

    // The device went away: report it and keep trying to reopen the same path.
    void lose(const std::string& reason) {
        if (!is_open) return;
        ++stats.losses;
        shut();
        if (auto h = connection_handler) h(false, error_text("lost (" + reason + ")"));
        // The handler may have closed or reopened the port itself.
        if (!stopped && !is_open) schedule_reopen();
    }

    // Closes the device and forgets everything tied to it; stale handlers see the new generation.
    void shut() {
        is_open = false;
        ++generation;
        queue.clear();
        queue_bytes = 0;
        writing.clear();
        write_active = false;
        parser.reset();
        echo.clear();
        boost::system::error_code ignored;
        port.close(ignored);
    }

    void schedule_reopen() {
        timer.expires_after(backoff);
        backoff = std::min(backoff * 2, options.max_backoff);
        timer.async_wait(
            [self = shared_from_this(), gen = generation](const boost::system::error_code& ec) {
                if (ec || self->stopped || self->is_open || gen != self->generation) return;
                self->reopen();
            });
    }

    void reopen() {
        if (open_device()) {
            schedule_reopen();
            return;
        }
        if (auto h = connection_handler) h(true, "");
    }

    void send(const CanFrame& frame) {
        if (!is_open) {
            ++stats.frames_dropped;
            return;
        }
        std::array<char, gridconnect::kMaxFormattedSize> text{};
        const std::size_t size = gridconnect::format_into(frame, text.data()) + 2;  // "\r\n"
        if (queue_bytes + writing.size() + size > options.max_queue_bytes) {
            ++stats.frames_dropped;
            return;
        }
        queue.push_back(frame);
        queue_bytes += size;
        ++stats.frames_sent;
        write();
    }

    void write() {
        if (write_active || queue.empty()) return;
        write_active = true;
        writing.clear();
        const auto now = Clock::now();
        for (std::size_t i = 0; i < kMaxBatchFrames && !queue.empty(); ++i) {
            const std::size_t before = writing.size();
            gridconnect::format_to(queue.front(), writing);
            writing += "\r\n";
            queue_bytes -= writing.size() - before;
            if (options.drop_echoes) echo.sent(queue.front(), now);
            queue.pop_front();
        }
        boost::asio::async_write(port, boost::asio::buffer(writing),
                                 [self = shared_from_this(), gen = generation](
                                     const boost::system::error_code& ec, std::size_t) {
                                     if (self->stopped || gen != self->generation) return;
                                     self->write_active = false;
                                     self->writing.clear();
                                     if (ec) {
                                         self->lose(ec.message());
                                         return;
                                     }
                                     self->write();
                                 });
    }

    void close() {
        stopped = true;
        timer.cancel();
        shut();
    }

    boost::asio::serial_port port;
    boost::asio::steady_timer timer;
    std::string device;
    SerialOptions options;
    Stats stats;
    gridconnect::Parser parser;
    EchoFilter echo;
    std::array<char, 4096> read_buf{};
    std::deque<CanFrame> queue;  // formatted when handed to the device
    std::size_t queue_bytes = 0;
    std::string writing;
    bool write_active = false;
    bool is_open = false;
    bool stopped = false;
    std::chrono::milliseconds backoff{};
    std::uint64_t generation = 0;
    HandlerSlot handler;
    std::function<void(bool, const std::string&)> connection_handler;
};

SerialPort::SerialPort(boost::asio::io_context& io, std::string device, SerialOptions options)
    : impl_(std::make_shared<Impl>(io, std::move(device), options)) {}

SerialPort::~SerialPort() {
    try {
        impl_->close();
    } catch (...) {
        // @nothrow: closing a descriptor that is already gone leaves nothing to release.
    }
}

std::optional<std::string> SerialPort::open() {
    if (impl_->is_open) return std::nullopt;
    impl_->stopped = false;
    return impl_->open_device();
}

void SerialPort::close() {
    impl_->close();
}

bool SerialPort::connected() const {
    return impl_->is_open;
}

void SerialPort::set_connection_handler(
    std::function<void(bool up, const std::string& reason)> handler) {
    impl_->connection_handler = std::move(handler);
}

const std::string& SerialPort::device() const {
    return impl_->device;
}

SerialPort::Stats SerialPort::stats() const {
    return impl_->stats;
}

std::size_t SerialPort::queued_bytes() const {
    return impl_->queue_bytes + impl_->writing.size();
}

void SerialPort::send(const CanFrame& frame) {
    impl_->send(frame);
}

void SerialPort::set_handler(FrameHandler handler) {
    impl_->handler.set(std::move(handler));
}

}  // namespace olcb
