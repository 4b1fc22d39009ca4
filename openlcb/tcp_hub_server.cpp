#include "openlcb/tcp_hub_server.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <deque>
#include <optional>
#include <string_view>
#include <utility>
#include <vector>

#include "openlcb/bus_pacer.hpp"
#include "openlcb/flag_guard.hpp"
#include "openlcb/gridconnect.hpp"
#include "openlcb/tcp_listener.hpp"

namespace olcb {

namespace {
using boost::asio::ip::tcp;
using SteadyClock = std::chrono::steady_clock;
constexpr std::size_t kReadChunk = 4096;
// How often idle clients, slow readers and paused reads are looked at.
constexpr auto kHousekeeping = std::chrono::milliseconds(100);
}  // namespace

struct TcpHubServer::Impl : std::enable_shared_from_this<TcpHubServer::Impl> {
    // Who sent a frame: a number per client and local endpoint, never reused, so a frame still
    // waiting for the bus after its client left is not mistaken for a newcomer's.
    using SourceKey = BusPacer::Source;

    struct Client {
        Client(tcp::socket s, SourceKey k) : socket(std::move(s)), key(k) {}
        tcp::socket socket;
        SourceKey key;
        gridconnect::Parser parser;
        std::array<char, kReadChunk> read_buf{};
        std::string pending;  // waiting for the next write
        std::string writing;  // owned by the write in flight
        std::string remote;   // "HOST:PORT", for log lines
        std::string address;  // HOST only: the per-address limit counts these
        SteadyClock::time_point last_rx = SteadyClock::now();
        std::optional<SteadyClock::time_point> congested_since;  // queue above the pause level
        double tokens = 0;  // frames it may still send now (max_client_frames_per_second)
        SteadyClock::time_point refilled_at = SteadyClock::now();
        bool write_active = false;
        bool paused = false;  // no read outstanding: backpressure
        bool closed = false;
        std::size_t held() const { return pending.size() + writing.size(); }
    };

    class LocalPort final : public Transport {
    public:
        LocalPort(Impl& hub, SourceKey key, FrameHandler handler) : hub_(hub), key_(key) {
            handler_.set(std::move(handler));
        }
        void send(const CanFrame& frame) override {
            ++hub_.stats.frames_received;
            hub_.relay(key_, frame);
        }
        void set_handler(FrameHandler handler) override { handler_.set(std::move(handler)); }
        void receive(const CanFrame& frame) { handler_(frame); }
        SourceKey key() const { return key_; }

    private:
        Impl& hub_;
        SourceKey key_;
        HandlerSlot handler_;
    };

    Impl(boost::asio::io_context& io_context, Options opts)
        : io(io_context),
          acceptor(io_context),
          timer(io_context),
          bus_timer(io_context),
          accept_timer(io_context),
          options(opts) {
        if (options.bitrate > 0) pacer.emplace(options.bitrate);
    }

    void accept() {
        acceptor.async_accept(
            [self = shared_from_this()](const boost::system::error_code& ec, tcp::socket socket) {
                if (self->stopped || ec == boost::asio::error::operation_aborted) return;
                if (!ec) {
                    self->accept_failing = false;
                    self->add_client(std::move(socket));
                    self->accept();
                    return;
                }
                self->accept_failed(ec);
            });
    }

    // Out of descriptors, accept() fails at once until some are closed: rest instead of
    // spinning, and say so once per episode.
    void accept_failed(const boost::system::error_code& ec) {
        ++stats.accept_errors;
        const auto delay = accept_retry_delay(ec);
        if (delay.count() == 0) {
            accept();
            return;
        }
        if (!std::exchange(accept_failing, true)) {
            log("cannot accept a client: " + ec.message() + "; trying again every " +
                std::to_string(delay.count()) + " ms");
        }
        accept_timer.expires_after(delay);
        accept_timer.async_wait([self = shared_from_this()](const boost::system::error_code& e) {
            if (!e && !self->stopped) self->accept();
        });
    }

