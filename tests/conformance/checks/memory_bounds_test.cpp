// The memory edge checks (conformance/checks/memory_bounds.cpp) against the simulated node: all
// pass on the well-behaved node, each fails under its fault, and no run leaves memory changed.
#include <gtest/gtest.h>

#include <map>
#include <span>
#include <variant>

#include "conformance/checks/check_run.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

using testing::contains;
using testing::dump;
using testing::expect_status;
using testing::find_check;
using testing::io_board_cdi;
using testing::SimBench;

struct Ran {
    std::vector<CheckResult> results;
    Duration took{};
};

// Every entry of specs, in order, in one CheckRun against the node.
Ran run_specs(Session& session, const NodeInfo& node, const std::vector<CheckSpec>& specs,
              const ProtocolOptions& options = {}) {
    CheckRun run(session, node, options);
    const TimePoint start = session.link().now();
    for (const CheckSpec& spec : specs) run.run(spec);
    return {run.take(), session.link().now() - start};
}

// The crossing writes run only when asked (--write-past-end): these tests ask.
ProtocolOptions crossing() {
    ProtocolOptions o;
    o.selection.write_past_end = true;
    return o;
}

Ran run_bounds(SimBench& b, const ProtocolOptions& options = crossing()) {
    auto node = b.start();
    if (!node) return {};
    return run_specs(*b.session, *node, checks::memory_bounds_checks(), options);
}

// Every served space's bytes as a client reads them.
std::map<std::uint8_t, std::vector<std::uint8_t>> snapshot(SimBench& b) {
    std::map<std::uint8_t, std::vector<std::uint8_t>> out;
    for (std::uint8_t sp : b.dut->memory().served_spaces())
        out[sp] = b.dut->memory().read(sp, 0, 1u << 16);
    return out;
}

TEST(MemoryBoundsTest, DefaultNodePassesAndMemoryIsUnchanged) {
    SimBench b;
    const auto before = snapshot(b);
    const Ran ran = run_bounds(b);
    for (const char* sp : {"ff", "fd", "fc", "fb"}) {
        expect_status(ran.results, std::string("memory.read-at-highest.") + sp, Status::kPass);
        expect_status(ran.results, std::string("memory.read-past-end.") + sp, Status::kPass);
    }
    const CheckResult& fb = expect_status(ran.results, "memory.write-past-end.fb", Status::kPass);
    EXPECT_TRUE(contains(fb.message, "refused with 0x1082")) << fb.message;
    // The last byte of 0xFD is an <action>: no crossing write may include it.
    const CheckResult& fd = expect_status(ran.results, "memory.write-past-end.fd", Status::kSkip);
    EXPECT_TRUE(contains(fd.message, "Settings.Flash LEDs (<action> triggers a command)"))
        << fd.message;
    EXPECT_EQ(find_check(ran.results, "memory.write-past-end.ff"), nullptr);
    EXPECT_EQ(find_check(ran.results, "memory.write-past-end.fc"), nullptr);
    expect_status(ran.results, "memory.write-under-mask", Status::kPass);
    expect_status(ran.results, "memory.update-complete", Status::kPass);
    const CheckResult& wl =
        expect_status(ran.results, "memory.options-write-lengths", Status::kPass);
    EXPECT_TRUE(contains(wl.message, "0xE2")) << wl.message;
    for (const auto& r : ran.results) {
        EXPECT_EQ(r.category, Category::kMemory) << r.id;
        EXPECT_FALSE(r.section.empty()) << r.id;
    }
    EXPECT_EQ(snapshot(b), before);
    EXPECT_LT(ran.took, std::chrono::milliseconds(200))
        << std::chrono::duration_cast<std::chrono::milliseconds>(ran.took).count() << " ms";
}

TEST(MemoryBoundsTest, IoBoardNodePasses) {
    SimBench b({}, io_board_cdi());
    const auto before = snapshot(b);
    const Ran ran = run_bounds(b);
    ASSERT_GT(ran.results.size(), 10u);
    for (const auto& r : ran.results) EXPECT_EQ(r.status, Status::kPass) << dump(ran.results);
    EXPECT_EQ(snapshot(b), before);
}

TEST(MemoryBoundsTest, ReadPastEndGarbageFailsQuotingTheData) {
    SimBench b({"read-past-end-garbage"});
    const Ran ran = run_bounds(b);
    const CheckResult& c = expect_status(ran.results, "memory.read-past-end.fd", Status::kFail);
    EXPECT_TRUE(contains(c.message, "returned 8 bytes")) << c.message;
    EXPECT_EQ(c.expected, "a failure with an error code (0x1082)");
    expect_status(ran.results, "memory.read-past-end.fb", Status::kPass);
}

