// The simnode hub under attack, on loopback and bounded in time: a client flooding valid frames
// is slowed while a well-behaved tool keeps getting answers within 750 ms and passive readers
// stay connected; connections beyond the per-address limit are refused with a log line.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <sys/socket.h>

#include <atomic>
#include <thread>

#include "e2e/e2e_util.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb::e2e {
namespace {

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};

// True when the peer closed fd (reads until EOF or timeout, discarding data).
bool closed_by_peer(int fd, milliseconds timeout) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
        pollfd p{fd, POLLIN, 0};
        if (::poll(&p, 1, 20) <= 0) continue;
        char buf[4096];
        if (::read(fd, buf, sizeof buf) <= 0) return true;
    }
    return false;
}

#ifdef SIMNODE_PATH
TEST(SimnodeHub, AFloodDoesNotStarveAWellBehavedTool) {
    TempDir images("simnode-hub-flood");
    auto child = spawn_default_simnode(SIMNODE_PATH, images.str());
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port) << child->output();
    ToolNode tool(*port);
    ASSERT_TRUE(tool.wait_ready());
    const auto node = tool.find(kDefaultNode);
    ASSERT_TRUE(node);

    // Passive readers that drain everything, as monitors do.
    std::vector<int> readers;
    readers.reserve(4);
    for (int i = 0; i < 4; ++i) readers.push_back(connect_to(*port));
    std::atomic<bool> stop{false};
    std::atomic<std::uint64_t> flooded{0};
    std::thread drain([&] {
        char buf[65536];
        while (!stop) {
            for (int fd : readers) {
                pollfd p{fd, POLLIN, 0};
                if (::poll(&p, 1, 1) > 0) (void)::read(fd, buf, sizeof buf);
            }
        }
    });
    std::thread flood([&] {
        const int fd = connect_to(*port);
        if (fd < 0) return;
        timeval limit{0, 200'000};  // a paused hub must not keep this thread past the test
        ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &limit, sizeof limit);
        std::string chunk;
        for (int i = 0; i < 2000; ++i) chunk += ":X195B4123N0501010100000000;\n";
        while (!stop) {
            const ssize_t n = ::send(fd, chunk.data(), chunk.size(), MSG_NOSIGNAL);
            if (n <= 0) break;
            flooded += static_cast<std::uint64_t>(n);
        }
        ::close(fd);
    });

    milliseconds worst{0};
    int answered = 0;
    const auto end = std::chrono::steady_clock::now() + std::chrono::seconds(4);
    while (std::chrono::steady_clock::now() < end) {
        const auto t0 = std::chrono::steady_clock::now();
        tool.send(Mti::kVerifyNodeIdAddressed, {}, node);
        const auto m = tool.take(
            [&](const Message& m) {
                return m.mti == Mti::kVerifiedNodeId && m.source.alias == *node;
            },
            milliseconds(2000));
        const auto took =
            std::chrono::duration_cast<milliseconds>(std::chrono::steady_clock::now() - t0);
        EXPECT_TRUE(m) << "no answer within 2 s during the flood";
        if (m) ++answered;
        worst = std::max(worst, took);
        tool.run_for(milliseconds(50));
    }
    stop = true;
    flood.join();
    drain.join();
    EXPECT_LT(worst, milliseconds(750)) << "worst answer " << worst.count() << " ms";
    EXPECT_GT(answered, 10);
    EXPECT_GT(flooded.load(), 1u << 20) << "the flood did not flood";
    child->wait_line("\x01never", milliseconds(200));
    EXPECT_EQ(child->output().find("simnode: hub: dropped"), std::string::npos) << child->output();
    EXPECT_EQ(tool.client().stats().disconnects, 0u);
    for (int fd : readers) {
        EXPECT_FALSE(closed_by_peer(fd, milliseconds(50))) << "a passive reader was dropped";
        ::close(fd);
    }
    std::printf("flood %.1f MB in 4 s, %d answers, worst %lld ms\n",
                static_cast<double>(flooded.load()) / 1e6, answered,
                static_cast<long long>(worst.count()));
}

TEST(SimnodeHub, ConnectionsBeyondThePerAddressLimitAreRefused) {
    TempDir images("simnode-hub-limit");
    auto child =
        spawn_default_simnode(SIMNODE_PATH, images.str(), {"--max-clients-per-address", "2"});
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port) << child->output();
    const int a = connect_to(*port), b = connect_to(*port), c = connect_to(*port);
    ASSERT_TRUE(a >= 0 && b >= 0 && c >= 0);
    EXPECT_TRUE(closed_by_peer(c, milliseconds(2000)));
    EXPECT_FALSE(closed_by_peer(a, milliseconds(100)));
    const auto line = child->wait_line("simnode: hub: refused client 127.0.0.1:");
    ASSERT_TRUE(line) << child->output();
    EXPECT_NE(line->find("(max-clients-per-address 2)"), std::string::npos) << *line;
    for (int fd : {a, b, c}) ::close(fd);
}
#endif

}  // namespace
}  // namespace olcb::e2e
