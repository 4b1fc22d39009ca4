// Scenario files and command lines: transports (TCP, SocketCAN, serial with its line settings),
// node groups, overrides and the errors a user sees for bad values.
#include "simnode/scenario.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <future>
#include <string>
#include <vector>

#include "support/temp_files.hpp"

namespace olcb::simnode {
namespace {

namespace fs = std::filesystem;

fs::path scenarios_dir() {
    return fs::path(OLCB_SOURCE_DIR) / "scenarios";
}

std::optional<Scenario> parse(const std::string& ini, const std::vector<std::string>& overrides,
                              std::string& error) {
    return parse_scenario_text(ini, scenarios_dir(), overrides, error);
}

constexpr const char* kOneNode = "node-id = 05.01.01.01.22.00\ncdi = default.xml\n";

TEST(ScenarioTest, SerialWithDefaultLineSettings) {
    std::string error;
    const auto s = parse(std::string(kOneNode) + "serial = /dev/ttyACM0\n", {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->serial, "/dev/ttyACM0");
    EXPECT_EQ(s->baud, 115200u);
    EXPECT_FALSE(s->rtscts);
    EXPECT_FALSE(s->listen);
    EXPECT_FALSE(s->connect);
}

TEST(ScenarioTest, SerialLineSettingsFromTheCommandLine) {
    std::string error;
    const auto s =
        parse(kOneNode, {"--serial", "/dev/ttyUSB1", "--baud", "57600", "--flow-control", "rtscts"},
              error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->serial, "/dev/ttyUSB1");
    EXPECT_EQ(s->baud, 57600u);
    EXPECT_TRUE(s->rtscts);
}

TEST(ScenarioTest, BadBaudAndFlowControlAreRefusedByName) {
    for (const char* baud : {"0", "fast", "115200x", "-1", "99999999999"}) {
        std::string error;
        EXPECT_FALSE(parse(kOneNode, {"--serial", "/dev/x", "--baud", baud}, error)) << baud;
        EXPECT_NE(error.find("baud"), std::string::npos) << error;
    }
    std::string error;
    EXPECT_FALSE(parse(kOneNode, {"--serial", "/dev/x", "--flow-control", "xonxoff"}, error));
    EXPECT_NE(error.find("flow-control"), std::string::npos) << error;
}

TEST(ScenarioTest, LogMaxBytesAndWatchVariableFromFileAndCommandLine) {
    std::string error;
    auto s = parse(kOneNode, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->log_max_bytes, 67'108'864u) << "a log left running stays bounded by default";
    s = parse(std::string(kOneNode) + "log-max-bytes = 4096\n", {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->log_max_bytes, 4096u);
    s = parse(kOneNode, {"--log-max-bytes", "0", "--watch-variable", "Settings/Trim"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->log_max_bytes, 0u);
    ASSERT_EQ(s->nodes.size(), 1u);
    EXPECT_EQ(s->nodes[0].watch_variable, "Settings/Trim");
    EXPECT_FALSE(parse(kOneNode, {"--log-max-bytes", "lots"}, error));
    EXPECT_NE(error.find("log-max-bytes"), std::string::npos) << error;
}

TEST(ScenarioTest, ACdiThatIsNoRegularFileIsRefusedUnread) {
    const test_support::TempDir dir("simnode-cdi-fifo");
    const fs::path fifo = dir.path() / "cdi.xml";
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
    using namespace std::chrono_literals;
    auto parsed = std::async(std::launch::async, [&fifo] {
        std::string error;
        const auto s =
            parse("node-id = 05.01.01.01.22.00\ncdi = " + fifo.string() + "\n", {}, error);
        return s ? std::string("parsed") : error;
    });
    if (parsed.wait_for(1s) != std::future_status::ready) {
        std::ofstream(fifo) << "";  // a writer that comes and goes releases the blocked open
        FAIL() << "a FIFO without a writer blocked the scenario: " << parsed.get();
    }
    EXPECT_EQ(parsed.get(),
              "node: CDI file: cannot read " + fifo.string() + ": not a regular file");
    std::string error;
    EXPECT_FALSE(parse("node-id = 05.01.01.01.22.00\ncdi = /dev/zero\n", {}, error));
    EXPECT_EQ(error, "node: CDI file: cannot read /dev/zero: not a regular file");
}

TEST(ScenarioTest, StreamsOnByDefaultOffByKeyOrCommandLine) {
    std::string error;
    auto s = parse(kOneNode, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->nodes.at(0).streams);
    s = parse(std::string(kOneNode) + "streams = false\n", {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_FALSE(s->nodes.at(0).streams);
    s = parse(kOneNode, {"--streams", "false"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_FALSE(s->nodes.at(0).streams);
    EXPECT_FALSE(parse(kOneNode, {"--streams", "sometimes"}, error));
    EXPECT_NE(error.find("streams"), std::string::npos) << error;
}

TEST(ScenarioTest, AuditFilesFromFileRelativeToItAndFromTheCommandLine) {
    std::string error;
    auto s = parse(std::string(kOneNode) + "audit = out/audit.json\naudit-junit = audit.xml\n", {},
                   error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->audit, scenarios_dir() / "out/audit.json");
    EXPECT_EQ(s->audit_junit, scenarios_dir() / "audit.xml");
    s = parse(kOneNode, {"--audit", "/tmp/a.json"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->audit, fs::path("/tmp/a.json"));
    EXPECT_TRUE(s->audit_junit.empty());
    s = parse(kOneNode, {}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->audit.empty());  // no audit unless asked for
}

TEST(ScenarioTest, ConnectTakesAHostName) {
    std::string error;
    const auto s = parse(kOneNode, {"--connect", "jmri.local:12021"}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_TRUE(s->connect);
    EXPECT_EQ(s->connect->host, "jmri.local");
    EXPECT_EQ(s->connect->port, 12021);
    std::string why;
    EXPECT_FALSE(parse(kOneNode, {"--connect", "host:0"}, why));
}

TEST(ScenarioTest, EveryTransportAtOnce) {
    std::string error;
    // Both listen and connect on the command line: a --connect alone replaces a file's listen.
    const auto s = parse(kOneNode,
                         {"--listen", "127.0.0.1:0", "--connect", "10.0.0.2:12021", "--socketcan",
                          "can0", "--serial", "/dev/ttyACM0"},
                         error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->listen);
    EXPECT_TRUE(s->connect);
    EXPECT_EQ(s->socketcan, "can0");
    EXPECT_EQ(s->serial, "/dev/ttyACM0");
}

// A vcan is faster than any CAN bus: on SocketCAN the segment keeps LCC's 125 kbit/s unless
// bitrate is given, in the file or on the command line (0 turns pacing off).
TEST(ScenarioTest, SocketCanPacesAtLccBitrateUnlessTold) {
    std::string error;
    auto s = parse(kOneNode, {"--socketcan", "vcan0"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->bitrate, 125000u);
    s = parse(kOneNode, {"--socketcan", "vcan0", "--bitrate", "0"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->bitrate, 0u);
    s = parse(std::string("bitrate = 250000\n") + kOneNode, {"--socketcan", "vcan0"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->bitrate, 250000u);
    s = parse(kOneNode, {"--listen", "127.0.0.1:0"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->bitrate, 0u);  // a TCP hub alone stays unpaced
}

TEST(ScenarioTest, CountMakesConsecutiveNodeIds) {
    std::string error;
    const auto s = parse(std::string(kOneNode) + "count = 3\n", {}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_EQ(s->nodes.size(), 3u);
    EXPECT_EQ(s->nodes[2].node_id.to_string(), "05.01.01.01.22.02");
}

// More nodes than a segment has aliases would contend for one for ever.
TEST(ScenarioTest, NodesPastTheAliasesOfASegmentAreRefused) {
    std::string error;
    const auto full = parse(std::string(kOneNode) + "count = 4095\n", {}, error);
    ASSERT_TRUE(full) << error;
    EXPECT_EQ(full->nodes.size(), 4095u);
    const std::string two_groups =
        "cdi = default.xml\n[node.first]\nnode-id = 05.01.01.01.00.00\ncount = 4000\n"
        "[node.more]\nnode-id = 05.01.01.02.00.00\ncount = 96\n";
    EXPECT_FALSE(parse(two_groups, {}, error));
    EXPECT_EQ(error,
              "[node.more]: 4096 nodes on one segment, more than its 4095 aliases (one per "
              "node)");
}

TEST(ScenarioTest, ControlBindsLoopbackUnlessToldOtherwise) {
    std::string error;
    auto s = parse(std::string(kOneNode) + "control = 12022\n", {}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_TRUE(s->control);
    EXPECT_EQ(*s->control, (HostPort{"127.0.0.1", 12022}));
    EXPECT_FALSE(s->control_remote);
    s = parse(kOneNode, {"--control", "[::1]:0"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_EQ(s->control->host, "::1");
    EXPECT_FALSE(parse(kOneNode, {"--control", "0.0.0.0:12022"}, error));
    EXPECT_EQ(error,
              "control: 0.0.0.0 is not a loopback address; give control-remote = true "
              "(--control-remote) to let other machines change the nodes");
    s = parse(kOneNode, {"--control", "0.0.0.0:12022", "--control-remote"}, error);
    ASSERT_TRUE(s) << error;
    EXPECT_TRUE(s->control_remote);
    EXPECT_FALSE(parse(kOneNode, {"--control", "localhost:1"}, error));
    EXPECT_EQ(error, "control: 'localhost' is not a numeric address");
    EXPECT_FALSE(parse(kOneNode, {"--control", "127.0.0.1:1", "--control-remote", "maybe"}, error));
    EXPECT_EQ(error, "control-remote 'maybe' must be true or false");
}

TEST(ScenarioTest, NodeGroupsAddedLaterFollowTheRunningScenario) {
    std::string error;
    const auto running =
        parse(std::string(kOneNode) + "image-dir = /tmp/imgs\nlatency = 30\n", {}, error);
    ASSERT_TRUE(running) << error;
    EXPECT_EQ(running->image_root, "/tmp/imgs");
    EXPECT_EQ(running->latency, "30");
    const std::string cdi = (scenarios_dir() / "default.xml").string();
    const std::vector<NodeKey> keys{{"node-id", {"05.01.01.01.22.10"}},
                                    {"count", {"2"}},
                                    {"cdi", {cdi}},
                                    {"fault", {"int-byte-order"}},
                                    {"user-name", {"N{n}"}}};
    const auto nodes = parse_node_group(keys, *running, error);
    ASSERT_TRUE(nodes) << error;
    ASSERT_EQ(nodes->size(), 2u);
    EXPECT_EQ((*nodes)[1].node_id, NodeId(0x05'01'01'01'22'11ull));
    EXPECT_EQ((*nodes)[1].image_dir, fs::path("/tmp/imgs/05.01.01.01.22.11"));
    EXPECT_EQ((*nodes)[1].user_name, "N2");
    EXPECT_EQ((*nodes)[0].faults.value("int-byte-order"), FaultValue{1});
    EXPECT_EQ((*nodes)[0].faults.value("latency"), FaultValue{30}) << "the process latency";
    const std::vector<NodeKey> bad{{"listen", {"1"}}};
    EXPECT_FALSE(parse_node_group(bad, *running, error));
    EXPECT_EQ(error, "'listen' is not a node key (see docs/scenarios.md)");
    const std::vector<NodeKey> no_cdi{{"node-id", {"05.01.01.01.22.10"}}};
    EXPECT_FALSE(parse_node_group(no_cdi, *running, error));
    EXPECT_EQ(error, "node: cdi is missing");
}

}  // namespace
}  // namespace olcb::simnode

namespace olcb::simnode {
namespace {

TEST(ScenarioTrainTest, TheTrainScenarioHasTwoTrainsWithTheirFdi) {
    std::string error;
    const auto s = parse_scenario_text(test_support::read_text(scenarios_dir() / "train.ini"),
                                       scenarios_dir(), {}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_EQ(s->nodes.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
        const NodeConfig& n = s->nodes[k];
        ASSERT_TRUE(n.train);
        EXPECT_EQ(n.train->identity.address, 1732 + k);
        EXPECT_TRUE(n.train->identity.long_address);
        EXPECT_EQ(n.train->heartbeat, 1);
        EXPECT_TRUE(n.train->fdi.starts_with("<?xml")) << n.train->fdi.substr(0, 20);
        EXPECT_FALSE(n.command_station);
    }
}

TEST(ScenarioTrainTest, TheCommandStationScenarioHasAStationAndATrain) {
    std::string error;
    const auto s =
        parse_scenario_text(test_support::read_text(scenarios_dir() / "command-station.ini"),
                            scenarios_dir(), {}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_EQ(s->nodes.size(), 2u);
    EXPECT_TRUE(s->nodes[0].command_station);
    EXPECT_FALSE(s->nodes[0].train);
    ASSERT_TRUE(s->nodes[1].train);
    EXPECT_EQ(s->nodes[1].train->identity.address, 3u);
    EXPECT_FALSE(s->nodes[1].train->identity.long_address);
}

TEST(ScenarioTrainTest, BadTrainKeysAreRefusedByName) {
    std::string error;
    const std::string node = "node-id = 05.01.01.01.22.00\ncdi = train.xml\n";
    EXPECT_FALSE(
        parse_scenario_text(node + "train-address = 1000000\n", scenarios_dir(), {}, error));
    EXPECT_EQ(error, "node: train-address '1000000' must be a whole number 0..999999");
    EXPECT_FALSE(parse_scenario_text(node + "train-address = 3\ntrain-protocol = mfx\n",
                                     scenarios_dir(), {}, error));
    EXPECT_EQ(error, "node: train-protocol 'mfx' must be dcc, dcc-long, dcc-short, native or mm");
    EXPECT_FALSE(parse_scenario_text(node + "heartbeat = 300\n", scenarios_dir(), {}, error));
    EXPECT_EQ(error, "node: heartbeat '300' must be 0..255 s");
    EXPECT_FALSE(parse_scenario_text(node + "train-address = 3\ncommand-station = true\n",
                                     scenarios_dir(), {}, error));
    EXPECT_NE(error.find("a command station is no train"), std::string::npos) << error;
    EXPECT_FALSE(parse_scenario_text(node + "train-address = 3\nfdi = nowhere.xml\n",
                                     scenarios_dir(), {}, error));
    EXPECT_NE(error.find("node: FDI file: "), std::string::npos) << error;
}

TEST(ScenarioClockTest, ClockKeysGiveEachNodeItsClocks) {
    std::string error;
    const auto s = parse_scenario_text(
        test_support::read_text(fs::path(OLCB_SOURCE_DIR) / "scenarios/clock.ini"),
        fs::path(OLCB_SOURCE_DIR) / "scenarios", {}, error);
    ASSERT_TRUE(s) << error;
    ASSERT_EQ(s->nodes.size(), 4u);
    ASSERT_EQ(s->nodes[0].clocks.size(), 1u);
    EXPECT_EQ(clock_config_text(s->nodes[0].clocks[0]),
              "generator default-fast rate=60.00 time=1955-07-04T06:00 running");
    EXPECT_EQ(s->nodes[1].clocks.size(), 2u);
    EXPECT_EQ(s->nodes[3].clocks.at(1).role, ClockRole::kConsumer);
    // The command line replaces the file's clocks; a bad one is refused by name.
    const auto over = parse(std::string(kOneNode) + "clock = generator\n",
                            {"--clock", "consumer alternate-2"}, error);
    ASSERT_TRUE(over) << error;
    ASSERT_EQ(over->nodes[0].clocks.size(), 1u);
    EXPECT_EQ(over->nodes[0].clocks[0].clock, broadcast_time::kAlternateClock2);
    EXPECT_FALSE(parse(std::string(kOneNode) + "clock = generator rate=fast\n", {}, error));
    EXPECT_NE(error.find("rate 'fast'"), std::string::npos) << error;
}

}  // namespace
}  // namespace olcb::simnode
