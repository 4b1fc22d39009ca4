// The rule registry of the client audit: names unique and found, levels named, and
// docs/audit.md lists the registry exactly.
#include "simnode/audit/audit_rule.hpp"

#include <gtest/gtest.h>

#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "simnode/sim_node_test_util.hpp"

namespace olcb::simnode::audit {
namespace {

// docs/audit.md: the table between <!-- rules:begin --> and <!-- rules:end -->, one row per
// rule in registry order: | `id` | level | standard | ...
TEST(AuditDoc, ListsEveryRuleWithItsLevelAndStandardInOrder) {
    const std::string doc = simnode::test::read_source_file("docs/audit.md");
    const auto begin = doc.find("<!-- rules:begin -->");
    const auto end = doc.find("<!-- rules:end -->");
    ASSERT_NE(begin, std::string::npos);
    ASSERT_NE(end, std::string::npos);
    std::istringstream table(doc.substr(begin, end - begin));
    std::vector<std::vector<std::string>> rows;
    for (std::string line; std::getline(table, line);) {
        if (!line.starts_with("| `")) continue;
        std::vector<std::string> cells;
        std::istringstream cols(line.substr(1));
        for (std::string cell; std::getline(cols, cell, '|');) {
            const auto a = cell.find_first_not_of(' ');
            const auto b = cell.find_last_not_of(' ');
            cells.push_back(a == std::string::npos ? "" : cell.substr(a, b - a + 1));
        }
        rows.push_back(cells);
    }
    ASSERT_EQ(rows.size(), rules().size());
    for (std::size_t i = 0; i < rows.size(); ++i) {
        const Rule& r = rules()[i];
        ASSERT_GE(rows[i].size(), 5u) << i;
        EXPECT_EQ(rows[i][0], "`" + std::string(r.name) + "`");
        EXPECT_EQ(rows[i][1], level_name(r.level)) << r.name;
        EXPECT_EQ(rows[i][2], r.standard) << r.name;
    }
}

TEST(AuditRules, IdsAreUniqueAndFoundByName) {
    std::set<std::string_view> names;
    for (const Rule& r : rules()) {
        EXPECT_TRUE(names.insert(r.name).second) << r.name;
        EXPECT_EQ(&rule(r.id), &r);
        EXPECT_EQ(find_rule(r.name), &r);
    }
    EXPECT_EQ(find_rule("no.such-rule"), nullptr);
}

TEST(AuditRules, EveryRuleCitesAClause) {
    for (const Rule& r : rules()) {
        EXPECT_NE(r.standard.find("§"), std::string_view::npos) << r.name;
        EXPECT_FALSE(r.summary.empty()) << r.name;
    }
}

// The levels follow the standards' words (docs/audit.md, "Rules"): a few that are easy to get
// wrong, pinned.
TEST(AuditRules, LevelsFollowTheWordsOfTheClausesCited) {
    // No "shall" forbids another request once the OK came (DatagramTransportS §6.1).
    EXPECT_EQ(rule(RuleId::kMemoryRequestBeforeReply).level, Level::kNote);
    // "Configuration tools should send it" (MemoryConfigurationS §4.23).
    EXPECT_EQ(rule(RuleId::kMemoryNoUpdateComplete).level, Level::kWarning);
    // "shall not transmit any other message type" (MessageNetworkS §3.2).
    EXPECT_EQ(rule(RuleId::kMessageBeforeInitComplete).level, Level::kError);
    // "Such a timeout shall not be shorter than 3 seconds" (MessageNetworkS §3.7).
    EXPECT_EQ(rule(RuleId::kDatagramResendBeforeTimeout).level, Level::kError);
    EXPECT_EQ(rule(RuleId::kDatagramResendAfterOk).level, Level::kError);
    // "a node shall: ... Wait at least 200 milliseconds" (CanFrameTransferS §6.2.1).
    EXPECT_EQ(rule(RuleId::kAliasRidTooEarly).level, Level::kError);
    // "shall send messages required ... within 750 milliseconds" (MessageNetworkS §3.7).
    EXPECT_EQ(rule(RuleId::kDatagramReplyAckLate).level, Level::kError);
}

TEST(AuditRules, LevelsAreNamedAsReportsWriteThem) {
    EXPECT_EQ(level_name(Level::kError), "error");
    EXPECT_EQ(level_name(Level::kWarning), "warning");
    EXPECT_EQ(level_name(Level::kNote), "note");
}

TEST(AuditRules, TheRegistryIsInRuleIdOrderFromFirstToLast) {
    ASSERT_FALSE(rules().empty());
    for (std::size_t i = 0; i < rules().size(); ++i)
        EXPECT_EQ(static_cast<std::size_t>(rules()[i].id), i) << rules()[i].name;
    EXPECT_EQ(rules().back().id, RuleId::kMemoryNoUpdateComplete);
    EXPECT_EQ(rule(RuleId::kAliasUnreserved).name, "alias.unreserved");
    EXPECT_EQ(rule(RuleId::kAliasUnreserved).level, Level::kError);
}

}  // namespace
}  // namespace olcb::simnode::audit
