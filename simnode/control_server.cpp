#include "simnode/control_server.hpp"

#include <array>
#include <utility>
#include <vector>

#include "openlcb/tcp_listener.hpp"

namespace olcb::simnode {
namespace {

using boost::asio::ip::tcp;

// The kernel's send buffer of a control connection. Left to autotune it grows to megabytes on
// loopback, which a client that never reads made simnode fill with answers it would never take
// (15 such clients: seconds of list answers before anything else ran); loopback needs no more.
constexpr int kControlSendBuffer = 64 * 1024;

std::string refusal_line(const std::string& error) {
    ControlJson out;
    out["ok"] = false;
    out["error"] = error;
    return out.dump() + "\n";
}

// One control connection: reads lines, answers them a batch at a time, writes the answers, and
// reads on only when every line read is answered and every answer written. So a client costs at
// most one line of input and one batch of answers, whatever it sends and however it reads.
class Session : public std::enable_shared_from_this<Session> {
public:
    Session(tcp::socket socket, ControlCommands& commands,
            std::shared_ptr<const ControlServer::LogHandler> log,
            std::chrono::milliseconds write_timeout)
        : socket_(std::move(socket)),
          timer_(socket_.get_executor()),
          commands_(commands),
          log_(std::move(log)),
          write_timeout_(write_timeout) {
        boost::system::error_code ignored;
        const auto remote = socket_.remote_endpoint(ignored);
        peer_ = remote.address().to_string() + ":" + std::to_string(remote.port());
    }

    void start() { read(); }

    void close() {
        closed_ = true;
        timer_.cancel();
        boost::system::error_code ignored;
        socket_.shutdown(tcp::socket::shutdown_both, ignored);
        socket_.close(ignored);
    }

    // Sends one line, then closes (a refused connection).
    void refuse(const std::string& error) {
        output_ = refusal_line(error);
        send(true);
    }

    const std::string& peer() const { return peer_; }
    // When the client last sent something (or connected).
    std::chrono::steady_clock::time_point last_heard() const { return last_heard_; }
    std::size_t queued() const { return output_.size() - written_; }
    bool open() const { return !closed_; }

private:
    void read() {
        socket_.async_read_some(
            boost::asio::buffer(chunk_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                if (ec) {
                    self->close();
                    return;
                }
                self->last_heard_ = std::chrono::steady_clock::now();
                self->input_.append(self->chunk_.data(), n);
                self->answer();
            });
    }

    // Answers complete lines until the batch or the queued answers reach their limit; the lines
    // left wait for the answers to be written.
    void answer() {
        std::size_t begin = 0;
        std::size_t answered = 0;
        bool close_after = false;
        while (answered < kMaxControlBatch && output_.size() < kMaxControlQueuedBytes) {
            const auto nl = input_.find('\n', begin);
            if (nl == std::string::npos) break;
            std::string_view line(input_.data() + begin, nl - begin);
            begin = nl + 1;
            if (line.size() > kMaxControlLineBytes) {
                close_after = true;  // complete or not, the limit is the same
                break;
            }
            if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
            if (line.find_first_not_of(" \t") == std::string_view::npos) continue;
            output_ += commands_.handle_line(line).dump(-1, ' ', false,
                                                        ControlJson::error_handler_t::replace);
            output_ += '\n';
            ++answered;
        }
        input_.erase(0, begin);
        if (close_after || (!has_line() && input_.size() > kMaxControlLineBytes)) {
            output_ += refusal_line("request line longer than " +
                                    std::to_string(kMaxControlLineBytes) + " bytes; closing");
            input_.clear();
            close_after = true;
        }
        if (output_.empty()) {
            read();  // every line was blank: none is left
            return;
        }
        send(close_after);
    }

    bool has_line() const { return input_.find('\n') != std::string::npos; }

    void send(bool close_after) {
        close_after_ = close_after;
        written_ = 0;
        write_some();
    }

    // Writes what is left of the answers; every byte the client takes restarts its timeout.
    void write_some() {
        arm_timeout();
        socket_.async_write_some(
            boost::asio::buffer(output_.data() + written_, output_.size() - written_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                self->written_ += n;
                if (ec || self->closed_) {
                    self->close();
                    return;
                }
                if (self->written_ < self->output_.size()) {
                    self->write_some();
                    return;
                }
                self->timer_.cancel();
                self->output_.clear();
                self->written_ = 0;
                if (self->close_after_) {
                    self->close();
                } else if (self->has_line()) {
                    self->answer();
                } else {
                    self->read();
                }
            });
    }

    void arm_timeout() {
        timer_.expires_after(write_timeout_);
        timer_.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            // A wait re-armed after this one fired is not a timeout.
            if (ec || self->closed_ || self->timer_.expiry() > std::chrono::steady_clock::now())
                return;
            if (*self->log_) {
                (*self->log_)("control: closed " + self->peer_ + ": it read none of its " +
                              std::to_string(self->queued()) + " bytes of answers for " +
                              std::to_string(self->write_timeout_.count()) + " ms");
            }
            self->close();
        });
    }

