// Black-box tests of the lcc-cdi program: exit codes, output formats, the shipped sample CDI.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace {

struct RunResult {
    int status = -1;
    std::string out;
};

// Runs lcc-cdi with `args` (shell-quoted by the caller); captures stdout and, when asked, stderr.
RunResult lcc_cdi(const std::string& args, bool merge_stderr = false) {
    std::string command =
        std::string(LCC_CDI_PATH) + " " + args + (merge_stderr ? " 2>&1" : " 2>/dev/null");
    RunResult run;
    FILE* pipe = popen(command.c_str(), "r");
    if (pipe == nullptr) return run;
    std::array<char, 4096> buf{};
    std::size_t n = 0;
    while ((n = fread(buf.data(), 1, buf.size(), pipe)) > 0) run.out.append(buf.data(), n);
    int status = pclose(pipe);
    run.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    return run;
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
    EXPECT_NE(vars[26]["path"].get<std::string>().find("[4]"), std::string::npos)
        << vars[26]["path"];
    EXPECT_EQ(vars[27]["type"], "action");
    EXPECT_EQ(vars[27]["address"], 178);
    EXPECT_EQ(vars[2]["map"].size(), 2U);
}

TEST(LccCdi, LayoutTextOneLinePerVariable) {
    RunResult r = lcc_cdi("layout " + kDefault);
    ASSERT_EQ(r.status, 0);
    EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 28);
    EXPECT_NE(r.out.find("space 253\taddress 178\tsize 1"), std::string::npos) << r.out;
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

}  // namespace
