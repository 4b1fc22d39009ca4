// FindingLog: repeats of one violation count on its first finding, times count from the start,
// the frames and the number of findings kept are bounded.
#include "simnode/audit/finding.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

using namespace std::chrono_literals;

const TimePoint kStart = TimePoint{} + 100s;

Finding finding(RuleId rule, std::uint16_t alias, std::uint64_t connection = 1) {
    Finding f;
    f.rule = rule;
    f.message = "what the client did";
    f.client.alias = alias;
    f.client.connection = connection;
    return f;
}

TEST(FindingLog, TheSameViolationAgainOnlyCountsAndMovesItsLastTime) {
    FindingLog log(kStart);
    log.add(finding(RuleId::kAliasUnreserved, 0x12C), "", kStart + 1500ms);
    log.add(finding(RuleId::kAliasUnreserved, 0x12C), "", kStart + 4s);
    ASSERT_EQ(log.findings().size(), 1u);
    const Finding& f = log.findings()[0];
    EXPECT_EQ(f.count, 2u);
    EXPECT_DOUBLE_EQ(f.time, 1.5);
    EXPECT_DOUBLE_EQ(f.last_time, 4.0);
    EXPECT_EQ(log.revision(), 2u) << "a count is a change a writer must see";
    EXPECT_EQ(log.dropped(), 0u);
}

TEST(FindingLog, RuleClientConnectionNodeAndKeyEachTellFindingsApart) {
    FindingLog log(kStart);
    log.add(finding(RuleId::kCdiIntOutOfRange, 0x12C), "FD:00000001", kStart);
    log.add(finding(RuleId::kCdiIntOutOfRange, 0x12C), "FD:00000002", kStart);  // key
    log.add(finding(RuleId::kCdiNotInMap, 0x12C), "FD:00000001", kStart);       // rule
    log.add(finding(RuleId::kCdiIntOutOfRange, 0x12D), "FD:00000001", kStart);  // alias
    log.add(finding(RuleId::kCdiIntOutOfRange, 0x12C, 2), "FD:00000001", kStart);
    auto at_node = finding(RuleId::kCdiIntOutOfRange, 0x12C);
    at_node.node = NodeRef{NodeId(0x050101012200), 0x343};
    log.add(at_node, "FD:00000001", kStart);
    ASSERT_EQ(log.findings().size(), 6u);
    for (const Finding& f : log.findings()) EXPECT_EQ(f.count, 1u);
    EXPECT_EQ(log.findings()[1].rule, RuleId::kCdiIntOutOfRange) << "kept in order";
    EXPECT_EQ(log.findings()[2].rule, RuleId::kCdiNotInMap);
}

TEST(FindingLog, KeepsTheFirstFramesOfAFindingOnly) {
    FindingLog log(kStart);
    auto f = finding(RuleId::kDatagramFrameSequence, 0x12C);
    for (std::size_t i = 0; i < kMaxFindingFrames + 3; ++i)
        f.frames.push_back(":X1B34312CN" + std::to_string(i) + ";");
    log.add(f, "", kStart);
    ASSERT_EQ(log.findings()[0].frames.size(), kMaxFindingFrames);
    EXPECT_EQ(log.findings()[0].frames.front(), ":X1B34312CN0;");
}

TEST(FindingLog, BeyondItsBoundNewFindingsAreCountedAsDroppedButRepeatsStillCount) {
    FindingLog log(kStart);
    for (std::size_t i = 0; i < kMaxFindings; ++i)
        log.add(finding(RuleId::kMemoryReadPastEnd, 0x12C), std::to_string(i), kStart);
    log.add(finding(RuleId::kMemoryReadPastEnd, 0x12C), "one more", kStart + 1s);
    log.add(finding(RuleId::kMemoryReadPastEnd, 0x12C), "0", kStart + 2s);
    EXPECT_EQ(log.findings().size(), kMaxFindings);
    EXPECT_EQ(log.dropped(), 1u);
    EXPECT_EQ(log.findings()[0].count, 2u);
    EXPECT_DOUBLE_EQ(log.seconds(kStart + 2s), 2.0);
}

}  // namespace
}  // namespace olcb::simnode::audit