    tcp::socket socket_;
    boost::asio::steady_timer timer_;
    ControlCommands& commands_;
    std::shared_ptr<const ControlServer::LogHandler> log_;
    std::chrono::milliseconds write_timeout_;
    std::string peer_;
    std::array<char, 4096> chunk_{};
    std::string input_;
    std::string output_;
    std::size_t written_ = 0;  // bytes of output_ the socket took
    std::chrono::steady_clock::time_point last_heard_ = std::chrono::steady_clock::now();
    bool close_after_ = false;
    bool closed_ = false;
};

}  // namespace

struct ControlServer::Impl : std::enable_shared_from_this<Impl> {
    Impl(boost::asio::io_context& io, ControlCommands& answerer)
        : acceptor(io), commands(answerer) {}

    void accept() {
        acceptor.async_accept(
            [self = shared_from_this()](const boost::system::error_code& ec, tcp::socket socket) {
                if (self->stopped || ec == boost::asio::error::operation_aborted) return;
                if (!ec) self->take(std::move(socket));
                self->accept_again(accept_retry_delay(ec));
            });
    }

    // Out of descriptors, accept() fails at once until some are closed: rest instead of
    // spinning.
    void accept_again(std::chrono::milliseconds delay) {
        if (delay.count() == 0) {
            accept();
            return;
        }
        retry.expires_after(delay);
        retry.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            if (!ec && !self->stopped) self->accept();
        });
    }

    // A full server makes room by closing the connection silent longest, if it has been silent
    // evict_idle_after with nothing left to write: idle clients cannot lock out the port.
    bool evict_idle(const std::string& newcomer) {
        const auto now = std::chrono::steady_clock::now();
        std::shared_ptr<Session> longest;
        for (const auto& weak : sessions) {
            auto s = weak.lock();
            if (s && s->open() && s->queued() == 0 &&
                (!longest || s->last_heard() < longest->last_heard())) {
                longest = std::move(s);
            }
        }
        if (!longest || now - longest->last_heard() < evict_idle_after) return false;
        const auto idle =
            std::chrono::duration_cast<std::chrono::milliseconds>(now - longest->last_heard());
        if (*on_log) {
            (*on_log)("control: closed " + longest->peer() + ": silent for " +
                      std::to_string(idle.count()) + " ms, the longest, to admit " + newcomer);
        }
        longest->close();
        std::erase_if(sessions, [&](const auto& w) { return w.lock() == longest; });
        return true;
    }

    void take(tcp::socket socket) {
        boost::system::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);  // one short line each way
        socket.set_option(tcp::socket::send_buffer_size(kControlSendBuffer), ignored);
        std::erase_if(sessions, [](const auto& s) { return s.expired(); });
        auto session =
            std::make_shared<Session>(std::move(socket), commands, on_log, write_timeout);
        if (sessions.size() >= kMaxControlClients && !evict_idle(session->peer())) {
            const std::string why = std::to_string(sessions.size()) +
                                    " control connections open (at most " +
                                    std::to_string(kMaxControlClients) + ")";
            if (*on_log) (*on_log)("control: refused " + session->peer() + ": " + why);
            session->refuse(why);
            return;
        }
        sessions.push_back(session);
        session->start();
    }

    tcp::acceptor acceptor;
    boost::asio::steady_timer retry{acceptor.get_executor()};  // accept_again()'s rest
    ControlCommands& commands;
    // Shared with the sessions, which may outlive the server by a pending handler.
    std::shared_ptr<LogHandler> on_log = std::make_shared<LogHandler>();
    std::chrono::milliseconds write_timeout = kControlWriteTimeout;
    std::chrono::milliseconds evict_idle_after = kControlEvictIdleAfter;
    std::vector<std::weak_ptr<Session>> sessions;
    bool stopped = true;
};

ControlServer::ControlServer(boost::asio::io_context& io, ControlCommands& commands)
    : impl_(std::make_shared<Impl>(io, commands)) {}

ControlServer::~ControlServer() {
    try {
        stop();
    } catch (...) {
        // @nothrow: cancelling a timer or closing a socket already gone leaves nothing.
    }
}

boost::system::error_code ControlServer::listen(const std::string& address, std::uint16_t port) {
    if (const auto ec = listen_on(impl_->acceptor, address, port)) return ec;
    impl_->stopped = false;
    impl_->accept();
    return {};
}

std::uint16_t ControlServer::port() const {
    return listening_port(impl_->acceptor);
}

void ControlServer::set_log_handler(LogHandler handler) {
    *impl_->on_log = std::move(handler);
}

void ControlServer::set_evict_idle_after(std::chrono::milliseconds silence) {
    impl_->evict_idle_after = silence;
}

void ControlServer::set_write_timeout(std::chrono::milliseconds timeout) {
    impl_->write_timeout = timeout;
}

std::size_t ControlServer::queued_bytes() const {
    std::size_t total = 0;
    for (const auto& weak : impl_->sessions) {
        if (auto session = weak.lock()) total += session->queued();
    }
    return total;
}

std::size_t ControlServer::connections() const {
    std::size_t open = 0;
    for (const auto& weak : impl_->sessions) {
        if (auto session = weak.lock(); session && session->open()) ++open;
    }
    return open;
}

void ControlServer::stop() {
    impl_->stopped = true;
    boost::system::error_code ignored;
    impl_->acceptor.close(ignored);
    impl_->retry.cancel();
    for (const auto& weak : impl_->sessions) {
        if (auto session = weak.lock()) session->close();
    }
    impl_->sessions.clear();
}

}  // namespace olcb::simnode
