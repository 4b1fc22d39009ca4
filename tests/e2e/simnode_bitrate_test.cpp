// simnode --bitrate: the hub's segment paced as one CAN bus, seen from loopback clients with the
// steady clock and bounded waits: a burst reaches another client no sooner than its frame time,
// two senders share the bus, an answer costs its request's and its own frame time on top of
// --latency, and a bad value is a usage error.
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>

#include <fstream>

#include "e2e/e2e_util.hpp"
#include "openlcb/can_timing.hpp"
#include "openlcb/gridconnect.hpp"

namespace olcb::e2e {
namespace {

using std::chrono::steady_clock;

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
constexpr std::uint32_t kBitrate = 125000;

// A frame of the burst: a PCER-shaped frame from `alias` numbered `seq`.
CanFrame burst_frame(std::uint16_t alias, std::uint32_t seq) {
    CanFrame f;
    f.id = 0x195B4000u | alias;
    f.len = 8;
    f.data = {
        5, 1, 1, 1, 0, 0, static_cast<std::uint8_t>(seq >> 8), static_cast<std::uint8_t>(seq)};
    return f;
}

// A raw client collecting the arrival time of every burst frame (other traffic is ignored).
struct Receiver {
    explicit Receiver(int socket) : fd(socket) {}
    int fd;
    gridconnect::Parser parser;
    std::vector<std::pair<std::uint32_t, steady_clock::time_point>> got;  // id and time

    // Reads until `count` burst frames arrived or `timeout` passed; true when they did.
    bool collect(std::size_t count, milliseconds timeout) {
        const auto deadline = steady_clock::now() + timeout;
        while (got.size() < count && steady_clock::now() < deadline) {
            pollfd p{fd, POLLIN, 0};
            if (::poll(&p, 1, 20) <= 0) continue;
            char buf[4096];
            const ssize_t n = ::read(fd, buf, sizeof buf);
            if (n <= 0) return false;
            const auto now = steady_clock::now();
            parser.feed(std::string_view(buf, static_cast<std::size_t>(n)), [&](const CanFrame& f) {
                if ((f.id & 0x1FFFF000u) == 0x195B4000u && f.data[0] == 5)
                    got.emplace_back(f.id, now);
            });
        }
        return got.size() >= count;
    }
};

bool send_burst(int fd, std::uint16_t alias, std::uint32_t frames) {
    std::string text;
    for (std::uint32_t i = 0; i < frames; ++i)
        text += gridconnect::format(burst_frame(alias, i)) + "\n";
    return ::send(fd, text.data(), text.size(), MSG_NOSIGNAL) == static_cast<ssize_t>(text.size());
}

#ifdef SIMNODE_PATH
// simnode on the default scenario at 125 kbit/s, every node initialized.
struct PacedSimnode {
    TempDir images{"simnode-bitrate"};
    std::unique_ptr<Child> child;
    std::uint16_t port = 0;
    std::string listening;