    void add_client(tcp::socket socket) {
        boost::system::error_code ignored;
        const std::string remote = remote_of(socket);
        const std::string address = remote.substr(0, remote.rfind(':'));
        const auto same = static_cast<std::size_t>(
            std::count_if(clients.begin(), clients.end(),
                          [&](const auto& c) { return !c->closed && c->address == address; }));
        if (clients.size() >= options.max_clients && same < options.max_clients_per_address) {
            evict_longest_idle(remote);
        }
        if (clients.size() >= options.max_clients || same >= options.max_clients_per_address) {
            const bool full = clients.size() >= options.max_clients;
            ++(full ? stats.clients_rejected : stats.clients_rejected_per_address);
            log("refused client " + remote + ": " +
                (full ? std::to_string(clients.size()) + " clients connected (max-clients " +
                            std::to_string(options.max_clients) + ")"
                      : std::to_string(same) + " connections from " + address +
                            " already (max-clients-per-address " +
                            std::to_string(options.max_clients_per_address) + ")"));
            socket.close(ignored);
            return;
        }
        socket.set_option(tcp::no_delay(true), ignored);
        if (options.socket_send_buffer_bytes > 0) {
            socket.set_option(boost::asio::socket_base::send_buffer_size(
                                  static_cast<int>(options.socket_send_buffer_bytes)),
                              ignored);
        }
        auto client = std::make_shared<Client>(std::move(socket), next_key++);
        client->remote = remote;
        client->address = address;
        client->tokens = options.max_client_frames_per_second;  // a full second's burst
        clients.push_back(client);
        ++stats.clients_accepted;
        read(client);
        if (on_connect) on_connect(remote);
    }

    // A full hub makes room for a newcomer by closing the client that has sent nothing for the
    // longest time, if that is at least evict_idle_after: connections that only sit there (a
    // flood of them from a few addresses) cannot lock out a client that talks.
    void evict_longest_idle(const std::string& newcomer) {
        if (options.evict_idle_after.count() <= 0) return;
        const auto now = SteadyClock::now();
        Client* longest = nullptr;
        for (const auto& client : clients) {
            if (!client->closed && (longest == nullptr || client->last_rx < longest->last_rx)) {
                longest = client.get();
            }
        }
        if (longest == nullptr || now - longest->last_rx < options.evict_idle_after) return;
        const auto idle =
            std::chrono::duration_cast<std::chrono::milliseconds>(now - longest->last_rx);
        ++stats.clients_evicted_idle;
        log("closed client " + longest->remote + ": idle for " + std::to_string(idle.count()) +
            " ms, the longest, to admit " + newcomer + " (max-clients " +
            std::to_string(options.max_clients) + ")");
        close(*longest);
        sweep();
    }

    void log(const std::string& text) {
        if (on_log) on_log(text);
    }

    static std::string remote_of(const tcp::socket& socket) {
        boost::system::error_code ec;
        const auto endpoint = socket.remote_endpoint(ec);
        if (ec) return "?";
        const auto address = endpoint.address();
        const std::string host = address.to_string();
        return (address.is_v6() ? "[" + host + "]" : host) + ":" + std::to_string(endpoint.port());
    }

    void read(const std::shared_ptr<Client>& client) {
        client->socket.async_read_some(
            boost::asio::buffer(client->read_buf),
            [self = shared_from_this(), client](const boost::system::error_code& ec,
                                                std::size_t n) {
                if (self->stopped || client->closed) return;
                if (ec) {
                    self->close(*client);
                    self->sweep();
                    return;
                }
                const auto errors_before = client->parser.errors();
                const auto frames_before = client->parser.frames();
                client->parser.feed(std::string_view(client->read_buf.data(), n),
                                    [&](const CanFrame& frame) {
                                        ++self->stats.frames_received;
                                        self->relay(client->key, frame);
                                    });
                self->stats.parse_errors += client->parser.errors() - errors_before;
                client->last_rx = SteadyClock::now();
                if (client->closed) return;
                self->charge(*client, client->parser.frames() - frames_before);
                if (client->tokens < 0 || self->congested(client->last_rx, self->pause_level()) ||
                    self->bus_backlogged(*client, self->options.max_client_bus_frames)) {
                    // Its bytes wait in the kernel; TCP slows the sender until the queues drain.
                    client->paused = true;
                    ++self->stats.read_pauses;
                    return;
                }
                self->read(client);
            });
    }

