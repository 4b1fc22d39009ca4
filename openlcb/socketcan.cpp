#include "openlcb/socketcan.hpp"

#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/ioctl.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace olcb::socketcan {

::can_frame to_kernel(const CanFrame& frame) {
    ::can_frame out{};
    out.can_id = (frame.id & CAN_EFF_MASK) | CAN_EFF_FLAG;
    out.can_dlc = frame.len > 8 ? 8 : frame.len;
    std::memcpy(out.data, frame.data.data(), out.can_dlc);
    return out;
}

std::optional<CanFrame> from_kernel(const ::can_frame& frame) {
    if ((frame.can_id & CAN_EFF_FLAG) == 0) return std::nullopt;
    if ((frame.can_id & (CAN_RTR_FLAG | CAN_ERR_FLAG)) != 0) return std::nullopt;
    CanFrame out;
    out.id = frame.can_id & CAN_EFF_MASK;
    out.len = frame.can_dlc > 8 ? 8 : frame.can_dlc;
    std::memcpy(out.data.data(), frame.data, out.len);
    return out;
}

namespace {

constexpr auto kSendRetry = std::chrono::milliseconds(1);
// How often a port whose interface went down looks whether it is up again: the kernel tells a
// bound socket when its interface goes down, not when it comes back.
constexpr auto kLinkPoll = std::chrono::milliseconds(100);
// Room for about 8,000 frames (the kernel counts each near 1 KiB of buffer).
constexpr int kReceiveBufferBytes = 8 << 20;

// Only extended data frames enter the socket's queue: standard, remote and error frames of other
// equipment on the bus never take the room OpenLCB's frames need. And a deep queue: a process
// busy for a moment must not lose a stream's frames to a burst (the kernel drops silently).
// Both best effort: without them from_kernel() still filters and the default queue still works.
void configure_receive(int fd) {
    const ::can_filter only_extended{CAN_EFF_FLAG, CAN_EFF_FLAG | CAN_RTR_FLAG};
    (void)::setsockopt(fd, SOL_CAN_RAW, CAN_RAW_FILTER, &only_extended, sizeof only_extended);
    const int bytes = kReceiveBufferBytes;
    if (::setsockopt(fd, SOL_SOCKET, SO_RCVBUFFORCE, &bytes, sizeof bytes) != 0) {
        (void)::setsockopt(fd, SOL_SOCKET, SO_RCVBUF, &bytes, sizeof bytes);  // up to rmem_max
    }
}

OpenError make_error(const std::string& interface, const char* step, int err) {
    std::string reason = std::strerror(err);
    if (err == EAFNOSUPPORT) reason = "AF_CAN not supported by this kernel";
    return OpenError{err, "SocketCAN " + interface + ": " + step + " failed: " + reason +
                              " (errno " + std::to_string(err) + ")"};
}

// Whether the interface fd is bound to is administratively up; nullopt when it is gone.
std::optional<bool> interface_up(int fd, const std::string& interface) {
    ::ifreq request{};
    std::memcpy(request.ifr_name, interface.c_str(), interface.size());
    if (::ioctl(fd, SIOCGIFFLAGS, &request) != 0) return std::nullopt;
    return (request.ifr_flags & IFF_UP) != 0;
}
}  // namespace

struct SocketCanPort::Impl : std::enable_shared_from_this<SocketCanPort::Impl> {
    explicit Impl(boost::asio::io_context& io) : stream(io), retry(io), poll(io) {}

    void read() {
        stream.async_read_some(boost::asio::buffer(&in, sizeof in),
                               [self = shared_from_this(), generation = generation](
                                   const boost::system::error_code& ec, std::size_t n) {
                                   if (generation != self->generation || !self->stream.is_open())
                                       return;
                                   // The kernel reports a down interface once; the socket stays
                                   // bound and its reads wait for frames until it is up again.
                                   if (ec == boost::asio::error::network_down) {
                                       self->link_down(ec);
                                   } else if (ec) {
                                       self->lost(ec);
                                       return;
                                   }
                                   if (n == sizeof self->in) {
                                       if (auto frame = from_kernel(self->in)) {
                                           ++self->stats.frames_received;
                                           self->handler(*frame);
                                       } else {
                                           ++self->stats.frames_ignored;
                                       }
                                   }
                                   if (generation == self->generation) self->read();
                               });
    }

    void write() {
        if (write_active || out.empty() || !stream.is_open()) return;
        write_active = true;
        writing = out.front();
        out.pop_front();
        stream.async_write_some(boost::asio::buffer(&writing, sizeof writing),
                                [self = shared_from_this(), generation = generation](
                                    const boost::system::error_code& ec, std::size_t) {
                                    if (generation != self->generation) return;
                                    self->write_active = false;
                                    if (ec == boost::asio::error::no_buffer_space) {
                                        self->wait_for_room();
                                        return;
                                    }
                                    if (ec == boost::asio::error::network_down) {
                                        ++self->stats.frames_dropped;
                                        self->link_down(ec);
                                    } else if (ec) {
                                        ++self->stats.frames_dropped;
                                    } else {
                                        ++self->stats.frames_sent;
                                    }
                                    self->write();
                                });
    }

