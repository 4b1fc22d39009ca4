// lcc-conform on busy, slow and shared segments, as a user runs it: every node is found (also one
// that logs in when the tool connects, and 1,000 of them on a loaded machine), a slow node and a
// node among 1,000 get no false failure, concurrent runs leave each other alone, and every exit,
// 2 included, writes valid JSON and JUnit reports.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>
#include <pugixml.hpp>

#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>
#include <thread>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

std::size_t lines_with(const std::string& text, const std::string& prefix) {
    std::size_t n = 0;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) n += line.starts_with(prefix) ? 1 : 0;
    return n;
}

std::string failures(const std::string& text) {
    std::string out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) {
        if (line.starts_with("FAIL")) out += "\n  " + line;
    }
    return out;
}

TEST(LccConformDiscovery, ANodeThatLogsInWhenTheToolConnectsIsFoundEveryTime) {
    Simnode sim(source_path("scenarios/default.ini"), {"--start-on-connect"});
    ASSERT_NE(sim.port, 0);
    int found = 0;
    for (int i = 0; i < 20; ++i) {
        const auto [code, text] = conform({"--connect", sim.connect(), "--list"});
        if (code == 0 && text.find(kNode) != std::string::npos) ++found;
    }
    EXPECT_EQ(found, 20);
}

// One simnode of 1,000 nodes for both (their fresh images take a while: an fsync each). The
// frame probe's global AME gets 999 other AMDs before the node's own answers; on a loaded machine
// they took longer than one answer window (tests/conformance/checks/frame_test.cpp has the same
// on a bus paced at 125 kbit/s, simulated).
TEST(LccConformDiscovery, AThousandNodesAreListedOnALoadedMachineAndOneHasNoFalseFailure) {
    Simnode sim(source_path("scenarios/network-1000.ini"), {}, milliseconds(120000));
    ASSERT_NE(sim.port, 0);
    ASSERT_TRUE(sim.wait_initialized(milliseconds(120000)));
    // Two busy loops, one per core, bounded in time whatever happens to the test.
    std::vector<std::unique_ptr<Child>> load;
    load.reserve(2);
    for (int i = 0; i < 2; ++i) {
        // The shell itself loops (a SIGKILL ends it) and stops by itself after a bounded count.
        load.push_back(Child::spawn(
            "/bin/sh", {"-c", "i=0; while [ $i -lt 100000000 ]; do i=$((i + 1)); done"}));
    }
    const auto [code, text] = conform({"--connect", sim.connect(), "--list"}, milliseconds(60000));
    for (auto& l : load) l->signal(SIGKILL);
    EXPECT_EQ(code, 0) << text.substr(0, 400);
    EXPECT_EQ(lines_with(text, "05.01.01.01."), 1000u);

    const auto [one, report] =
        conform({"--connect", sim.connect(), "--node", "05.01.01.01.30.00", "--read-only"},
                milliseconds(60000));
    EXPECT_EQ(one, 0) << failures(report);
    // With --node the rest of the segment is not news, though all of it answered the AME.
    EXPECT_EQ(report.find("appeared during the run"), std::string::npos) << report.substr(0, 400);
}

TEST(LccConformDiscovery, ASlowNodeHasNoFalseFailure) {
    Simnode sim(source_path("scenarios/one-line.ini"), {"--latency", "300"});
    ASSERT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    const auto before = snapshot_images(sim.images.path());
    const auto [code, text] = conform(
        {"--connect", sim.connect(), "--node", kNode, "--backup", (out.path() / "b.txt").string()},
        milliseconds(240000));
    EXPECT_EQ(code, 0) << failures(text);
    EXPECT_NE(text.find("timing: latency 3"), std::string::npos) << text.substr(0, 300);
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
}

TEST(LccConformDiscovery, FourConcurrentReadOnlyRunsAllPass) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0);
    std::vector<std::unique_ptr<Child>> runs;
    for (int i = 0; i < 4; ++i) {
        runs.push_back(Child::spawn(LCC_CONFORM_PATH,
                                    {"--connect", sim.connect(), "--node", kNode, "--read-only"}));
        ASSERT_TRUE(runs.back());
    }
    for (auto& r : runs) {
        r->wait_line("\x01never", milliseconds(60000));
        ASSERT_TRUE(r->wait_for(milliseconds(60000)));
        EXPECT_EQ(r->wait(), 0) << failures(r->output());
    }
}

