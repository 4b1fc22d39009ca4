// Every fault of docs/faults.md misbehaves as documented, and a good node does not.
#include <gtest/gtest.h>

#include <cstring>

#include "base/utf8.hpp"
#include "cdi/validator.hpp"
#include "memory/acdi.hpp"
#include "memory/snip.hpp"
#include "sim_node_test_util.hpp"

namespace olcb::simnode::test {
namespace {

class FaultTest : public SimNodeTest {
protected:
    std::uint32_t highest(std::uint8_t space) {
        const auto r = exchange({0x20, 0x84, space}).reply;
        if (!r || r->size() < 7) return 0;
        return static_cast<std::uint32_t>((*r)[3]) << 24 | (*r)[4] << 16 | (*r)[5] << 8 | (*r)[6];
    }
};

constexpr std::uint32_t kTrim = 1, kDelay = 3, kScale = 22, kLabel = 30, kPort0On = 62;

TEST_F(FaultTest, SnipMismatch) {
    start_with({"snip-mismatch"});
    const memory::Snip snip = memory::decode_snip(request_snip());
    const auto fixed = memory::decode_acdi_manufacturer(node_->memory().read(0xFC, 0, 125));
    EXPECT_NE(snip.model, fixed.model);
    EXPECT_EQ(fixed.model, "simnode default");
    EXPECT_EQ(snip.manufacturer, fixed.manufacturer);
}

TEST_F(FaultTest, SnipInvalidUtf8) {
    start_with({"snip-invalid-utf8"});
    const memory::Snip snip = memory::decode_snip(request_snip());
    const auto user = memory::decode_acdi_user(node_->memory().read(0xFB, 0, 128));
    EXPECT_EQ(user.name, "Test node");  // space 251 keeps the valid name
    EXPECT_EQ(snip.user_name, user.name + "\xFF\xFE");
    EXPECT_FALSE(base::is_valid_utf8(snip.user_name));
    EXPECT_EQ(snip.model, "simnode default");  // only the user name is touched
}

TEST_F(FaultTest, AcdiVersion) {
    start_with({"acdi-version"});
    EXPECT_EQ(read(0xFC, 0, 1), (std::vector<std::uint8_t>{5}));
    EXPECT_EQ(read(0xFB, 0, 1), (std::vector<std::uint8_t>{3}));
}

TEST_F(FaultTest, PipMissingBit) {
    start_with({"pip-missing-bit"});
    take();
    send_addressed(0x828);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19668343N012C745000000000;"});
    EXPECT_TRUE(node_->served_protocols().has(Protocol::kCdi));
}

TEST_F(FaultTest, PipMissingAcdiBit) {
    start_with({"pip-missing-bit=acdi"});
    take();
    send_addressed(0x828);
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X19668343N012C741800000000;"});
}

TEST_F(FaultTest, CdiUnterminated) {
    start_with({"cdi-unterminated"});
    const auto cdi = served_cdi();
    EXPECT_EQ(cdi.size(), default_cdi().size());
    EXPECT_EQ(std::find(cdi.begin(), cdi.end(), 0), cdi.end());
    EXPECT_EQ(highest(0xFF), default_cdi().size() - 1);
}

TEST_F(FaultTest, CdiPadding) {
    start_with({"cdi-padding"});
    EXPECT_GT(highest(0xFF), default_cdi().size());
    const auto tail = read(0xFF, static_cast<std::uint32_t>(default_cdi().size()), 64);
    ASSERT_GT(tail.size(), 8u);
    EXPECT_EQ(tail[0], 0);
    EXPECT_NE(std::string(tail.begin(), tail.end()).find("PADDING"), std::string::npos);
}

TEST_F(FaultTest, CdiInvalidServesASchemaViolation) {
    start_with({"cdi-invalid"});
    auto cdi = served_cdi();
    ASSERT_FALSE(cdi.empty());
    const std::string text(cdi.begin(), cdi.end() - 1);
    EXPECT_NE(text.rfind("<?xml", 0), 0u);
    EXPECT_FALSE(cdi::validate(text).ok());
    EXPECT_TRUE(cdi::validate(default_cdi()).ok());
}

TEST_F(FaultTest, InvalidButParseableCdiIsServedWithItsProblem) {
    NodeConfig c = default_config();
    // Schema-invalid (unknown element) but parseable: served as real firmware would.
    c.cdi.insert(c.cdi.find("<acdi/>"), "<bogus/>");
    std::string error;
    auto node = SimNode::create(c, error);
    ASSERT_NE(node, nullptr) << error;
    EXPECT_NE(node->cdi_problem().find("bogus"), std::string::npos) << node->cdi_problem();
    c.cdi = "<cdi><segment space='253'><int size='3'/></segment";  // not well-formed
    EXPECT_EQ(SimNode::create(c, error), nullptr);
    EXPECT_FALSE(error.empty());
}

TEST_F(FaultTest, IntByteOrder) {
    start_with({"int-byte-order"});
    EXPECT_EQ(read(0xFD, kTrim, 2), (std::vector<std::uint8_t>{0xFB, 0xFF}));  // -5 little-endian
    write_ok(0xFD, kDelay, {0, 0, 1, 2});
    EXPECT_EQ(read(0xFD, kDelay, 4), (std::vector<std::uint8_t>{2, 1, 0, 0}));
}

TEST_F(FaultTest, StringUnterminated) {
    start_with({"string-unterminated"});
    EXPECT_EQ(read(0xFD, kLabel, 16), bytes_of("                "));
    write_ok(0xFD, kLabel, {'a', 'b', 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0});
    EXPECT_EQ(read(0xFD, kLabel, 16), bytes_of("ab              "));
    EXPECT_EQ(node_->snip().user_name, "Test node") << "ACDI strings keep their NUL";
}

TEST_F(FaultTest, EventIdByteOrder) {
    start_with({"eventid-byte-order"});
    const auto frames = take();
    EXPECT_EQ(read(0xFD, kPort0On, 8), (std::vector<std::uint8_t>{0, 0, 0, 0x22, 1, 1, 1, 5}));
    EXPECT_EQ(count_prefix(frames, ":X194C7343N0000002201010105"), 1u);
    write_ok(0xFD, kPort0On, {1, 2, 3, 4, 5, 6, 7, 8});
    EXPECT_EQ(read(0xFD, kPort0On, 8), (std::vector<std::uint8_t>{8, 7, 6, 5, 4, 3, 2, 1}));
}

TEST_F(FaultTest, FloatWidth) {
    start_with({"float-width"});
    double tenth = 0.1;
    std::uint64_t bits = 0;
    std::memcpy(&bits, &tenth, 8);
    std::vector<std::uint8_t> be(8);
    for (int i = 0; i < 8; ++i) be[i] = static_cast<std::uint8_t>(bits >> (56 - 8 * i));
    write_ok(0xFD, kScale, be);
    const auto back = read(0xFD, kScale, 8);
    EXPECT_NE(back, be);
    const double as_float = static_cast<float>(0.1);
    std::memcpy(&bits, &as_float, 8);
    for (int i = 0; i < 8; ++i) be[i] = static_cast<std::uint8_t>(bits >> (56 - 8 * i));
    EXPECT_EQ(back, be) << "stored with single precision";
}

TEST_F(FaultTest, WriteDropped) {
    start_with({"write-dropped"});
    write_ok(0xFD, 15, {3});
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
}

TEST_F(FaultTest, WriteNotPersisted) {
    TempDir dir;
    NodeConfig c = default_config();
    c.image_dir = dir.path();
    c.faults = faults_of({"write-not-persisted"});
    start(c);
    write_ok(0xFD, 15, {3});
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{3}));
    EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
    net_.run_for(1s);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2})) << "lost on reboot";
}

