#include "openlcb/tcp_client.hpp"

#include <array>
#include <string_view>
#include <utility>

#include "openlcb/echo_filter.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb {

namespace {
using boost::asio::ip::tcp;

// Frames are recorded when queued; the filter must hold every frame between then and its echo,
// a burst of a bulk sender included.
constexpr std::size_t kEchoCapacity = 4096;
}  // namespace

std::chrono::milliseconds reconnect_delay(const TcpClientOptions& options, unsigned failures) {
    auto delay = options.initial_backoff;
    for (unsigned i = 0; i < failures && delay < options.max_backoff; ++i) {
        delay *= options.backoff_factor == 0 ? 1 : options.backoff_factor;
    }
    return std::min(delay, options.max_backoff);
}

struct TcpClient::Impl : std::enable_shared_from_this<TcpClient::Impl> {
    Impl(boost::asio::io_context& io_context, std::string h, std::uint16_t p, TcpClientOptions o)
        : io(io_context),
          resolver(io_context),
          socket(io_context),
          timer(io_context),
          host(std::move(h)),
          port(p),
          options(o),
          echo(kEchoCapacity) {}

    void connect() {
        if (stopped) return;
        ++stats.connect_attempts;
        const auto generation = ++conn_generation;
        resolver.async_resolve(
            host, std::to_string(port),
            [self = shared_from_this(), generation](const boost::system::error_code& ec,
                                                    const tcp::resolver::results_type& results) {
                if (self->stopped || generation != self->conn_generation) return;
                if (ec) {
                    self->last_error = "host " + self->host + " not found (" + ec.message() + ")";
                    self->retry(true);
                    return;
                }
                boost::asio::async_connect(
                    self->socket, results,
                    [self, generation](const boost::system::error_code& cec, const tcp::endpoint&) {
                        if (self->stopped || generation != self->conn_generation) return;
                        if (cec) {
                            self->last_error = cec == boost::asio::error::connection_refused
                                                   ? std::string("connection refused")
                                                   : cec.message();
                            self->retry(true);
                            return;
                        }
                        self->on_connected();
                    });
            });
    }

    // after_failure: a connect attempt failed (counts towards max_attempts), rather than a
    // working connection breaking.
    void retry(bool after_failure) {
        boost::system::error_code ignored;
        socket.close(ignored);
        if (after_failure && options.max_attempts != 0 && failures + 1 >= options.max_attempts) {
            given_up = true;
            return;
        }
        timer.expires_after(reconnect_delay(options, failures));
        ++failures;
        timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            if (ec || self->stopped) return;
            self->connect();
        });
    }

    void on_connected() {
        boost::system::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        is_connected = true;
        failures = 0;
        ++stats.connects;
        parser.reset();
        echo.clear();
        if (connection_handler) connection_handler(true);
        read(conn_generation);
    }

    void disconnect() {
        if (!is_connected) return;
        is_connected = false;
        ++stats.disconnects;
        ++conn_generation;  // stale handlers of this connection do nothing
        pending.clear();
        write_active = false;
        echo.clear();
        boost::system::error_code ignored;
        socket.close(ignored);
        if (connection_handler) connection_handler(false);
        if (!stopped) retry(false);
    }

    void read(std::uint64_t generation) {
        socket.async_read_some(
            boost::asio::buffer(read_buf), [self = shared_from_this(), generation](
                                               const boost::system::error_code& ec, std::size_t n) {
                if (self->stopped || generation != self->conn_generation) return;
                if (ec) {
                    self->disconnect();
                    return;
                }
                const auto errors_before = self->parser.errors();
                const auto now = Clock::now();
                self->parser.feed(
                    std::string_view(self->read_buf.data(), n), [&](const CanFrame& frame) {
                        // The handler may have stopped or broken the connection.
                        if (generation != self->conn_generation) return;
                        if (self->options.drop_echoes && self->echo.is_echo(frame, now)) {
                            ++self->stats.echoes_dropped;
                            return;
                        }
                        ++self->stats.frames_received;
                        self->handler(frame);
                    });
                self->stats.parse_errors += self->parser.errors() - errors_before;
                if (generation == self->conn_generation) self->read(generation);
            });
    }

    void send(const CanFrame& frame) {
        if (!is_connected) {
            ++stats.frames_dropped;
            return;
        }
        gridconnect::format_to(frame, pending);
        pending.push_back('\n');
        ++stats.frames_sent;
        if (options.drop_echoes) echo.sent(frame, Clock::now());
        if (pending.size() > options.max_queue_bytes) {
            disconnect();
            return;
        }
        write();
    }

    void write() {
        if (write_active || pending.empty()) return;
        write_active = true;
        std::swap(pending, writing);
        pending.clear();
        boost::asio::async_write(socket, boost::asio::buffer(writing),
                                 [self = shared_from_this(), generation = conn_generation](
                                     const boost::system::error_code& ec, std::size_t) {
                                     if (self->stopped || generation != self->conn_generation)
                                         return;
                                     self->write_active = false;
                                     self->writing.clear();
                                     if (ec) {
                                         self->disconnect();
                                         return;
                                     }
                                     self->write();
                                 });
    }

    void stop() {
        if (stopped) return;
        stopped = true;
        const bool was_connected = is_connected;
        is_connected = false;
        ++conn_generation;
        boost::system::error_code ignored;
        resolver.cancel();
        timer.cancel();
        socket.close(ignored);
        if (was_connected) ++stats.disconnects;
    }

    boost::asio::io_context& io;
    tcp::resolver resolver;
    tcp::socket socket;
    boost::asio::steady_timer timer;
    std::string host;
    std::uint16_t port;
    TcpClientOptions options;
    Stats stats;
    gridconnect::Parser parser;
    EchoFilter echo;
    std::array<char, 4096> read_buf{};
    std::string pending;
    std::string writing;
    bool write_active = false;
    bool is_connected = false;
    bool stopped = false;
    bool started = false;
    bool given_up = false;
    std::string last_error;
    unsigned failures = 0;
    std::uint64_t conn_generation = 0;
    HandlerSlot handler;
    std::function<void(bool)> connection_handler;
};

TcpClient::TcpClient(boost::asio::io_context& io, std::string host, std::uint16_t port,
                     TcpClientOptions options)
    : impl_(std::make_shared<Impl>(io, std::move(host), port, options)) {}

TcpClient::~TcpClient() {
    try {
        impl_->stop();
    } catch (...) {
        // @nothrow: cancelling a resolver or closing a socket already gone leaves nothing.
    }
}

void TcpClient::start() {
    if (impl_->started) return;
    impl_->started = true;
    impl_->connect();
}

void TcpClient::stop() {
    impl_->stop();
}
bool TcpClient::connected() const {
    return impl_->is_connected;
}
bool TcpClient::gave_up() const {
    return impl_->given_up;
}
std::string TcpClient::last_error() const {
    return impl_->last_error;
}

void TcpClient::set_connection_handler(std::function<void(bool)> handler) {
    impl_->connection_handler = std::move(handler);
}

TcpClient::Stats TcpClient::stats() const {
    return impl_->stats;
}
std::size_t TcpClient::queued_bytes() const {
    return impl_->pending.size() + impl_->writing.size();
}
void TcpClient::send(const CanFrame& frame) {
    impl_->send(frame);
}
void TcpClient::set_handler(FrameHandler handler) {
    impl_->handler.set(std::move(handler));
}

}  // namespace olcb