// Four runs without --node (two CI jobs, a developer and CI): each checks the one simnode node and
// lists the other runs' tool nodes as lcc-conform runs; none checks another (that gave 11-12
// FAILs each and timeouts).
TEST(LccConformDiscovery, FourConcurrentRunsWithoutNodeCheckTheNodeAndNotEachOther) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    std::vector<std::unique_ptr<Child>> runs;
    for (int i = 0; i < 4; ++i) {
        runs.push_back(Child::spawn(LCC_CONFORM_PATH,
                                    {"--connect", sim.connect(), "--read-only", "--json",
                                     (out.path() / ("r" + std::to_string(i) + ".json")).string()}));
        ASSERT_TRUE(runs.back());
        // Later runs start while the earlier ones are on the segment.
        std::this_thread::sleep_for(std::chrono::milliseconds(300));
    }
    std::size_t listed = 0;
    for (int i = 0; i < 4; ++i) {
        runs[i]->wait_line("\x01never", milliseconds(90000));
        ASSERT_TRUE(runs[i]->wait_for(milliseconds(90000)));
        EXPECT_EQ(runs[i]->wait(), 0) << failures(runs[i]->output()) << runs[i]->output();
        const auto j = read_report(out.path() / ("r" + std::to_string(i) + ".json"));
        ASSERT_EQ(j["nodes"].size(), 1u) << runs[i]->output();
        EXPECT_EQ(j["nodes"][0]["id"], kNode);
        for (const auto& id : j["run"]["other_runs"])
            EXPECT_TRUE(id.get<std::string>().starts_with("05.01.01.01.3F.")) << id;
        listed += j["run"]["other_runs"].size();
        EXPECT_EQ(runs[i]->output().find("05.01.01.01.3F.") != std::string::npos,
                  !j["run"]["other_runs"].empty());
    }
    EXPECT_GT(listed, 0u) << "the runs saw each other";
}

// A node that is no configurable node (a throttle) on the segment gets the protocol checks a node
// of any kind owes, no FAIL, and a line saying why it got no more.
TEST(LccConformDiscovery, ANonConfigurableNodeGetsTheShortCheckAndNoFailure) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    TempDir images("lcc-conform-discovery-throttle");
    auto throttle = Child::spawn(
        SIMNODE_PATH, {"--scenario", source_path("scenarios/throttle.ini").string(), "--connect",
                       sim.connect(), "--image-dir", images.str(), "--run-for", "120"});
    ASSERT_TRUE(throttle);
    ASSERT_TRUE(throttle->wait_line("simnode: 1 node(s) initialized", milliseconds(10000)));
    const std::string json = (out.path() / "r.json").string();
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--read-only", "--json", json}, milliseconds(90000));
    EXPECT_EQ(code, 0) << failures(text) << text;
    EXPECT_NE(text.find("not a configurable node (its PIP has neither Memory Configuration nor "
                        "CDI): checked for frame, message, SNIP, PIP, events, train, train search "
                        "and FDI only"),
              std::string::npos)
        << text;
    EXPECT_NE(text.find("summary of 2 node(s):"), std::string::npos) << text;
    const auto j = read_report(json);
    ASSERT_EQ(j["nodes"].size(), 2u);
    const auto& t = j["nodes"][1];
    EXPECT_EQ(t["id"], "05.01.01.01.22.40");
    EXPECT_TRUE(t["scope"].get<std::string>().starts_with("protocol only")) << t["scope"];
    for (const auto& c : t["checks"]) {
        const std::string cat = c["category"];
        // A throttle claims no Traction Control and identifies no clock: the train and clock
        // families are listed, never run.
        if (cat == "train" || cat == "search" || cat == "fdi" || cat == "clock") {
            EXPECT_EQ(c["status"], "SKIP") << c["id"] << ": " << c["message"];
            continue;
        }
        EXPECT_TRUE(cat == "frame" || cat == "message" || cat == "snip" || cat == "pip" ||
                    cat == "events")
            << c["id"];
        EXPECT_NE(c["status"], "FAIL") << c["id"] << ": " << c["message"];
    }
}