TEST_F(FaultTest, ReadonlyWritable) {
    start_with({"readonly-writable"});
    write_ok(0xFF, 0, bytes_of("<!--"));
    EXPECT_EQ(read(0xFF, 0, 4), bytes_of("<!--"));
    write_ok(0xFC, 1, bytes_of("Evil"));
    EXPECT_EQ(read(0xFC, 1, 4), bytes_of("Evil"));
}

TEST_F(FaultTest, ReadPastEnd) {
    start_with({"read-past-end"});
    const auto end = static_cast<std::uint32_t>(default_cdi().size() + 1);
    const Answer a = exchange(read_cmd(0xFF, end, 16));
    ASSERT_TRUE(a.reply);
    EXPECT_EQ((*a.reply)[1], 0x53);
    EXPECT_EQ(a.reply->size(), 6u + 16u);
}

TEST_F(FaultTest, SpaceInfoShort) {
    start_with({"space-info-short"});
    EXPECT_EQ(highest(0xFD), 178u - 16u);
    EXPECT_EQ(highest(0xFB), 127u - 16u);
}

TEST_F(FaultTest, ReplyForm) {
    start_with({"reply-form"});
    Answer a = exchange({0x20, 0x43, 0, 0, 0, 0, 2});  // short form
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x50, 0, 0, 0, 0, 0xFF, '<', '?'}));
    a = exchange({0x20, 0x40, 0, 0, 0, 15, 0xFD, 1});  // byte-6 form
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x51, 0, 0, 0, 15, 2}));
}

