// The process keys of the test hooks (latency, start-on-connect) and --connect replacing a
// scenario's listen.
#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "simnode/scenario.hpp"

namespace olcb::simnode {
namespace {

namespace fs = std::filesystem;
using std::chrono::milliseconds;

const fs::path kScenarios = fs::path(OLCB_SOURCE_DIR) / "scenarios";
constexpr const char* kTwoGroups =
    "cdi = default.xml\nlisten = 127.0.0.1:0\n"
    "[node.a]\nnode-id = 05.01.01.01.50.00\ncount = 2\n"
    "[node.b]\nnode-id = 05.01.01.01.51.00\nfault = latency=5\n";

std::optional<Scenario> parse(const std::string& ini, const std::vector<std::string>& overrides,
                              std::string& error) {
    return parse_scenario_text(ini, kScenarios, overrides, error);
}

TEST(ScenarioHooks, LatencyAppliesToEveryNodeWithoutItsOwn) {
    std::string error;
    const auto s = parse(kTwoGroups, {"--latency", "100:20"}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_EQ(s->nodes.size(), 3u);
    EXPECT_EQ(s->nodes[0].faults.value("latency").value, 100u);
    EXPECT_EQ(s->nodes[1].faults.value("latency").jitter, 20u);
    EXPECT_EQ(s->nodes[2].faults.value("latency").value, 5u);
    EXPECT_EQ(s->nodes[2].faults.value("latency").jitter, 0u);
    const auto file = parse(std::string("latency = 7\n") + kTwoGroups, {}, error);
    ASSERT_TRUE(file) << error;
    EXPECT_EQ(file->nodes[0].faults.value("latency").value, 7u);
    for (const char* bad : {"x", "0", "1:2:3", "-4"}) {
        EXPECT_FALSE(parse(kTwoGroups, {"--latency", bad}, error)) << bad;
        EXPECT_NE(error.find("latency"), std::string::npos) << error;
    }
}

TEST(ScenarioHooks, StartOnConnectAsFlagAndKey) {
    std::string error;
    auto s = parse(kTwoGroups, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_FALSE(s->start_on_connect);
    s = parse(kTwoGroups, {"--start-on-connect"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->start_on_connect);
    s = parse(std::string("start-on-connect = yes\n") + kTwoGroups, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->start_on_connect);
    s = parse(std::string("start-on-connect = true\n") + kTwoGroups, {"--start-on-connect=false"},
              error);
    ASSERT_TRUE(s) << error;
    EXPECT_FALSE(s->start_on_connect);
    EXPECT_FALSE(parse(kTwoGroups, {"--start-on-connect=maybe"}, error));
}

TEST(ScenarioHooks, ConnectReplacesTheScenariosListen) {
    std::string error;
    auto s = parse(kTwoGroups, {"--connect", "127.0.0.1:12021"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->connect);
    EXPECT_FALSE(s->listen) << "a scenario's listen stayed next to --connect";
    s = parse(kTwoGroups, {"--connect", "127.0.0.1:12021", "--listen", "127.0.0.1:12022"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->connect);
    ASSERT_TRUE(s->listen);
    EXPECT_EQ(s->listen->port, 12022);
    // Both in the file: both stay.
    s = parse(std::string("connect = 127.0.0.1:12021\n") + kTwoGroups, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->connect && s->listen);
}

TEST(ScenarioHooks, NodesKnowTheirCdiFile) {
    std::string error;
    const auto s = parse(kTwoGroups, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->nodes[0].cdi_file, (kScenarios / "default.xml").lexically_normal());
}

}  // namespace
}  // namespace olcb::simnode

namespace olcb::simnode {
namespace {

TEST(ScenarioLimits, ACdiOver16MiBIsRefusedUnread) {
    const fs::path dir =
        fs::temp_directory_path() / ("simnode-big-cdi-" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const fs::path big = dir / "big.xml";
    {
        std::ofstream out(big, std::ios::binary);
        out << "<cdi>";
    }
    // Sparse: 100 MB on paper, nothing on disk, and nothing read.
    fs::resize_file(big, 100'000'000);
    std::string error;
    const auto s =
        parse_scenario_text("node-id = 05.01.01.01.22.00\ncdi = big.xml\n", dir, {}, error);
    EXPECT_FALSE(s);
    EXPECT_NE(error.find("over the limit of 16777216"), std::string::npos) << error;
    fs::remove_all(dir);
}

TEST(ScenarioLimits, SimNodeRefusesAnOversizedCdiText) {
    NodeConfig c;
    c.node_id = NodeId(0x050101012200ull);
    c.cdi = std::string(16 * 1024 * 1024 + 1, ' ');
    std::string error;
    EXPECT_FALSE(SimNode::create(c, error));
    EXPECT_NE(error.find("16 MiB"), std::string::npos) << error;
}

}  // namespace
}  // namespace olcb::simnode
