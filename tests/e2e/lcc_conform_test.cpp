// lcc-conform as a user runs it, against the simnode program over GridConnect TCP: the default
// scenario passes, every fault scenario fails in the fault's category, the node's image files
// are untouched after a full and an interrupted run, and the JMRI backup/restore round trip.
#include <gtest/gtest.h>
#include <pugixml.hpp>

#include <algorithm>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <thread>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

namespace olcb::e2e {
namespace {

namespace fs = std::filesystem;
constexpr const char* kNode = "05.01.01.01.22.00";

TEST(LccConformE2e, DefaultScenarioPassesWithValidJsonAndJunit) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-out");
    const auto before = snapshot_images(sim.images.path());
    ASSERT_FALSE(before.empty()) << "simnode wrote no image files";
    const std::string json = (out.path() / "r.json").string();
    const std::string junit = (out.path() / "r.xml").string();
    const auto [code, text] =
        conform({"--connect", sim.connect(), "--node", kNode, "--backup",
                 (out.path() / "safety.txt").string(), "--json", json, "--junit", junit});
    EXPECT_EQ(code, 0) << text;
    const auto lines = check_lines(text);
    ASSERT_FALSE(lines.empty()) << text;
    for (const auto& [status, id] : lines) EXPECT_NE(status, "FAIL") << id;

    const auto j = read_report(json);
    ASSERT_FALSE(j.is_discarded()) << "JSON report does not parse";
    ASSERT_EQ(j["nodes"].size(), 1u);
    EXPECT_EQ(report_checks(j).size(), lines.size());
    EXPECT_EQ(j["run"]["summary"]["fail"], 0);
    EXPECT_EQ(j["run"]["exit_code"], 0);
    expect_valid_junit(junit);

    pugi::xml_document doc;
    const auto parsed = doc.load_file(junit.c_str());
    ASSERT_TRUE(parsed) << "JUnit XML not well-formed: " << parsed.description();
    std::size_t testcases = 0;
    for (auto tc : doc.select_nodes("//testcase")) {
        (void)tc;
        ++testcases;
    }
    EXPECT_EQ(testcases, lines.size());
    EXPECT_EQ(doc.select_nodes("//failure").size(), 0u);

    // Restore proven: the images are byte-identical after the full run.
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
}

TEST(LccConformE2e, SigintDuringEncodingChecksRestoresTheImages) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-out");
    const auto before = snapshot_images(sim.images.path());
    const fs::path backup = out.path() / "safety.txt";
    auto run = Child::spawn(LCC_CONFORM_PATH, {"--connect", sim.connect(), "--node", kNode,
                                               "--backup", backup.string()});
    ASSERT_TRUE(run);
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!fs::exists(backup) && std::chrono::steady_clock::now() < deadline &&
           !run->wait_for(milliseconds(2))) {
    }
    ASSERT_TRUE(fs::exists(backup)) << "the safety backup file never appeared";
    run->signal(SIGINT);
    ASSERT_TRUE(run->wait_for(milliseconds(30000))) << "lcc-conform did not stop after SIGINT";
    EXPECT_NE(run->wait(), 0) << "an interrupted run must not report success";
    EXPECT_EQ(settled_images(sim.images.path(), before), before);
}

TEST(LccConformE2e, ListShowsTheNodeWithItsSnipNames) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    const auto [code, text] = conform({"--connect", sim.connect(), "--list"});
    EXPECT_EQ(code, 0) << text;
    EXPECT_NE(text.find(kNode), std::string::npos) << text;
    EXPECT_NE(text.find("OpenLCB Tools"), std::string::npos) << text;
    EXPECT_NE(text.find("simnode default"), std::string::npos) << text;
}

