// ControlServer on 127.0.0.1 with clients on the same io_context, driven by the test: what a
// client that pipelines requests costs, read or unread.
#include "simnode/control_server.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "openlcb/in_process_bus.hpp"
#include "openlcb/stack_driver.hpp"
#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode {
namespace {

using boost::asio::ip::tcp;
using namespace std::chrono_literals;

constexpr std::size_t kNodes = 20;
constexpr std::string_view kList = "{\"cmd\":\"list\"}\n";

class ControlServerTest : public ::testing::Test {
protected:
    ControlServerTest()
        : bus_(io_),
          driver_(io_, bus_.add_endpoint()),
          registry_(nodes_, driver_),
          commands_(registry_, scenario_),
          server_(io_, commands_) {
        for (std::size_t k = 0; k < kNodes; ++k) {
            NodeConfig c;  // RAM only: list describes it all the same
            c.node_id = NodeId(test::kNodeId.value() + k);
            c.cdi = test::default_cdi();
            std::string error;
            EXPECT_TRUE(registry_.add(c, error)) << error;
        }
        server_.set_log_handler([this](const std::string& line) { log_.push_back(line); });
        EXPECT_FALSE(server_.listen("127.0.0.1", 0));
    }

    // A client that sends its bytes and reads only when told; a small receive buffer, so the
    // kernel holds few answers for it.
    tcp::socket connect_client(const std::string& bytes) {
        tcp::socket client(io_);
        client.open(tcp::v4());
        client.set_option(tcp::socket::receive_buffer_size(4096));
        client.connect({boost::asio::ip::address_v4::loopback(), server_.port()});
        auto sent = std::make_shared<std::string>(bytes);
        boost::asio::async_write(client, boost::asio::buffer(*sent),
                                 [sent](const boost::system::error_code&, std::size_t) {});
        return client;
    }

    // Runs the io_context until done() (or the limit), noting the most answers queued.
    bool run_until(const std::function<bool()>& done, std::chrono::milliseconds limit = 10s) {
        const auto end = std::chrono::steady_clock::now() + limit;
        while (!done() && std::chrono::steady_clock::now() < end) {
            io_.run_one_for(5ms);
            if (io_.stopped()) io_.restart();
            most_queued_ = std::max(most_queued_, server_.queued_bytes());
        }
        return done();
    }

    std::size_t answer_size(std::string_view line) {
        return commands_.handle_line(line).dump().size() + 1;
    }

    bool logged(std::string_view text) const {
        return std::any_of(log_.begin(), log_.end(),
                           [text](const std::string& l) { return l.find(text) != l.npos; });
    }

    // As many connections as the server takes, none of them sending anything.
    std::vector<tcp::socket> fill_with_silent_clients() {
        std::vector<tcp::socket> silent;
        silent.reserve(kMaxControlClients);
        for (std::size_t i = 0; i < kMaxControlClients; ++i) silent.push_back(connect_client(""));
        run_until([&] { return server_.connections() == kMaxControlClients; });
        return silent;
    }

    // What the server sends client until a line has come or it closes.
    std::string first_line(tcp::socket& client) {
        std::string text;
        std::array<char, 4096> chunk{};
        bool done = false;
        std::function<void()> read = [&] {
            client.async_read_some(boost::asio::buffer(chunk),
                                   [&](const boost::system::error_code& ec, std::size_t n) {
                                       text.append(chunk.data(), n);
                                       done = ec || text.find('\n') != std::string::npos;
                                       if (!done) read();
                                   });
        };
        read();
        run_until([&] { return done; });
        client.cancel();  // a read still pending ends now, while what it refers to lives
        io_.poll();
        return text.substr(0, text.find('\n'));
    }

    static std::string repeated(std::string_view line, std::size_t times) {
        std::string out;
        for (std::size_t i = 0; i < times; ++i) out += line;
        return out;
    }