TEST_F(FaultTest, NoDatagramAck) {
    start_with({"no-datagram-ack"});
    const Answer a = exchange(read_cmd(0xFD, 15, 1));
    ASSERT_TRUE(a.reply);
    ASSERT_TRUE(a.ok);
    EXPECT_LT(a.reply_index, a.ok_index) << "reply datagram came before the Datagram OK";
}

TEST_F(FaultTest, SlowReply) {
    start_with({"slow-reply"});
    const Answer a = exchange(read_cmd(0xFD, 15, 1), 5s);
    ASSERT_TRUE(a.ok);
    ASSERT_TRUE(a.reply);
    EXPECT_GE(a.reply_at - a.ok_at, std::chrono::milliseconds(1200));
    EXPECT_GT(a.reply_at - a.ok_at, std::chrono::milliseconds(750));
}

TEST_F(FaultTest, SlowReplyHoldsBackEveryThirtySecondReply) {
    constexpr std::uint64_t kSlowReplyEvery = 32;  // as docs/faults.md says
    start_with({"slow-reply"});
    for (std::uint64_t i = 0; i <= kSlowReplyEvery; ++i) {
        const Answer a = exchange(read_cmd(0xFD, 15, 1), 5s);
        ASSERT_TRUE(a.reply) << i;
        const bool slow = a.reply_at - a.ok_at >= std::chrono::milliseconds(1200);
        EXPECT_EQ(slow, i % kSlowReplyEvery == 0) << "reply " << i;
    }
}

TEST_F(FaultTest, SlowReplyDroppedByReboot) {
    start_with({"slow-reply=2000"});
    const Answer probe = exchange(read_cmd(0xFD, 15, 1), 100ms);
    EXPECT_TRUE(probe.ok);
    EXPECT_FALSE(probe.reply);
    EXPECT_TRUE(exchange({0x20, 0xA9}).ok);
    take();
    net_.run_for(3s);
    EXPECT_EQ(count_prefix(take(), ":X1A12C343N"), 0u);
}

TEST_F(FaultTest, RejectTemporaryThenWorks) {
    start_with({"reject-temporary=3"});
    for (int i = 0; i < 3; ++i) {
        const Answer a = exchange(read_cmd(0xFD, 15, 1));
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x2020);
    }
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
    EXPECT_EQ(node_->counters().temporary_rejects, 3u);
}

TEST_F(FaultTest, GoodNodeDefendsItsAlias) {
    start(default_config());
    take();
    send_text(":X17050343N;");  // someone checks our alias
    net_.run_for(10ms);
    EXPECT_EQ(take(), std::vector<std::string>{":X10700343N;"});
    send_text(":X19170343N020000000001;");  // someone uses it
    net_.run_for(10ms);
    const auto frames = take();
    ASSERT_FALSE(frames.empty());
    EXPECT_EQ(frames[0], ":X10703343N050101012200;");
}

TEST_F(FaultTest, AliasConflictIgnored) {
    start_with({"alias-conflict-ignored"});
    take();
    send_text(":X17050343N;");
    net_.run_for(10ms);
    EXPECT_TRUE(take().empty());
    send_text(":X19170343N020000000001;");
    net_.run_for(1s);
    EXPECT_TRUE(take().empty());
    EXPECT_EQ(alias(), 0x343);
    EXPECT_TRUE(node_->stack().initialized());
}

TEST_F(FaultTest, UnsolicitedTraffic) {
    start_with({"unsolicited-traffic"});
    take();
    net_.run_for(3500ms);
    EXPECT_EQ(count_prefix(take(), ":X19490343N"), 3u);
}

TEST_F(FaultTest, GoodNodeLocksAndReportsStandardErrors) {
    start(default_config());
    Answer a = exchange({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1});
    ASSERT_TRUE(a.reply);
    EXPECT_EQ(*a.reply, (std::vector<std::uint8_t>{0x20, 0x8A, 2, 1, 0x0D, 0, 0, 1}));
    a = exchange(read_cmd(0x10, 0, 4));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1081);
    a = exchange(write_cmd(0xFF, 0, {'x'}));
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1083);
    EXPECT_EQ(read(0xFC, 0, 64).size(), 64u) << "a good node fills the count asked";
}