    // Frames sent from inside a local handler are queued so that relays never nest. On a paced
    // bus every frame waits for its turn on the wire instead.
    void relay(SourceKey source, const CanFrame& frame) {
        if (pacer) {
            pacer->push(source, frame, bus_now());
            arm_bus();
            return;
        }
        relay_queue.emplace_back(source, frame);
        if (relaying) return;
        relaying = true;
        while (!relay_queue.empty() && !stopped) {
            auto [src, f] = relay_queue.front();
            relay_queue.pop_front();
            relay_one(src, f);
        }
        relay_queue.clear();
        relaying = false;
        sweep();
    }

    void relay_one(SourceKey source, const CanFrame& frame) {
        if (on_frame) on_frame(frame, FrameSource{source, remote_of_key(source)});
        line.clear();
        gridconnect::format_to(frame, line);
        line.push_back('\n');
        for (const auto& client : clients) {
            if (client->key == source || client->closed) continue;
            if (client->pending.size() + line.size() > options.max_client_queue_bytes) {
                ++stats.clients_dropped_slow;
                log("dropped client " + client->remote + ": it reads too slowly (" +
                    std::to_string(client->held()) + " bytes waiting for it)");
                close(*client);
                continue;
            }
            client->pending += line;
            stats.queued_bytes += line.size();
            const std::size_t held = client->held();
            if (held > stats.peak_client_queue_bytes) stats.peak_client_queue_bytes = held;
            if (held > pause_level() && !client->congested_since)
                client->congested_since = SteadyClock::now();
            write(client);
        }
        // Index loop: a local handler may add local endpoints.
        for (std::size_t i = 0; i < locals.size() && !stopped; ++i) {
            if (locals[i]->key() != source) locals[i]->receive(frame);
        }
    }

    // A client still listed (a frame may wait for the bus after its client left); "" for a local
    // endpoint or a client already swept away.
    std::string_view remote_of_key(SourceKey key) const {
        for (const auto& client : clients) {
            if (client->key == key) return client->remote;
        }
        return {};
    }

    BusPacer::Duration bus_now() const {
        return std::chrono::duration_cast<BusPacer::Duration>(SteadyClock::now() - bus_epoch);
    }

