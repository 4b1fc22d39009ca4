// The programs as a user meets them from a shell: --version everywhere, a node's invalid UTF-8
// reported (not crashing the reports), errors that name their cause, progress lines in a log,
// and simnode's --trace - on standard output.
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <nlohmann/json.hpp>
#include <pugixml.hpp>
#include <regex>

#include "e2e/conform_util.hpp"

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH) && defined(LCC_CDI_PATH)

namespace olcb::e2e {
namespace {

constexpr const char* kNode = "05.01.01.01.22.00";

// The checks of the (only) node of a JSON report.
const nlohmann::json& node_checks(const nlohmann::json& root) {
    return root["nodes"].at(0)["checks"];
}

TEST(VersionE2e, EveryProgramPrintsItsNameAndVersion) {
    for (const auto& [program, name] :
         std::vector<std::pair<std::string, std::string>>{{SIMNODE_PATH, "simnode"},
                                                          {LCC_CONFORM_PATH, "lcc-conform"},
                                                          {LCC_CDI_PATH, "lcc-cdi"}}) {
        const auto [code, out] = run_program(program, {"--version"});
        EXPECT_EQ(code, 0) << name << ": " << out;
        EXPECT_TRUE(std::regex_match(out, std::regex(name + R"( [0-9]+\.[0-9]+\.[0-9]+\n)")))
            << name << ": \"" << out << "\"";
    }
}

// Space 251 holds it too: acdi.utf8 FAILs (CDI §5.1.4.3), snip.utf8 WARNs (only a TN says SNIP
// text is UTF-8).
TEST(UntrustedBytesE2e, AnInvalidUtf8UserNameFailsAcdiUtf8AndBothReportsAreWritten) {
    Simnode sim(source_path("scenarios/default.ini"), {"--user-name", "bad\xff\xfename"});
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    TempDir out("lcc-conform-e2e-utf8");
    const std::string json = (out.path() / "r.json").string();
    const std::string junit = (out.path() / "r.xml").string();
    const auto [code, text] = conform({"--connect", sim.connect(), "--node", kNode, "--read-only",
                                       "--json", json, "--junit", junit});
    EXPECT_EQ(code, 1) << text;
    EXPECT_NE(text.find("FAIL  acdi.utf8"), std::string::npos) << text;
    EXPECT_NE(text.find("WARN  snip.utf8"), std::string::npos) << text;
    // Shown replaced, with the raw bytes next to it; never raw on the terminal.
    EXPECT_NE(text.find("\"bad\xEF\xBF\xBD\xEF\xBF\xBDname\" (bytes 62 61 64 FF FE 6E 61 6D 65)"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find("bad\xff\xfe"), std::string::npos) << "raw bytes reached the terminal";

    const auto j = read_report(json);  // validated against docs/report.schema.json
    ASSERT_FALSE(j.is_discarded()) << "the JSON report does not parse:\n" << read_text(json);
    expect_valid_junit(junit);
    bool failed = false;
    for (const auto& c : node_checks(j))
        failed = failed || (c["id"] == "acdi.utf8" && c["status"] == "FAIL");
    EXPECT_TRUE(failed) << j.dump(2);

    pugi::xml_document doc;
    const auto parsed = doc.load_file(junit.c_str());
    ASSERT_TRUE(parsed) << "the JUnit report is not well-formed: " << parsed.description();
    bool junit_failed = false;
    for (const auto& tc : doc.select_nodes("//testcase[failure]"))
        junit_failed =
            junit_failed ||
            std::string(tc.node().attribute("name").value()).find("acdi.utf8") != std::string::npos;
    EXPECT_TRUE(junit_failed) << read_text(junit);
}

TEST(UntrustedBytesE2e, TheSnipInvalidUtf8FaultIsListedWithItsMeaning) {
    const auto [code, out] = run_program(SIMNODE_PATH, {"--list-faults"});
    EXPECT_EQ(code, 0);
    EXPECT_NE(out.find("snip-invalid-utf8"), std::string::npos) << out;
    EXPECT_NE(out.find("not UTF-8"), std::string::npos) << out;
}

TEST(ErrorsE2e, ARefusedConnectionSaysSo) {
    const std::string where = "127.0.0.1:" + std::to_string(closed_port());
    const auto [code, out] = run_merged(LCC_CONFORM_PATH, {"--connect", where});
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("cannot connect to " + where + ": connection refused"), std::string::npos)
        << out;
}

TEST(ErrorsE2e, AnUnknownHostSaysItIsNotFound) {
    const auto [code, out] = run_merged(LCC_CONFORM_PATH, {"--connect", "no-such-host.invalid:1"});
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("host no-such-host.invalid not found"), std::string::npos) << out;
}

TEST(ErrorsE2e, ANodeIdWithAShortLastByteIsAUsageError) {
    const auto [code, out] =
        run_merged(LCC_CONFORM_PATH, {"--connect", "127.0.0.1:1", "--node", "05.01.01.01.22.0"});
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("--node: byte 6 of node ID '05.01.01.01.22.0' has 1 hex digit; expected "
                       "exactly 2"),
              std::string::npos)
        << out;
    EXPECT_EQ(out.find("cannot connect"), std::string::npos) << "refused before connecting";
}