TEST(MemoryBoundsTest, ReadPastEndInEverySpaceFailsPerSpace) {
    SimBench b({"read-past-end"});
    const Ran ran = run_bounds(b);
    for (const char* sp : {"ff", "fd", "fc", "fb"})
        expect_status(ran.results, std::string("memory.read-past-end.") + sp, Status::kFail);
    EXPECT_EQ(find_check(ran.results, "memory.read-past-end.ff")->message,
              "8-byte read at 0x00000A02, past the end of space 0xFF, returned 8 bytes; it must "
              "fail with an error code (0x1082 recommended)");
}

TEST(MemoryBoundsTest, HighestUnreadableFailsNamingAddressAndCode) {
    SimBench b({"highest-unreadable"});
    const auto before = snapshot(b);
    const Ran ran = run_bounds(b);
    const CheckResult& fb = expect_status(ran.results, "memory.read-at-highest.fb", Status::kFail);
    EXPECT_TRUE(contains(fb.message, "0x00000080")) << fb.message;
    EXPECT_TRUE(contains(fb.message, "0x1082")) << fb.message;
    EXPECT_TRUE(contains(fb.message, "gives the size")) << fb.message;
    expect_status(ran.results, "memory.read-at-highest.fd", Status::kFail);
    expect_status(ran.results, "memory.read-at-highest.ff", Status::kPass);
    // The crossing write starts at the last byte that reads and is still refused.
    const CheckResult& w = expect_status(ran.results, "memory.write-past-end.fb", Status::kPass);
    EXPECT_TRUE(contains(w.message, "0x0000007F")) << w.message;
    EXPECT_EQ(snapshot(b), before);
}

// No clause makes a node refuse a crossing write: accepted is a WARN that says what the node
// may keep past the end; what spilled into readable memory is put back at once.
TEST(MemoryBoundsTest, SpillingWriteWarnsAndLeavesMemoryAsItWas) {
    for (const std::string& cdi : {std::string(), io_board_cdi()}) {
        SimBench b({"write-past-end-spills"}, cdi);
        const auto before = snapshot(b);
        const Ran ran = run_bounds(b);
        const CheckResult& fb =
            expect_status(ran.results, "memory.write-past-end.fb", Status::kWarn);
        EXPECT_TRUE(contains(fb.message, "was accepted")) << fb.message;
        EXPECT_TRUE(contains(fb.message,
                             "may have stored 1 byte past the end of space 0xFB (at "
                             "0x00000080)"))
            << fb.message;
        // The excess byte landed in 0xFD at 0x80 (OpenMRN's shared file): put back at once.
        EXPECT_TRUE(contains(fb.message,
                             "space 0xFD byte 0x00000080 changed (the write spilled); "
                             "restored"))
            << fb.message;
        // io-board's 0xFD ends in a plain variable; the default's in an <action> (skipped).
        if (!cdi.empty()) expect_status(ran.results, "memory.write-past-end.fd", Status::kWarn);
        for (const auto& r : ran.results) EXPECT_NE(r.status, Status::kFail) << dump(ran.results);
        EXPECT_EQ(snapshot(b), before);
    }
}

// Without --write-past-end no write crosses an end: the check is not run at all.
TEST(MemoryBoundsTest, CrossingWritesNeedTheirOwnOption) {
    SimBench b({"write-past-end-grows"}, io_board_cdi());
    const Ran ran = run_bounds(b, ProtocolOptions{});
    EXPECT_EQ(find_check(ran.results, "memory.write-past-end.fd"), nullptr) << dump(ran.results);
    EXPECT_EQ(find_check(ran.results, "memory.write-past-end.fb"), nullptr) << dump(ran.results);
    EXPECT_TRUE(b.dut->memory().past_end(0xFD).empty());
    EXPECT_TRUE(b.dut->memory().past_end(0xFB).empty());
}

// OpenMRN's file-backed 251 as measured (real-world.md §1): Space Info one too high and the
// excess of a crossing write landing in 253.
TEST(MemoryBoundsTest, OpenMrnLike251IsCaughtAndLeftAsItWas) {
    SimBench b({"highest-unreadable", "write-past-end-spills"});
    const auto before = snapshot(b);
    const Ran ran = run_bounds(b);
    expect_status(ran.results, "memory.read-at-highest.fb", Status::kFail);
    const CheckResult& w = expect_status(ran.results, "memory.write-past-end.fb", Status::kWarn);
    EXPECT_TRUE(contains(w.message, "at 0x0000007F")) << w.message;
    EXPECT_TRUE(contains(w.message, "highest address 0x00000080 does not read")) << w.message;
    EXPECT_EQ(snapshot(b), before);
}

