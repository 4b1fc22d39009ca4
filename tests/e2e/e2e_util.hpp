// Helpers of the end-to-end suites: run a program as a child process (reading its stdout for the
// "simnode: listening on HOST:PORT" line), and a tool-side node joining its TCP hub.
#pragma once

#include <arpa/inet.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <poll.h>
#include <signal.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <deque>
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <string_view>
#include <vector>

#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_defs.hpp"
#include "openlcb/asio.hpp"
#include "openlcb/datagram_defs.hpp"
#include "openlcb/node_stack.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/tcp_client.hpp"
#include "support/temp_files.hpp"

namespace olcb::e2e {

using std::chrono::milliseconds;

/// A running program whose stdout is read through a pipe; killed (SIGKILL) when destroyed.
class Child {
public:
    /// Starts program with args (argv[0] is added); nullptr when fork/exec setup fails.
    static std::unique_ptr<Child> spawn(const std::string& program,
                                        const std::vector<std::string>& args) {
        int fds[2];
        if (::pipe2(fds, O_CLOEXEC) != 0) return nullptr;
        std::vector<std::string> all{program};
        all.insert(all.end(), args.begin(), args.end());
        std::vector<char*> argv;
        argv.reserve(all.size() + 1);
        for (auto& a : all) argv.push_back(a.data());
        argv.push_back(nullptr);
        const pid_t pid = ::fork();
        if (pid < 0) {
            ::close(fds[0]);
            ::close(fds[1]);
            return nullptr;
        }
        if (pid == 0) {
            ::dup2(fds[1], STDOUT_FILENO);
            ::execv(program.c_str(), argv.data());
            ::_exit(127);
        }
        ::close(fds[1]);
        return std::unique_ptr<Child>(new Child(pid, fds[0]));
    }

    ~Child() {
        if (pid_ > 0 && !exited_) {
            ::kill(pid_, SIGKILL);
            wait();
        }
        if (out_ >= 0) ::close(out_);
    }
    Child(const Child&) = delete;
    Child& operator=(const Child&) = delete;

    /// The process ID.
    pid_t pid() const { return pid_; }

    /// Reads stdout until a line starting with prefix arrives; that line, or nullopt on timeout
    /// or end of output. A zero timeout only takes what is already there.
    std::optional<std::string> wait_line(std::string_view prefix,
                                         milliseconds timeout = milliseconds(10000)) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        for (;;) {
            for (auto nl = buffer_.find('\n'); nl != std::string::npos; nl = buffer_.find('\n')) {
                std::string line = buffer_.substr(0, nl);
                buffer_.erase(0, nl + 1);
                output_ += line + "\n";
                if (line.starts_with(prefix)) return line;
            }
            const auto left =
                std::max(milliseconds(0), std::chrono::duration_cast<milliseconds>(
                                              deadline - std::chrono::steady_clock::now()));
            pollfd p{out_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) {
                if (left.count() == 0) return std::nullopt;
                continue;
            }
            char chunk[4096];
            const ssize_t n = ::read(out_, chunk, sizeof chunk);
            if (n <= 0) return std::nullopt;
            buffer_.append(chunk, static_cast<std::size_t>(n));
        }
    }

    /// The port of the "simnode: listening on HOST:PORT" line, or nullopt.
    std::optional<std::uint16_t> wait_listening(milliseconds timeout = milliseconds(10000)) {
        const auto line = wait_line("simnode: listening on ", timeout);
        if (!line) return std::nullopt;
        const auto colon = line->rfind(':');
        return static_cast<std::uint16_t>(std::stoi(line->substr(colon + 1)));
    }

    /// Every stdout line read so far.
    const std::string& output() const { return output_; }

    /// Sends sig to the process.
    void signal(int sig) { ::kill(pid_, sig); }

    /// Waits for the process to end; its exit code, or -signal when a signal ended it.
    int wait() {
        if (exited_) return status_;
        int status = 0;
        while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
        }
        exited_ = true;
        status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
        return status_;
    }

    /// Waits at most timeout for the process to end; true when it did.
    bool wait_for(milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < deadline) {
            int status = 0;
            const pid_t r = ::waitpid(pid_, &status, WNOHANG);
            if (r == pid_) {
                exited_ = true;
                status_ = WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
                return true;
            }
            ::usleep(5000);
        }
        return false;
    }

