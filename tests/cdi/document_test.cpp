// The typed model of a CDI (cdi/document.cpp): WideInt text, element kinds, and the walk over the
// element tree in document order.
#include "cdi/document.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace olcb::cdi {
namespace {

Element named(ElementKind kind, std::string name, std::vector<Element> children = {}) {
    Element e;
    e.kind = kind;
    e.name = std::move(name);
    e.children = std::move(children);
    return e;
}

TEST(Document, WideIntToString) {
    EXPECT_EQ(to_string(WideInt{0}), "0");
    EXPECT_EQ(to_string(WideInt{-123}), "-123");
    EXPECT_EQ(to_string(static_cast<WideInt>(18446744073709551615ULL)), "18446744073709551615");
    const WideInt min = -(static_cast<WideInt>(1) << 126) * 2;  // -2^127
    EXPECT_EQ(to_string(min), "-170141183460469231731687303715884105728");
    EXPECT_STREQ(kind_name(ElementKind::kEventId), "eventid");
    EXPECT_STREQ(kind_name(ElementKind::kUnknown), "unknown");
}

TEST(Document, WideIntExtremes) {
    const WideInt max = ~(static_cast<WideInt>(1) << 127);  // 2^127 - 1
    EXPECT_EQ(to_string(max), "170141183460469231731687303715884105727");
    EXPECT_EQ(to_string(WideInt{-1}), "-1");
    EXPECT_EQ(to_string(WideInt{10}), "10");
    EXPECT_EQ(to_string(-(WideInt{1} << 63)), "-9223372036854775808");
}

TEST(Document, EveryKindHasItsElementName) {
    const std::pair<ElementKind, const char*> kinds[] = {
        {ElementKind::kGroup, "group"},     {ElementKind::kInt, "int"},
        {ElementKind::kString, "string"},   {ElementKind::kEventId, "eventid"},
        {ElementKind::kFloat, "float"},     {ElementKind::kAction, "action"},
        {ElementKind::kBlob, "blob"},       {ElementKind::kBit, "bit"},
        {ElementKind::kUnknown, "unknown"},
    };
    for (const auto& [kind, name] : kinds) EXPECT_STREQ(kind_name(kind), name);
}

TEST(Document, ElementDefaultsAndPredicates) {
    Element e;
    EXPECT_EQ(e.kind, ElementKind::kUnknown);
    EXPECT_EQ(e.replication, 1u);
    EXPECT_EQ(e.offset, 0);
    EXPECT_EQ(e.size, 0u);
    EXPECT_FALSE(e.link);
    EXPECT_FALSE(e.map);
    EXPECT_TRUE(e.is_variable());
    EXPECT_FALSE(e.is_signed());
    e.int_min = WideInt{0};
    EXPECT_FALSE(e.is_signed());
    e.int_min = WideInt{-1};
    EXPECT_TRUE(e.is_signed());
    e.kind = ElementKind::kGroup;
    EXPECT_FALSE(e.is_variable());
    const Acdi acdi;
    EXPECT_EQ(acdi.fixed, 4u);
    EXPECT_EQ(acdi.var, 2u);
}

TEST(Document, WalkVisitsGroupsBeforeTheirChildrenWithTheirDepth) {
    const std::vector<Element> top = {
        named(ElementKind::kInt, "a"),
        named(ElementKind::kGroup, "g",
              {named(ElementKind::kString, "b"),
               named(ElementKind::kGroup, "h", {named(ElementKind::kEventId, "c")}),
               named(ElementKind::kGroup, "empty")}),
        named(ElementKind::kFloat, "d"),
    };
    std::vector<std::pair<std::string, std::size_t>> seen;
    walk_elements(top,
                  [&](const Element& e, std::size_t depth) { seen.emplace_back(e.name, depth); });
    EXPECT_EQ(seen, (std::vector<std::pair<std::string, std::size_t>>{
                        {"a", 0}, {"g", 0}, {"b", 1}, {"h", 1}, {"c", 2}, {"empty", 1}, {"d", 0}}));
    seen.clear();
    walk_elements(std::vector<Element>{},
                  [&](const Element& e, std::size_t depth) { seen.emplace_back(e.name, depth); });
    EXPECT_TRUE(seen.empty());
}

}  // namespace
}  // namespace olcb::cdi
