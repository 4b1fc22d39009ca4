// The whole protocol check run over GridConnect TCP against a SimNode on a hub in another thread
// (real time, loopback): no false failure, and the wall time the benchmark budget talks about.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "openlcb/stack_driver.hpp"
#include "openlcb/tcp_hub_server.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

constexpr NodeId kDut{0x050101012200ull};
constexpr NodeId kTool{0x0501010122FEull};

TEST(TcpLinkTest, RefusedConnectionIsAnError) {
    std::string error;
    // Port 1 on loopback: nothing listens there.
    auto link = connect_tcp("127.0.0.1", 1, kTool, error);
    EXPECT_FALSE(link);
    EXPECT_FALSE(error.empty());
}

TEST(TcpLinkTest, DefaultNodeOverTcpHasNoFailure) {
    std::ifstream in(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios/default.xml");
    std::stringstream ss;
    ss << in.rdbuf();
    simnode::NodeConfig cfg;
    cfg.node_id = kDut;
    cfg.cdi = ss.str();
    cfg.user_name = "simnode default";
    std::string error;
    auto dut = simnode::SimNode::create(cfg, error);
    ASSERT_TRUE(dut) << error;

    boost::asio::io_context io;
    TcpHubServer hub(io);
    ASSERT_FALSE(hub.listen("127.0.0.1", 0));
    const std::uint16_t port = hub.port();
    StackDriver driver(io, hub.add_local_endpoint());
    driver.attach(dut->stack());
    driver.start_all();
    auto guard = boost::asio::make_work_guard(io);
    std::thread server([&] { io.run(); });
    // Stops and joins the hub's thread on every way out, failed assertions included.
    struct Joiner {
        std::thread& thread;
        boost::asio::io_context& io;
        ~Joiner() {
            if (!thread.joinable()) return;
            io.stop();
            thread.join();
        }
    } joiner{server, io};

    const auto t0 = std::chrono::steady_clock::now();
    auto link = connect_tcp("127.0.0.1", port, kTool, error);
    ASSERT_TRUE(link) << error;
    std::vector<CheckResult> results;
    {
        Session session(*link);
        ASSERT_TRUE(session.start());
        auto node = session.find_node(kDut);
        ASSERT_TRUE(node);
        CheckContext ctx;
        results = run_protocol_checks(session, *node, ProtocolOptions{}, ctx);
    }
    const auto wall = std::chrono::steady_clock::now() - t0;
    link.reset();
    boost::asio::post(io, [&] {
        hub.stop();
        guard.reset();
        io.stop();
    });
    server.join();
    driver.detach(dut->stack());

    ASSERT_GT(results.size(), 25u);
    for (const auto& r : results) {
        EXPECT_NE(r.status, Status::kFail)
            << r.id << ": " << r.message << " expected " << r.expected << " seen " << r.seen;
    }
    std::printf("protocol checks over TCP: %zu checks in %lld ms\n", results.size(),
                static_cast<long long>(
                    std::chrono::duration_cast<std::chrono::milliseconds>(wall).count()));
}

}  // namespace
}  // namespace olcb::conform