private:
    Child(pid_t pid, int out) : pid_(pid), out_(out) {}

    pid_t pid_ = -1;
    int out_ = -1;
    bool exited_ = false;
    int status_ = 0;
    std::string buffer_;
    std::string output_;
};

/// Runs a program to completion; its exit code and stdout.
inline std::pair<int, std::string> run_program(const std::string& program,
                                               const std::vector<std::string>& args,
                                               milliseconds timeout = milliseconds(20000)) {
    auto child = Child::spawn(program, args);
    if (!child) return {-1000, {}};
    child->wait_line("\x01never", timeout);  // reads until end of output
    if (!child->wait_for(timeout)) return {-1001, child->output()};
    return {child->wait(), child->output()};
}

/// Runs program with its stderr merged into stdout (what a user sees in a terminal or a log).
inline std::pair<int, std::string> run_merged(const std::string& program,
                                              const std::vector<std::string>& args,
                                              milliseconds timeout = milliseconds(60000)) {
    std::vector<std::string> sh = {"-c", "exec \"$0\" \"$@\" 2>&1", program};
    sh.insert(sh.end(), args.begin(), args.end());
    return run_program("/bin/sh", sh, timeout);
}

/// A loopback TCP port nothing listens on (bound, then closed again).
inline std::uint16_t closed_port() {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    socklen_t len = sizeof addr;
    const bool bound = ::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0 &&
                       ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) == 0;
    ::close(fd);
    return bound ? ntohs(addr.sin_port) : 1;  // port 1: nothing listens there either
}

using test_support::TempDir;

