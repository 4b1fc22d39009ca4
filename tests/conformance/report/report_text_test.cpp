// The text report: one line per check with what was expected and seen, and node bytes shown safely.
#include "conformance/report/report.hpp"

#include <gtest/gtest.h>

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

TEST(WriteText, OneLinePerCheckAndTotals) {
    std::ostringstream out;
    write_text(out, sample(), false);
    std::string text = out.str();
    EXPECT_NE(text.find("PASS  frame.ame-answered"), std::string::npos);
    EXPECT_NE(text.find("SKIP  encoding.blob"), std::string::npos);
    EXPECT_NE(text.find("restore: node memory byte-identical"), std::string::npos);
    EXPECT_NE(text.find("4 checks: 1 passed, 1 failed, 1 warnings, 1 skipped"), std::string::npos);
    EXPECT_EQ(text.find('\x01'), std::string::npos);
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