TEST(MemoryBoundsTest, ReadOnlySkipsEveryWrite) {
    SimBench b({"write-past-end-spills"});
    const auto before = snapshot(b);
    ProtocolOptions o = crossing();
    o.read_only = true;
    const Ran ran = run_bounds(b, o);
    for (const char* id : {"memory.write-past-end.fb", "memory.write-past-end.fd",
                           "memory.write-under-mask", "memory.update-complete"}) {
        const CheckResult& c = expect_status(ran.results, id, Status::kSkip);
        EXPECT_EQ(c.message, "--read-only");
    }
    expect_status(ran.results, "memory.options-write-lengths", Status::kPass);
    EXPECT_EQ(snapshot(b), before);
}

// A node with one byte-wide variable in 0xFD whose write under mask ignores the mask, and whose
// Options give an old write-lengths byte.
struct MaskIgnoringNode {
    static constexpr NodeId kId{0x0501010122AAull};
    std::string cdi =
        "<?xml version=\"1.0\"?><cdi><segment space=\"253\"><int size=\"1\"><name>A</name>"
        "</int><int size=\"1\"><name>B</name></int></segment></cdi>";
    std::vector<std::uint8_t> fd = {0x5A, 0x11};

    testing::ScriptedNode::Answer answer(const memory::Message& m) {
        using namespace memory;
        if (std::holds_alternative<GetConfigOptions>(m)) {
            ConfigOptionsReply r;
            r.available_commands = available_commands::kWriteUnderMask;
            r.write_lengths = 0x80;
            r.lowest_space = Space::kConfig;
            return {0, encode(r)};
        }
        if (const auto* i = std::get_if<GetSpaceInfo>(&m)) {
            if (i->space == Space::kCdi)
                return {0, encode(SpaceInfoReply{
                               i->space, static_cast<std::uint32_t>(cdi.size()), true, {}, ""})};
            if (i->space == Space::kConfig)
                return {0, encode(SpaceInfoReply{i->space, 1, false, {}, ""})};
            return {0, encode(SpaceInfoNotPresent{i->space})};
        }
        if (const auto* r = std::get_if<Read>(&m)) return {0, read(*r)};
        if (const auto* w = std::get_if<Write>(&m)) {
            if (w->space != Space::kConfig || w->address + w->data.size() > fd.size())
                return {0, encode(WriteReplyFail{w->space, w->address, ErrorCode::kOutOfBounds, "",
                                                 w->form})};
            std::copy(w->data.begin(), w->data.end(), fd.begin() + w->address);
            return {0, encode(WriteReply{w->space, w->address, w->form})};
        }
        if (const auto* w = std::get_if<WriteUnderMask>(&m)) {
            fd[w->address] = w->bytes[0].value;  // the bug: the mask is not applied
            return {0, encode(WriteReply{w->space, w->address, w->form})};
        }
        if (std::holds_alternative<UpdateComplete>(m)) return {};
        return {0x1041, {}};
    }

    std::vector<std::uint8_t> read(const memory::Read& r) const {
        using namespace memory;
        std::vector<std::uint8_t> bytes(cdi.begin(), cdi.end());
        bytes.push_back(0);
        if (r.space == Space::kConfig) bytes = fd;
        if (r.address >= bytes.size())
            return encode(ReadReplyFail{r.space, r.address, ErrorCode::kOutOfBounds, "", r.form});
        const std::size_t n = std::min<std::size_t>(r.count, bytes.size() - r.address);
        const auto reply = std::span(bytes).subspan(r.address, n);
        return encode(ReadReply{r.space, r.address, {reply.begin(), reply.end()}, r.form});
    }
};

TEST(MemoryBoundsTest, MaskIgnoredFailsAndTheByteIsPutBack) {
    SimNetwork net;
    MaskIgnoringNode script;
    testing::ScriptedNode node{net, MaskIgnoringNode::kId};
    node.answer = [&](const memory::Message& m) { return script.answer(m); };
    auto link = make_sim_link(net, kTool);
    Session session(*link);
    ASSERT_TRUE(session.start());
    auto info = session.find_node(MaskIgnoringNode::kId);
    ASSERT_TRUE(info);
    const Ran ran = run_specs(session, *info, checks::memory_bounds_checks(), crossing());
    const CheckResult& c = expect_status(ran.results, "memory.write-under-mask", Status::kFail);
    EXPECT_TRUE(contains(c.message, "left 0xA5 instead of 0x5A; restored")) << c.message;
    EXPECT_EQ(script.fd, (std::vector<std::uint8_t>{0x5A, 0x11}));
    const CheckResult& wl =
        expect_status(ran.results, "memory.options-write-lengths", Status::kFail);
    EXPECT_EQ(wl.seen, "0x80");
    expect_status(ran.results, "memory.write-past-end.fd", Status::kPass);
    expect_status(ran.results, "memory.read-past-end.fd", Status::kPass);
}

}  // namespace
}  // namespace olcb::conform
