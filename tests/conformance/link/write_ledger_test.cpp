// The write ledger (conformance/link/write_ledger.hpp): every write recorded before it goes out,
// its gate's refusal kept, and the bytes past the end counted once each.
#include "conformance/link/write_ledger.hpp"

#include <gtest/gtest.h>

namespace olcb::conform {
namespace {

constexpr NodeId kNode{0x050101012200ull};
constexpr NodeId kOther{0x050101012201ull};

PlannedWrite write_of(std::uint8_t space, std::uint32_t address, std::size_t n,
                      NodeId node = kNode) {
    return {node, space, address, std::vector<std::uint8_t>(n, 0xAA), {}, false};
}

TEST(WriteLedgerTest, RecordsEveryWriteWithItsOriginAndOutcome) {
    WriteLedger ledger;
    std::string why;
    {
        WriteLedger::Origin origin(ledger, "memory.write-under-mask");
        const auto a = ledger.open(write_of(0xFB, 1, 1), why);
        ASSERT_TRUE(a);
        ledger.close(*a, WriteOutcome::kAccepted);
    }
    const auto b = ledger.open(write_of(0xFD, 0, 4), why);
    ASSERT_TRUE(b);
    ledger.close(*b, WriteOutcome::kNoAnswer);
    ASSERT_EQ(ledger.entries().size(), 2u);
    EXPECT_EQ(ledger.entries()[0].origin, "memory.write-under-mask");
    EXPECT_EQ(ledger.entries()[1].origin, "");
    EXPECT_EQ(ledger.entries()[1].outcome, WriteOutcome::kNoAnswer);
    EXPECT_EQ(ledger.sent(kNode), 2u);
    EXPECT_EQ(ledger.sent(kOther), 0u);
}

TEST(WriteLedgerTest, AWriteTheGateRefusesIsRecordedButNotSent) {
    WriteLedger ledger;
    ledger.set_gate([](const PlannedWrite& w, bool) {
        return GateDecision{w.space != 0xFD, "cannot be saved", 0};
    });
    std::string why;
    EXPECT_FALSE(ledger.open(write_of(0xFD, 0, 1), why));
    EXPECT_EQ(why, "cannot be saved");
    EXPECT_TRUE(ledger.open(write_of(0xFB, 1, 1), why));
    ASSERT_EQ(ledger.entries().size(), 2u);
    EXPECT_EQ(ledger.entries()[0].outcome, WriteOutcome::kNotSent);
    EXPECT_EQ(ledger.entries()[0].refused_why, "cannot be saved");
    EXPECT_EQ(ledger.sent(kNode), 1u);  // pending counts: the node saw it
}

TEST(WriteLedgerTest, BytesPastTheEndNeedThePermitOfTheirSpace) {
    WriteLedger ledger;
    ledger.set_gate([](const PlannedWrite&, bool) { return GateDecision{true, "", 1}; });
    std::string why;
    EXPECT_FALSE(ledger.open(write_of(0xFD, 0x156, 2), why)) << "no permit";
    EXPECT_NE(why.find("--write-past-end"), std::string::npos) << why;
    {
        WriteLedger::PastEndPermit permit(ledger, 0xFB);
        EXPECT_FALSE(ledger.open(write_of(0xFD, 0x156, 2), why)) << "another space's permit";
    }
    WriteLedger::PastEndPermit permit(ledger, 0xFD);
    const auto i = ledger.open(write_of(0xFD, 0x156, 2), why);
    ASSERT_TRUE(i) << why;
    EXPECT_EQ(ledger.entries()[*i].past_end, 1u);
}

TEST(WriteLedgerTest, UnrestorableBytesAreThoseOfAcceptedOrUnansweredWrites) {
    WriteLedger ledger;
    ledger.set_gate([](const PlannedWrite&, bool) { return GateDecision{true, "", 1}; });
    std::string why;
    WriteLedger::PastEndPermit fd(ledger, 0xFD);
    // The same byte past the end twice, and one refused crossing write: one byte kept.
    ledger.close(*ledger.open(write_of(0xFD, 0x156, 2), why), WriteOutcome::kAccepted);
    ledger.close(*ledger.open(write_of(0xFD, 0x156, 2), why), WriteOutcome::kNoAnswer);
    {
        WriteLedger::PastEndPermit fb(ledger, 0xFB);
        ledger.close(*ledger.open(write_of(0xFB, 0x7F, 2), why), WriteOutcome::kRefused);
    }
    {
        WriteLedger::Restoring restoring(ledger);
        ledger.close(*ledger.open(write_of(0xFD, 0x156, 2), why), WriteOutcome::kAccepted);
    }
    const auto kept = ledger.unrestorable(kNode);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0].space, 0xFD);
    EXPECT_EQ(kept[0].address, 0x157u);
    EXPECT_EQ(kept[0].count, 1u);
    EXPECT_EQ(ledger.sent(kNode), 3u) << "the restore's own write is not the run's";
    EXPECT_TRUE(ledger.unrestorable(kOther).empty());
}

