// Deeply nested groups: a valid CDI of 200 or 1,000 nested groups is parsed, laid out, rendered
// and validated like any other; hostile nesting (100,000 and 1,000,000 levels) is refused with a
// diagnostic, quickly and without exhausting the stack (run under the ASan build too).
#include <gtest/gtest.h>

#include <chrono>
#include <cstddef>
#include <sstream>
#include <string>

#include "cdi/layout.hpp"
#include "cdi/memory_map.hpp"
#include "cdi/parser.hpp"
#include "cdi/render.hpp"
#include "cdi/rule_finding.hpp"
#include "cdi/validator.hpp"

namespace olcb::cdi {
namespace {

// A schema-valid CDI whose one variable sits under `depth` nested groups.
std::string nested_cdi(std::size_t depth) {
    std::string out =
        "<?xml version=\"1.0\"?>\n"
        "<cdi xmlns:xsi=\"http://www.w3.org/2001/XMLSchema-instance\" "
        "xsi:noNamespaceSchemaLocation=\"http://openlcb.org/schema/cdi/1/4/cdi.xsd\">\n"
        "<identification><manufacturer>Deep</manufacturer><model>Nest</model>"
        "<hardwareVersion>1</hardwareVersion><softwareVersion>1</softwareVersion>"
        "</identification>\n<acdi/>\n<segment space=\"253\" origin=\"0\"><name>S</name>\n";
    for (std::size_t i = 0; i < depth; ++i) {
        out += "<group><name>L" + std::to_string(i + 1) + "</name>\n";
    }
    out += "<int size=\"2\"><name>Leaf</name></int>\n";
    for (std::size_t i = 0; i < depth; ++i) out += "</group>\n";
    return out + "</segment>\n</cdi>\n";
}

// depth bare nested groups around nothing: no names, no variables, only nesting.
std::string hostile_cdi(std::size_t depth) {
    std::string out = "<?xml version=\"1.0\"?>\n<cdi><segment space=\"253\">";
    out.reserve(out.size() + depth * 15 + 32);
    for (std::size_t i = 0; i < depth; ++i) out += "<group>";
    for (std::size_t i = 0; i < depth; ++i) out += "</group>";
    return out + "</segment></cdi>\n";
}

std::string first_error(const Diagnostics& diagnostics) {
    for (const Diagnostic& d : diagnostics) {
        if (d.severity == Severity::kError) return d.message;
    }
    return {};
}

class ValidDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ValidDeepNesting, ParsesLaysOutRendersAndValidates) {
    const std::size_t depth = GetParam();
    const std::string text = nested_cdi(depth);

    ParseResult parsed = parse(text);
    ASSERT_TRUE(parsed.document) << first_error(parsed.diagnostics);
    const Element* e = &parsed.document->segments.at(0).children.at(0);
    for (std::size_t level = 1; level < depth; ++level) {
        ASSERT_EQ(e->kind, ElementKind::kGroup);
        ASSERT_EQ(e->children.size(), 1u);
        e = &e->children[0];
    }
    ASSERT_EQ(e->children.size(), 1u);
    EXPECT_EQ(e->children[0].name, "Leaf");

    LayoutResult laid = build_layout(*parsed.document);
    ASSERT_TRUE(laid.layout) << first_error(laid.diagnostics);
    EXPECT_EQ(laid.layout->variable_count(), 1u);
    const Cursor c = laid.layout->begin();
    ASSERT_TRUE(c.valid());
    EXPECT_EQ(c.group_depth(), depth);
    EXPECT_EQ(c.element().name, "Leaf");
    EXPECT_EQ(c.address(), 0u);
    EXPECT_EQ(laid.layout->find(253, 1).ordinal(), 0u);
    EXPECT_NE(c.path().find("L" + std::to_string(depth) + "/Leaf"), std::string::npos);

    std::ostringstream rendered;
    render(*laid.layout, rendered);
    EXPECT_NE(rendered.str().find("\"Leaf\""), std::string::npos);
    EXPECT_EQ(build_memory_map(*laid.layout).at(0).variable_count, 1u);

    const ValidationReport report = validate(text);
    EXPECT_TRUE(report.ok()) << first_error(report.diagnostics);
    EXPECT_TRUE(report.schema.well_formed);
    EXPECT_TRUE(report.parsed);
    for (const RuleFinding& f : check_rules(text)) {
        if (f.check_id == "cdi.valid" || f.check_id == "cdi.well-formed") {
            EXPECT_NE(f.status, RuleStatus::kFail) << f.check_id << ": " << f.message;
        }
    }
}

INSTANTIATE_TEST_SUITE_P(Depths, ValidDeepNesting, ::testing::Values(200, 1000));

TEST(DeepNesting, GroupsBeyondTheLimitAreRefusedByParserAndValidator) {
    const std::string text = nested_cdi(kMaxGroupDepth + 1);
    const ParseResult parsed = parse(text);
    EXPECT_FALSE(parsed.document);
    EXPECT_NE(first_error(parsed.diagnostics).find("nested deeper"), std::string::npos);
    const ValidationReport report = validate(text);
    EXPECT_FALSE(report.ok());
    EXPECT_FALSE(report.parsed);
}

class HostileDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(HostileDeepNesting, IsRefusedQuicklyWithADiagnostic) {
    const std::string text = hostile_cdi(GetParam());
    ASSERT_LE(text.size(), kMaxCdiBytes);
    const auto start = std::chrono::steady_clock::now();
    const ParseResult parsed = parse(text);
    EXPECT_FALSE(parsed.document);
    EXPECT_NE(first_error(parsed.diagnostics).find("nested deeper"), std::string::npos);
    const ValidationReport report = validate(text);
    EXPECT_FALSE(report.ok());
    EXPECT_FALSE(report.parsed);
    EXPECT_NE(first_error(report.diagnostics).find("nested deeper"), std::string::npos);
    // Generous for sanitizer builds on a loaded machine; linear work takes well under a second.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

INSTANTIATE_TEST_SUITE_P(Depths, HostileDeepNesting, ::testing::Values(100000, 1000000));

}  // namespace
}  // namespace olcb::cdi
