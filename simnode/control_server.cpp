#include "simnode/control_server.hpp"

#include <array>
#include <utility>
#include <vector>

#include "openlcb/tcp_listener.hpp"

namespace olcb::simnode {
namespace {

using boost::asio::ip::tcp;

std::string refusal_line(const std::string& error) {
    ControlJson out;
    out["ok"] = false;
    out["error"] = error;
    return out.dump() + "\n";
}

// One control connection: reads lines, answers each, writes the answers, reads on.
class Session : public std::enable_shared_from_this<Session> {
public:
    Session(tcp::socket socket, ControlCommands& commands)
        : socket_(std::move(socket)), commands_(commands) {}

    void start() { read(); }

    void close() {
        boost::system::error_code ignored;
        socket_.shutdown(tcp::socket::shutdown_both, ignored);
        socket_.close(ignored);
    }

    // Sends one line, then closes (a refused connection).
    void refuse(const std::string& error) {
        output_ = refusal_line(error);
        send(true);
    }

private:
    void read() {
        socket_.async_read_some(
            boost::asio::buffer(chunk_),
            [self = shared_from_this()](const boost::system::error_code& ec, std::size_t n) {
                if (ec) {
                    self->close();
                    return;
                }
                self->input_.append(self->chunk_.data(), n);
                self->answer();
            });
    }

    // Answers every complete line read so far; one batch of answers is written at a time, so
    // a client that never reads its answers stops being read from.
    void answer() {
        std::size_t begin = 0;
        bool close_after = false;
        for (auto nl = input_.find('\n'); nl != std::string::npos; nl = input_.find('\n', begin)) {
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
        }
        input_.erase(0, begin);
        if (close_after || input_.size() > kMaxControlLineBytes) {
            output_ += refusal_line("request line longer than " +
                                    std::to_string(kMaxControlLineBytes) + " bytes; closing");
            input_.clear();
            close_after = true;
        }
        if (output_.empty()) {
            read();
            return;
        }
        send(close_after);
    }

    void send(bool close_after) {
        boost::asio::async_write(socket_, boost::asio::buffer(output_),
                                 [self = shared_from_this(), close_after](
                                     const boost::system::error_code& ec, std::size_t) {
                                     self->output_.clear();
                                     if (ec || close_after) {
                                         self->close();
                                         return;
                                     }
                                     self->read();
                                 });
    }

    tcp::socket socket_;
    ControlCommands& commands_;
    std::array<char, 4096> chunk_{};
    std::string input_;
    std::string output_;
};

}  // namespace

struct ControlServer::Impl : std::enable_shared_from_this<Impl> {
    Impl(boost::asio::io_context& io, ControlCommands& answerer)
        : acceptor(io), commands(answerer) {}

    void accept() {
        acceptor.async_accept(
            [self = shared_from_this()](const boost::system::error_code& ec, tcp::socket socket) {
                if (self->stopped) return;
                if (!ec) self->take(std::move(socket));
                self->accept();
            });
    }

    void take(tcp::socket socket) {
        boost::system::error_code ignored;
        socket.set_option(tcp::no_delay(true), ignored);  // one short line each way
        const auto remote = socket.remote_endpoint(ignored);
        std::erase_if(sessions, [](const auto& s) { return s.expired(); });
        auto session = std::make_shared<Session>(std::move(socket), commands);
        if (sessions.size() >= kMaxControlClients) {
            const std::string why = std::to_string(sessions.size()) +
                                    " control connections open (at most " +
                                    std::to_string(kMaxControlClients) + ")";
            if (on_log) {
                on_log("control: refused " + remote.address().to_string() + ":" +
                       std::to_string(remote.port()) + ": " + why);
            }
            session->refuse(why);
            return;
        }
        sessions.push_back(session);
        session->start();
    }

    tcp::acceptor acceptor;
    ControlCommands& commands;
    LogHandler on_log;
    std::vector<std::weak_ptr<Session>> sessions;
    bool stopped = true;
};

ControlServer::ControlServer(boost::asio::io_context& io, ControlCommands& commands)
    : impl_(std::make_shared<Impl>(io, commands)) {}

ControlServer::~ControlServer() {
    stop();
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
    impl_->on_log = std::move(handler);
}

void ControlServer::stop() {
    impl_->stopped = true;
    boost::system::error_code ignored;
    impl_->acceptor.close(ignored);
    for (const auto& weak : impl_->sessions) {
        if (auto session = weak.lock()) session->close();
    }
    impl_->sessions.clear();
}

}  // namespace olcb::simnode