TEST_F(FaultTest, LockRejected) {
    start_with({"lock-rejected"});
    const Answer a = exchange({0x20, 0x88, 2, 1, 0x0D, 0, 0, 1});
    EXPECT_TRUE(a.rejected);
    EXPECT_EQ(a.code, 0x1041);
    EXPECT_FALSE(a.reply);
    EXPECT_EQ(node_->server().lock_holder(), 0u);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2})) << "the rest still works";
}

// A string as stored in an ACDI field: its bytes and the NUL.
std::vector<std::uint8_t> with_nul(std::string_view s) {
    auto bytes = bytes_of(s);
    bytes.push_back(0);
    return bytes;
}

TEST_F(FaultTest, FieldReadsOnly) {
    start_with({"field-reads-only"});
    EXPECT_EQ(read(0xFC, 0, 64), (std::vector<std::uint8_t>{4})) << "version byte alone";
    EXPECT_EQ(read(0xFC, 1, 64), with_nul("OpenLCB Tools"));
    EXPECT_EQ(read(0xFC, 1, 4), bytes_of("Open")) << "never more than asked";
    EXPECT_EQ(read(0xFC, 42, 64), with_nul("simnode default"));
    EXPECT_EQ(read(0xFC, 83, 64), with_nul("1.0"));
    EXPECT_EQ(read(0xFC, 104, 64), with_nul("0.1.0"));
    EXPECT_EQ(read(0xFC, 2, 64), bytes_of("p")) << "off a field start: one byte";
    EXPECT_EQ(read(0xFC, 124, 64).size(), 1u);
    const Answer end = exchange(read_cmd(0xFC, 125, 8));
    ASSERT_TRUE(end.reply);
    EXPECT_EQ((*end.reply)[1], 0x58) << "at the end still a Read Reply Fail";
    EXPECT_EQ((*end.reply)[7], 0x10);
    EXPECT_EQ((*end.reply)[8], 0x82);

    EXPECT_EQ(read(0xFB, 0, 64), (std::vector<std::uint8_t>{2}));
    EXPECT_EQ(read(0xFB, 1, 64), with_nul("Test node"));
    EXPECT_EQ(read(0xFB, 64, 64), with_nul("Bench"));
    EXPECT_EQ(read(0xFB, 10, 64).size(), 1u);
    const std::vector<std::uint8_t> full(63, 'x');
    write_ok(0xFB, 1, full);
    EXPECT_EQ(read(0xFB, 1, 64), full) << "a field without NUL is returned whole, no more";
    EXPECT_EQ(read(0xFD, 0, 8).size(), 8u) << "other spaces are read as usual";
}

TEST_F(FaultTest, UnknownSpace0x1041) {
    start_with({"unknown-space-0x1041"});
    for (const auto& cmd : {read_cmd(0x10, 0, 4), write_cmd(0x10, 0, {1}), read_cmd(0xFE, 0, 4),
                            write_cmd(0xFE, 0, {1})}) {
        const Answer a = exchange(cmd);
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x1041);
        EXPECT_FALSE(a.reply);
    }
    const Answer info = exchange({0x20, 0x84, 0x10});
    ASSERT_TRUE(info.reply) << "Get Address Space Information is unchanged";
    EXPECT_EQ((*info.reply)[1], 0x86);
    EXPECT_EQ(read(0xFD, 15, 1), (std::vector<std::uint8_t>{2}));
}

TEST_F(FaultTest, Readonly0x1041) {
    start_with({"readonly-0x1041"});
    for (const auto& cmd : {write_cmd(0xFF, 0, {'x'}), write_cmd(0xFC, 1, {'x'})}) {
        const Answer a = exchange(cmd);
        EXPECT_TRUE(a.rejected);
        EXPECT_EQ(a.code, 0x1041);
    }
    EXPECT_EQ(read(0xFF, 0, 2), bytes_of("<?"));
    write_ok(0xFD, 15, {3});
    const Answer unknown = exchange(read_cmd(0x10, 0, 4));
    EXPECT_EQ(unknown.code, 0x1081) << "only the read-only code changes";
}

}  // namespace
}  // namespace olcb::simnode::test
