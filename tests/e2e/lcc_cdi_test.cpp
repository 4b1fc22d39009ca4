// Black-box tests of the lcc-cdi program: exit codes, output formats, the shipped sample CDI.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "e2e/conform_util.hpp"
#include "support/run_shell.hpp"

namespace {

using RunResult = olcb::test_support::ShellResult;

// Runs lcc-cdi with `args` (shell-quoted by the caller); captures stdout and, when asked, stderr.
RunResult lcc_cdi(const std::string& args, bool merge_stderr = false) {
    return olcb::test_support::run_shell(std::string(LCC_CDI_PATH) + " " + args +
                                         (merge_stderr ? " 2>&1" : " 2>/dev/null"));
}

const std::string kDefault = std::string(OLCB_SOURCE_DIR) + "/scenarios/default.xml";

std::string temp_file(const std::string& name, const std::string& content) {
    auto path = std::filesystem::temp_directory_path() / ("lcc_cdi_test_" + name);
    std::ofstream(path, std::ios::binary) << content;
    return path.string();
}

TEST(LccCdi, ValidateSampleIsOk) {
    RunResult r = lcc_cdi("validate " + kDefault);
    EXPECT_EQ(r.status, 0);
    EXPECT_EQ(r.out, kDefault + ": ok\n");
}

TEST(LccCdi, ValidateReportsFileLineAndExitsOne) {
    std::string bad = temp_file("bad_int.xml",
                                "<?xml version=\"1.0\"?>\n<cdi>\n<segment space=\"253\">\n"
                                "<int size=\"3\"><name>Odd</name></int>\n</segment>\n</cdi>\n");
    RunResult r = lcc_cdi("validate " + kDefault + " " + bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.out.find(kDefault + ": ok\n"), std::string::npos);
    EXPECT_NE(r.out.find(bad + ":4: error: "), std::string::npos) << r.out;
}

TEST(LccCdi, UsageErrorsExitTwo) {
    EXPECT_EQ(lcc_cdi("").status, 2);
    EXPECT_EQ(lcc_cdi("frobnicate x.xml").status, 2);
    EXPECT_EQ(lcc_cdi("validate").status, 2);
    EXPECT_EQ(lcc_cdi("validate --no-such-option " + kDefault).status, 2);
    EXPECT_EQ(lcc_cdi("layout a.xml b.xml").status, 2);
}

TEST(LccCdi, HelpEverywhere) {
    for (const char* cmd : {"--help", "validate --help", "layout --help", "render --help"}) {
        RunResult r = lcc_cdi(cmd);
        EXPECT_EQ(r.status, 0) << cmd;
        EXPECT_NE(r.out.find("usage"), std::string::npos) << cmd;
    }
}

TEST(LccCdi, LayoutJsonOfSample) {
    RunResult r = lcc_cdi("layout --json " + kDefault);
    ASSERT_EQ(r.status, 0);
    auto json = nlohmann::json::parse(r.out);
    const auto& vars = json.at("variables");
    ASSERT_EQ(vars.size(), 28U);
    // space 251 (ACDI user data as a segment at origin 1)
    EXPECT_EQ(vars[0]["space"], 251);
    EXPECT_EQ(vars[0]["address"], 1);
    EXPECT_EQ(vars[0]["size"], 63);
    EXPECT_EQ(vars[1]["address"], 64);
    // space 253: Enabled@0, Trim@1 (signed), Delay@3, Counter@7, Mode@15, floats, Label@30
    EXPECT_EQ(vars[2]["type"], "int");
    EXPECT_EQ(vars[3]["address"], 1);
    EXPECT_EQ(vars[3]["signed"], true);
    EXPECT_EQ(vars[3]["min"], -1000);
    EXPECT_EQ(vars[5]["address"], 7);
    EXPECT_EQ(vars[5]["size"], 8);
    EXPECT_EQ(vars[7]["type"], "float");
    EXPECT_EQ(vars[7]["address"], 16);
    EXPECT_EQ(vars[10]["address"], 30);
    // Port group: 4 replicas of 33 bytes from 46; the last replica's Output at 46 + 3*33 + 32.
    EXPECT_EQ(vars[11]["address"], 46);
    EXPECT_EQ(vars[26]["address"], 46 + 3 * 33 + 32);
    EXPECT_EQ(vars[26]["name"], "Settings.Port(3).Output");
    EXPECT_EQ(vars[26]["replica"], "Port 4");
    EXPECT_FALSE(vars[0].contains("replica"));  // only where the CDI names the replica
    EXPECT_EQ(vars[27]["type"], "action");
    EXPECT_EQ(vars[27]["address"], 178);
    EXPECT_EQ(vars[2]["map"].size(), 2U);
}

TEST(LccCdi, LayoutTextOneLinePerVariable) {
    RunResult r = lcc_cdi("layout " + kDefault);
    ASSERT_EQ(r.status, 0);
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 28);
    EXPECT_NE(r.out.find("space 253\taddress 178\tsize 1"), std::string::npos) << r.out;
    // Named as its backup key; the CDI's replica name beside it, not in it.
    EXPECT_NE(r.out.find("\nSettings.Port(0).Port name\tstring\tspace 253\taddress 46\tsize 16"
                         "\treplica Port 1\n"),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("\nSettings.Trim\tint\tspace 253\taddress 1\tsize 2\tsigned"),
              std::string::npos)
        << r.out;
}