TEST(ErrorsE2e, AReportThatCannotBeWrittenSaysWhy) {
    const auto [code, out] = run_merged(
        LCC_CONFORM_PATH, {"--connect", "127.0.0.1:1", "--json", "/nonexistent-dir/r.json"});
    EXPECT_EQ(code, 2) << out;
    EXPECT_NE(out.find("/nonexistent-dir/r.json for writing: No such file or directory"),
              std::string::npos)
        << out;
}

TEST(ProgressE2e, WithoutATerminalEveryPhaseSaysHowLongItTook) {
    Simnode sim(source_path("scenarios/default.ini"));
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    const auto [code, out] =
        run_merged(LCC_CONFORM_PATH, {"--connect", sim.connect(), "--node", kNode, "--read-only"});
    EXPECT_EQ(code, 0) << out;
    const std::string prefix = std::string("lcc-conform: ") + kNode + " ";
    EXPECT_NE(out.find(prefix + "protocol checks...\n"), std::string::npos) << out;
    EXPECT_TRUE(
        std::regex_search(out, std::regex(prefix + R"(protocol checks done in [0-9]+\.[0-9] s)")))
        << out;
    EXPECT_TRUE(std::regex_search(out, std::regex(prefix + R"(done in [0-9]+\.[0-9] s)"))) << out;
    // What --read-only left out, with the option that tests it.
    EXPECT_NE(out.find("writes not tested"), std::string::npos) << out;
    EXPECT_NE(out.find(": add --thorough"), std::string::npos) << out;
}

TEST(TraceE2e, TraceDashWritesTheTrafficToStandardOutput) {
    Simnode sim(source_path("scenarios/default.ini"), {"--trace", "-"});
    ASSERT_NE(sim.port, 0) << "simnode did not start";
    const auto [code, out] = conform({"--connect", sim.connect(), "--list"});
    EXPECT_EQ(code, 0) << out;
    // A decoded Verify Node ID line: seconds, then the GridConnect frame.
    bool traced = false;
    for (int i = 0; i < 50 && !traced; ++i) {
        const auto line = sim.child->wait_line("", milliseconds(200));
        traced = line && line->find(":X19490") != std::string::npos;
    }
    EXPECT_TRUE(traced) << sim.child->output();
    EXPECT_FALSE(fs::exists(fs::path("-"))) << "a file named '-' was written";
}

}  // namespace
}  // namespace olcb::e2e

#endif  // SIMNODE_PATH && LCC_CONFORM_PATH && LCC_CDI_PATH