TEST(LccConformE2e, JmriBackupRestoreRoundTripOverTcp) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-out");
    const std::string file = (out.path() / "config.txt").string();
    auto [code, text] = conform({"--connect", sim.connect(), "backup", "--node", kNode, file});
    ASSERT_EQ(code, 0) << text;
    const std::string saved = read_text(file);
    // OpenLCB_Java writes ints of 1, 2 and 4 bytes unsigned: -5 in 2 bytes is 65531.
    ASSERT_NE(saved.find("\nSettings.Trim=65531\n"), std::string::npos) << saved;
    ASSERT_NE(saved.find("\nNode identity.User Name=simnode default\n"), std::string::npos);

    // Change two values with a JMRI-format file (the whole backup with two lines edited: a
    // file matching under half of the node's keys is refused), then check the backup shows them.
    const std::string change = (out.path() / "change.txt").string();
    std::string edited = saved;
    for (const auto& [from, to] :
         {std::pair<std::string, std::string>{"\nSettings.Trim=65531\n", "\nSettings.Trim=7\n"},
          {"\nNode identity.User Name=simnode default\n",
           "\nNode identity.User Name=changed\\x003D\n"}}) {
        const auto at = edited.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        edited.replace(at, from.size(), to);
    }
    std::ofstream(change) << edited;
    std::tie(code, text) = conform({"--connect", sim.connect(), "restore", change});
    ASSERT_EQ(code, 0) << text;
    const std::string changed_file = (out.path() / "changed.txt").string();
    std::tie(code, text) =
        conform({"--connect", sim.connect(), "backup", "--node", kNode, changed_file});
    ASSERT_EQ(code, 0) << text;
    const std::string changed = read_text(changed_file);
    EXPECT_NE(changed.find("\nSettings.Trim=7\n"), std::string::npos) << changed;
    // Escapes are written as OpenLCB_Java writes them: lower-case hex (both cases are read).
    EXPECT_NE(changed.find("\nNode identity.User Name=changed\\x003d\n"), std::string::npos);

    // Restore the first backup: every value is back.
    std::tie(code, text) = conform({"--connect", sim.connect(), "restore", file});
    ASSERT_EQ(code, 0) << text;
    std::tie(code, text) =
        conform({"--connect", sim.connect(), "backup", "--node", kNode, changed_file});
    ASSERT_EQ(code, 0) << text;
    EXPECT_EQ(read_text(changed_file), saved);
}

// ---- fault x check matrix ----

/// What a fault's declaration (simnode/faults/) says lcc-conform must conclude.
struct FaultRow {
    std::string category;     ///< the check category that should flag it ("none": no check)
    bool breaks_rule = true;  ///< false when a careful client sees nothing wrong (exit 0)
    bool warn_only = false;   ///< verdict warn: flagged by a WARN, the run exits 0
    /// Verdict incomplete: the node stops or restarts mid-run, flagged in the category and the
    /// run is incomplete (checks not run): exit 2.
    bool incomplete = false;
};

/// Fault name -> its row, from the declarations as `simnode --list-faults=json` prints them.
std::map<std::string, FaultRow> fault_categories() {
    std::map<std::string, FaultRow> out;
    const auto [code, text] =
        run_program(SIMNODE_PATH, {"--list-faults=json"}, milliseconds(10000));
    const auto decls = nlohmann::json::parse(text, nullptr, false);
    if (code != 0 || !decls.is_array()) return out;
    for (const auto& d : decls) {
        const std::string verdict = d["verdict"];
        std::string cat = d["category"];
        if (cat.empty()) cat = "none";
        out[d["name"]] = {cat, verdict == "fail", verdict == "warn", verdict == "incomplete"};
    }
    return out;
}

/// The options a fault scenario's "# lcc-conform: ARGS" comment asks for (e.g. --thorough).
std::vector<std::string> scenario_conform_args(const fs::path& ini) {
    std::istringstream in(read_text(ini));
    std::vector<std::string> out;
    for (std::string line; std::getline(in, line);) {
        static const std::string kTag = "# lcc-conform:";
        if (!line.starts_with(kTag)) continue;
        std::istringstream words(line.substr(kTag.size()));
        for (std::string w; words >> w;) out.push_back(w);
    }
    return out;
}

/// The node ID of a scenario's (first) "node-id = ID" line: the node lcc-conform names.
std::string scenario_node(const fs::path& ini) {
    std::istringstream in(read_text(ini));
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("node-id")) continue;
        auto v = line.substr(line.find('=') + 1);
        v.erase(0, v.find_first_not_of(' '));
        return v.substr(0, v.find_first_of(" \t"));
    }
    return kNode;
}

/// The fault named by a scenario's "fault = NAME" line.
std::string scenario_fault(const fs::path& ini) {
    std::istringstream in(read_text(ini));
    for (std::string line; std::getline(in, line);) {
        if (!line.starts_with("fault")) continue;
        auto v = line.substr(line.find('=') + 1);
        v.erase(0, v.find_first_not_of(' '));
        return v.substr(0, v.find_first_of(" ,="));
    }
    return {};
}

std::vector<std::string> fault_scenarios() {
    std::vector<std::string> out;
    const fs::path dir = source_path("scenarios/faults");
    std::error_code ec;
    for (const auto& e : fs::directory_iterator(dir, ec)) {
        if (e.path().extension() == ".ini") out.push_back(e.path().stem().string());
    }
    std::sort(out.begin(), out.end());
    return out;
}