    // One wait for the paced bus: the completion of the frame on the wire is fixed once the
    // pacer chose it, so a wait already armed never has to move.
    void arm_bus() {
        if (bus_armed || relaying || stopped) return;
        const auto next = pacer->next_completion();
        if (!next) return;
        bus_armed = true;
        bus_timer.expires_at(bus_epoch + *next);
        bus_timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            self->bus_armed = false;
            if (ec || self->stopped) return;
            self->release_due();
        });
    }

    // Delivers every frame whose transmission completed by now. A late wake-up delivers what
    // completed meanwhile at once: the bus keeps its own schedule, so lateness does not add up.
    // Frames sent from handlers meanwhile complete after now (a frame takes > 0 s), so this ends.
    void release_due() {
        {
            FlagGuard guard(relaying);
            const auto now = bus_now();
            while (!stopped) {
                const auto done = pacer->pop(now);
                if (!done) break;
                relay_one(done->source, done->frame);
            }
        }
        sweep();
        resume_if_clear(SteadyClock::now());
        arm_bus();
    }

    bool bus_backlogged(const Client& c, std::size_t level) const {
        return pacer && pacer->queued(c.key) > level;
    }

    void write(const std::shared_ptr<Client>& client) {
        if (client->write_active || client->pending.empty() || client->closed) return;
        client->write_active = true;
        std::swap(client->pending, client->writing);
        client->pending.clear();
        boost::asio::async_write(
            client->socket, boost::asio::buffer(client->writing),
            [self = shared_from_this(), client](const boost::system::error_code& ec, std::size_t) {
                client->write_active = false;
                if (self->stopped || client->closed) return;
                self->stats.queued_bytes -= client->writing.size();
                client->writing.clear();
                if (ec) {
                    self->close(*client);
                    self->sweep();
                    return;
                }
                if (client->held() <= self->pause_level() / 2) client->congested_since.reset();
                self->write(client);
                self->resume_if_clear(SteadyClock::now());
            });
    }

    // The token bucket of max_client_frames_per_second: refilled by elapsed time, then charged.
    void charge(Client& c, std::uint64_t frames) {
        const double rate = options.max_client_frames_per_second;
        if (rate <= 0) return;
        refill(c, SteadyClock::now());
        c.tokens -= static_cast<double>(frames);
    }

    void refill(Client& c, SteadyClock::time_point now) const {
        const double rate = options.max_client_frames_per_second;
        if (rate <= 0) return;
        const double elapsed = std::chrono::duration<double>(now - c.refilled_at).count();
        c.tokens = std::min(rate, c.tokens + elapsed * rate);
        c.refilled_at = now;
    }

    std::size_t pause_level() const {
        return std::min(options.pause_above_bytes, options.max_client_queue_bytes / 2);
    }

    bool slow_reader(const Client& c, SteadyClock::time_point now) const {
        return c.congested_since && now - *c.congested_since >= options.slow_reader_grace;
    }

    // True while a client that still keeps up has more than `level` bytes queued.
    bool congested(SteadyClock::time_point now, std::size_t level) const {
        return std::any_of(clients.begin(), clients.end(), [&](const auto& c) {
            return !c->closed && c->held() > level && !slow_reader(*c, now);
        });
    }

    // Reads resume once every queue is down to half the pause level: without the gap a flood
    // would keep the slowest reader's queue at the pause level, and it would look stalled.
    void resume_if_clear(SteadyClock::time_point now) {
        if (stopped || congested(now, pause_level() / 2)) return;
        for (std::size_t i = 0; i < clients.size(); ++i) {
            const auto client = clients[i];  // read() may not change clients, but be safe
            if (!client->paused || client->closed) continue;
            if (options.max_client_frames_per_second > 0) {
                refill(*client, now);
                if (client->tokens < 0) continue;  // over its rate: the next tick looks again
            }
            // Its frames going out on the bus call this again.
            if (bus_backlogged(*client, options.max_client_bus_frames / 2)) continue;
            client->paused = false;
            read(client);
        }
    }

    void housekeeping() {
        timer.expires_after(kHousekeeping);
        timer.async_wait([self = shared_from_this()](const boost::system::error_code& ec) {
            if (ec || self->stopped) return;
            self->check_clients(SteadyClock::now());
            self->housekeeping();
        });
    }

    void check_clients(SteadyClock::time_point now) {
        for (const auto& client : clients) {
            if (client->closed) continue;
            if (client->congested_since &&
                now - *client->congested_since >= options.slow_reader_timeout) {
                ++stats.clients_dropped_slow;
                log("dropped client " + client->remote + ": it has not read its traffic for " +
                    std::to_string(options.slow_reader_timeout.count()) + " ms");
                close(*client);
            } else if (options.idle_timeout.count() > 0 && !client->paused &&
                       now - client->last_rx >= options.idle_timeout) {
                ++stats.clients_dropped_idle;
                log("closed client " + client->remote + ": idle for " +
                    std::to_string(options.idle_timeout.count()) + " ms (idle-timeout)");
                close(*client);
            }
        }
        sweep();
        resume_if_clear(now);
    }

    void close(Client& client) {
        if (client.closed) return;
        client.closed = true;
        if (on_disconnect) on_disconnect(client.key, client.remote);
        stats.queued_bytes -= client.pending.size() + client.writing.size();
        // Free the memory now; a write in flight keeps its buffer until its handler runs.
        std::string().swap(client.pending);
        boost::system::error_code ignored;
        client.socket.shutdown(tcp::socket::shutdown_both, ignored);
        client.socket.close(ignored);
    }

    void sweep() {
        if (relaying) return;
        std::erase_if(clients, [](const std::shared_ptr<Client>& c) { return c->closed; });
    }

    void stop() {
        if (stopped) return;
        stopped = true;
        boost::system::error_code ignored;
        acceptor.close(ignored);
        timer.cancel();
        bus_timer.cancel();
        accept_timer.cancel();
        for (const auto& client : clients) close(*client);
        clients.clear();
    }

    boost::asio::io_context& io;
    tcp::acceptor acceptor;
    boost::asio::steady_timer timer;
    boost::asio::steady_timer bus_timer;
    boost::asio::steady_timer accept_timer;  // accept_failed()'s rest
    bool accept_failing = false;             // its log line was written
    Options options;
    Stats stats;
    std::optional<BusPacer> pacer;  // options.bitrate > 0
    SteadyClock::time_point bus_epoch = SteadyClock::now();
    bool bus_armed = false;
    SourceKey next_key = 0;
    std::vector<std::shared_ptr<Client>> clients;
    std::vector<std::unique_ptr<LocalPort>> locals;
    std::deque<std::pair<SourceKey, CanFrame>> relay_queue;
    std::string line;
    ConnectionHandler on_connect;
    LogHandler on_log;
    FrameObserver on_frame;
    DisconnectHandler on_disconnect;
    bool relaying = false;
    bool stopped = false;
};

