// Every byte a node sends is untrusted: invalid UTF-8 is replaced for display with the raw bytes
// in hex next to it, control bytes never reach a terminal, and snip.utf8 / acdi.utf8 fail such
// strings.
#include <gtest/gtest.h>

#include <sstream>

#include "conformance/conform_test_util.hpp"
#include "conformance/report/report.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::dump;
using testing::expect_status;

constexpr const char* kFffd = "\xEF\xBF\xBD";

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

// SimpleNodeInformationS names no encoding (only CommonInformationTN does): a WARN that still
// names the field and its bytes; the FAIL is snip.matches-acdi's (251 holds the valid name).
TEST(SnipUtf8, TheFaultWarnsNamingTheFieldAndItsBytes) {
    testing::SimBench b({"snip-invalid-utf8"});
    CheckContext ctx;
    const auto results = b.run(ctx);
    const CheckResult& c = expect_status(results, "snip.utf8", Status::kWarn);
    EXPECT_EQ(c.message, "user name is not valid UTF-8");
    EXPECT_EQ(c.expected, "valid UTF-8");
    EXPECT_EQ(c.seen, std::string("user name \"simnode default") + kFffd + kFffd +
                          "\" (bytes 73 69 6D 6E 6F 64 65 20 64 65 66 61 75 6C 74 FF FE)");
    // Space 251 holds the valid name: ACDI is fine, and SNIP disagrees with it.
    expect_status(results, "acdi.utf8", Status::kPass);
    expect_status(results, "snip.matches-acdi", Status::kFail);
}

TEST(SnipUtf8, AGoodNodePasses) {
    testing::SimBench b;
    CheckContext ctx;
    const auto results = b.run(ctx);
    expect_status(results, "snip.utf8", Status::kPass);
    expect_status(results, "acdi.utf8", Status::kPass);
}

TEST(AcdiUtf8, AnInvalidUserNameInSpace251Fails) {
    // What `simnode --user-name $'bad\xff\xfename'` serves: the bytes in 251 and in SNIP.
    SimNetwork net;
    simnode::NodeConfig cfg;
    cfg.node_id = kDut;
    cfg.cdi = testing::default_cdi();
    cfg.user_name = "bad\xff\xfename";
    std::string error;
    auto dut = simnode::SimNode::create(cfg, error);
    ASSERT_TRUE(dut) << error;
    net.set_logging(false);
    net.add_stack(dut->stack());
    dut->stack().start(net.now());
    auto link = make_sim_link(net, kTool);
    Session session(*link);
    ASSERT_TRUE(session.start());
    auto node = session.find_node(kDut);
    ASSERT_TRUE(node);
    CheckContext ctx;
    const auto results = run_protocol_checks(session, *node, ProtocolOptions{}, ctx);
    const CheckResult& acdi = expect_status(results, "acdi.utf8", Status::kFail);
    EXPECT_EQ(acdi.seen, std::string("space 251 @1 user name \"bad") + kFffd + kFffd +
                             "name\" (bytes 62 61 64 FF FE 6E 61 6D 65)");
    const CheckResult& snip = expect_status(results, "snip.utf8", Status::kWarn);
    EXPECT_NE(snip.seen.find("(bytes 62 61 64 FF FE 6E 61 6D 65)"), std::string::npos);
    // The same bytes on both sides: the strings still match.
    expect_status(results, "snip.matches-acdi", Status::kPass);
}

}  // namespace
}  // namespace olcb::conform