class LccConformFault : public ::testing::TestWithParam<std::string> {};

TEST_P(LccConformFault, ExitsOneWithAFailureInTheFaultsCategory) {
    const fs::path ini = source_path("scenarios/faults") / (GetParam() + ".ini");
    const std::string fault = scenario_fault(ini);
    ASSERT_FALSE(fault.empty()) << ini << " names no fault";
    const auto categories = fault_categories();
    const auto cat = categories.find(fault);
    ASSERT_NE(cat, categories.end()) << "simnode declares no fault " << fault;

    Simnode sim(ini);
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-out");
    const std::string json = (out.path() / "r.json").string();
    const std::string junit = (out.path() / "r.xml").string();
    std::vector<std::string> args = {"--connect", sim.connect(),
                                     "--node",    scenario_node(ini),
                                     "--backup",  (out.path() / "safety.txt").string(),
                                     "--json",    json,
                                     "--junit",   junit};
    // What a careful client copes with is also tried across a Reset/Reboot.
    if (fault == "write-not-persisted" || (!cat->second.breaks_rule && !cat->second.warn_only))
        args.push_back("--reboot");
    for (const std::string& a : scenario_conform_args(ini)) args.push_back(a);
    const auto before = snapshot_images(sim.images.path());
    // A slow node (latency=200:50) takes ~100 s for the whole run: every exchange waits 2 answers.
    const auto [code, text] = conform(args, milliseconds(180000));
    // Every fault's reports validate, whatever the node got wrong.
    expect_valid_junit(junit);
    EXPECT_EQ(test::json_report_errors(read_text(json)), "") << fault;
    // Whenever lcc-conform says it restored the node byte-identical, the image files agree.
    const auto lines = check_lines(text);
    if (std::find(lines.begin(), lines.end(),
                  std::pair<std::string, std::string>("PASS", "encoding.restore")) != lines.end()) {
        EXPECT_EQ(settled_images(sim.images.path(), before), before) << text;
    }
    if (cat->second.incomplete) {
        EXPECT_EQ(code, 2) << text;
        const auto j = read_report(json);
        ASSERT_FALSE(j.is_discarded()) << "no JSON report\n" << text;
        EXPECT_TRUE(j["nodes"][0]["incomplete"].get<bool>()) << text;
        bool flagged = false;
        for (const auto& c : report_checks(j))
            flagged = flagged || ((c["status"] == "FAIL" || c["status"] == "WARN") &&
                                  c["category"] == cat->second.category);
        EXPECT_TRUE(flagged) << "fault " << fault << ": nothing in " << cat->second.category << "\n"
                             << text;
        return;
    }
    if (cat->second.warn_only) {
        // An optional behaviour missing: reported as a WARN in its category, the run passes.
        EXPECT_EQ(code, 0) << text;
        const auto j = read_report(json);
        ASSERT_FALSE(j.is_discarded()) << "no JSON report\n" << text;
        bool warned = false;
        for (const auto& c : report_checks(j))
            warned = warned || (c["status"] == "WARN" && c["category"] == cat->second.category);
        EXPECT_TRUE(warned) << "fault " << fault << ": no WARN in " << cat->second.category << "\n"
                            << text;
        return;
    }
    if (!cat->second.breaks_rule) {
        // Nothing is wrong with such a node: a good client copes and every check passes.
        EXPECT_EQ(code, 0) << text;
        return;
    }
    EXPECT_EQ(code, 1) << text;
    const auto j = read_report(json);
    ASSERT_FALSE(j.is_discarded()) << "no JSON report\n" << text;
    std::vector<std::string> failing;
    bool found = false;
    for (const auto& c : report_checks(j)) {
        if (c["status"] != "FAIL") continue;
        failing.push_back(c["id"].get<std::string>() + " (" + c["category"].get<std::string>() +
                          ")");
        if (c["category"] == cat->second.category) found = true;
    }
    std::string list;
    for (const auto& f : failing) list += "\n  " + f;
    EXPECT_TRUE(found) << "fault " << fault << ": no FAIL in category " << cat->second.category
                       << "; failing:" << list;
}

INSTANTIATE_TEST_SUITE_P(Scenarios, LccConformFault, ::testing::ValuesIn(fault_scenarios()),
                         [](const auto& info) {
                             std::string name = info.param;
                             std::replace(name.begin(), name.end(), '-', '_');
                             return name;
                         });
GTEST_ALLOW_UNINSTANTIATED_PARAMETERIZED_TEST(LccConformFault);

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH
