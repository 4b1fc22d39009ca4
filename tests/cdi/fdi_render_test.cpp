#include "cdi/fdi_render.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/fdi_parser.hpp"
#include "cdi/fdi_validator.hpp"

namespace olcb::cdi {
namespace {

using test::fdi_text;
using test::listing;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

constexpr const char* kBody =
    "<name>Loco</name><description>All functions</description>\n"
    "<function><name>Light</name><number>0</number></function>\n"
    "<group><name>Sound</name><description>Toot</description>\n"
    "<function kind=\"momentary\"><name>Horn</name><icon>7</icon><number>2</number></function>\n"
    "<group><function kind=\"analog\"><name>Volume</name><number>5</number><max>31</max>"
    "</function></group>\n"
    "</group>\n"
    "<function kind=\"analog\"><number>9</number></function>\n";

FdiDocument parsed(const std::string& text) {
    FdiParseResult r = parse_fdi(text);
    EXPECT_TRUE(r.document);
    EXPECT_THAT(r.diagnostics, IsEmpty()) << listing(r.diagnostics);
    return r.document ? std::move(*r.document) : FdiDocument{};
}

TEST(RenderFdi, TheFunctionListInDocumentOrder) {
    std::ostringstream out;
    render_fdi(parsed(fdi_text(kBody)), out);
    EXPECT_EQ(out.str(),
              "Segment \"Loco\", space 249 (functions)\n"
              "  | All functions\n"
              "  F0 binary \"Light\"\n"
              "  group \"Sound\"\n"
              "    | Toot\n"
              "    F2 momentary \"Horn\" icon 7\n"
              "    group (unnamed)\n"
              "      F5 analog 0..31 \"Volume\"\n"
              "  F9 analog 0..255 (unnamed)\n");
}

TEST(RenderFdi, UntrustedTextIsMadePrintable) {
    FdiDocument doc;
    doc.functions.resize(1);
    doc.functions[0].name = "Bell\x1b[2J\n";
    std::ostringstream out;
    render_fdi(doc, out);
    EXPECT_EQ(out.str(), "Segment (unnamed), space 249 (functions)\n  F0 binary \"Bell?[2J?\"\n");
}

TEST(WriteFdi, RoundTripsThroughTheValidator) {
    const FdiDocument doc = parsed(fdi_text(kBody));
    const std::string text = write_fdi(doc);
    const ValidatedFdi v = validate_fdi(text);
    EXPECT_TRUE(v.ok()) << listing(v.diagnostics) << text;
    ASSERT_TRUE(v.document);
    std::ostringstream a;
    std::ostringstream b;
    render_fdi(doc, a);
    render_fdi(*v.document, b);
    EXPECT_EQ(a.str(), b.str());
    EXPECT_TRUE(text.starts_with("<?xml version=\"1.0\"?>\n<fdi "));
    EXPECT_THAT(text, HasSubstr("https://openlcb.org/schema/fdi/1/1/fdi.xsd"));
}

TEST(WriteFdi, AHandBuiltListWithTextsThatNeedEscaping) {
    FdiDocument doc;
    doc.name = "A & B <train>";
    FdiGroup lights;
    lights.name = "Lights";
    doc.groups.push_back(lights);
    FdiFunction horn;
    horn.number = 2;
    horn.kind = FunctionKind::kMomentary;
    horn.name = "Horn \"loud\" </name>";
    FdiFunction light;
    light.number = 0;
    light.name = "Head\x01light";
    light.group = 0;
    doc.functions = {horn, light};
    doc.space_given = true;
    const std::string text = write_fdi(doc);
    EXPECT_THAT(text, HasSubstr("<segment space=\"249\">\n"));
    EXPECT_THAT(text, HasSubstr("<name>A &amp; B &lt;train&gt;</name>"));
    EXPECT_THAT(text, HasSubstr("<name>Horn \"loud\" &lt;/name&gt;</name>"));
    const ValidatedFdi v = validate_fdi(text);
    EXPECT_TRUE(v.ok()) << listing(v.diagnostics) << text;
    ASSERT_TRUE(v.document);
    ASSERT_EQ(v.document->functions.size(), 2U);
    // The hand-built group had first_function 0: it comes before the segment's own functions.
    EXPECT_EQ(v.document->functions[0].name, "Head?light");
    EXPECT_EQ(v.document->functions[0].group, 0U);
    EXPECT_EQ(v.document->functions[1].name, "Horn \"loud\" </name>");
    EXPECT_TRUE(v.document->functions[1].momentary());
    EXPECT_EQ(v.document->name, "A & B <train>");
}

}  // namespace
}  // namespace olcb::cdi