    test::TempDir images_;
    boost::asio::io_context io_;
    InProcessBus bus_;
    StackDriver driver_;
    std::vector<std::unique_ptr<SimNode>> nodes_;
    NodeRegistry registry_;
    Scenario scenario_;
    ControlCommands commands_;
    ControlServer server_;
    std::vector<std::string> log_;
    std::size_t most_queued_ = 0;
};

TEST_F(ControlServerTest, AClientThatNeverReadsCostsBoundedMemoryAndIsDropped) {
    server_.set_write_timeout(300ms);
    const std::size_t list = answer_size(kList);
    ASSERT_GT(list, 4000u) << "answers big enough that 4,000 of them would be 16 MB";
    // 4,000 requests in 60 KB: before, every complete line read was answered in one batch.
    tcp::socket flooder = connect_client(repeated(kList, 4000));
    EXPECT_TRUE(run_until([this] { return logged("control: closed 127.0.0.1:"); }))
        << "the client never read, yet it was not closed";
    EXPECT_LE(most_queued_, kMaxControlQueuedBytes + list);
    EXPECT_GT(most_queued_, 0u) << "answers were queued, so the measure measured";
    EXPECT_TRUE(logged("bytes of answers for 300 ms")) << log_.front();
    EXPECT_TRUE(run_until([this] { return server_.queued_bytes() == 0; })) << "memory freed";
    EXPECT_EQ(server_.connections(), 0u);
}

TEST_F(ControlServerTest, OneTurnAnswersABatchOfRequests) {
    const std::string unknown = "{\"cmd\":\"nope\"}\n";
    tcp::socket flooder = connect_client(repeated(unknown, 1000));
    ASSERT_TRUE(run_until([this] { return most_queued_ > 0 && server_.queued_bytes() == 0; }));
    EXPECT_LE(most_queued_, kMaxControlBatch * answer_size(unknown));
}

TEST_F(ControlServerTest, AClientThatReadsGetsEveryPipelinedAnswerInOrder) {
    // More answers than the queue holds, so the bound is reached while the client reads.
    constexpr std::size_t kRequests = 300;
    ASSERT_GT(kRequests * answer_size(kList), kMaxControlQueuedBytes);
    std::string requests;
    for (std::size_t i = 0; i < kRequests; ++i) {
        requests += "{\"cmd\":\"list\",\"id\":" + std::to_string(i) + "}\n";
    }
    tcp::socket client = connect_client(requests);
    std::string answers;
    std::array<char, 65536> chunk{};
    std::size_t lines = 0;
    std::function<void()> read = [&] {
        client.async_read_some(
            boost::asio::buffer(chunk), [&](const boost::system::error_code& ec, std::size_t n) {
                if (ec) return;
                answers.append(chunk.data(), n);
                // Only the new bytes: counting the whole answer text each time was quadratic,
                // 9 s under ASan with this file at -O0.
                lines += static_cast<std::size_t>(std::count(
                    chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(n), '\n'));
                read();
            });
    };
    read();
    // A guard against a hang, not a speed limit.
    ASSERT_TRUE(run_until([&] { return lines >= kRequests; }, 60s)) << lines << " answers";
    EXPECT_LE(most_queued_, kMaxControlQueuedBytes + answer_size(kList));
    std::size_t begin = 0;
    for (std::size_t i = 0; i < kRequests; ++i) {
        const auto nl = answers.find('\n', begin);
        const auto answer = ControlJson::parse(answers.substr(begin, nl - begin));
        begin = nl + 1;
        ASSERT_EQ(answer["id"], i);
        ASSERT_EQ(answer["nodes"].size(), kNodes);
    }
    EXPECT_EQ(server_.connections(), 1u);
    EXPECT_TRUE(log_.empty()) << log_.front();
}

TEST_F(ControlServerTest, AFullServerClosesItsLongestSilentClientForANewcomer) {
    server_.set_evict_idle_after(100ms);
    const auto silent = fill_with_silent_clients();
    ASSERT_EQ(server_.connections(), kMaxControlClients);
    run_until([] { return false; }, 150ms);
    tcp::socket newcomer = connect_client(std::string(kList));
    const std::string answer = first_line(newcomer);
    EXPECT_EQ(ControlJson::parse(answer)["ok"], true) << answer;
    EXPECT_EQ(server_.connections(), kMaxControlClients);
    EXPECT_TRUE(logged("ms, the longest, to admit 127.0.0.1:")) << (log_.empty() ? "" : log_[0]);
}

TEST_F(ControlServerTest, AFullServerOfRecentClientsRefusesTheNewcomer) {
    server_.set_evict_idle_after(60s);
    const auto silent = fill_with_silent_clients();
    ASSERT_EQ(server_.connections(), kMaxControlClients);
    tcp::socket newcomer = connect_client(std::string(kList));
    const std::string answer = first_line(newcomer);
    EXPECT_NE(answer.find("control connections open (at most 16)"), std::string::npos) << answer;
}

}  // namespace
}  // namespace olcb::simnode