// Pairs of encoding-only runs started together against the scenario's node (only the writes and
// the restore, so the two runs' write phases meet): every pair must exit `code` (nullopt: any)
// and leave the node's images identical. Returns the runs' output.
std::string concurrent_pairs(const std::string& scenario, int pairs, std::optional<int> code) {
    Simnode sim(source_path(scenario));
    EXPECT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    const auto before = snapshot_images(sim.images.path());
    std::string all;
    for (int pair = 0; pair < pairs; ++pair) {
        std::vector<std::unique_ptr<Child>> runs;
        for (int i = 0; i < 2; ++i) {
            runs.push_back(Child::spawn(
                LCC_CONFORM_PATH,
                {"--connect", sim.connect(), "--node", kNode, "--only", "encoding.*", "--backup",
                 (out.path() / ("b" + std::to_string(i) + ".txt")).string()}));
            if (!runs.back()) return "spawn failed";
        }
        for (auto& r : runs) {
            r->wait_line("\x01never", milliseconds(60000));
            EXPECT_TRUE(r->wait_for(milliseconds(60000)));
            const int status = r->wait();
            if (code) EXPECT_EQ(status, *code) << failures(r->output());
            all += r->output();
        }
        EXPECT_EQ(settled_images(sim.images.path(), before), before);
    }
    return all;
}

// Whether the write phases overlap is a race: three pairs; at least one run must find the
// other's lock.
TEST(LccConformDiscovery, TwoConcurrentWritersLeaveTheNodeIdenticalAndOneFindsTheLock) {
    const std::string all = concurrent_pairs("scenarios/default.ini", 3, std::nullopt);
    EXPECT_NE(all.find("locked by 05.01.01.01.3F."), std::string::npos) << all;
    // The run without the lock wrote nothing, so its restore must not write either: it once put
    // back its saved User Description over the holder's test value, and the holder FAILed
    // encoding.string on reading back the old first byte.
    EXPECT_EQ(all.find("FAIL  encoding."), std::string::npos) << all;
}

// A node without Lock/Reserve (OpenMRN on Linux rejects it) keeps no two writers apart: each run
// read the other's test values back as the node's failures and saved them as the values to
// restore (a User Name left changed). A run that sees another on the segment writes nothing.
TEST(LccConformDiscovery, TwoConcurrentRunsOnANodeWithoutLockWriteNothing) {
    const std::string all = concurrent_pairs("scenarios/faults/lock-rejected.ini", 2, 0);
    EXPECT_EQ(all.find("FAIL  encoding."), std::string::npos) << all;
    EXPECT_NE(all.find("and the node has no Lock/Reserve to keep two writers apart"),
              std::string::npos)
        << all;
}

// A whole --thorough --reboot run on a bus paced at CAN speed: the windows wait for the frames
// queued ahead (2,047 standard frames take seconds at 125 kbit/s), so every check runs and none
// is skipped for a node that only seemed silent (29-30 were, and the run still exited 0).
void expect_every_check_runs_at_can_speed(const std::string& scenario, const std::string& node) {
    Simnode sim(source_path(scenario), {"--bitrate", "125000"});
    ASSERT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    const std::string json = (out.path() / "r.json").string();
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--node", node, "--thorough", "--reboot", "--json",
                 json, "--backup", (out.path() / "b.txt").string()},
                milliseconds(180000));
    EXPECT_EQ(code, 0) << failures(text) << text;
    EXPECT_EQ(text.find("stopped answering"), std::string::npos) << text;
    const auto j = read_report(json);
    ASSERT_EQ(j["nodes"].size(), 1u) << text;
    EXPECT_FALSE(j["nodes"][0]["incomplete"].get<bool>()) << text;
    EXPECT_EQ(j["nodes"][0]["summary"]["fail"], 0) << text;
}

