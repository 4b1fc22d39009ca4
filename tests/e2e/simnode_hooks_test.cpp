// simnode's test hooks as a tool sees them over TCP: --latency holds back every answer, and
// --start-on-connect shows a connecting client every node's login (CID..RID, AMD, Init Complete).
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};

// A plain TCP connection to the hub that collects the GridConnect lines it receives.
class RawClient {
public:
    explicit RawClient(std::uint16_t port) : fd_(::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0)) {
        sockaddr_in addr{};
        addr.sin_family = AF_INET;
        addr.sin_port = htons(port);
        addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
        connected_ =
            fd_ >= 0 && ::connect(fd_, reinterpret_cast<sockaddr*>(&addr), sizeof addr) == 0;
    }
    ~RawClient() {
        if (fd_ >= 0) ::close(fd_);
    }
    RawClient(const RawClient&) = delete;
    RawClient& operator=(const RawClient&) = delete;

    bool connected() const { return connected_; }

    /// Reads until every one of wanted was seen (as a whole line) or timeout; true when all were.
    bool wait_for_lines(const std::vector<std::string>& wanted, milliseconds timeout) {
        const auto deadline = std::chrono::steady_clock::now() + timeout;
        while (!has_all(wanted)) {
            const auto left = std::chrono::duration_cast<milliseconds>(
                deadline - std::chrono::steady_clock::now());
            if (left.count() <= 0) return false;
            pollfd p{fd_, POLLIN, 0};
            if (::poll(&p, 1, static_cast<int>(left.count())) <= 0) continue;
            char chunk[4096];
            const ssize_t n = ::read(fd_, chunk, sizeof chunk);
            if (n <= 0) return false;
            text_.append(chunk, static_cast<std::size_t>(n));
        }
        return true;
    }
    /// Everything received so far.
    const std::string& text() const { return text_; }

private:
    bool has_all(const std::vector<std::string>& wanted) const {
        for (const auto& w : wanted) {
            if (text_.find(w + "\n") == std::string::npos) return false;
        }
        return true;
    }

    int fd_;
    bool connected_ = false;
    std::string text_;
};

#ifdef SIMNODE_PATH
// The default node's login: CID7 (first 12 bits of the node ID), RID, AMD, Init Complete.
const std::vector<std::string> kLogin = {":X17050343N;", ":X10700343N;", ":X10701343N050101012200;",
                                         ":X19100343N050101012200;"};

std::unique_ptr<Child> spawn_default(const TempDir& images, std::vector<std::string> extra) {
    std::vector<std::string> args{"--scenario",  source_path("scenarios/default.ini").string(),
                                  "--listen",    "127.0.0.1:0",
                                  "--image-dir", images.str()};
    args.insert(args.end(), extra.begin(), extra.end());
    return Child::spawn(SIMNODE_PATH, args);
}

TEST(SimnodeHooks, StartOnConnectShowsEveryClientTheLogin) {
    TempDir images("simnode-start-on-connect");
    auto child = spawn_default(images, {"--start-on-connect"});
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port) << child->output();
    ASSERT_TRUE(child->wait_line("simnode: 1 node(s) initialized")) << child->output();
    for (int round = 0; round < 2; ++round) {
        RawClient client(*port);
        ASSERT_TRUE(client.connected());
        EXPECT_TRUE(client.wait_for_lines(kLogin, milliseconds(3000))) << "round " << round << ":\n"
                                                                       << client.text();
        // In wire order: the reservation first, Initialization Complete last.
        EXPECT_LT(client.text().find(kLogin[0]), client.text().find(kLogin[1]));
        EXPECT_LT(client.text().find(kLogin[2]), client.text().find(kLogin[3]));
    }
    EXPECT_TRUE(child->wait_line("simnode: client 127.0.0.1:", milliseconds(1000)));
}

TEST(SimnodeHooks, WithoutStartOnConnectAClientSeesNoLogin) {
    TempDir images("simnode-no-start-on-connect");
    auto child = spawn_default(images, {});
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port);
    ASSERT_TRUE(child->wait_line("simnode: 1 node(s) initialized"));
    RawClient client(*port);
    ASSERT_TRUE(client.connected());
    EXPECT_FALSE(client.wait_for_lines({kLogin[0]}, milliseconds(400))) << client.text();
}

// Time from sending `mti` to the node until a message matching pred arrives.
std::optional<milliseconds> answer_time(ToolNode& tool, Mti mti, std::uint16_t node,
                                        const std::function<bool(const Message&)>& pred) {
    const auto t0 = std::chrono::steady_clock::now();
    tool.send(mti, {}, node);
    if (!tool.take(pred, milliseconds(3000))) return std::nullopt;
    return std::chrono::duration_cast<milliseconds>(std::chrono::steady_clock::now() - t0);
}

TEST(SimnodeHooks, LatencyHoldsBackEveryAnswer) {
    TempDir images("simnode-latency");
    auto child = spawn_default(images, {"--latency", "300:50"});
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port) << child->output();
    EXPECT_NE(child->output().find("faults latency=300:50"), std::string::npos) << child->output();
    ToolNode tool(*port);
    ASSERT_TRUE(tool.wait_ready());
    const auto node = tool.find(kDefaultNode);
    ASSERT_TRUE(node);
    tool.run_for(milliseconds(900));  // answers to find()'s repeated requests
    tool.messages().clear();

    const auto verified = answer_time(tool, Mti::kVerifyNodeIdAddressed, *node, [&](const auto& m) {
        return m.mti == Mti::kVerifiedNodeId && m.source.alias == *node;
    });
    ASSERT_TRUE(verified);
    EXPECT_GE(*verified, milliseconds(300));
    EXPECT_LT(*verified, milliseconds(1000));
    const auto pip = answer_time(tool, Mti::kProtocolSupportInquiry, *node, [&](const auto& m) {
        return m.mti == Mti::kProtocolSupportReply && m.source.alias == *node;
    });
    ASSERT_TRUE(pip);
    EXPECT_GE(*pip, milliseconds(300));

    const auto t0 = std::chrono::steady_clock::now();
    const auto data = tool.read(*node, memory::Space::kCdi, 0, 5);
    const auto took = std::chrono::steady_clock::now() - t0;
    ASSERT_TRUE(data);
    EXPECT_EQ(std::string(data->begin(), data->end()), "<?xml");
    EXPECT_GE(took, milliseconds(300));
}
#endif

}  // namespace
}  // namespace olcb::e2e