    // ENOBUFS: the interface's queue is full. The frame goes first again once it has drained,
    // so nothing is lost or reordered (the kernel gives no readiness event for this).
    void wait_for_room() {
        out.push_front(writing);
        write_active = true;
        ++stats.send_retries;
        retry.expires_after(kSendRetry);
        retry.async_wait([self = shared_from_this(),
                          generation = generation](const boost::system::error_code& ec) {
            if (ec || generation != self->generation) return;
            self->write_active = false;
            self->write();
        });
    }

    void link_down(const boost::system::error_code& ec) {
        stats.frames_dropped += out.size();
        out.clear();
        if (!up) return;
        up = false;
        ++stats.link_losses;
        report(false, "SocketCAN " + interface + " went down (" + ec.message() + ")");
        watch_link();
    }

    // Any other read error (the interface deleted: ENODEV) ends the port for good.
    void lost(const boost::system::error_code& ec) {
        const bool was_up = up;
        up = false;
        close();
        if (was_up) report(false, "SocketCAN " + interface + " is gone (" + ec.message() + ")");
    }

    void report(bool now_up, const std::string& reason) {
        if (on_connection) on_connection(now_up, reason);
    }

    void watch_link() {
        poll.expires_after(kLinkPoll);
        poll.async_wait([self = shared_from_this(),
                         generation = generation](const boost::system::error_code& ec) {
            if (ec || generation != self->generation || !self->stream.is_open()) return;
            const std::optional<bool> now =
                interface_up(self->stream.native_handle(), self->interface);
            if (!now.value_or(false)) return self->watch_link();
            self->up = true;
            self->report(true, {});
            self->write();
        });
    }

    void close() {
        ++generation;
        boost::system::error_code ignored;
        stream.close(ignored);
        // A pending retry finds another generation and does nothing (at most kSendRetry away).
        out.clear();
        write_active = false;
    }

    boost::asio::posix::stream_descriptor stream;
    boost::asio::steady_timer retry;
    boost::asio::steady_timer poll;
    std::string interface;
    bool up = true;
    std::function<void(bool, const std::string&)> on_connection;
    ::can_frame in{};
    ::can_frame writing{};
    std::deque<::can_frame> out;
    bool write_active = false;
    std::uint64_t generation = 0;
    Stats stats;
    HandlerSlot handler;
};

SocketCanPort::SocketCanPort(boost::asio::io_context& io) : impl_(std::make_shared<Impl>(io)) {}

SocketCanPort::~SocketCanPort() {
    impl_->close();
}

std::optional<OpenError> SocketCanPort::open(const std::string& interface) {
    close();
    if (interface.empty() || interface.size() >= IFNAMSIZ) {
        return OpenError{EINVAL, "SocketCAN: invalid interface name '" + interface + "'"};
    }
    const int fd = ::socket(PF_CAN, SOCK_RAW | SOCK_NONBLOCK | SOCK_CLOEXEC, CAN_RAW);
    if (fd < 0) return make_error(interface, "socket(PF_CAN, SOCK_RAW, CAN_RAW)", errno);
    const unsigned index = ::if_nametoindex(interface.c_str());
    if (index == 0) {
        const int err = errno;
        ::close(fd);
        return make_error(interface, "if_nametoindex", err);
    }
    sockaddr_can address{};
    address.can_family = AF_CAN;
    address.can_ifindex = static_cast<int>(index);
    if (::bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address) != 0) {
        const int err = errno;
        ::close(fd);
        return make_error(interface, "bind", err);
    }
    if (!interface_up(fd, interface).value_or(false)) {
        ::close(fd);
        return OpenError{ENETDOWN, "SocketCAN " + interface +
                                       ": the interface is down (ip link set " + interface +
                                       " up)"};
    }
    configure_receive(fd);
    impl_->interface = interface;
    impl_->up = true;
    impl_->stream.assign(fd);
    impl_->stats = {};
    impl_->read();
    return std::nullopt;
}

void SocketCanPort::close() {
    impl_->close();
}
bool SocketCanPort::is_open() const {
    return impl_->stream.is_open();
}
bool SocketCanPort::link_up() const {
    return impl_->stream.is_open() && impl_->up;
}
void SocketCanPort::set_connection_handler(
    std::function<void(bool up, const std::string& reason)> handler) {
    impl_->on_connection = std::move(handler);
}
SocketCanPort::Stats SocketCanPort::stats() const {
    return impl_->stats;
}
void SocketCanPort::set_handler(FrameHandler handler) {
    impl_->handler.set(std::move(handler));
}

void SocketCanPort::send(const CanFrame& frame) {
    if (!frame.extended || frame.remote) {
        ++impl_->stats.frames_ignored;  // OpenLCB puts only extended data frames on the bus
        return;
    }
    if (!impl_->stream.is_open() || !impl_->up || impl_->out.size() >= kMaxQueuedFrames) {
        ++impl_->stats.frames_dropped;
        return;
    }
    impl_->out.push_back(to_kernel(frame));
    impl_->write();
}

}  // namespace olcb::socketcan