TEST(WriteLedgerTest, SavingAheadAsksTheGateWithoutRecording) {
    WriteLedger ledger;
    std::string why;
    EXPECT_TRUE(ledger.save_ahead(kNode, 0xFD, 0, 16, why)) << "no gate: nothing to save";
    std::uint32_t asked = 0;
    ledger.set_gate([&](const PlannedWrite& w, bool past_end) {
        asked = static_cast<std::uint32_t>(w.data.size());
        EXPECT_FALSE(past_end);
        return GateDecision{false, "unreadable", 0};
    });
    EXPECT_FALSE(ledger.save_ahead(kNode, 0xFD, 0, 16, why));
    EXPECT_EQ(why, "unreadable");
    EXPECT_EQ(asked, 16u);
    EXPECT_TRUE(ledger.entries().empty());
}

TEST(WriteLedgerTest, TouchedAreTheBytesOfWritesThatReachedTheNode) {
    WriteLedger ledger;
    ledger.set_gate([](const PlannedWrite& w, bool) {
        return GateDecision{w.address != 0x40, "cannot be saved", 0};
    });
    std::string why;
    ledger.close(*ledger.open(write_of(0xFD, 0x10, 4), why), WriteOutcome::kRefused);
    EXPECT_FALSE(ledger.open(write_of(0xFD, 0x40, 4), why)) << "refused by the gate";
    EXPECT_TRUE(ledger.touched(kNode, 0xFD, 0x13, 1)) << "its last byte";
    EXPECT_TRUE(ledger.touched(kNode, 0xFD, 0x00, 0x11)) << "its first byte";
    EXPECT_FALSE(ledger.touched(kNode, 0xFD, 0x14, 8)) << "just after it";
    EXPECT_FALSE(ledger.touched(kNode, 0xFD, 0x0C, 4)) << "just before it";
    EXPECT_FALSE(ledger.touched(kNode, 0xFB, 0x10, 4)) << "another space";
    EXPECT_FALSE(ledger.touched(kOther, 0xFD, 0x10, 4)) << "another node";
    EXPECT_FALSE(ledger.touched(kNode, 0xFD, 0x40, 4)) << "never sent";
}

TEST(WriteLedgerTest, AWriteCrossingTheEndMayHaveTouchedAnything) {
    WriteLedger ledger;
    ledger.set_gate([](const PlannedWrite&, bool) { return GateDecision{true, "", 1}; });
    WriteLedger::PastEndPermit permit(ledger, 0xFD);
    std::string why;
    EXPECT_FALSE(ledger.touched(kNode, 0xFB, 0x10, 4));
    ledger.close(*ledger.open(write_of(0xFD, 0x156, 2), why), WriteOutcome::kAccepted);
    EXPECT_TRUE(ledger.touched(kNode, 0xFB, 0x10, 4)) << "a spill may land in another space";
    EXPECT_FALSE(ledger.touched(kOther, 0xFB, 0x10, 4));
}

}  // namespace
}  // namespace olcb::conform
