// The check registry: unique IDs in their categories, docs/checks.md generated from it, every
// OlcbChecker node check covered or said why not, and --only / --skip / --thorough selection.
#include "conformance/checks/check_registry.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <set>
#include <sstream>

#include "conformance/conform_test_util.hpp"
#include "conformance/run/runner.hpp"
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

TEST(CheckRunTest, IdsAreUniqueInADefaultNodesProtocolChecks) {
    testing::SimBench b;
    CheckContext ctx;
    auto results = b.run(ctx);
    ASSERT_FALSE(results.empty());
    std::set<std::string> ids;
    for (const CheckResult& r : results) {
        EXPECT_TRUE(ids.insert(r.id).second) << "duplicate " << r.id;
        const CheckSpec* spec = find_check(r.id);
        ASSERT_NE(spec, nullptr) << r.id << " is not in the registry";
        EXPECT_EQ(r.category, spec->category) << r.id;
    }
}

TEST(CheckRunTest, OnlyRunsTheSelectedChecks) {
    testing::SimBench b;
    auto node = b.start();
    ASSERT_TRUE(node);
    CheckContext ctx;
    ProtocolOptions o;
    o.selection.only = {"pip.*"};
    const std::size_t frames = b.session->frame_mark();
    auto results = run_protocol_checks(*b.session, *node, o, ctx);
    ASSERT_FALSE(results.empty());
    for (const CheckResult& r : results) EXPECT_TRUE(r.id.starts_with("pip.")) << r.id;
    // The PIP checks still judge: they asked what they needed (SNIP, Options, the CDI).
    for (const CheckResult& r : results) EXPECT_EQ(r.status, Status::kPass) << r.id << r.message;
    EXPECT_GT(b.session->frame_mark(), frames);
}

}  // namespace
}  // namespace olcb::conform

namespace olcb::conform {
namespace {

// The whole run, every check of the registry (--thorough and --reboot too), in-process: no false
// failure on the project's two scenarios.
void expect_no_failure_in_process(const std::string& cdi_file) {
    const std::string cdi =
        read_text(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / cdi_file);
    testing::SimBench b({}, cdi);
    auto node = b.start();
    ASSERT_TRUE(node);
    RunOptions options;
    options.reboot = true;
    options.selection.thorough = true;
    options.backup_path = (std::filesystem::temp_directory_path() /
                           ("registry_full_" + cdi_file + std::to_string(::getpid())))
                              .string();
    ProtocolChecks checks = [&](Session& s, const NodeInfo& n, CheckContext& ctx) {
        ProtocolOptions o;
        o.reboot = true;
        o.selection = options.selection;
        return run_protocol_checks(s, n, o, ctx);
    };
    std::ostringstream progress;
    const NodeReport report = run_node(*b.session, *node, options, checks, progress);
    std::set<std::string> ids;
    for (const CheckResult& c : report.checks) {
        EXPECT_NE(c.status, Status::kFail) << cdi_file << ": " << c.id << " " << c.message;
        EXPECT_TRUE(ids.insert(c.id).second) << "duplicate " << c.id;
    }
    EXPECT_GT(report.checks.size(), 80u);
    EXPECT_NE(report.restore_summary.find("byte-identical"), std::string::npos)
        << report.restore_summary;
}

TEST(CheckRunTest, DefaultScenarioHasNoFailureInProcess) {
    expect_no_failure_in_process("default.xml");
}

TEST(CheckRunTest, IoBoardScenarioHasNoFailureInProcess) {
    expect_no_failure_in_process("io-board.xml");
}

}  // namespace
}  // namespace olcb::conform
