#include "openlcb/tcp_hub_server.hpp"

#include <array>
#include <deque>
#include <string_view>
#include <utility>
#include <vector>

#include "openlcb/gridconnect.hpp"

namespace olcb {

namespace {
using boost::asio::ip::tcp;
constexpr std::size_t kReadChunk = 4096;
}  // namespace

struct TcpHubServer::Impl : std::enable_shared_from_this<TcpHubServer::Impl> {
    struct Client {
        explicit Client(tcp::socket s) : socket(std::move(s)) {}
        tcp::socket socket;
        gridconnect::Parser parser;
        std::array<char, kReadChunk> read_buf{};
        std::string pending;  // waiting for the next write
        std::string writing;  // owned by the write in flight
        bool write_active = false;
        bool closed = false;
    };

    class LocalPort final : public Transport {
    public:
        LocalPort(Impl& hub, FrameHandler handler) : hub_(hub) { handler_.set(std::move(handler)); }
        void send(const CanFrame& frame) override {
            ++hub_.stats.frames_received;
            hub_.relay(Source{nullptr, this}, frame);
        }
        void set_handler(FrameHandler handler) override { handler_.set(std::move(handler)); }
        void receive(const CanFrame& frame) { handler_(frame); }

    private:
        Impl& hub_;
        HandlerSlot handler_;
    };

    struct Source {
        const Client* client;
        const LocalPort* local;
    };

    Impl(boost::asio::io_context& io_context, Options opts)
        : io(io_context), acceptor(io_context), options(opts) {}

    void accept() {
        acceptor.async_accept(
            [self = shared_from_this()](const boost::system::error_code& ec, tcp::socket socket) {
                if (self->stopped) return;
                if (!ec) self->add_client(std::move(socket));
                if (ec != boost::asio::error::operation_aborted) self->accept();
            });
    }

    void add_client(tcp::socket socket) {
        if (clients.size() >= options.max_clients) {
            ++stats.clients_rejected;
            boost::system::error_code ignored;
            socket.close(ignored);
            return;
        }
        boost::system::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);
        auto client = std::make_shared<Client>(std::move(socket));
        clients.push_back(client);
        ++stats.clients_accepted;
        read(client);
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
                client->parser.feed(std::string_view(client->read_buf.data(), n),
                                    [&](const CanFrame& frame) {
                                        ++self->stats.frames_received;
                                        self->relay(Source{client.get(), nullptr}, frame);
                                    });
                self->stats.parse_errors += client->parser.errors() - errors_before;
                if (!client->closed) self->read(client);
            });
    }

    // Frames sent from inside a local handler are queued so that relays never nest.
    void relay(Source source, const CanFrame& frame) {
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

    void relay_one(Source source, const CanFrame& frame) {
        line.clear();
        gridconnect::format_to(frame, line);
        line.push_back('\n');
        for (const auto& client : clients) {
            if (client.get() == source.client || client->closed) continue;
            if (client->pending.size() + line.size() > options.max_client_queue_bytes) {
                ++stats.clients_dropped_slow;
                close(*client);
                continue;
            }
            client->pending += line;
            stats.queued_bytes += line.size();
            const std::size_t held = client->pending.size() + client->writing.size();
            if (held > stats.peak_client_queue_bytes) stats.peak_client_queue_bytes = held;
            write(client);
        }
        // Index loop: a local handler may add local endpoints.
        for (std::size_t i = 0; i < locals.size() && !stopped; ++i) {
            if (locals[i].get() != source.local) locals[i]->receive(frame);
        }
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
                self->write(client);
            });
    }

    void close(Client& client) {
        if (client.closed) return;
        client.closed = true;
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
        for (const auto& client : clients) close(*client);
        clients.clear();
    }

    boost::asio::io_context& io;
    tcp::acceptor acceptor;
    Options options;
    Stats stats;
    std::vector<std::shared_ptr<Client>> clients;
    std::vector<std::unique_ptr<LocalPort>> locals;
    std::deque<std::pair<Source, CanFrame>> relay_queue;
    std::string line;
    bool relaying = false;
    bool stopped = false;
};

TcpHubServer::TcpHubServer(boost::asio::io_context& io, Options options)
    : impl_(std::make_shared<Impl>(io, options)) {}

TcpHubServer::~TcpHubServer() {
    impl_->stop();
}

boost::system::error_code TcpHubServer::listen(const std::string& address, std::uint16_t port) {
    boost::system::error_code ec;
    const auto ip = boost::asio::ip::make_address(address, ec);
    if (ec) return ec;
    const tcp::endpoint endpoint(ip, port);
    auto& acceptor = impl_->acceptor;
    if (acceptor.is_open()) return boost::asio::error::already_open;
    if (acceptor.open(endpoint.protocol(), ec)) return ec;
    // Lets a restarted hub bind its port again while old connections sit in TIME_WAIT.
    if (acceptor.set_option(tcp::acceptor::reuse_address(true), ec)) return ec;
    if (acceptor.bind(endpoint, ec) || acceptor.listen(tcp::socket::max_listen_connections, ec)) {
        boost::system::error_code ignored;
        acceptor.close(ignored);
        return ec;
    }
    impl_->stopped = false;
    impl_->accept();
    return {};
}

std::uint16_t TcpHubServer::port() const {
    boost::system::error_code ec;
    if (!impl_->acceptor.is_open()) return 0;
    const auto endpoint = impl_->acceptor.local_endpoint(ec);
    return ec ? 0 : endpoint.port();
}

Transport& TcpHubServer::add_local_endpoint(FrameHandler handler) {
    impl_->locals.push_back(std::make_unique<Impl::LocalPort>(*impl_, std::move(handler)));
    return *impl_->locals.back();
}

void TcpHubServer::stop() {
    impl_->stop();
}

std::size_t TcpHubServer::client_count() const {
    std::size_t n = 0;
    for (const auto& c : impl_->clients) n += c->closed ? 0 : 1;
    return n;
}

TcpHubServer::Stats TcpHubServer::stats() const {
    return impl_->stats;
}

}  // namespace olcb
