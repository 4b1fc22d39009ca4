// The check registry: unique IDs in their categories, docs/checks.md generated from it, every
// OlcbChecker node check covered or said why not, and --only / --skip / --thorough selection.
#include "conformance/checks/check_registry.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <set>

#include "conformance/sim_bench.hpp"

namespace olcb::conform {
namespace {

TEST(CheckRegistryTest, IdsAreUniqueAndStartWithTheirCategory) {
    std::set<std::string_view> seen;
    for (const CheckSpec& s : check_registry()) {
        EXPECT_TRUE(seen.insert(s.id).second) << "duplicate " << s.id;
        const std::string_view first = s.id.substr(0, s.id.find('.'));
        EXPECT_EQ(first, category_name(s.category)) << s.id;
        EXPECT_FALSE(s.summary.empty()) << s.id;
        // Empty only where no standard rules the check (the transport, lcc-conform's own choice);
        // report_quality_test.cpp holds every other citation to the one style.
        const bool uncited =
            s.id == "link.lost" || s.id == "encoding.excluded" || s.id == "message.no-unsolicited";
        EXPECT_EQ(s.section.empty(), uncited) << s.id;
        EXPECT_TRUE(is_check_pattern(s.id)) << s.id;
    }
    EXPECT_GT(seen.size(), 60u);
}

// Families place their entries by order alone: two entries of one order would run in whichever
// order the families happen to be joined.
TEST(CheckRegistryTest, OrdersAreUniqueAndTheRegistryIsSortedByThem) {
    std::set<int> orders;
    int last = 0;
    for (const CheckSpec& s : check_registry()) {
        EXPECT_TRUE(orders.insert(s.order).second) << s.id << " shares order " << s.order;
        EXPECT_GT(s.order, last) << s.id;
        last = s.order;
    }
}

TEST(CheckRegistryTest, PerSpaceResultsFindTheirEntry) {
    const CheckSpec* s = find_check("memory.space-info-layout.fd");
    ASSERT_NE(s, nullptr);
    EXPECT_EQ(s->id, "memory.space-info-layout.<sp>");
    EXPECT_EQ(find_check("memory.space-info-layout.fdx"), nullptr);
    EXPECT_EQ(find_check("cdi.valid")->category, Category::kCdi);
    EXPECT_EQ(find_check("no.such-check"), nullptr);
}

// A FAIL of a check without a "shall" becomes a WARN that says why, in the standard's words
// where it has some ("should", "may"), and never quoting "none" as if the standard said it.
CheckResult failed(std::string_view id, std::string message) {
    CheckResult r;
    r.id = std::string(id);
    r.status = Status::kFail;
    r.message = std::move(message);
    return r;
}

TEST(CheckRegistryTest, CiteTurnsAFailWithoutShallIntoAWarnThatSaysWhy) {
    CheckResult none = failed("pip.datagram-bit", "bit clear");
    cite(none);
    EXPECT_EQ(none.status, Status::kWarn);
    EXPECT_EQ(none.message,
              "bit clear (a WARN, not a FAIL: no \"shall\" covers it, "
              "MessageNetworkS §3.3.7, §3.4.3)");
    CheckResult shall = failed("pip.acdi-bit", "bit clear");
    cite(shall);
    EXPECT_EQ(shall.status, Status::kFail);
    EXPECT_EQ(shall.message, "bit clear");
    for (const CheckSpec& s : check_registry()) {
        if (s.strength != Strength::kShould) continue;
        CheckResult should = failed(s.id, "x");
        cite(should);
        EXPECT_NE(should.message.find("the standard says \"should\" here"), std::string::npos)
            << should.message;
        break;
    }
}

TEST(CheckRegistryTest, DocsCarryTheGeneratedTables) {
    const std::string doc = read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "docs/checks.md");
    const std::string begin = "<!-- registry:begin -->\n";
    const std::string end = "<!-- registry:end -->";
    const auto b = doc.find(begin);
    const auto e = doc.find(end);
    ASSERT_NE(b, std::string::npos);
    ASSERT_NE(e, std::string::npos);
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), format_check_markdown())
        << "regenerate with: ci/update-checks-doc [BUILD_DIR]";
}

TEST(CheckRegistryTest, EveryOlcbCheckerNodeCheckIsCoveredOrSaysWhyNot) {
    std::set<std::string> named;
    for (const CheckSpec& s : check_registry()) {
        std::string_view list = s.olcbchecker;
        while (!list.empty()) {
            const auto comma = list.find(',');
            std::string one(list.substr(0, comma));
            one.erase(0, one.find_first_not_of(' '));
            named.insert(one);
            list = comma == std::string_view::npos ? "" : list.substr(comma + 1);
        }
    }
    for (const OlcbCheckerCheck& c : olcbchecker_checks()) {
        EXPECT_TRUE(named.count(std::string(c.id)) || !c.not_why.empty())
            << c.id << " is neither covered nor explained";
    }
    // Every OlcbChecker ID a check names is one of the inventory's.
    for (const std::string& n : named) {
        bool known = false;
        for (const OlcbCheckerCheck& c : olcbchecker_checks()) known = known || c.id == n;
        EXPECT_TRUE(known) << n;
    }
}

TEST(CheckSelectionTest, OnlySkipAndThorough) {
    CheckSelection all;
    EXPECT_TRUE(all.wants_id("cdi.valid"));
    EXPECT_TRUE(all.wants_writes());
    CheckSelection mem;
    mem.only = {"memory.*"};
    EXPECT_TRUE(mem.wants(*find_check("memory.lock")));
    EXPECT_FALSE(mem.wants(*find_check("cdi.valid")));
    EXPECT_TRUE(mem.wants(*find_check("memory.space-info-layout.fd")));
    EXPECT_FALSE(mem.wants_writes());
    CheckSelection one_space;
    one_space.only = {"memory.space-info-layout.fd"};
    EXPECT_TRUE(one_space.wants(*find_check("memory.space-info-layout.fd")));
    EXPECT_TRUE(one_space.wants_id("memory.space-info-layout.fd"));
    EXPECT_FALSE(one_space.wants_id("memory.space-info-layout.fb"));
    CheckSelection skip;
    skip.skip = {"encoding.*", "snip.follows-acdi-user-write", "events.*"};
    EXPECT_FALSE(skip.wants_writes());
    EXPECT_TRUE(skip.wants_id("cdi.valid"));
    for (const CheckSpec& s : check_registry()) {
        if (!s.thorough) continue;
        EXPECT_FALSE(all.wants(s)) << s.id;
        CheckSelection thorough;
        thorough.thorough = true;
        EXPECT_TRUE(thorough.wants(s)) << s.id;
    }
}

TEST(CheckSelectionTest, PatternsWithACategoryNameChecks) {
    EXPECT_TRUE(is_check_pattern("memory.*"));
    EXPECT_TRUE(is_check_pattern("frame.collision"));
    EXPECT_TRUE(is_check_pattern("events.*"));
    EXPECT_FALSE(is_check_pattern("*.Internal data.*"));
    EXPECT_FALSE(is_check_pattern("Settings.Trim"));
    EXPECT_FALSE(is_check_pattern("*"));
}

}  // namespace
}  // namespace olcb::conform
