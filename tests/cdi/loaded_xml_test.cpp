// One pugixml parse of a CDI text kept with its source (cdi/loaded_xml.cpp): trailing NULs
// dropped, elements' byte offsets in the source, the last element of a subtree.
#include "cdi/loaded_xml.hpp"

#include <gtest/gtest.h>

#include <string>
#include <string_view>
#include <tuple>

namespace olcb::cdi {
namespace {

using namespace std::string_literals;

TEST(LoadedXml, TrailingNulsAreNotPartOfTheText) {
    EXPECT_EQ(without_trailing_nuls("<cdi/>\0\0\0"s), "<cdi/>");
    EXPECT_EQ(without_trailing_nuls("a\0b\0"s), "a\0b"s);  // only the trailing ones
    EXPECT_EQ(without_trailing_nuls("\0\0"s), "");
    EXPECT_EQ(without_trailing_nuls(""), "");
    const std::string bytes = "<cdi><segment space='1'/></cdi>\0\0"s;
    const LoadedXml xml(bytes);
    EXPECT_EQ(xml.text(), "<cdi><segment space='1'/></cdi>");
    EXPECT_EQ(xml.text().data(), bytes.data());  // a view of the caller's bytes
    ASSERT_TRUE(xml.result());
    EXPECT_EQ(std::string(xml.document().document_element().name()), "cdi");
}

TEST(LoadedXml, ParseErrorsAreReportedWithTheirOffset) {
    const LoadedXml xml("<cdi>\n<segment>\n</cdi>");
    EXPECT_FALSE(xml.result());
    EXPECT_EQ(xml.result().status, pugi::status_end_element_mismatch);
    EXPECT_GT(xml.result().offset, 0);
}

TEST(LoadedXml, ADoctypeIsKeptAsANode) {
    const LoadedXml xml(
        "<?xml version=\"1.0\"?>\n<!DOCTYPE cdi [<!ENTITY a \"b\">]>\n<cdi>&a;</cdi>");
    ASSERT_TRUE(xml.result());
    bool doctype = false;
    for (pugi::xml_node n : xml.document().children()) doctype |= n.type() == pugi::node_doctype;
    EXPECT_TRUE(doctype);
}

TEST(LoadedXml, SourceOffsetsPointAtElementNamesInTheOriginalText) {
    const std::string text = "<cdi>\n  <segment space=\"253\">\n    <int/>\n  </segment>\n</cdi>";
    const LoadedXml xml(text);
    ASSERT_TRUE(xml.result());
    const pugi::xml_node cdi = xml.document().document_element();
    const pugi::xml_node segment = cdi.child("segment");
    const pugi::xml_node leaf = segment.child("int");
    EXPECT_EQ(xml.text().substr(source_offset(segment), 7), "segment");
    EXPECT_EQ(source_offset(segment), text.find("segment"));
    EXPECT_EQ(source_offset(leaf), text.find("int"));
    EXPECT_EQ(source_offset(cdi), text.find("cdi"));
    EXPECT_EQ(source_offset(pugi::xml_node()), 0u);
}

TEST(LoadedXml, LastElementOfASubtreeAndItsDepth) {
    const LoadedXml xml("<cdi><a><b/><c><d/><e>text</e><!-- after --></c></a><f/>text</cdi>");
    ASSERT_TRUE(xml.result());
    const pugi::xml_node cdi = xml.document().document_element();
    auto [last, depth] = last_element(cdi);
    EXPECT_EQ(std::string(last.name()), "f");
    EXPECT_EQ(depth, 0);
    std::tie(last, depth) = last_element(cdi.child("a"));
    EXPECT_EQ(std::string(last.name()), "e");  // comments and text are not elements
    EXPECT_EQ(depth, 1);
    std::tie(last, depth) = last_element(cdi.child("f"));
    EXPECT_EQ(last, cdi.child("f"));
    EXPECT_EQ(depth, -1);
}

TEST(LoadedXml, DepthBoundIsRecorded) {
    const LoadedXml xml("<cdi/>");
    EXPECT_FALSE(xml.depth_bound());
    xml.note_depth_bound(3);
    EXPECT_EQ(xml.depth_bound(), 3u);
}

}  // namespace
}  // namespace olcb::cdi
