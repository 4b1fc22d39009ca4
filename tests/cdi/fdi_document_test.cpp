#include "cdi/fdi_document.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace olcb::cdi {
namespace {

FdiFunction function(std::uint32_t number, std::optional<std::size_t> group = std::nullopt) {
    FdiFunction f;
    f.number = number;
    f.group = group;
    return f;
}

FdiGroup group(std::optional<std::size_t> parent, std::size_t first_function) {
    FdiGroup g;
    g.parent = parent;
    g.first_function = first_function;
    return g;
}

// The walk as text: "F<n>" for a function, "(<g>" and ")<g>" for a group, each with its depth.
std::string trace(const FdiDocument& doc) {
    std::string out;
    doc.walk([&](const FdiStep& step) {
        if (!out.empty()) out += " ";
        switch (step.kind) {
            case FdiStep::Kind::kFunction:
                out += "F" + std::to_string(doc.functions[step.index].number);
                break;
            case FdiStep::Kind::kOpenGroup:
                out += "(" + std::to_string(step.index);
                break;
            case FdiStep::Kind::kCloseGroup:
                out += ")" + std::to_string(step.index);
                break;
        }
        out += "@" + std::to_string(step.depth);
    });
    return out;
}

TEST(FdiDocument, KindNames) {
    EXPECT_EQ(function_kind_name(FunctionKind::kBinary), "binary");
    EXPECT_EQ(function_kind_name(FunctionKind::kMomentary), "momentary");
    EXPECT_EQ(function_kind_name(FunctionKind::kAnalog), "analog");
}

TEST(FdiDocument, AnalogRangeDefaultsToZeroTo255) {
    FdiFunction f = function(3);
    f.kind = FunctionKind::kAnalog;
    EXPECT_EQ(f.value_min(), 0);
    EXPECT_EQ(f.value_max(), 255);
    f.min = 10;
    f.max = 20;
    EXPECT_EQ(f.value_min(), 10);
    EXPECT_EQ(f.value_max(), 20);
    EXPECT_FALSE(f.momentary());
    EXPECT_FALSE(f.latching());
    f.kind = FunctionKind::kBinary;
    EXPECT_TRUE(f.latching());
}

TEST(FdiDocument, FindReturnsTheFirstWithTheNumber) {
    FdiDocument doc;
    doc.functions = {function(4), function(7), function(4)};
    doc.functions[0].name = "first";
    doc.functions[2].name = "second";
    ASSERT_NE(doc.find(4), nullptr);
    EXPECT_EQ(doc.find(4)->name, "first");
    EXPECT_EQ(doc.find(5), nullptr);
}

TEST(FdiDocument, WalkKeepsDocumentOrder) {
    // <segment> F0 <group 0> F1 <group 1> F2 </group 1> </group 0> F3 <group 2/> F4
    FdiDocument doc;
    doc.functions = {function(0), function(1, 0), function(2, 1), function(3), function(4)};
    doc.groups = {group(std::nullopt, 1), group(0, 2), group(std::nullopt, 4)};
    EXPECT_EQ(trace(doc), "F0@0 (0@0 F1@1 (1@1 F2@2 )1@1 )0@0 F3@0 (2@0 )2@0 F4@0");
}

TEST(FdiDocument, WalkOfAHandBuiltModelPutsGroupsFirstAndBadIndicesInTheSegment) {
    FdiDocument doc;
    // A group naming itself or a later group as parent, a function naming no group that
    // exists: both count as the segment's, so nothing is lost and the walk ends.
    doc.groups = {group(0, 0), group(5, 0)};
    doc.functions = {function(1, 9), function(2, 1)};
    EXPECT_EQ(trace(doc), "(0@0 )0@0 (1@0 F2@1 )1@0 F1@0");
}

TEST(FdiDocument, WalkOfDeepNestingUsesNoRecursion) {
    FdiDocument doc;
    constexpr std::size_t kDepth = 100000;
    for (std::size_t i = 0; i < kDepth; ++i)
        doc.groups.push_back(group(i == 0 ? std::nullopt : std::optional(i - 1), 0));
    doc.functions = {function(9, kDepth - 1)};
    std::size_t deepest = 0;
    std::size_t steps = 0;
    doc.walk([&](const FdiStep& step) {
        deepest = std::max(deepest, step.depth);
        ++steps;
    });
    EXPECT_EQ(deepest, kDepth);
    EXPECT_EQ(steps, 2 * kDepth + 1);
}

}  // namespace
}  // namespace olcb::cdi
