// lcc-conform against scenarios/clock.ini over GridConnect TCP, as a user runs it: the fast clock
// master passes every generator check (the clock put back), a display every consumer check. The
// master's checks run in two selections, the Set exchange's and the run through midnight's, each
// under 10 s (clock.restored and clock.report-frequency judge the session each made). The clock
// faults' own scenarios run in lcc_conform_test.cpp's fault matrix.
#include <gtest/gtest.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;

constexpr const char* kMaster = "05.01.01.01.22.00";
constexpr const char* kDisplay = "05.01.01.01.22.02";

// The statuses of the clock.* checks of a JSON report, by check ID.
std::map<std::string, std::string> clock_statuses(const fs::path& json) {
    std::map<std::string, std::string> out;
    const auto report = read_report(json);
    for (const auto& c : report_checks(report)) {
        const std::string id = c["id"];
        if (id.starts_with("clock.")) out[id] = c["status"];
    }
    return out;
}

// lcc-conform --node node --only each of `only` (and --reboot) on a fresh clock.ini: the clock
// checks' statuses and the text.
std::pair<std::map<std::string, std::string>, std::string> run_clock(
    const std::string& node, const std::vector<std::string>& only) {
    Simnode sim(source_path("scenarios/clock.ini"));
    EXPECT_NE(sim.port, 0) << "simnode did not start";
    EXPECT_TRUE(sim.wait_initialized(milliseconds(10000)));
    TempDir out("lcc-conform-clock-e2e");
    const fs::path json = out.path() / "r.json";
    std::vector<std::string> args = {"--connect", sim.connect(), "--node",     node,
                                     "--reboot",  "--json",      json.string()};
    for (const std::string& o : only) {
        args.push_back("--only");
        args.push_back(o);
    }
    const auto [code, text] = conform(args, milliseconds(30000));
    EXPECT_EQ(code, 0) << text;
    EXPECT_EQ(test::json_report_errors(read_text(json)), "") << text;
    return {clock_statuses(json), text};
}

void expect_all_pass(const std::map<std::string, std::string>& got,
                     const std::vector<std::string>& ids, const std::string& text) {
    EXPECT_EQ(got.size(), ids.size()) << text;
    for (const std::string& id : ids) {
        const auto it = got.find(id);
        ASSERT_NE(it, got.end()) << id << "\n" << text;
        EXPECT_EQ(it->second, "PASS") << id << "\n" << text;
    }
}

TEST(LccConformClockE2e, MasterPassesTheQueryAndSetChecks) {
    const std::vector<std::string> ids = {
        "clock.identify-ranges",  "clock.query",    "clock.set-immediate",
        "clock.set-sync",         "clock.set-once", "clock.set-effective",
        "clock.report-frequency", "clock.startup",  "clock.restored"};
    const auto [got, text] = run_clock(kMaster, ids);
    expect_all_pass(got, ids, text);
}

TEST(LccConformClockE2e, MasterPassesTheRunThroughMidnight) {
    const std::vector<std::string> ids = {"clock.requested-minute", "clock.report-frequency",
                                          "clock.rate", "clock.rollover", "clock.restored"};
    const auto [got, text] = run_clock(kMaster, ids);
    expect_all_pass(got, ids, text);
}

TEST(LccConformClockE2e, DisplayPassesTheConsumerChecks) {
    const auto [got, text] = run_clock(kDisplay, {"clock.*"});
    EXPECT_EQ(got.size(), 16u) << text;
    for (const auto& [id, status] : got) {
        const bool consumer = id.starts_with("clock.consumer-");
        EXPECT_EQ(status, consumer ? "PASS" : "SKIP") << id << "\n" << text;
    }
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
