// The fault declarations (simnode/faults/): complete and consistent, and docs/faults.md carries
// the table generated from them.
#include "simnode/faults/fault_catalog.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {
namespace {

std::string read_doc(const std::filesystem::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

TEST(FaultCatalogTest, DocsCarryTheGeneratedTable) {
    const std::string doc = read_doc(std::filesystem::path(OLCB_SOURCE_DIR) / "docs/faults.md");
    const std::string begin = "<!-- faults:begin -->\n";
    const std::string end = "<!-- faults:end -->";
    const auto b = doc.find(begin);
    const auto e = doc.find(end);
    ASSERT_NE(b, std::string::npos);
    ASSERT_NE(e, std::string::npos);
    EXPECT_EQ(doc.substr(b + begin.size(), e - b - begin.size()), format_fault_markdown())
        << "regenerate with: ci/update-faults-doc [BUILD_DIR]";
}

// README says how many faults there are, twice: ci/update-faults-doc writes both from the table.
TEST(FaultCatalogTest, ReadmeCountsTheDeclarations) {
    const std::string readme = read_doc(std::filesystem::path(OLCB_SOURCE_DIR) / "README.md");
    const std::string n = std::to_string(fault_decls().size());
    EXPECT_NE(readme.find("with " + n + " named faults"), std::string::npos)
        << "regenerate with: ci/update-faults-doc [BUILD_DIR]";
    EXPECT_TRUE(std::regex_search(readme, std::regex("each of the\\s+" + n + " faults")))
        << "regenerate with: ci/update-faults-doc [BUILD_DIR]";
}

TEST(FaultCatalogTest, EveryDeclarationIsComplete) {
    std::set<std::string_view> names;
    for (const FaultDecl& d : fault_decls()) {
        EXPECT_TRUE(names.insert(d.name).second) << "declared twice: " << d.name;
        EXPECT_FALSE(d.summary.empty()) << d.name;
        EXPECT_FALSE(d.rule_broken.empty()) << d.name;
        EXPECT_FALSE(d.client_sees.empty()) << d.name;
        // Its hooks are all a fault does: without one it would change nothing.
        EXPECT_NE(d.hooks, FaultHooks{}) << d.name << " would change nothing";
        // Only a fault a careful client copes with may lack a category.
        EXPECT_TRUE(!d.category.empty() || d.verdict == Verdict::kNone) << d.name;
        EXPECT_EQ(d.param.kind == ParamKind::kNone, d.doc_parameter.empty()) << d.name;
        for (const auto id : d.checks) {
            EXPECT_TRUE(id.starts_with(d.category)) << d.name << ": " << id;
        }
    }
}

TEST(FaultCatalogTest, EachFaultSetsOnlyItself) {
    for (const FaultDecl& d : fault_decls()) {
        std::string error;
        const auto one = parse_faults({std::string(d.name)}, error);
        ASSERT_TRUE(one) << error;
        EXPECT_FALSE(one->none()) << d.name;
        EXPECT_NE(fault_value(*one, d), FaultValue{}) << d.name;
        for (const FaultDecl& other : fault_decls()) {
            if (other.name != d.name) {
                EXPECT_EQ(fault_value(*one, other), FaultValue{}) << d.name;
            }
        }
    }
}

TEST(FaultCatalogTest, OrdersAreUniqueAndTheCatalogueIsSortedByThem) {
    std::set<int> orders;
    int last = 0;
    for (const FaultDecl& d : fault_decls()) {
        EXPECT_TRUE(orders.insert(d.order).second) << d.name << ": order " << d.order << " taken";
        EXPECT_GT(d.order, last) << d.name;
        last = d.order;
    }
}

TEST(FaultCatalogTest, EveryFamilyFileIsInTheGeneratedList) {
    std::size_t files = 0;
    const auto dir = std::filesystem::path(OLCB_SOURCE_DIR) / "simnode/faults";
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        if (e.path().stem().string().ends_with("_faults") && e.path().extension() == ".cpp")
            ++files;
    }
    EXPECT_EQ(fault_families().size(), files);
    std::size_t declared = 0;
    for (const FaultFamily family : fault_families()) declared += family().size();
    EXPECT_EQ(declared, fault_decls().size());
}

TEST(FaultCatalogTest, ParametersAndCategoriesReadAsBefore) {
    EXPECT_EQ(help_parameter(*find_fault("pip-missing-bit")),
              "cdi|acdi|snip|datagram|memory|events (default acdi)");
    EXPECT_EQ(help_parameter(*find_fault("latency")), "MS[:JITTER] (default 200)");
    EXPECT_EQ(help_parameter(*find_fault("reject-temporary")), "N (default 3)");
    EXPECT_EQ(help_parameter(*find_fault("write-dropped")), "");
    EXPECT_EQ(category_column(*find_fault("latency")), "none (above 750 ms: message)");
    EXPECT_EQ(category_column(*find_fault("reboot-on-write")), "node (incomplete)");
    EXPECT_EQ(category_column(*find_fault("reply-form")), "memory (warn)");
    EXPECT_EQ(category_column(*find_fault("reject-temporary")), "datagram");
    EXPECT_EQ(find_fault("no-such-fault"), nullptr);
}

TEST(FaultCatalogTest, JsonListsEveryFault) {
    const std::string json = format_fault_json();
    for (const FaultDecl& d : fault_decls()) {
        EXPECT_NE(json.find("\"name\": \"" + std::string(d.name) + "\""), std::string::npos);
    }
}

}  // namespace
}  // namespace olcb::simnode
