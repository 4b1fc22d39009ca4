// The text report: one line per check with what was expected and seen, and node bytes shown safely.
#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <regex>
#include <sstream>
#include <string>

#include "conformance/report_test_util.hpp"

namespace olcb::conform {
namespace {

using testing::kFffd;
using testing::sample;

TEST(FormatCheck, FailureCarriesExpectedSeenAndSection) {
    std::string line = format_check(sample().checks[1], false);
    EXPECT_EQ(line.rfind("FAIL  encoding.int", 0), 0u) << line;
    EXPECT_NE(line.find("expected: 03 E8"), std::string::npos);
    EXPECT_NE(line.find("seen:     E8 03"), std::string::npos);
    EXPECT_NE(line.find("CDI S 5.1.4.2"), std::string::npos);
    EXPECT_EQ(line.find('\033'), std::string::npos);
    EXPECT_NE(format_check(sample().checks[1], true).find("\033[31m"), std::string::npos);
}

TEST(WriteText, EveryCheckAndTotals) {
    std::ostringstream out;
    write_text(out, sample(), false);
    std::string text = out.str();
    EXPECT_NE(text.find("\nPASS  1 check: frame.ame-answered\n"), std::string::npos) << text;
    EXPECT_NE(text.find("SKIP  encoding.blob"), std::string::npos);
    EXPECT_NE(text.find("restore: node memory byte-identical"), std::string::npos);
    EXPECT_NE(text.find("4 checks: 1 passed, 1 failed, 1 warnings, 1 skipped"), std::string::npos);
    EXPECT_NE(text.find("\nfailed: encoding.int\nwarnings: cdi.xml-declaration\n"),
              std::string::npos)
        << text;
    EXPECT_EQ(text.find('\x01'), std::string::npos);
}

// A report of many passes, a FAIL late in the run, a SKIP that depends on it and one that depends
// on that SKIP, and an unrelated SKIP.
NodeReport late_failure() {
    NodeReport r = sample();
    r.checks.clear();
    for (int i = 0; i < 60; ++i)
        r.checks.push_back({"frame.pass-" + std::to_string(i), Category::kFrame, Status::kPass,
                            "fine", "", "", ""});
    r.checks.push_back({"cdi.read", Category::kCdi, Status::kFail, "read refused with 0x1081",
                        "MemoryConfigurationS §4.4", "data", "0x1081"});
    r.checks.push_back({"cdi.valid", Category::kCdi, Status::kSkip,
                        "depends on cdi.read: the CDI could not be read", "", "", ""});
    r.checks.push_back({"pip.cdi-bit", Category::kPip, Status::kSkip,
                        "depends on cdi.valid: no CDI document", "", "", ""});
    r.checks.push_back(
        {"frame.startup-sequence", Category::kFrame, Status::kSkip, "needs --reboot", "", "", ""});
    r.not_tested = {"persistence not tested (values surviving Reset/Reboot): add --reboot"};
    return r;
}

std::vector<std::string> lines_of(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    for (std::string line; std::getline(in, line);) out.push_back(line);
    return out;
}

TEST(WriteText, FailuresComeFirstWithWhatTheyLeftUnjudgedUnderThem) {
    std::ostringstream out;
    write_text(out, late_failure(), false);
    const std::vector<std::string> lines = lines_of(out.str());
    ASSERT_GT(lines.size(), 8u) << out.str();
    EXPECT_EQ(lines[0], "node 05.01.01.01.22.00  ACME Sim CDI Node");
    EXPECT_TRUE(lines[1].starts_with("timing: ")) << lines[1];
    EXPECT_EQ(lines[2], "FAIL  cdi.read  read refused with 0x1081");
    EXPECT_EQ(lines[6], "      SKIP  cdi.valid  the CDI could not be read");
    // Through a chain: under the root cause, its own "depends on" kept.
    EXPECT_EQ(lines[7], "      SKIP  pip.cdi-bit  depends on cdi.valid: no CDI document");
    // The passes in one block within 100 columns, then the unrelated SKIP, then the summary.
    EXPECT_TRUE(lines[8].starts_with("PASS  60 checks: frame.pass-0 frame.pass-1 ")) << lines[8];
    std::size_t ids = 0;
    std::size_t i = 8;
    for (; i < lines.size() && (i == 8 || lines[i].starts_with("      ")); ++i) {
        EXPECT_LE(lines[i].size(), 100u) << lines[i];
        ids += static_cast<std::size_t>(std::count(lines[i].begin(), lines[i].end(), '.'));
    }
    EXPECT_EQ(ids, 60u);
    ASSERT_LT(i + 3, lines.size());
    EXPECT_EQ(lines[i], "SKIP  frame.startup-sequence  needs --reboot");
    EXPECT_EQ(lines[i + 1], "restore: node memory byte-identical to before");
    EXPECT_EQ(lines[i + 2], "64 checks: 60 passed, 1 failed, 0 warnings, 3 skipped");
    EXPECT_EQ(lines[i + 3], "failed: cdi.read");
    EXPECT_EQ(lines.back(), "persistence not tested (values surviving Reset/Reboot): add --reboot");
}

TEST(WriteText, FailuresOnlyLeavesOutThePassesAndTheUnrelatedSkips) {
    std::ostringstream out;
    write_text(out, late_failure(), TextStyle{false, TextDetail::kFailuresOnly});
    const std::string text = out.str();
    EXPECT_EQ(text.find("PASS"), std::string::npos) << text;
    EXPECT_EQ(text.find("frame.startup-sequence"), std::string::npos) << text;
    EXPECT_NE(text.find("      SKIP  cdi.valid"), std::string::npos) << text;
    EXPECT_NE(text.find("\ntiming: "), std::string::npos) << text;
    EXPECT_NE(text.find("\npersistence not tested"), std::string::npos) << text;
}

TEST(WriteText, QuietPrintsTheFailuresAndTheSummaryOnly) {
    std::ostringstream out;
    write_text(out, late_failure(), TextStyle{false, TextDetail::kQuiet});
    const std::vector<std::string> lines = lines_of(out.str());
    ASSERT_EQ(lines.size(), 10u) << out.str();
    EXPECT_EQ(lines[0], "node 05.01.01.01.22.00");
    EXPECT_EQ(lines[1], "FAIL  cdi.read  read refused with 0x1081");
    EXPECT_EQ(lines[7], "restore: node memory byte-identical to before");
    EXPECT_EQ(lines[9], "failed: cdi.read");
}

TEST(WriteText, TheSameOrderWithColour) {
    std::ostringstream plain, coloured;
    write_text(plain, late_failure(), false);
    write_text(coloured, late_failure(), true);
    const std::string stripped =
        std::regex_replace(coloured.str(), std::regex("\033\\[[0-9;]*m"), "");
    EXPECT_EQ(stripped, plain.str());
}

TEST(DependsOn, NamesTheCauseOfASkipOnly) {
    CheckResult c{"cdi.valid",
                  Category::kCdi,
                  Status::kSkip,
                  "depends on cdi.read: the CDI could not be read",
                  "",
                  "",
                  ""};
    EXPECT_EQ(depends_on(c), "cdi.read");
    c.message = "depends on memory.space-info-layout.fd";
    EXPECT_EQ(depends_on(c), "memory.space-info-layout.fd");
    c.status = Status::kFail;
    EXPECT_EQ(depends_on(c), "");
    c.status = Status::kSkip;
    c.message = "needs --reboot";
    EXPECT_EQ(depends_on(c), "");
}

TEST(Printable, EachInvalidByteBecomesOneReplacementCharacter) {
    EXPECT_EQ(printable("bad\xff\xfename"), std::string("bad") + kFffd + kFffd + "name");
    EXPECT_EQ(printable("\xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80"),
              "\xC3\xA9t\xC3\xA9 \xE2\x82\xAC \xF0\x9F\x98\x80");              // valid UTF-8 stays
    EXPECT_EQ(printable("\xC0\xAF"), std::string(kFffd) + kFffd);              // overlong
    EXPECT_EQ(printable("\xED\xA0\x80"), std::string(kFffd) + kFffd + kFffd);  // surrogate
    EXPECT_EQ(printable("ab\xE2\x82"), std::string("ab") + kFffd + kFffd);     // truncated
}

TEST(Printable, NoControlCharacterReachesATerminal) {
    EXPECT_EQ(printable("a\x1B[31mb\x07\x7F\n"), "a?[31mb???");
    EXPECT_EQ(printable("x\xC2\x9B"
                        "31m"),
              "x?31m");  // C1 CSI, which some terminals obey
    // Not allowed in XML: the JUnit report must stay well-formed.
    EXPECT_EQ(printable("\xEF\xBF\xBE\xEF\xBF\xBF"), std::string(kFffd) + kFffd);
}

TEST(ShowNodeText, InvalidTextCarriesItsBytesInHex) {
    EXPECT_EQ(show_node_text("bad\xff\xfename"),
              std::string("\"bad") + kFffd + kFffd + "name\" (bytes 62 61 64 FF FE 6E 61 6D 65)");
    EXPECT_EQ(show_node_text("plain"), "\"plain\"");
    EXPECT_EQ(show_node_text("tab\there", false), "tab?here (bytes 74 61 62 09 68 65 72 65)");
    const std::string longer(100, 'x');
    EXPECT_EQ(show_node_text(longer), "\"" + std::string(80, 'x') + "...\"");
}

TEST(TextReport, NodeBytesAreShownSafely) {
    NodeReport r;
    r.node_id = "05.01.01.01.22.00";
    r.name = "ACME Node \"bad\xff\"";
    r.identity.user_name = "bad\xff";
    CheckResult c;
    c.id = "snip.utf8";
    c.status = Status::kFail;
    c.message = "escape \x1B[2J in a message";
    c.expected = "valid UTF-8";
    c.seen = "user name \xff";
    r.checks.push_back(c);
    r.not_tested = {"persistence not tested (values surviving Reset/Reboot): add --reboot"};
    std::ostringstream out;
    write_text(out, r, false);
    const std::string text = out.str();
    EXPECT_EQ(text.find('\x1B'), std::string::npos) << text;
    EXPECT_EQ(text.find('\xff'), std::string::npos) << text;
    EXPECT_NE(
        text.find(std::string("ACME Node \"bad") + kFffd + "\" (user name bytes 62 61 64 FF)"),
        std::string::npos)
        << text;
    EXPECT_NE(text.find("persistence not tested (values surviving Reset/Reboot): add --reboot\n"),
              std::string::npos)
        << text;
}

}  // namespace
}  // namespace olcb::conform
