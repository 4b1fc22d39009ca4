// Load on the simnode program: 32 TCP clients each download the whole CDI 50 times at once while
// another client measures how fast Verify Node ID is answered.
#include <gtest/gtest.h>

#include <atomic>
#include <fstream>
#include <sstream>
#include <thread>

#include "e2e/e2e_util.hpp"

namespace olcb::e2e {
namespace {

using memory::Space;

constexpr NodeId kDefaultNode{0x05'01'01'01'22'00ull};
constexpr int kClients = 32;
constexpr int kDownloads = 50;
constexpr auto kVerifyLimit = milliseconds(750);
constexpr auto kVerifyPeriod = milliseconds(50);
constexpr auto kLoadTimeout = std::chrono::seconds(240);

// One downloading client: reads space 0xFF in 64-byte reads, one at a time, kDownloads times,
// driven by callbacks on a shared io_context.
class Downloader {
public:
    Downloader(boost::asio::io_context& io, std::uint16_t port, NodeId id,
               const std::vector<std::uint8_t>& expected)
        : io_(io),
          client_(io, "127.0.0.1", port),
          driver_(io, client_),
          stack_(config(id)),
          expected_(expected) {
        stack_.set_message_handler([](const Message&) { return true; });
        stack_.set_datagram_handler([this](const ReceivedDatagram& d) { on_datagram(d); });
        stack_.set_outcome_handler([this](const DatagramOutcome& o) {
            if (o.status != DatagramOutcome::Status::kAccepted) {
                fail("read datagram not accepted, code " + std::to_string(o.error_code));
            }
        });
        driver_.attach(stack_);
        client_.set_connection_handler([this](bool up) {
            if (up && !started_) {
                started_ = true;
                driver_.start_all();
            } else if (!up && started_) {
                fail("disconnected");
            }
        });
        client_.start();
    }

    bool ready() const { return stack_.initialized(); }
    bool finished() const { return failed_ || downloads_ == kDownloads; }
    bool failed() const { return failed_; }
    const std::string& why() const { return why_; }
    int downloads() const { return downloads_; }

    void begin(std::uint16_t node) {
        node_ = node;
        next_read();
    }

private:
    static NodeStackConfig config(NodeId id) {
        NodeStackConfig c;
        c.node_id = id;
        c.protocols = {Protocol::kDatagram, Protocol::kMemoryConfiguration};
        return c;
    }

    void fail(std::string why) {
        if (failed_ || downloads_ == kDownloads) return;
        failed_ = true;
        why_ = std::move(why);
    }

    void next_read() {
        if (finished()) return;
        memory::Read r;
        r.space = Space::kCdi;
        r.address = static_cast<std::uint32_t>(current_.size());
        r.count = 64;
        if (!stack_.send_datagram(node_, memory::encode(r), Clock::now())) {
            fail("send_datagram refused");
        }
    }

    void on_datagram(const ReceivedDatagram& d) {
        stack_.accept_datagram(d.source_alias);
        if (d.source_alias != node_ || finished()) return;
        const auto decoded = memory::decode(d.payload);
        const auto* reply =
            decoded.ok() ? std::get_if<memory::ReadReply>(&decoded.message) : nullptr;
        if (!reply || reply->address != current_.size()) {
            fail("unexpected reply at " + std::to_string(current_.size()));
            return;
        }
        current_.insert(current_.end(), reply->data.begin(), reply->data.end());
        if (current_.size() > expected_.size()) {
            fail("CDI longer than the file");
            return;
        }
        if (reply->data.size() < 64) {
            if (current_ != expected_) {
                fail("download " + std::to_string(downloads_) + " differs from the file");
                return;
            }
            ++downloads_;
            current_.clear();
        }
        boost::asio::post(io_, [this] { next_read(); });
    }

    boost::asio::io_context& io_;
    TcpClient client_;
    StackDriver driver_;
    NodeStack stack_;
    const std::vector<std::uint8_t>& expected_;
    std::uint16_t node_ = 0;
    bool started_ = false;
    bool failed_ = false;
    std::string why_;
    int downloads_ = 0;
    std::vector<std::uint8_t> current_;
};

TEST(SimnodeLoad, ThirtyTwoClientsDownloadTheCdiWhileVerifyStaysFast) {
#ifndef SIMNODE_PATH
    GTEST_SKIP() << "simnode is not built";
#else
    std::ifstream in(source_path("scenarios/default.xml"), std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string cdi = text.str();
    std::vector<std::uint8_t> expected(cdi.begin(), cdi.end());
    expected.push_back(0);

    TempDir images("simnode-load");
    auto child = spawn_default_simnode(SIMNODE_PATH, images.str());
    ASSERT_TRUE(child);
    const auto port = child->wait_listening();
    ASSERT_TRUE(port) << child->output();

    ToolNode verifier(*port);
    ASSERT_TRUE(verifier.wait_ready());
    const auto node = verifier.find(kDefaultNode);
    ASSERT_TRUE(node);

    boost::asio::io_context io;
    std::vector<std::unique_ptr<Downloader> > clients;
    clients.reserve(kClients);
    for (int i = 0; i < kClients; ++i) {
        clients.push_back(
            std::make_unique<Downloader>(io, *port, NodeId(0x02'01'0D'00'01'00ull + i), expected));
    }
    const auto setup_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (std::chrono::steady_clock::now() < setup_deadline &&
           !std::all_of(clients.begin(), clients.end(), [](auto& c) { return c->ready(); })) {
        io.run_one_for(milliseconds(5));
    }
    ASSERT_TRUE(std::all_of(clients.begin(), clients.end(), [](auto& c) { return c->ready(); }));

    std::atomic<bool> done{false};
    const auto load_start = std::chrono::steady_clock::now();
    std::thread load([&] {
        for (auto& c : clients) c->begin(*node);
        const auto deadline = std::chrono::steady_clock::now() + kLoadTimeout;
        while (
            std::chrono::steady_clock::now() < deadline &&
            !std::all_of(clients.begin(), clients.end(), [](auto& c) { return c->finished(); })) {
            io.run_one_for(milliseconds(5));
        }
        done = true;
    });

    const auto id = kDefaultNode.to_bytes();
    const std::vector<std::uint8_t> id_bytes(id.begin(), id.end());
    milliseconds worst{0};
    int probes = 0;
    int late = 0;
    while (!done) {
        verifier.messages().clear();
        const auto sent = std::chrono::steady_clock::now();
        verifier.send(Mti::kVerifyNodeIdGlobal, id_bytes);
        const auto answer = verifier.take(
            [&](const Message& m) {
                return m.mti == Mti::kVerifiedNodeId && m.payload == id_bytes;
            },
            milliseconds(5000));
        const auto took =
            std::chrono::duration_cast<milliseconds>(std::chrono::steady_clock::now() - sent);
        ++probes;
        if (!answer || took > kVerifyLimit) ++late;
        worst = std::max(worst, took);
        verifier.run_for(kVerifyPeriod);
    }
    load.join();
    const auto load_time =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - load_start).count();

    int downloads = 0;
    for (const auto& c : clients) {
        EXPECT_FALSE(c->failed()) << c->why();
        downloads += c->downloads();
    }
    EXPECT_EQ(downloads, kClients * kDownloads);
    std::cout << "[ load     ] " << downloads << " CDI downloads of " << expected.size()
              << " bytes by " << kClients << " clients in " << load_time << " s; " << probes
              << " Verify Node ID probes, worst answer " << worst.count() << " ms\n";
    EXPECT_GT(probes, 0);
    EXPECT_EQ(late, 0) << "worst Verify Node ID answer " << worst.count() << " ms";
    EXPECT_LE(worst, kVerifyLimit);
#endif
}

}  // namespace
}  // namespace olcb::e2e
