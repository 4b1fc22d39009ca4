// GridConnect TCP and SocketCAN links: a RealLink that owns its transport.
#include "conformance/link/real_link.hpp"
#include "openlcb/socketcan.hpp"
#include "openlcb/tcp_client.hpp"

namespace olcb::conform {
namespace {

// How long lcc-conform tries to reach a hub before giving up with the reason.
constexpr std::chrono::seconds kConnectWait{2};

class TcpLink final : public RealLink {
public:
    TcpLink(std::unique_ptr<boost::asio::io_context> io, const std::string& host,
            std::uint16_t port, NodeId tool_id)
        : RealLink(std::move(io), tool_id), client_(this->io(), host, port, options()) {
        const std::string where = host + ":" + std::to_string(port);
        client_.set_connection_handler([this, where](bool connected) {
            set_up(connected, "the connection to " + where + " broke");
        });
    }
    ~TcpLink() override {
        detach();
        client_.stop();
    }

    static TcpClientOptions options() {
        TcpClientOptions o;
        o.initial_backoff = std::chrono::milliseconds(100);
        o.max_backoff = std::chrono::milliseconds(500);
        return o;
    }

    TcpClient& client() { return client_; }

private:
    TcpClient client_;
};

class CanLink final : public RealLink {
public:
    CanLink(std::unique_ptr<boost::asio::io_context> io, NodeId tool_id)
        : RealLink(std::move(io), tool_id), port_(this->io()) {
        port_.set_connection_handler(
            [this](bool up, const std::string& reason) { set_up(up, reason); });
    }
    ~CanLink() override {
        detach();
        port_.close();
    }
    socketcan::SocketCanPort& port() { return port_; }

private:
    socketcan::SocketCanPort port_;
};

}  // namespace

std::unique_ptr<Link> connect_tcp(const std::string& host, std::uint16_t port, NodeId tool_id,
                                  std::string& error) {
    auto link =
        std::make_unique<TcpLink>(std::make_unique<boost::asio::io_context>(), host, port, tool_id);
    link->client().start();
    // Connect before the stack starts, so alias reservation is seen by the segment.
    if (!link->run_until([&] { return link->client().connected(); }, kConnectWait)) {
        // Refused, not found or silent: each asks the user for something else.
        const std::string why = link->client().last_error();
        error = "cannot connect to " + host + ":" + std::to_string(port) + ": " +
                (why.empty()
                     ? "no answer within " + std::to_string(kConnectWait.count()) + " s (timed out)"
                     : why);
        return nullptr;
    }
    link->attach(link->client());
    return link;
}

std::unique_ptr<Link> open_socketcan(const std::string& interface, NodeId tool_id,
                                     std::string& error) {
    auto link = std::make_unique<CanLink>(std::make_unique<boost::asio::io_context>(), tool_id);
    if (auto failure = link->port().open(interface)) {
        error = failure->message;
        return nullptr;
    }
    link->attach(link->port());
    return link;
}

}  // namespace olcb::conform