TEST(LccCdi, RenderShowsTree) {
    RunResult r = lcc_cdi("render " + kDefault);
    ASSERT_EQ(r.status, 0);
    EXPECT_NE(r.out.find("manufacturer: OpenLCB Tools"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("group \"Port\" x4, stride 33 bytes"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("@0x00000001 int(2) \"Trim\" signed min -1000"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("hints: checkbox"), std::string::npos) << r.out;
}

TEST(LccCdi, LayoutRefusesBrokenXml) {
    std::string bad =
        temp_file("broken.xml", "<?xml version=\"1.0\"?>\n<cdi><segment space=\"253\">\n");
    RunResult r = lcc_cdi("layout " + bad, true);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.out.find(bad + ":"), std::string::npos) << r.out;
}

// The default CDI with its first line replaced by `first` ("": no declaration at all).
std::string default_with_first_line(const std::string& first) {
    std::ifstream in(kDefault, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string rest = text.str().substr(text.str().find('\n') + 1);
    return first.empty() ? rest : first + "\n" + rest;
}

// The FAIL and WARN findings of `lcc-cdi validate` ("FILE[:LINE]: STATUS ID: message"), by ID.
std::map<std::string, std::string> validate_findings(const std::string& out) {
    static const std::regex finding_line(R"(^.*?(?::\d+)?: (FAIL|WARN) (cdi\.[a-z0-9.-]+): )");
    std::map<std::string, std::string> found;
    std::istringstream in(out);
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_search(line, m, finding_line)) found[m[2]] = m[1];
    }
    return found;
}

TEST(LccCdi, ValidateSaysWhatLccConformsCdiChecksSay) {
    const std::string none = temp_file("no_declaration.xml", default_with_first_line(""));
    RunResult r = lcc_cdi("validate " + none);
    EXPECT_EQ(r.status, 1) << r.out;
    EXPECT_EQ(validate_findings(r.out),
              (std::map<std::string, std::string>{{"cdi.xml-declaration", "FAIL"}}))
        << r.out;
    EXPECT_NE(r.out.find(none + ":1: FAIL cdi.xml-declaration: first line is not the XML "
                                "declaration <?xml version=\"1.0\"?>\n      expected: <?xml "
                                "version=\"1.0\"?>\n      seen:     \"<cdi "),
              std::string::npos)
        << r.out;

    const std::string utf8 =
        temp_file("utf8_declaration.xml",
                  default_with_first_line("<?xml version=\"1.0\" encoding=\"utf-8\"?>"));
    r = lcc_cdi("validate " + utf8);
    EXPECT_EQ(r.status, 0) << r.out;
    EXPECT_EQ(validate_findings(r.out),
              (std::map<std::string, std::string>{{"cdi.xml-declaration", "WARN"}}))
        << r.out;
    EXPECT_NE(r.out.find(utf8 + ": ok\n"), std::string::npos) << r.out;
}

TEST(LccCdi, EveryScenarioCdiValidatesWithoutAFinding) {
    int files = 0;
    for (const auto& e :
         std::filesystem::directory_iterator(std::string(OLCB_SOURCE_DIR) + "/scenarios")) {
        if (e.path().extension() != ".xml") continue;
        ++files;
        RunResult r = lcc_cdi("validate " + e.path().string());
        EXPECT_EQ(r.status, 0) << r.out;
        EXPECT_EQ(r.out, e.path().string() + ": ok\n");
    }
    EXPECT_GE(files, 3);
}

// A <name> and a <repname> holding bytes that are not UTF-8 (0xFF 0xFE): still a layout, as
// valid JSON.
std::string cdi_with_invalid_utf8() {
    std::string text = default_with_first_line("<?xml version=\"1.0\"?>");
    const std::size_t name = text.find("<name>", text.find("<segment")) + 6;
    text.insert(name, "\xFF\xFE");
    text.insert(text.find("<repname>") + 9, "\xFF\xFE");
    return text;
}

TEST(LccCdi, LayoutJsonReplacesInvalidUtf8AndStaysValid) {
    const std::string bad = temp_file("invalid_utf8.xml", cdi_with_invalid_utf8());
    RunResult r = lcc_cdi("layout --json " + bad);
    EXPECT_EQ(r.status, 0) << r.out;
    const auto json = nlohmann::json::parse(r.out, nullptr, false);
    ASSERT_FALSE(json.is_discarded()) << r.out;
    ASSERT_EQ(json.at("variables").size(), 28U);
    // A name shows the bytes as a backup key escapes them; a replica name, as U+FFFD.
    EXPECT_EQ(json["variables"][0]["name"], "\\x00ff\\x00feNode identity.User Name");
    EXPECT_NE(json.dump().find("\xEF\xBF\xBD"), std::string::npos) << r.out;  // U+FFFD

    RunResult warned = lcc_cdi("layout --json " + bad, true);
    EXPECT_NE(warned.out.find(bad + ":"), std::string::npos) << warned.out;
    EXPECT_NE(warned.out.find("warning: invalid UTF-8 at offset"), std::string::npos) << warned.out;
    EXPECT_EQ(warned.out.find("exception"), std::string::npos) << warned.out;

    RunResult text = lcc_cdi("layout " + bad);
    EXPECT_EQ(text.status, 0);
    EXPECT_EQ(std::count(text.out.begin(), text.out.end(), '\n'), 28) << text.out;
    EXPECT_EQ(text.out.find('\xFF'), std::string::npos);

    RunResult validated = lcc_cdi("validate " + bad);
    EXPECT_EQ(validated.status, 1);
    EXPECT_EQ(validate_findings(validated.out).at("cdi.utf8"), "FAIL") << validated.out;
}

const std::string kFdiData = std::string(OLCB_SOURCE_DIR) + "/tests/data/fdi";

// The FDI test data's verdicts, as tests/data/fdi/README.md's Files table lists them: file name
// and whether it is valid.
std::map<std::string, bool> fdi_verdicts() {
    std::ifstream in(kFdiData + "/README.md");
    static const std::regex row(R"(^\| `([^`]+\.xml)` \|[^|]*\|[^|]*\|[^|]*\| (valid|invalid))");
    std::map<std::string, bool> out;
    for (std::string line; std::getline(in, line);) {
        std::smatch m;
        if (std::regex_search(line, m, row)) out[m[1]] = m[2] == "valid";
    }
    return out;
}

// The issue's acceptance: the FDIs kept from real projects pass `lcc-cdi validate`, the broken
// fixtures fail it.
TEST(LccCdiFdi, ValidatePassesTheValidTestDataAndFailsTheRest) {
    const auto verdicts = fdi_verdicts();
    ASSERT_GE(verdicts.size(), 17U);
    for (const auto& [name, valid] : verdicts) {
        const std::string path = (std::filesystem::path(kFdiData) / name).string();
        RunResult r = lcc_cdi("validate " + path);
        EXPECT_EQ(r.status, valid ? 0 : 1) << r.out;
        EXPECT_EQ(r.out.ends_with(path + ": ok\n"), valid) << r.out;
    }
    // Several files in one run: the FDIs and a CDI side by side.
    RunResult both = lcc_cdi("validate -q " + kFdiData + "/openmrn__train_node.xml " + kDefault);
    EXPECT_EQ(both.status, 0) << both.out;
    EXPECT_NE(both.out.find("WARN fdi.schema-location"), std::string::npos) << both.out;
}

TEST(LccCdiFdi, AnInvalidFdiFailsCitingTheClause) {
    const std::string bad = temp_file(
        "fdi_bad_number.xml",
        "<?xml version=\"1.0\"?>\n<fdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"https://openlcb.org/schema/fdi/1/1/fdi.xsd\">\n"
        "<segment>\n<function><number>16777216</number></function>\n</segment>\n</fdi>\n");
    RunResult r = lcc_cdi("validate " + bad);
    EXPECT_EQ(r.status, 1);
    EXPECT_NE(r.out.find(bad + ":4: FAIL fdi.valid: 1 error(s), 0 warning(s); first: line 4: "
                               "FDI 1.1 schema: "),
              std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("      clause:   FunctionDescriptionInformationS §5\n"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find(bad + ":4: error: FDI 1.1 schema: Element 'number'"), std::string::npos)
        << r.out;
    EXPECT_EQ(r.out.find("cdi."), std::string::npos) << r.out;
}

TEST(LccCdiFdi, RenderPrintsTheFunctionList) {
    RunResult r = lcc_cdi("render " + kFdiData + "/documents__tn_sample.xml");
    ASSERT_EQ(r.status, 0);
    EXPECT_EQ(r.out,
              "Segment (unnamed), space 249 (functions)\n"
              "  group \"Lighting Functions\"\n"
              "    | Headlights and Marker lights and Running lights, oh my.\n"
              "    F0 binary \"Headlights\"\n"
              "    F4 binary \"Ditch Lights\"\n"
              "  group \"Sound Functions\"\n"
              "    | Toot toot!.\n"
              "    F8 analog 0..2 \"Horn\"\n");
    RunResult html = lcc_cdi("render --html " + kFdiData + "/documents__tn_sample.xml", true);
    EXPECT_EQ(html.status, 2);
    EXPECT_NE(html.out.find("--html renders a CDI; an FDI renders as text"), std::string::npos)
        << html.out;
}

TEST(LccCdiFdi, LayoutListsTheFunctionSpace) {
    RunResult text = lcc_cdi("layout " + kFdiData + "/openmrn__train_node.xml");
    ASSERT_EQ(text.status, 0);
    EXPECT_EQ(text.out,
              "Light\tbinary\tspace 249\taddress 0\tsize 1\n"
              "Blue\tmomentary\tspace 249\taddress 1\tsize 1\n");
    RunResult json = lcc_cdi("layout --json " + kFdiData + "/documents__tn_sample.xml");
    ASSERT_EQ(json.status, 0);
    const auto vars = nlohmann::json::parse(json.out).at("variables");
    ASSERT_EQ(vars.size(), 3U);
    EXPECT_EQ(vars[2]["name"], "Horn");
    EXPECT_EQ(vars[2]["type"], "analog");
    EXPECT_EQ(vars[2]["address"], 8);
    EXPECT_EQ(vars[2]["min"], 0);
    EXPECT_EQ(vars[2]["max"], 2);
    EXPECT_FALSE(vars[0].contains("min"));

    // A function whose number cannot be read would make the list wrong: refused.
    const std::string bad =
        temp_file("fdi_no_number.xml", "<fdi><segment><function/></segment></fdi>\n");
    RunResult refused = lcc_cdi("layout " + bad, true);
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.out.find(bad + ":1: error: <function> has no <number>"), std::string::npos)
        << refused.out;
}

#if defined(SIMNODE_PATH) && defined(LCC_CONFORM_PATH)

// lcc-conform --only 'cdi.*' against simnode serving `cdi`: its FAIL and WARN checks by ID.
std::map<std::string, std::string> conform_findings(const std::string& cdi, int& code) {
    olcb::e2e::TempDir dir("lcc-cdi-e2e");
    const auto ini = dir.path() / "node.ini";
    std::ofstream(ini) << "node-id = 05.01.01.01.22.00\ncdi = " << cdi << "\n";
    olcb::e2e::Simnode sim(ini);
    if (sim.port == 0) {
        ADD_FAILURE() << "simnode did not start for " << cdi;
        return {};
    }
    std::string out;
    std::tie(code, out) = olcb::e2e::conform(
        {"--connect", sim.connect(), "--node", "05.01.01.01.22.00", "--only", "cdi.*"});
    std::map<std::string, std::string> found;
    for (const auto& [status, id] : olcb::e2e::check_lines(out))
        if (status == "FAIL" || status == "WARN") found[id] = status;
    EXPECT_FALSE(olcb::e2e::check_lines(out).empty()) << out;
    return found;
}

TEST(LccCdiAndLccConform, SameIdsAndVerdictsForTheSameText) {
    const std::vector<std::string> files = {
        temp_file("same_none.xml", default_with_first_line("")),
        temp_file("same_utf8.xml",
                  default_with_first_line("<?xml version=\"1.0\" encoding=\"utf-8\"?>")),
        temp_file("same_clean.xml", default_with_first_line("<?xml version=\"1.0\"?>")),
        temp_file("same_invalid_utf8.xml", cdi_with_invalid_utf8())};
    for (const std::string& file : files) {
        SCOPED_TRACE(file);
        const RunResult validated = lcc_cdi("validate " + file);
        int code = -1;
        const auto conformed = conform_findings(file, code);
        EXPECT_EQ(validate_findings(validated.out), conformed) << validated.out;
        EXPECT_EQ(validated.status, code);
    }
}

#endif

}  // namespace
