// lcc-conform against scenarios/clock.ini over GridConnect TCP, as a user runs it: the fast clock
// master passes every generator check (the clock put back), a display every consumer check. The
// clock faults' own scenarios run in lcc_conform_test.cpp's fault matrix.
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

TEST(LccConformClockE2e, MasterAndDisplayPassTheirChecks) {
    Simnode sim(source_path("scenarios/clock.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    ASSERT_TRUE(sim.wait_initialized(milliseconds(10000)));
    TempDir out("lcc-conform-clock-e2e");
    const auto run = [&](const std::string& node, const std::string& name) {
        const fs::path json = out.path() / (name + ".json");
        const auto [code, text] = conform({"--connect", sim.connect(), "--node", node, "--only",
                                           "clock.*", "--reboot", "--json", json.string()},
                                          milliseconds(90000));
        EXPECT_EQ(code, 0) << text;
        EXPECT_EQ(test::json_report_errors(read_text(json)), "") << name;
        return std::make_pair(clock_statuses(json), text);
    };
    const auto [master, master_text] = run("05.01.01.01.22.00", "master");
    EXPECT_EQ(master.size(), 16u) << master_text;
    for (const auto& [id, status] : master) {
        const bool consumer = id.starts_with("clock.consumer-");
        EXPECT_EQ(status, consumer ? "SKIP" : "PASS") << id << "\n" << master_text;
    }
    const auto [display, display_text] = run("05.01.01.01.22.02", "display");
    for (const auto& [id, status] : display) {
        const bool consumer = id.starts_with("clock.consumer-");
        EXPECT_EQ(status, consumer ? "PASS" : "SKIP") << id << "\n" << display_text;
    }
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
