// lcc-conform against simnode's train scenarios as a user runs them: the train node passes every
// train, search and FDI check (those that move it too: the node is named), a whole run finds no
// FAIL anywhere, the command station creates the trains the search checks ask for, and trains and
// a clock answer side by side in one simnode.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

constexpr const char* kTrain = "05.01.01.01.22.60";
constexpr const char* kStation = "05.01.01.01.22.80";

// The JSON report's checks by ID.
std::map<std::string, std::string> statuses(const fs::path& json) {
    std::map<std::string, std::string> out;
    for (const auto& c : report_checks(read_report(json.string())))
        out[c["id"].get<std::string>()] = c["status"].get<std::string>();
    return out;
}

TEST(LccConformTrainE2e, TheTrainPassesEveryTrainSearchAndFdiCheck) {
    Simnode sim(source_path("scenarios/train.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-train");
    const fs::path json = out.path() / "r.json";
    const auto [code, text] = conform(
        {"--connect", sim.connect(), "--node", kTrain, "--train-address", "1732", "--thorough",
         "--only", "train.*", "--only", "search.*", "--only", "fdi.*", "--json", json.string()});
    EXPECT_EQ(code, 0) << text;
    const auto s = statuses(json);
    for (const char* id : {"train.is-train-event",
                           "train.memory-spaces",
                           "train.controller",
                           "train.reserve",
                           "train.speed",
                           "train.function",
                           "train.function-space",
                           "train.estop",
                           "train.global-estop",
                           "train.global-eoff",
                           "train.listener",
                           "train.listener-forward",
                           "train.heartbeat",
                           "search.name-match",
                           "search.address-match",
                           "search.no-match-silent",
                           "search.reserved-ignored",
                           "fdi.space",
                           "fdi.read",
                           "fdi.no-bom",
                           "fdi.utf8",
                           "fdi.xml-declaration",
                           "fdi.well-formed",
                           "fdi.valid",
                           "fdi.schema-location",
                           "fdi.functions",
                           "fdi.read-only"}) {
        const auto it = s.find(id);
        ASSERT_NE(it, s.end()) << id << "\n" << text;
        EXPECT_EQ(it->second, "PASS") << id << "\n" << text;
    }
}

TEST(LccConformTrainE2e, AWholeRunOfTheTrainFindsNoFailure) {
    Simnode sim(source_path("scenarios/train.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-train");
    const auto before = snapshot_images(sim.images.path());
    // The train families are the test above's: the rest of the run, judged as a train node.
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--node", kTrain, "--skip", "train.*", "--skip",
                 "search.*", "--skip", "fdi.*", "--backup", (out.path() / "safety.txt").string()},
                milliseconds(120000));
    EXPECT_EQ(code, 0) << text;
    for (const auto& [status, id] : check_lines(text)) EXPECT_NE(status, "FAIL") << id;
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
}

TEST(LccConformTrainE2e, TheCommandStationCreatesTheTrainsTheSearchChecksAskFor) {
    Simnode sim(source_path("scenarios/command-station.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-station");
    const fs::path json = out.path() / "r.json";
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--node", kStation, "--command-station", "--only",
                 "search.*", "--json", json.string()});
    EXPECT_EQ(code, 0) << text;
    const auto s = statuses(json);
    for (const char* id :
         {"search.allocate", "search.allocate-partial", "search.allocate-reserved"})
        EXPECT_EQ(s.count(id) ? s.at(id) : "missing", "PASS") << id << "\n" << text;
    // The trains it created are on the segment now, besides the station and its locomotive.
    const auto [list_code, list] = conform({"--connect", sim.connect(), "--list"});
    EXPECT_EQ(list_code, 0) << list;
    EXPECT_NE(list.find("05.01.01.01.22.81"), std::string::npos) << list;
    EXPECT_NE(list.find("DCC 7301"), std::string::npos) << list;
}

// scenarios/layout.ini: trains, a command station and a clock in one simnode; each answers as
// in its own scenario, beside the others.
TEST(LccConformTrainE2e, TrainsAndAClockShareOneProcess) {
    Simnode sim(source_path("scenarios/layout.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    ASSERT_TRUE(sim.wait_initialized(milliseconds(10000)));
    const auto [list_code, list] = conform({"--connect", sim.connect(), "--list"});
    EXPECT_EQ(list_code, 0) << list;
    for (const char* id : {"05.01.01.01.22.00", "05.01.01.01.22.02", "05.01.01.01.22.80",
                           "05.01.01.01.22.A0", "05.01.01.01.22.A1"})
        EXPECT_NE(list.find(id), std::string::npos) << id << "\n" << list;
    TempDir out("lcc-conform-e2e-layout");
    const fs::path train_json = out.path() / "train.json";
    const auto [train_code, train_text] =
        conform({"--connect", sim.connect(), "--node", "05.01.01.01.22.A1", "--train-address",
                 "1732", "--only", "train.controller", "--only", "train.speed", "--only",
                 "search.address-match", "--json", train_json.string()});
    EXPECT_EQ(train_code, 0) << train_text;
    const auto trains = statuses(train_json);
    for (const char* id : {"train.controller", "train.speed", "search.address-match"})
        EXPECT_EQ(trains.count(id) ? trains.at(id) : "missing", "PASS") << id << "\n" << train_text;
    const fs::path clock_json = out.path() / "clock.json";
    const auto [clock_code, clock_text] =
        conform({"--connect", sim.connect(), "--node", "05.01.01.01.22.00", "--only", "clock.query",
                 "--only", "clock.set-immediate", "--only", "clock.restored", "--json",
                 clock_json.string()});
    EXPECT_EQ(clock_code, 0) << clock_text;
    const auto clocks = statuses(clock_json);
    for (const char* id : {"clock.query", "clock.set-immediate", "clock.restored"})
        EXPECT_EQ(clocks.count(id) ? clocks.at(id) : "missing", "PASS") << id << "\n" << clock_text;
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
