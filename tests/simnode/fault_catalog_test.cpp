// The fault declarations (simnode/faults/): complete and consistent, and docs/faults.md carries
// the table generated from them.
#include "simnode/faults/fault_catalog.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

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

TEST(FaultCatalogTest, EveryDeclarationIsComplete) {
    std::set<std::string_view> names;
    for (const FaultDecl& d : fault_decls()) {
        EXPECT_TRUE(names.insert(d.name).second) << "declared twice: " << d.name;
        EXPECT_FALSE(d.summary.empty()) << d.name;
        EXPECT_FALSE(d.rule_broken.empty()) << d.name;
        EXPECT_FALSE(d.client_sees.empty()) << d.name;
        EXPECT_TRUE(d.access.apply && d.access.read) << d.name;
        // Only a fault a careful client copes with may lack a category.
        EXPECT_TRUE(!d.category.empty() || d.verdict == Verdict::kNone) << d.name;
        EXPECT_EQ(d.param.kind == ParamKind::kNone, d.doc_parameter.empty()) << d.name;
        for (const auto id : d.checks) {
            EXPECT_TRUE(id.starts_with(d.category)) << d.name << ": " << id;
        }
    }
}

TEST(FaultCatalogTest, EachFaultSetsAndReadsBackOnlyItsOwnFields) {
    for (const FaultDecl& d : fault_decls()) {
        std::string error;
        const auto one = parse_faults({std::string(d.name)}, error);
        ASSERT_TRUE(one) << error;
        EXPECT_FALSE(one->none()) << d.name;
        EXPECT_NE(d.access.read(*one), FaultValue{}) << d.name;
        for (const FaultDecl& other : fault_decls()) {
            if (other.name != d.name) EXPECT_EQ(other.access.read(*one), FaultValue{}) << d.name;
        }
    }
}

TEST(FaultCatalogTest, ParametersAndCategoriesReadAsBefore) {
    EXPECT_EQ(help_parameter(*find_fault("pip-missing-bit")),
              "cdi|acdi|snip|datagram|memory|events (default cdi)");
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