TEST(LccConformDiscovery, AtCanSpeedEveryCheckOfTheDefaultNodeRuns) {
    expect_every_check_runs_at_can_speed("scenarios/default.ini", kNode);
}

TEST(LccConformDiscovery, AtCanSpeedEveryCheckOfTheIoBoardRuns) {
    expect_every_check_runs_at_can_speed("scenarios/io-board.ini", "05.01.01.01.22.10");
}

// A node that really goes silent (it dies on a user name it accepted, abort-on-value): the checks
// it missed make the run incomplete, exit >= 1, never a green run.
TEST(LccConformDiscovery, ANodeThatReallyGoesSilentMakesTheRunIncomplete) {
    Simnode sim(source_path("scenarios/dies-on-user-name.ini"), {"--bitrate", "125000"});
    ASSERT_NE(sim.port, 0);
    TempDir out("lcc-conform-discovery");
    const std::string json = (out.path() / "r.json").string();
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--node", kNode, "--write-protected", "--node-wait",
                 "2", "--json", json, "--backup", (out.path() / "b.txt").string()},
                milliseconds(180000));
    EXPECT_GE(code, 1) << text;
    const auto j = read_report(json);
    ASSERT_EQ(j["nodes"].size(), 1u) << text;
    EXPECT_TRUE(j["nodes"][0]["incomplete"].get<bool>()) << text;
    EXPECT_FALSE(j["nodes"][0]["incomplete_reasons"].empty()) << text;
}

// Valid JSON with an "error", and JUnit whose <error> names it.
void expect_reports_name(const fs::path& json, const fs::path& junit, const std::string& why) {
    const auto j = read_report(json);
    ASSERT_FALSE(j.is_discarded()) << read_text(json);
    EXPECT_EQ(j["run"]["exit_code"], 2);
    EXPECT_NE(j["run"]["error"].get<std::string>().find(why), std::string::npos) << j.dump();
    expect_valid_junit(junit);
    pugi::xml_document doc;
    ASSERT_TRUE(doc.load_file(junit.c_str()));
    auto error = doc.select_node("//testcase/error");
    ASSERT_TRUE(error);
    EXPECT_NE(std::string(error.node().attribute("message").value()).find(why), std::string::npos);
}

std::pair<int, std::string> conform_with_reports(const TempDir& out,
                                                 std::vector<std::string> args) {
    args.insert(args.end(), {"--json", (out.path() / "r.json").string(), "--junit",
                             (out.path() / "r.xml").string(), "--discover", "1"});
    return conform(args);
}

TEST(LccConformDiscovery, ExitTwoStillWritesBothReports) {
    TempDir out("lcc-conform-discovery");
    // Connection refused: a port that was free a moment ago.
    int fd = ::socket(AF_INET, SOCK_STREAM, 0);
    sockaddr_in addr{};
    addr.sin_family = AF_INET;
    addr.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
    ASSERT_EQ(::bind(fd, reinterpret_cast<sockaddr*>(&addr), sizeof addr), 0);
    socklen_t len = sizeof addr;
    ::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len);
    const std::string refused = "127.0.0.1:" + std::to_string(ntohs(addr.sin_port));
    auto [code, text] = conform_with_reports(out, {"--connect", refused});
    EXPECT_EQ(code, 2);
    expect_reports_name(out.path() / "r.json", out.path() / "r.xml", "127.0.0.1");

    // An empty hub: it accepts the connection and nothing ever answers.
    ASSERT_EQ(::listen(fd, 4), 0);
    std::tie(code, text) = conform_with_reports(out, {"--connect", refused});
    EXPECT_EQ(code, 2);
    expect_reports_name(out.path() / "r.json", out.path() / "r.xml", "no node answered");
    ::close(fd);

    // A node ID nobody has.
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0);
    std::tie(code, text) =
        conform_with_reports(out, {"--connect", sim.connect(), "--node", "05.01.01.01.99.99"});
    EXPECT_EQ(code, 2);
    expect_reports_name(out.path() / "r.json", out.path() / "r.xml", "does not answer");
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