    explicit PacedSimnode(std::vector<std::string> extra = {}) {
        std::vector<std::string> args = {
            "--scenario",  source_path("scenarios/default.ini").string(),
            "--listen",    "127.0.0.1:0",
            "--image-dir", images.str(),
            "--run-for",   "120",
            "--bitrate",   std::to_string(kBitrate)};
        args.insert(args.end(), extra.begin(), extra.end());
        child = Child::spawn(SIMNODE_PATH, args);
        if (!child) return;
        if (auto line = child->wait_line("simnode: listening on ")) {
            listening = *line;
            port = static_cast<std::uint16_t>(std::stoi(line->substr(line->rfind(':') + 1)));
        }
        if (!child->wait_line("simnode: 1 node(s) initialized", milliseconds(10000))) port = 0;
    }
};

TEST(SimnodeBitrate, ABurstReachesASecondClientNoFasterThanTheFrameTime) {
    PacedSimnode sim;
    ASSERT_NE(sim.port, 0) << sim.child->output();
    EXPECT_NE(sim.listening.find("(bus paced at 125000 bit/s)"), std::string::npos)
        << sim.listening;
    Receiver b{connect_to(sim.port)};
    const int a = connect_to(sim.port);
    ASSERT_TRUE(a >= 0 && b.fd >= 0);
    constexpr std::uint32_t kFrames = 100;
    const auto sent = steady_clock::now();
    ASSERT_TRUE(send_burst(a, 0x123, kFrames));
    const auto bound = kFrames * can_frame_time(8, kBitrate);  // 128 ms
    ASSERT_TRUE(b.collect(kFrames, milliseconds(10000))) << b.got.size() << " frames";
    const auto took = b.got.back().second - sent;
    EXPECT_GE(took, bound);
    EXPECT_LT(took, bound + std::chrono::seconds(2));  // paced, not stuck
    // The first frame arrives once its own transmission completed, not before.
    EXPECT_GE(b.got.front().second - sent, can_frame_time(8, kBitrate));
    std::printf("%u frames in %.1f ms, bound %.1f ms\n", kFrames,
                std::chrono::duration<double, std::milli>(took).count(),
                std::chrono::duration<double, std::milli>(bound).count());
    ::close(a);
    ::close(b.fd);
}

TEST(SimnodeBitrate, TwoSendersShareOneBus) {
    PacedSimnode sim;
    ASSERT_NE(sim.port, 0) << sim.child->output();
    Receiver r{connect_to(sim.port)};
    const int a = connect_to(sim.port), c = connect_to(sim.port);
    ASSERT_TRUE(a >= 0 && c >= 0 && r.fd >= 0);
    constexpr std::uint32_t kEach = 60;
    const auto sent = steady_clock::now();
    ASSERT_TRUE(send_burst(a, 0x123, kEach));
    ASSERT_TRUE(send_burst(c, 0x124, kEach));
    ASSERT_TRUE(r.collect(std::size_t{2} * kEach, milliseconds(10000)))
        << r.got.size() << " frames";
    EXPECT_GE(r.got.back().second - sent, 2 * kEach * can_frame_time(8, kBitrate));
    std::size_t from_a = 0;
    for (const auto& [id, at] : r.got) from_a += (id & 0xFFF) == 0x123 ? 1 : 0;
    EXPECT_EQ(from_a, kEach);
    for (int fd : {a, c, r.fd}) ::close(fd);
}

TEST(SimnodeBitrate, AnAnswerCostsBothFrameTimesOnTopOfTheLatency) {
    PacedSimnode sim({"--latency", "20"});
    ASSERT_NE(sim.port, 0) << sim.child->output();
    ToolNode tool(sim.port);
    ASSERT_TRUE(tool.wait_ready());
    const auto node = tool.find(kDefaultNode);
    ASSERT_TRUE(node);
    // Verify Node ID addressed: 2 data bytes; Verified Node ID: 6.
    const auto bus = can_frame_time(2, kBitrate) + can_frame_time(6, kBitrate);  // 1.92 ms
    for (int i = 0; i < 5; ++i) {
        const auto t0 = steady_clock::now();
        tool.send(Mti::kVerifyNodeIdAddressed, {}, node);
        const auto m = tool.take(
            [&](const Message& m) {
                return m.mti == Mti::kVerifiedNodeId && m.source.alias == *node;
            },
            milliseconds(2000));
        ASSERT_TRUE(m);
        EXPECT_GE(steady_clock::now() - t0, milliseconds(20) + bus);
    }
}

std::pair<int, std::string> run_with_stderr(const std::vector<std::string>& args) {
    return run_merged(SIMNODE_PATH, args);
}

TEST(SimnodeBitrate, ABadValueIsAUsageError) {
    EXPECT_NE(run_program(SIMNODE_PATH, {"--help"}).second.find("--bitrate N"), std::string::npos);
    for (const char* bad : {"5000", "2000000", "fast", "-1", "125k"}) {
        const auto [code, out] = run_with_stderr({"--bitrate", bad, "--listen", "127.0.0.1:0"});
        EXPECT_EQ(code, 2) << bad << "\n" << out;
        EXPECT_NE(out.find("simnode: bitrate '" + std::string(bad) +
                           "' must be 0 (off) or 10000..1000000 bit/s"),
                  std::string::npos)
            << out;
    }
}

TEST(SimnodeBitrate, ZeroIsOffAndTheKeyWorksInAScenarioFile) {
    TempDir dir("simnode-bitrate-ini");
    const auto [off_code, off] =
        run_program(SIMNODE_PATH, {"--bitrate", "0", "--listen", "127.0.0.1:0", "--image-dir",
                                   dir.str(), "--run-for", "0.3"});
    EXPECT_EQ(off_code, 0) << off;
    EXPECT_NE(off.find("simnode: listening on 127.0.0.1:"), std::string::npos) << off;
    EXPECT_EQ(off.find("paced"), std::string::npos) << off;
    {
        std::ofstream ini(dir.path() / "paced.ini");
        ini << "node-id = 05.01.01.01.22.00\ncdi = "
            << source_path("scenarios/default.xml").string()
            << "\nlisten = 127.0.0.1:0\nbitrate = 250000\n";
    }
    const auto [code, out] = run_program(
        SIMNODE_PATH,
        {(dir.path() / "paced.ini").string(), "--image-dir", dir.str(), "--run-for", "0.5"});
    EXPECT_EQ(code, 0) << out;
    EXPECT_NE(out.find("(bus paced at 250000 bit/s)"), std::string::npos) << out;
    EXPECT_NE(out.find("1 node(s) initialized"), std::string::npos) << out;
    // Without a hub the in-process segment is paced and says so.
    const auto [in_code, in] =
        run_program(SIMNODE_PATH, {"--node-id", "05.01.01.01.22.00", "--cdi",
                                   source_path("scenarios/default.xml").string(), "--image-dir",
                                   dir.str(), "--bitrate", "125000", "--run-for", "0.5"});
    EXPECT_EQ(in_code, 0) << in;
    EXPECT_NE(in.find("simnode: in-process segment (bus paced at 125000 bit/s)"), std::string::npos)
        << in;
    EXPECT_NE(in.find("1 node(s) initialized"), std::string::npos) << in;
}
#endif

}  // namespace
}  // namespace olcb::e2e
