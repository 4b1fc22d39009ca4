// The protocol checks against the simulated node: no false failure on the default node, and each
// fault of docs/faults.md (J1's share) caught with its category.
#include <gtest/gtest.h>
#include <algorithm>
#include <cctype>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <variant>

#include "conformance/checks/protocol_checks.hpp"
#include "conformance/conform_test_util.hpp"
#include "conformance/link/link.hpp"
#include "conformance/link/session.hpp"
#include "conformance/sim_bench.hpp"
#include "openlcb/sim_network.hpp"
#include "simnode/faults.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::conform {
namespace {

using Bench = testing::SimBench;
using testing::dump;
using testing::find_check;

// No message may show the code 0x0000 (a failure without a code says what happened instead).
void expect_no_empty_code(const std::vector<CheckResult>& results) {
    for (const auto& r : results) {
        for (const std::string* text : {&r.message, &r.expected, &r.seen}) {
            for (std::size_t at = text->find("0x0000"); at != std::string::npos;
                 at = text->find("0x0000", at + 1)) {
                const bool longer = at + 6 < text->size() &&
                                    std::isxdigit(static_cast<unsigned char>((*text)[at + 6]));
                EXPECT_TRUE(longer) << r.id << ": " << *text;  // 0x0000ABCD is an address
            }
        }
    }
}

TEST(SessionTest, DiscoversAndReadsTheSimNode) {
    Bench b;
    ASSERT_TRUE(b.session->start());
    auto nodes = b.session->discover(std::chrono::milliseconds(200));
    ASSERT_EQ(nodes.size(), 1u);
    EXPECT_EQ(nodes[0].id, kDut);
    EXPECT_EQ(nodes[0].alias, b.dut->stack().alias());
    auto pip = b.session->protocol_support(nodes[0]);
    ASSERT_TRUE(pip);
    EXPECT_TRUE(pip->has(Protocol::kMemoryConfiguration));
    MemResult r = b.session->read(nodes[0], memory::Space::kCdi, 0, 5);
    ASSERT_TRUE(r.ok);
    EXPECT_EQ(std::string(r.data.begin(), r.data.end()), "<?xml");
    EXPECT_TRUE(r.datagram_ok_seen);
    EXPECT_TRUE(r.reply_pending);
    MemResult bad = b.session->read(nodes[0], static_cast<memory::Space>(0x51), 0, 5);
    EXPECT_FALSE(bad.ok);
    EXPECT_EQ(bad.error, 0x1081);
}

// A link that reports itself lost once armed and driven again; the simulated segment keeps
// running, so only what the link reports can change a verdict.
class LossyLink final : public Link {
public:
    explicit LossyLink(Link& inner) : inner_(inner) {}
    void arm() { armed_ = true; }
    NodeStack& stack() override { return inner_.stack(); }
    TimePoint now() override { return inner_.now(); }
    bool run_until(const std::function<bool()>& pred, Duration max) override {
        if (armed_ && up_) {
            up_ = false;
            ++losses_;
        }
        return inner_.run_until(pred, max);
    }
    void send_frame(const CanFrame& frame) override { inner_.send_frame(frame); }
    void set_frame_observer(FrameObserver observer) override {
        inner_.set_frame_observer(std::move(observer));
    }
    bool up() override { return up_; }
    std::uint64_t losses() override { return losses_; }

private:
    Link& inner_;
    bool armed_ = false;
    bool up_ = true;
    std::uint64_t losses_ = 0;
};

// The link lost during a check: that check is not judged, the later ones are not run, and none
// FAILs the node (the socketcan suite found events.pcer-payload-tolerated failed this way).
TEST(ProtocolChecksTest, ALinkLostDuringACheckJudgesNothingAfterIt) {
    Bench b;
    LossyLink lossy(*b.link);
    b.session.reset();
    b.session = std::make_unique<Session>(lossy);
    auto node = b.start();
    ASSERT_TRUE(node);
    CheckContext ctx;
    ctx.check_started = [&](std::string_view id) {
        if (id == "memory.unknown-command") lossy.arm();
    };
    const auto results = run_protocol_checks(*b.session, *node, ProtocolOptions{}, ctx);
    EXPECT_EQ(ctx.link_lost_during, "memory.unknown-command");
    EXPECT_EQ(ctx.lost_after, "");
    EXPECT_GT(ctx.not_run, 10u);
    const CheckResult* during = find_check(results, "memory.unknown-command");
    ASSERT_NE(during, nullptr);
    EXPECT_EQ(during->status, Status::kSkip);
    EXPECT_EQ(during->message, "not judged: the link went down during this check");
    const CheckResult* later = find_check(results, "memory.lock");
    ASSERT_NE(later, nullptr);
    EXPECT_EQ(later->message, "not run: the link went down during memory.unknown-command");
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
}

TEST(ProtocolChecksTest, DefaultNodeHasNoFailure) {
    Bench b;
    CheckContext ctx;
    auto results = b.run(ctx);
    ASSERT_GT(results.size(), 25u);
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    EXPECT_TRUE(ctx.layout.has_value());
    EXPECT_TRUE(ctx.cdi_nul_found);
    EXPECT_TRUE(ctx.snip.has_value());
    for (const char* id : {"memory.readonly-refused.ff", "memory.readonly-refused.fc",
                           "memory.unknown-space", "memory.read-past-end.ff"}) {
        const CheckResult* c = find_check(results, id);
        ASSERT_NE(c, nullptr) << id;
        EXPECT_EQ(c->status, Status::kPass) << id;
    }
    EXPECT_NE(
        find_check(results, "memory.readonly-refused.ff")->message.find("refused with 0x1083"),
        std::string::npos);
    // The deliberate read across the end of 0xFF is short, and at the end: no failure.
    auto shorts = short_read_checks(*b.session, *b.session->find_node(kDut), ctx);
    const CheckResult* ff = find_check(shorts, "memory.short-read.ff");
    ASSERT_NE(ff, nullptr) << dump(shorts);
    EXPECT_EQ(ff->status, Status::kPass);
    EXPECT_NE(ff->message.find("reads of space 0xFF returned the count asked or ended at the end "
                               "of the space"),
              std::string::npos)
        << ff->message;
    for (const auto& r : shorts) EXPECT_EQ(r.status, Status::kPass) << dump(shorts);
    ASSERT_NE(find_check(shorts, "memory.short-read.fc"), nullptr);
    ASSERT_NE(find_check(shorts, "memory.short-read.fb"), nullptr);
    expect_no_empty_code(results);
}

struct FaultCase {
    const char* fault;
    Category category;
    /// FAIL where a "shall" is broken; WARN where the standard only recommends or is silent.
    Status flagged = Status::kFail;
};

class FaultTest : public ::testing::TestWithParam<FaultCase> {};

TEST_P(FaultTest, IsFlaggedInTheFaultsCategory) {
    Bench b({GetParam().fault});
    CheckContext ctx;
    auto results = b.run(ctx);
    const bool caught = std::any_of(results.begin(), results.end(), [](const CheckResult& r) {
        return r.status == GetParam().flagged && r.category == GetParam().category;
    });
    // A fault that breaks only a recommendation is never a FAIL anywhere.
    if (GetParam().flagged == Status::kWarn) {
        for (const CheckResult& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    }
    EXPECT_TRUE(caught) << GetParam().fault << "\n" << dump(results);
    expect_no_empty_code(results);
}

INSTANTIATE_TEST_SUITE_P(
    Faults, FaultTest,
    ::testing::Values(
        FaultCase{"snip-mismatch", Category::kSnip}, FaultCase{"acdi-version", Category::kAcdi},
        FaultCase{"pip-missing-bit", Category::kPip},
        // MessageNetworkS §3.4.3 says the reply "will" carry these bits: no "shall", a WARN.
        FaultCase{"pip-missing-bit=datagram", Category::kPip, Status::kWarn},
        FaultCase{"pip-missing-bit=cdi", Category::kPip, Status::kWarn},
        FaultCase{"cdi-unterminated", Category::kCdi}, FaultCase{"cdi-invalid", Category::kCdi},
        FaultCase{"readonly-writable", Category::kMemory},
        FaultCase{"read-past-end", Category::kMemory},
        FaultCase{"space-info-short", Category::kAcdi},
        FaultCase{"reply-form", Category::kMemory, Status::kWarn},
        FaultCase{"no-datagram-ack", Category::kDatagram, Status::kWarn},
        FaultCase{"reply-without-ack", Category::kDatagram},
        FaultCase{"slow-reply", Category::kMemory},
        FaultCase{"alias-conflict-ignored", Category::kFrame},
        FaultCase{"unsolicited-traffic", Category::kMessage, Status::kWarn},
        FaultCase{"unknown-space-0x1041", Category::kMemory, Status::kWarn},
        FaultCase{"readonly-0x1041", Category::kMemory, Status::kWarn},
        FaultCase{"snip-invalid-utf8", Category::kSnip},
        FaultCase{"stream-wrong-count", Category::kStream, Status::kWarn},
        FaultCase{"stream-no-complete", Category::kStream},
        FaultCase{"stream-ignore-proceed", Category::kStream, Status::kWarn},
        FaultCase{"stream-exceed-buffer", Category::kStream, Status::kWarn}),
    [](const auto& info) {
        std::string n = info.param.fault;
        for (char& c : n)
            if (c == '-' || c == '=') c = '_';
        return n;
    });

// Bytes after the CDI's NUL break no rule (the space may be larger than the text).
TEST(FaultTest, CdiPaddingIsNoFault) {
    Bench b({"cdi-padding"});
    CheckContext ctx;
    auto results = b.run(ctx);
    for (const auto& r : results) EXPECT_EQ(r.status == Status::kFail, false) << dump(results);
    ASSERT_NE(find_check(results, "cdi.nul-at-highest"), nullptr);
    EXPECT_EQ(find_check(results, "cdi.nul-at-highest")->status, Status::kPass) << dump(results);
}

TEST(FaultTest, TemporaryRejectsAreRetriedAndPass) {
    Bench b({"reject-temporary=3"});
    CheckContext ctx;
    auto results = b.run(ctx);
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
    EXPECT_EQ(ctx.temporary_rejects, 3u);
    auto it = std::find_if(results.begin(), results.end(),
                           [](const auto& r) { return r.id == "datagram.temporary-rejects"; });
    ASSERT_NE(it, results.end());
    EXPECT_EQ(it->status, Status::kWarn);
}

TEST(ShortReadChecksTest, FieldReadsOnlyNodeIsReadCompletelyAndCaught) {
    Bench b({"field-reads-only"});
    CheckContext ctx;
    auto results = b.run(ctx);
    // Whole strings were read, so ACDI and SNIP agree and the version bytes are judged.
    for (const char* id : {"snip.matches-acdi", "acdi.manufacturer-version", "acdi.user-version"}) {
        const CheckResult* c = find_check(results, id);
        ASSERT_NE(c, nullptr) << id << "\n" << dump(results);
        EXPECT_EQ(c->status, Status::kPass) << dump(results);
    }
    ASSERT_TRUE(ctx.acdi_manufacturer && ctx.acdi_user);
    EXPECT_EQ(ctx.acdi_manufacturer->size(), 125u);
    EXPECT_EQ(ctx.acdi_user->size(), 128u);
    auto shorts = short_read_checks(*b.session, *b.session->find_node(kDut), ctx);
    for (const char* id : {"memory.short-read.fc", "memory.short-read.fb"}) {
        const CheckResult* c = find_check(shorts, id);
        ASSERT_NE(c, nullptr) << id << "\n" << dump(shorts);
        EXPECT_EQ(c->status, Status::kWarn) << dump(shorts);
        EXPECT_EQ(c->section, "MemoryConfigurationS §4.5; MemoryConfigurationTN §2.4.5");
        EXPECT_EQ(c->category, Category::kMemory);
        EXPECT_EQ(c->expected,
                  "the count asked: only the end of the space may shorten a Read Reply");
        // ACDI is read field by field: the name field (at 1, 63 or 41 bytes) comes back cut
        // after its NUL, which the standard does not allow either.
        EXPECT_NE(c->message.find("at 0x00000001 asked"), std::string::npos) << c->message;
    }
    EXPECT_NE(find_check(shorts, "memory.short-read.fc")->message.find("space 0xFC"),
              std::string::npos);
    EXPECT_EQ(find_check(shorts, "memory.short-read.ff")->status, Status::kPass);
}

TEST(ShortReadChecksTest, AShortReplyNothingFollowedIsSettledByAProbe) {
    Bench b({"field-reads-only"});
    auto node = b.start();
    ASSERT_TRUE(node);
    ASSERT_EQ(b.session->read(*node, memory::Space::kAcdiManufacturer, 0, 64).data.size(), 1u);
    CheckContext ctx;
    auto shorts = short_read_checks(*b.session, *node, ctx);
    ASSERT_EQ(shorts.size(), 1u) << dump(shorts);
    EXPECT_EQ(shorts[0].id, "memory.short-read.fc");
    EXPECT_EQ(shorts[0].status, Status::kWarn);
    EXPECT_TRUE(ctx.spaces.count(0xFC));  // Space Info was asked
    EXPECT_TRUE(b.session->short_reads().front().continued);
}

TEST(ProtocolChecksTest, SnipMismatchNamesTheFieldAndBothValues) {
    Bench b({"snip-mismatch"});
    CheckContext ctx;
    auto results = b.run(ctx);
    const CheckResult* acdi = find_check(results, "snip.matches-acdi");
    ASSERT_NE(acdi, nullptr);
    ASSERT_EQ(acdi->status, Status::kFail);
    ASSERT_TRUE(ctx.snip);
    EXPECT_NE(acdi->message.find("SNIP model \"" + ctx.snip->model + "\" differs from ACDI 252 \""),
              std::string::npos)
        << acdi->message;
    EXPECT_FALSE(acdi->expected.empty());
    EXPECT_EQ(acdi->seen, "\"" + ctx.snip->model + "\"");
    const CheckResult* cdi = find_check(results, "snip.matches-cdi");
    ASSERT_NE(cdi, nullptr);
    EXPECT_EQ(cdi->status, Status::kFail);
    EXPECT_EQ(cdi->expected, "\"simnode default\"");  // <model> of scenarios/default.xml
}

// MemoryConfigurationS asks for a failure with an error code; the codes 0x1081/0x1083 are the
// technical note's recommendation: another code WARNs, quoting both.
TEST(RejectCodeTest, OtherCodesWarnQuotingTheCodeGot) {
    Bench b({"unknown-space-0x1041", "readonly-0x1041"});
    CheckContext ctx;
    auto results = b.run(ctx);
    const CheckResult* unknown = find_check(results, "memory.unknown-space");
    ASSERT_NE(unknown, nullptr);
    EXPECT_EQ(unknown->status, Status::kWarn);
    EXPECT_NE(unknown->message.find("refused with 0x1041, not the recommended 0x1081"),
              std::string::npos)
        << unknown->message;
    std::vector<std::string> readonly;
    for (const auto& r : results)
        if (r.id.starts_with("memory.readonly-refused.")) readonly.push_back(r.message);
    ASSERT_EQ(readonly.size(), 2u) << dump(results);
    EXPECT_EQ(readonly[0],
              "write to read-only space 0xFF refused with 0x1041, not the recommended 0x1083 "
              "(MemoryConfigurationTN §2.4.3)");
    EXPECT_EQ(readonly[1],
              "write to read-only space 0xFC refused with 0x1041, not the recommended 0x1083 "
              "(MemoryConfigurationTN §2.4.3)");
    for (const auto& r : results) {
        EXPECT_NE(r.status, Status::kFail) << dump(results);
        if (r.id.starts_with("memory.readonly-refused.")) {
            EXPECT_EQ(r.status, Status::kWarn);
        }
    }
}

TEST(RejectCodeTest, ReadPastEndQuotesWhatCame) {
    Bench b({"read-past-end"});
    CheckContext ctx;
    auto results = b.run(ctx);
    const CheckResult* past = find_check(results, "memory.read-past-end.ff");
    ASSERT_NE(past, nullptr);
    EXPECT_EQ(past->status, Status::kFail);
    EXPECT_NE(past->message.find("past the end of space 0xFF, returned 8 bytes; it must fail "
                                 "with an error code (0x1082 recommended)"),
              std::string::npos)
        << past->message;
}

// Lock/Reserve is optional: "not implemented" (0x1041) is a SKIP quoting the code.
TEST(RejectCodeTest, ANotImplementedLockSkipsWithItsCode) {
    Bench b({"lock-rejected"});
    CheckContext ctx;
    auto results = b.run(ctx);
    const CheckResult* lock = find_check(results, "memory.lock");
    ASSERT_NE(lock, nullptr);
    EXPECT_EQ(lock->status, Status::kSkip);
    EXPECT_EQ(lock->message, "not implemented (0x1041): Lock/Reserve is optional");
    Bench good;
    CheckContext good_ctx;
    EXPECT_EQ(find_check(good.run(good_ctx), "memory.lock")->status, Status::kPass);
}

// The default CDI with its first line replaced by `first` and, with one_line, no line breaks.
std::string cdi_variant(const std::string& first, bool one_line) {
    std::string cdi = testing::default_cdi();
    cdi = first + cdi.substr(cdi.find('\n'));
    if (one_line) std::replace(cdi.begin(), cdi.end(), '\n', ' ');
    return cdi;
}

const CheckResult& xml_declaration(const std::string& cdi) {
    static std::vector<CheckResult> results;
    Bench b({}, cdi);
    CheckContext ctx;
    results = b.run(ctx);
    const CheckResult* c = find_check(results, "cdi.xml-declaration");
    static const CheckResult missing{"missing", Category::kCdi, Status::kSkip, "", "", "", ""};
    return c ? *c : missing;
}

TEST(XmlDeclarationTest, AOneLineCdiPasses) {
    const CheckResult& c = xml_declaration(cdi_variant("<?xml version=\"1.0\"?>", true));
    EXPECT_EQ(c.status, Status::kPass) << c.message;
}

TEST(XmlDeclarationTest, AnotherDeclarationWarnsQuotingOnlyIt) {
    const CheckResult& c =
        xml_declaration(cdi_variant("<?xml version=\"1.0\" encoding=\"utf-8\"?>", true));
    EXPECT_EQ(c.status, Status::kWarn);
    EXPECT_EQ(c.message,
              "first line is an XML declaration other than <?xml version=\"1.0\"?>: <?xml "
              "version=\"1.0\" encoding=\"utf-8\"?>");
}

TEST(XmlDeclarationTest, NoDeclarationFailsQuotingAtMost80Bytes) {
    const std::string cdi = cdi_variant("", true).substr(1);  // starts with <cdi ...>
    const CheckResult& c = xml_declaration(cdi);
    EXPECT_EQ(c.status, Status::kFail);
    EXPECT_EQ(c.expected, "<?xml version=\"1.0\"?>");
    EXPECT_EQ(c.seen, "\"" + cdi.substr(0, 80) + "...\"");
    EXPECT_LE(c.message.size() + c.seen.size(), 200u);
}

TEST(NodeTrackTest, ChecksReachANodeThatRestartedOnANewAlias) {
    Bench b({"new-alias-on-reboot"});
    auto node = b.start();
    ASSERT_TRUE(node);
    ASSERT_TRUE(b.reboot(*node));
    ASSERT_NE(b.session->alias_of(*node), node->alias);
    CheckContext ctx;
    auto results = run_protocol_checks(*b.session, *node, ProtocolOptions{}, ctx);
    ASSERT_GT(results.size(), 25u);
    for (const auto& r : results) EXPECT_NE(r.status, Status::kFail) << dump(results);
}

// A scripted node and a session on one segment.
struct ScriptedBench {
    SimNetwork net;
    testing::ScriptedNode node{net, kDut};
    std::unique_ptr<Link> link = make_sim_link(net, kTool);
    Session session{*link};

    std::optional<NodeInfo> start() {
        EXPECT_TRUE(session.start());
        return session.find_node(kDut);
    }
};

TEST(ProtocolChecksTest, AFailureWithoutACodeSaysWhatHappened) {
    ScriptedBench b;
    // Space 0xFF is empty: its first read already fails with 0x1082 (ok, no data).
    b.node.answer = [](const memory::Message& m) -> testing::ScriptedNode::Answer {
        const auto* read = std::get_if<memory::Read>(&m);
        if (!read || read->space != memory::Space::kCdi) return {0x1041, {}};
        return {0,
                memory::encode(memory::ReadReplyFail{
                    read->space, read->address, memory::ErrorCode::kOutOfBounds, "", read->form})};
    };
    auto node = b.start();
    ASSERT_TRUE(node);
    CheckContext ctx;
    auto results = run_protocol_checks(b.session, *node, ProtocolOptions{}, ctx);
    const CheckResult* read = find_check(results, "cdi.read");
    ASSERT_NE(read, nullptr);
    EXPECT_EQ(read->status, Status::kFail);
    EXPECT_EQ(read->seen, "no data");
    // Get Configuration Options is optional: a rejection says so, quoting the code.
    const CheckResult* options = find_check(results, "memory.config-options");
    ASSERT_NE(options, nullptr);
    EXPECT_EQ(options->status, Status::kSkip);
    EXPECT_NE(options->message.find("rejected with 0x1041"), std::string::npos) << options->message;
    expect_no_empty_code(results);
}

// A node whose space 0xFD answers a read at 0 with 1 byte and rejects every other read, so a
// 1-byte read where the short reply ended cannot tell whether it was the end: Space Info does.
std::vector<CheckResult> short_read_with_highest(std::uint32_t highest) {
    ScriptedBench b;
    b.node.answer = [highest](const memory::Message& m) -> testing::ScriptedNode::Answer {
        if (const auto* info = std::get_if<memory::GetSpaceInfo>(&m))
            return {0, memory::encode(memory::SpaceInfoReply{info->space, highest, false, {}, ""})};
        const auto* read = std::get_if<memory::Read>(&m);
        if (!read || read->address != 0) return {0x1041, {}};
        return {0, memory::encode(memory::ReadReply{read->space, 0, {0x41}, read->form})};
    };
    auto node = b.start();
    if (!node) return {};
    EXPECT_EQ(b.session.read(*node, memory::Space::kConfig, 0, 64).data.size(), 1u);
    CheckContext ctx;
    return short_read_checks(b.session, *node, ctx);
}

TEST(ShortReadChecksTest, SpaceInfoSettlesAShortReplyNothingElseCould) {
    auto inside = short_read_with_highest(100);
    ASSERT_EQ(inside.size(), 1u) << dump(inside);
    EXPECT_EQ(inside[0].id, "memory.short-read.fd");
    EXPECT_EQ(inside[0].status, Status::kWarn) << dump(inside);
    auto at_end = short_read_with_highest(0);  // a 1-byte space: the reply was whole
    ASSERT_EQ(at_end.size(), 1u) << dump(at_end);
    EXPECT_EQ(at_end[0].status, Status::kPass) << dump(at_end);
}

}  // namespace
}  // namespace olcb::conform