TcpHubServer::TcpHubServer(boost::asio::io_context& io, Options options)
    : impl_(std::make_shared<Impl>(io, options)) {}

TcpHubServer::~TcpHubServer() {
    try {
        impl_->stop();
    } catch (...) {
        // @nothrow: closing sockets cannot fail in a way a destructor could act on.
    }
}

boost::system::error_code TcpHubServer::listen(const std::string& address, std::uint16_t port) {
    if (const auto ec = listen_on(impl_->acceptor, address, port)) return ec;
    impl_->stopped = false;
    impl_->accept();
    impl_->housekeeping();
    return {};
}

std::uint16_t TcpHubServer::port() const {
    return listening_port(impl_->acceptor);
}

Transport& TcpHubServer::add_local_endpoint(FrameHandler handler) {
    impl_->locals.push_back(
        std::make_unique<Impl::LocalPort>(*impl_, impl_->next_key++, std::move(handler)));
    return *impl_->locals.back();
}

void TcpHubServer::set_connection_handler(ConnectionHandler handler) {
    impl_->on_connect = std::move(handler);
}

void TcpHubServer::set_log_handler(LogHandler handler) {
    impl_->on_log = std::move(handler);
}

void TcpHubServer::set_frame_observer(FrameObserver observer) {
    impl_->on_frame = std::move(observer);
}

void TcpHubServer::set_disconnect_handler(DisconnectHandler handler) {
    impl_->on_disconnect = std::move(handler);
}

std::optional<std::uint64_t> TcpHubServer::connection_of(const Transport& endpoint) const {
    for (const auto& local : impl_->locals) {
        if (local.get() == &endpoint) return local->key();
    }
    return std::nullopt;
}

void TcpHubServer::stop() {
    impl_->stop();
}

std::size_t TcpHubServer::client_count() const {
    std::size_t n = 0;
    for (const auto& c : impl_->clients) {
        if (!c->closed) ++n;
    }
    return n;
}

TcpHubServer::Stats TcpHubServer::stats() const {
    Stats s = impl_->stats;
    if (const auto& pacer = impl_->pacer) {
        s.bus_frames_waiting = pacer->pending();
        s.bus_busy_time = pacer->busy_time();
        s.bus_bits = pacer->bits_on_wire();
    }
    return s;
}

}  // namespace olcb