/// Node ID of the tool side (the fact sheet's runner).
inline constexpr NodeId kToolId{0x02'01'0D'00'00'01ull};

/// Result of one datagram exchange: the sender's outcome and the reply datagram, if any.
struct Exchange {
    std::optional<DatagramOutcome> outcome;          ///< nullopt: no OK/Rejected in time
    std::optional<std::vector<std::uint8_t>> reply;  ///< reply datagram payload
    /// True when Datagram Received OK arrived.
    bool accepted() const {
        return outcome && outcome->status == DatagramOutcome::Status::kAccepted;
    }
};

/// A tool-side node (its own NodeStack) joined to a hub over TCP, driven synchronously: every
/// call runs the event loop until its answer arrives or its timeout passes.
class ToolNode {
public:
    /// Joins 127.0.0.1:port as node id; the stack starts on the first connect.
    explicit ToolNode(std::uint16_t port, NodeId id = kToolId)
        : client_(io_, "127.0.0.1", port, fast_reconnect()),
          driver_(io_, client_),
          stack_(config(id)) {
        stack_.set_message_handler([this](const Message& m) {
            messages_.push_back(m);
            return true;  // a tool never rejects what it receives
        });
        stack_.set_datagram_handler([this](const ReceivedDatagram& d) {
            datagrams_.emplace_back(d.source_alias, d.payload);
            stack_.accept_datagram(d.source_alias);
        });
        stack_.set_outcome_handler([this](const DatagramOutcome& o) { outcomes_[o.id] = o; });
        driver_.attach(stack_);
        client_.set_connection_handler([this](bool up) {
            if (up && !started_) {
                started_ = true;
                driver_.start_all();
            }
        });
        client_.start();
    }
    ToolNode(const ToolNode&) = delete;
    ToolNode& operator=(const ToolNode&) = delete;

    /// Runs the event loop until done(), the abort predicate or timeout; returns done().
    bool run_until(const std::function<bool()>& done, milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (!done() && !(abort_ && abort_()) && std::chrono::steady_clock::now() < deadline) {
            if (io_.stopped()) io_.restart();
            io_.run_one_for(milliseconds(1));
        }
        return done();
    }
    /// Every wait also ends when abort() turns true (checked about every millisecond).
    void set_abort(std::function<bool()> abort) { abort_ = std::move(abort); }
    /// Runs the event loop for d.
    void run_for(milliseconds d) {
        run_until([] { return false; }, d);
    }
    /// Waits until our node is Initialized on the segment.
    bool wait_ready(milliseconds timeout = milliseconds(5000)) {
        return run_until([this] { return stack_.initialized(); }, timeout);
    }

    /// Our stack.
    NodeStack& stack() { return stack_; }
    /// The TCP client.
    TcpClient& client() { return client_; }
    /// Every message received so far (global, and addressed to us), oldest first.
    std::vector<Message>& messages() { return messages_; }

    /// Waits for a received message matching pred, removes and returns it.
    std::optional<Message> take(const std::function<bool(const Message&)>& pred,
                                milliseconds timeout) {
        std::optional<Message> found;
        run_until(
            [&] {
                for (auto it = messages_.begin(); it != messages_.end(); ++it) {
                    if (pred(*it)) {
                        found = std::move(*it);
                        messages_.erase(it);
                        return true;
                    }
                }
                return false;
            },
            timeout);
        return found;
    }

    /// Sends a message from our node (source filled in by the stack).
    SendStatus send(Mti mti, std::vector<std::uint8_t> payload = {},
                    std::optional<std::uint16_t> dest_alias = std::nullopt) {
        Message m;
        m.mti = mti;
        m.payload = std::move(payload);
        if (dest_alias) m.destination = NodeHandle{NodeId(), *dest_alias};
        return stack_.send_message(std::move(m));
    }

    /// The alias of node id, found with Verify Node ID (resent every 500 ms until timeout).
    std::optional<std::uint16_t> find(NodeId id, milliseconds timeout = milliseconds(10000)) {
        const auto bytes = id.to_bytes();
        const std::vector<std::uint8_t> payload(bytes.begin(), bytes.end());
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (std::chrono::steady_clock::now() < deadline) {
            send(Mti::kVerifyNodeIdGlobal, payload);
            const auto m = take(
                [&](const Message& m) {
                    return (m.mti == Mti::kVerifiedNodeId || m.mti == Mti::kVerifiedNodeIdSimple) &&
                           m.payload == payload;
                },
                milliseconds(500));
            if (m) return m->source.alias;
        }
        return std::nullopt;
    }

    /// Sends a datagram to dest and waits for its outcome and, with Reply Pending, the reply.
    Exchange datagram(std::uint16_t dest, const std::vector<std::uint8_t>& payload,
                      milliseconds timeout = milliseconds(5000)) {
        Exchange ex;
        std::erase_if(datagrams_, [&](const auto& d) { return d.first == dest; });
        const auto id = stack_.send_datagram(dest, payload, Clock::now());
        if (!id) return ex;
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        const auto left = [&] {
            return std::chrono::duration_cast<milliseconds>(deadline -
                                                            std::chrono::steady_clock::now());
        };
        run_until([&] { return outcomes_.contains(*id); }, left());
        if (const auto it = outcomes_.find(*id); it != outcomes_.end()) {
            ex.outcome = it->second;
            outcomes_.erase(it);
        }
        const bool pending = ex.accepted() && datagram::is_reply_pending(ex.outcome->flags);
        if (!pending) return ex;
        ex.reply = take_datagram(dest, left());
        return ex;
    }

    /// The next datagram from src (waiting at most timeout).
    std::optional<std::vector<std::uint8_t>> take_datagram(std::uint16_t src,
                                                           milliseconds timeout) {
        std::optional<std::vector<std::uint8_t>> found;
        run_until(
            [&] {
                for (auto it = datagrams_.begin(); it != datagrams_.end(); ++it) {
                    if (it->first == src) {
                        found = std::move(it->second);
                        datagrams_.erase(it);
                        return true;
                    }
                }
                return false;
            },
            timeout);
        return found;
    }

    /// A Memory Configuration request and its decoded reply (nullopt: no reply datagram).
    std::optional<memory::Message> memcfg(std::uint16_t dest, const memory::Message& request,
                                          Exchange* exchange = nullptr,
                                          milliseconds timeout = milliseconds(5000)) {
        const auto ex = datagram(dest, memory::encode(request), timeout);
        if (exchange) *exchange = ex;
        if (!ex.reply) return std::nullopt;
        const auto decoded = memory::decode(*ex.reply);
        if (!decoded.ok()) return std::nullopt;
        return decoded.message;
    }

    /// Reads a whole space from 0 in 64-byte reads until a short reply or a failure (bounded by
    /// max_bytes); nullopt when a read got no reply.
    std::optional<std::vector<std::uint8_t>> read_space(std::uint16_t dest, memory::Space space,
                                                        std::size_t max_bytes = 1 << 20) {
        std::vector<std::uint8_t> out;
        while (out.size() < max_bytes) {
            memory::Read r;
            r.space = space;
            r.address = static_cast<std::uint32_t>(out.size());
            r.count = 64;
            const auto reply = memcfg(dest, r);
            if (!reply) return std::nullopt;
            if (std::holds_alternative<memory::ReadReplyFail>(*reply)) break;
            const auto* ok = std::get_if<memory::ReadReply>(&*reply);
            if (!ok || ok->address != r.address) return std::nullopt;
            out.insert(out.end(), ok->data.begin(), ok->data.end());
            if (ok->data.size() < r.count) break;
        }
        return out;
    }

    /// Writes data and waits for the acknowledgement (Write Reply OK, or a plain Datagram OK);
    /// true when the write was acknowledged as done.
    bool write(std::uint16_t dest, memory::Space space, std::uint32_t address,
               std::vector<std::uint8_t> data, milliseconds timeout = milliseconds(5000)) {
        memory::Write w;
        w.space = space;
        w.address = address;
        w.data = std::move(data);
        Exchange ex;
        const auto reply = memcfg(dest, w, &ex, timeout);
        if (!ex.accepted()) return false;
        if (!datagram::is_reply_pending(ex.outcome->flags)) return true;
        return reply && std::holds_alternative<memory::WriteReply>(*reply);
    }

    /// Reads count bytes at address; the data, or nullopt on failure or no reply.
    std::optional<std::vector<std::uint8_t>> read(std::uint16_t dest, memory::Space space,
                                                  std::uint32_t address, std::uint8_t count) {
        memory::Read r;
        r.space = space;
        r.address = address;
        r.count = count;
        const auto reply = memcfg(dest, r);
        if (!reply) return std::nullopt;
        const auto* ok = std::get_if<memory::ReadReply>(&*reply);
        if (!ok) return std::nullopt;
        return ok->data;
    }

private:
    static TcpClientOptions fast_reconnect() {
        TcpClientOptions o;
        o.initial_backoff = milliseconds(20);
        o.max_backoff = milliseconds(200);
        return o;
    }
    static NodeStackConfig config(NodeId id) {
        NodeStackConfig c;
        c.node_id = id;
        c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration};
        return c;
    }

    boost::asio::io_context io_;
    TcpClient client_;
    StackDriver driver_;
    NodeStack stack_;
    bool started_ = false;
    std::function<bool()> abort_;
    std::vector<Message> messages_;
    std::deque<std::pair<std::uint16_t, std::vector<std::uint8_t>>> datagrams_;
    std::map<std::uint32_t, DatagramOutcome> outcomes_;
};

/// Path of a file in the source tree.
inline std::filesystem::path source_path(std::string_view relative) {
    return std::filesystem::path(OLCB_SOURCE_DIR) / relative;
}

/// The simnode program on scenarios/default.ini, listening on a free loopback port, its images
/// in images_dir, plus extra options; nullptr when it could not be started.
inline std::unique_ptr<Child> spawn_default_simnode(const std::string& program,
                                                    const std::string& images_dir,
                                                    const std::vector<std::string>& extra = {}) {
    std::vector<std::string> args{"--scenario",  source_path("scenarios/default.ini").string(),
                                  "--listen",    "127.0.0.1:0",
                                  "--image-dir", images_dir};
    args.insert(args.end(), extra.begin(), extra.end());
    return Child::spawn(program, args);
}

/// A TCP connection to 127.0.0.1:port (a raw hub client); -1 when refused.
inline int connect_to(std::uint16_t port) {
    const int fd = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_port = htons(port);
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    if (fd < 0 || ::connect(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr) != 0) {
        if (fd >= 0) ::close(fd);
        return -1;
    }
    return fd;
}

}  // namespace olcb::e2e
