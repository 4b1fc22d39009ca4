#include "cdi/parser.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {
namespace {

// Parses text that must be accepted and returns the document.
Document parse_ok(std::string_view text) {
    ParseResult r = parse(text);
    for (const Diagnostic& d : r.diagnostics) {
        EXPECT_NE(d.severity, Severity::kError) << d.line << ": " << d.message;
    }
    EXPECT_TRUE(r.document.has_value());
    return r.document ? *r.document : Document{};
}

// Parses text that must be refused; returns the first error.
Diagnostic parse_error(std::string_view text) {
    ParseResult r = parse(text);
    EXPECT_FALSE(r.document.has_value());
    for (const Diagnostic& d : r.diagnostics) {
        if (d.severity == Severity::kError) return d;
    }
    ADD_FAILURE() << "no error for: " << text;
    return {};
}

bool has_warning_containing(const Diagnostics& diagnostics, std::string_view text) {
    for (const Diagnostic& d : diagnostics) {
        if (d.severity == Severity::kWarning && d.message.find(text) != std::string::npos)
            return true;
    }
    return false;
}

std::string in_segment(const std::string& body) {
    return "<?xml version=\"1.0\"?>\n<cdi>\n<segment space=\"253\">\n" + body +
           "\n</segment>\n</cdi>\n";
}

TEST(Parser, IdentificationAcdiAndHeader) {
    Document doc = parse_ok(R"(<?xml version="1.0" encoding="utf-8"?>
<?xml-stylesheet type="text/xsl" href="x.xsl"?>
<!-- a comment -->
<cdi xmlns:xsi="http://www.w3.org/2001/XMLSchema-instance" xsi:noNamespaceSchemaLocation="https://openlcb.org/schema/cdi/1/4/cdi.xsd">
<identification>
  <manufacturer>Acme &amp; Co</manufacturer>
  <model>M1</model>
  <hardwareVersion>hw</hardwareVersion>
  <softwareVersion>sw</softwareVersion>
  <link ref="https://example.com">home</link>
  <map><relation><property>Size</property><value>Big</value></relation></map>
</identification>
<acdi fixed="5" var="3"/>
</cdi>)");
    EXPECT_TRUE(doc.has_xml_declaration);
    EXPECT_EQ(doc.xml_declaration, R"(<?xml version="1.0" encoding="utf-8"?>)");
    EXPECT_EQ(doc.schema_location, "https://openlcb.org/schema/cdi/1/4/cdi.xsd");
    ASSERT_TRUE(doc.identification);
    EXPECT_EQ(doc.identification->manufacturer, "Acme & Co");
    EXPECT_EQ(doc.identification->model, "M1");
    EXPECT_EQ(doc.identification->hardware_version, "hw");
    EXPECT_EQ(doc.identification->software_version, "sw");
    ASSERT_TRUE(doc.identification->link);
    EXPECT_EQ(doc.identification->link->ref, "https://example.com");
    EXPECT_EQ(doc.identification->link->text, "home");
    ASSERT_TRUE(doc.identification->map);
    ASSERT_EQ(doc.identification->map->entries.size(), 1u);
    EXPECT_EQ(doc.identification->map->entries[0].property, "Size");
    EXPECT_EQ(doc.identification->map->entries[0].value, "Big");
    EXPECT_EQ(doc.identification->pos.line, 5u);
    ASSERT_TRUE(doc.acdi);
    EXPECT_EQ(doc.acdi->fixed, 5u);
    EXPECT_EQ(doc.acdi->var, 3u);
    EXPECT_EQ(doc.acdi->pos.line, 13u);
    EXPECT_TRUE(doc.segments.empty());
}

TEST(Parser, AcdiDefaultsAndNoDeclaration) {
    Document doc = parse_ok("  \n<cdi><acdi/></cdi>");
    EXPECT_FALSE(doc.has_xml_declaration);
    EXPECT_EQ(doc.schema_location, "");
    ASSERT_TRUE(doc.acdi);
    EXPECT_EQ(doc.acdi->fixed, 4u);
    EXPECT_EQ(doc.acdi->var, 2u);
    EXPECT_EQ(doc.acdi->pos.line, 2u);
    EXPECT_FALSE(doc.identification);
}

TEST(Parser, SegmentAttributesAndText) {
    Document doc = parse_ok(R"(<cdi>
<segment space='251' origin='1'>
  <name>Seg</name><description>About</description><link ref='r'>t</link>
</segment>
<segment space="0"/>
</cdi>)");
    ASSERT_EQ(doc.segments.size(), 2u);
    EXPECT_EQ(doc.segments[0].space, 251u);
    EXPECT_EQ(doc.segments[0].origin, 1);
    EXPECT_EQ(doc.segments[0].name, "Seg");
    EXPECT_EQ(doc.segments[0].description, "About");
    ASSERT_TRUE(doc.segments[0].link);
    EXPECT_EQ(doc.segments[0].link->ref, "r");
    EXPECT_EQ(doc.segments[0].pos.line, 2u);
    EXPECT_EQ(doc.segments[1].space, 0u);
    EXPECT_EQ(doc.segments[1].origin, 0);
}

TEST(Parser, GroupEverything) {
    Document doc = parse_ok(in_segment(R"(<group offset="-3" replication="4">
  <name>G</name><description>D</description><link ref="u">L</link>
  <repname>A</repname><repname>B</repname>
  <hints><visibility hideable="yes" hidden="true"/><readOnly/></hints>
  <int/>
</group>
<group/>)"));
    ASSERT_EQ(doc.segments[0].children.size(), 2u);
    const Element& g = doc.segments[0].children[0];
    EXPECT_EQ(g.kind, ElementKind::kGroup);
    EXPECT_EQ(g.tag, "group");
    EXPECT_FALSE(g.is_variable());
    EXPECT_EQ(g.offset, -3);
    EXPECT_EQ(g.replication, 4u);
    EXPECT_EQ(g.name, "G");
    EXPECT_EQ(g.description, "D");
    ASSERT_TRUE(g.link);
    EXPECT_EQ(g.link->text, "L");
    EXPECT_EQ(g.repnames, (std::vector<std::string>{"A", "B"}));
    EXPECT_TRUE(g.hints.visibility);
    EXPECT_TRUE(g.hints.hideable);
    EXPECT_TRUE(g.hints.hidden);
    EXPECT_TRUE(g.hints.read_only);
    EXPECT_EQ(g.size, 0u);
    ASSERT_EQ(g.children.size(), 1u);
    EXPECT_EQ(g.children[0].pos.line, 8u);
    const Element& empty = doc.segments[0].children[1];
    EXPECT_EQ(empty.replication, 1u);
    EXPECT_FALSE(empty.hints.visibility);
    EXPECT_FALSE(empty.hints.read_only);
}

TEST(Parser, IntEverything) {
    Document doc = parse_ok(in_segment(R"(<int size="8" offset="2">
  <name>N</name><description>D</description>
  <min>-9223372036854775808</min><max>9223372036854775807</max><default>-1</default>
  <map><name>M</name><description>MD</description>
    <relation><property>0</property><value>Off</value></relation>
    <relation><property>1</property><value>On</value></relation>
  </map>
  <hints><slider tickSpacing="10" immediate="yes" showValue="true"/><radiobutton/><checkbox/></hints>
</int>
<int/>)"));
    const Element& e = doc.segments[0].children[0];
    EXPECT_EQ(e.kind, ElementKind::kInt);
    EXPECT_EQ(e.size, 8u);
    EXPECT_EQ(e.offset, 2);
    EXPECT_EQ(e.name, "N");
    EXPECT_EQ(e.int_min, -(WideInt{1} << 63));
    EXPECT_EQ(e.int_max, (WideInt{1} << 63) - 1);
    EXPECT_EQ(e.int_default, WideInt{-1});
    EXPECT_TRUE(e.is_signed());
    ASSERT_TRUE(e.map);
    EXPECT_EQ(e.map->name, "M");
    EXPECT_EQ(e.map->description, "MD");
    ASSERT_EQ(e.map->entries.size(), 2u);
    EXPECT_EQ(e.map->entries[1].property, "1");
    EXPECT_EQ(e.map->entries[1].value, "On");
    ASSERT_TRUE(e.hints.slider);
    EXPECT_EQ(e.hints.slider->tick_spacing, 10);
    EXPECT_TRUE(e.hints.slider->immediate);
    EXPECT_TRUE(e.hints.slider->show_value);
    EXPECT_TRUE(e.hints.radiobutton);
    EXPECT_TRUE(e.hints.checkbox);
    const Element& plain = doc.segments[0].children[1];
    EXPECT_EQ(plain.size, 1u);  // default size
    EXPECT_FALSE(plain.int_min);
    EXPECT_FALSE(plain.is_signed());
    EXPECT_FALSE(plain.hints.slider);
}

TEST(Parser, SliderDefaults) {
    Document doc = parse_ok(in_segment("<int><hints><slider> </slider></hints></int>"));
    const Element& e = doc.segments[0].children[0];
    ASSERT_TRUE(e.hints.slider);
    EXPECT_EQ(e.hints.slider->tick_spacing, 0);
    EXPECT_FALSE(e.hints.slider->immediate);
    EXPECT_FALSE(e.hints.slider->show_value);
}

TEST(Parser, StringEventIdFloatActionBlob) {
    Document doc = parse_ok(in_segment(R"(<string size="16"><name>S</name><default>hello</default>
  <map><relation><property>a</property><value>A</value></relation></map></string>
<eventid><name>E</name><default>05.01.01.01.22.00.00.FF</default></eventid>
<float size="8" formatting="%3.1f"><min>-1.5</min><max>1e3</max><default>0.25</default></float>
<float/>
<action size="2"><buttonText>Go</buttonText><dialogText>Sure?</dialogText><value>-5</value></action>
<blob size="10" mode="readwrite"><name>B</name></blob>)"));
    const auto& c = doc.segments[0].children;
    ASSERT_EQ(c.size(), 6u);
    EXPECT_EQ(c[0].kind, ElementKind::kString);
    EXPECT_EQ(c[0].size, 16u);
    EXPECT_EQ(c[0].text_default, "hello");
    ASSERT_TRUE(c[0].map);
    EXPECT_EQ(c[1].kind, ElementKind::kEventId);
    EXPECT_EQ(c[1].size, 8u);
    EXPECT_EQ(c[1].text_default, "05.01.01.01.22.00.00.FF");
    EXPECT_EQ(c[2].kind, ElementKind::kFloat);
    EXPECT_EQ(c[2].size, 8u);
    EXPECT_EQ(c[2].formatting, "%3.1f");
    EXPECT_EQ(c[2].float_min, -1.5);
    EXPECT_EQ(c[2].float_max, 1000.0);
    EXPECT_EQ(c[2].float_default, 0.25);
    EXPECT_EQ(c[3].size, 4u);  // CDI 1.2 default
    EXPECT_EQ(c[4].kind, ElementKind::kAction);
    EXPECT_EQ(c[4].size, 2u);
    EXPECT_EQ(c[4].button_text, "Go");
    EXPECT_EQ(c[4].dialog_text, "Sure?");
    EXPECT_EQ(c[4].action_value, WideInt{-5});
    EXPECT_EQ(c[5].kind, ElementKind::kBlob);
    EXPECT_EQ(c[5].size, 10u);
    EXPECT_EQ(c[5].blob_mode, "readwrite");
    EXPECT_EQ(c[5].name, "B");
}

TEST(Parser, EmptyRareTextsAreAbsent) {
    Document doc = parse_ok(in_segment(R"(<float size="4" formatting=""/>
<action size="1"><buttonText/><buttonText>Go</buttonText><dialogText>x</dialogText><dialogText/>
</action>
<blob size="2"/>)"));
    const auto& c = doc.segments[0].children;
    ASSERT_EQ(c.size(), 3u);
    EXPECT_FALSE(c[0].formatting);
    EXPECT_EQ(c[1].button_text, "Go");  // the last one counts
    EXPECT_FALSE(c[1].dialog_text);     // an empty last one leaves none
    EXPECT_FALSE(c[2].blob_mode);
    EXPECT_FALSE(c[2].float_min);
}

TEST(Parser, DecodesTextAndAttributes) {
    Document doc = parse_ok(
        "<cdi><segment space='1'><group><name>A &amp; B</name>"
        "<description>one\r\ntwo\rthree</description></group>"
        "<float size='4' formatting='%1.1f\t&lt;x&gt;'/></segment></cdi>");
    const auto& c = doc.segments[0].children;
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].name, "A & B");
    EXPECT_EQ(c[0].description, "one\ntwo\nthree");
    EXPECT_EQ(c[1].formatting, "%1.1f <x>");
}

TEST(Parser, BitIsSizedInBitsRoundedUpToBytes) {
    ParseResult r = parse(in_segment(
        R"(<bit><name>b</name><map><relation><property>1</property><value>on</value></relation></map></bit>
<bit size="8" mask="32" origin="29"/>
<bit size="12"/>)"));
    ASSERT_TRUE(r.document);
    const auto& c = r.document->segments[0].children;
    ASSERT_EQ(c.size(), 3u);
    EXPECT_EQ(c[0].kind, ElementKind::kBit);
    EXPECT_EQ(c[0].size, 1u);
    ASSERT_TRUE(c[0].map);
    EXPECT_EQ(c[1].size, 1u);
    EXPECT_EQ(c[2].size, 2u);
    // mask/origin are not schema attributes: reported, not fatal.
    EXPECT_TRUE(has_warning_containing(r.diagnostics, "'mask'"));
    EXPECT_TRUE(has_warning_containing(r.diagnostics, "'origin'"));
}

TEST(Parser, UnknownElementsWithAndWithoutSize) {
    ParseResult r =
        parse(in_segment(R"(<custom size="3" offset="1"><name>C</name><whatever/></custom>
<widget/>
<group><bogus size="2"/></group>)"));
    ASSERT_TRUE(r.document);
    const auto& c = r.document->segments[0].children;
    ASSERT_EQ(c.size(), 2u);
    EXPECT_EQ(c[0].kind, ElementKind::kUnknown);
    EXPECT_EQ(c[0].tag, "custom");
    EXPECT_EQ(c[0].size, 3u);
    EXPECT_EQ(c[0].offset, 1);
    EXPECT_EQ(c[0].name, "C");
    EXPECT_TRUE(c[0].is_variable());
    ASSERT_EQ(c[1].children.size(), 1u);
    EXPECT_EQ(c[1].children[0].tag, "bogus");
    ASSERT_EQ(r.diagnostics.size(), 1u);
    EXPECT_EQ(r.diagnostics[0].severity, Severity::kWarning);
    EXPECT_EQ(r.diagnostics[0].line, 5u);
    EXPECT_NE(r.diagnostics[0].message.find("<widget>"), std::string::npos);
}

TEST(Parser, AcceptsServedByteQuirks) {
    // Trailing NUL terminators, CRLF, single quotes, leading whitespace, no declaration.
    std::string text =
        "\r\n <cdi>\r\n<segment space='253'>\r\n<int size='2'/>\r\n</segment>\r\n</cdi>";
    text.push_back('\0');
    text.push_back('\0');
    Document doc = parse_ok(text);
    ASSERT_EQ(doc.segments.size(), 1u);
    EXPECT_EQ(doc.segments[0].pos.line, 3u);
    EXPECT_EQ(doc.segments[0].children[0].pos.line, 4u);
    EXPECT_EQ(doc.segments[0].children[0].size, 2u);
}

TEST(Parser, DuplicateSingletonsWarn) {
    ParseResult r = parse("<cdi><acdi/><acdi fixed='1'/><identification/><identification/></cdi>");
    ASSERT_TRUE(r.document);
    EXPECT_EQ(r.document->acdi->fixed, 4u);
    EXPECT_TRUE(has_warning_containing(r.diagnostics, "duplicate <acdi>"));
    EXPECT_TRUE(has_warning_containing(r.diagnostics, "duplicate <identification>"));
}

TEST(ParserRejects, ByteOrderMark) {
    Diagnostic d = parse_error("\xEF\xBB\xBF<cdi/>");
    EXPECT_NE(d.message.find("byte-order mark"), std::string::npos);
}

TEST(ParserRejects, EmbeddedNul) {
    Diagnostic d = parse_error(std::string("<cdi>\n</cdi>\0<x/>", 17));
    EXPECT_NE(d.message.find("NUL"), std::string::npos);
    EXPECT_EQ(d.line, 2u);
}

TEST(ParserRejects, EmptyInput) {
    EXPECT_NE(parse_error(std::string("\0\0", 2)).message.find("empty"), std::string::npos);
    EXPECT_NE(parse_error(" \n").message.find("empty"), std::string::npos);
}

TEST(ParserRejects, NonDecimalNumbers) {
    struct Case {
        std::string body;
        std::string needle;
    };
    const Case cases[] = {
        {"<int size='0x2'/>", "size='0x2'"},
        {"<int offset='1e3'/>", "offset='1e3'"},
        {"<group replication='0x10'/>", "replication='0x10'"},
        {"<int><min>0x10</min></int>", "<min> of <int>"},
        {"<int><max>1e3</max></int>", "<max> of <int>"},
        {"<int><default>1.5</default></int>", "<default> of <int>"},
        {"<float size='4'><min>0x1p3</min></float>", "<min> of <float>"},
        {"<action size='1'><value>abc</value></action>", "<value> of <action>"},
        {"<int><hints><slider tickSpacing='ten'/></hints></int>", "tickSpacing"},
    };
    for (const Case& c : cases) {
        Diagnostic d = parse_error(in_segment(c.body));
        EXPECT_NE(d.message.find(c.needle), std::string::npos) << d.message;
        EXPECT_EQ(d.line, 4u) << c.body;
    }
    EXPECT_NE(parse_error("<cdi><segment space='0xFD'/></cdi>").message.find("space"),
              std::string::npos);
    EXPECT_NE(parse_error("<cdi><acdi fixed='four'/></cdi>").message.find("fixed"),
              std::string::npos);
}

TEST(ParserRejects, OutOfRangeValues) {
    EXPECT_NE(parse_error(in_segment("<group replication='0'/>")).message.find("out of range"),
              std::string::npos);
    EXPECT_NE(
        parse_error(in_segment("<group replication='2147483648'/>")).message.find("replication"),
        std::string::npos);
    EXPECT_NE(parse_error(in_segment("<string size='4294967297'/>")).message.find("size"),
              std::string::npos);
    EXPECT_NE(parse_error(in_segment("<int size='0'/>")).message.find("size"), std::string::npos);
    EXPECT_NE(parse_error(in_segment("<int offset='4294967296'/>")).message.find("offset"),
              std::string::npos);
    EXPECT_NE(parse_error(in_segment("<int offset='-2147483649'/>")).message.find("offset"),
              std::string::npos);
    EXPECT_NE(parse_error("<cdi><segment space='256'/></cdi>").message.find("0..255"),
              std::string::npos);
    EXPECT_NE(parse_error("<cdi><segment space='-1'/></cdi>").message.find("space"),
              std::string::npos);
    EXPECT_NE(parse_error("<cdi><segment/></cdi>").message.find("space attribute"),
              std::string::npos);
    // The largest legal values are accepted.
    Document doc =
        parse_ok(in_segment("<group replication='2147483647'/><string size='4294967296'/>"
                            "<int offset='4294967295'/>"));
    EXPECT_EQ(doc.segments[0].children[0].replication, 2147483647u);
    EXPECT_EQ(doc.segments[0].children[1].size, std::uint64_t{1} << 32);
    EXPECT_EQ(doc.segments[0].children[2].offset, 4294967295);
}

TEST(ParserRejects, MissingRequiredSize) {
    for (const char* tag : {"string", "action", "blob"}) {
        Diagnostic d = parse_error(in_segment(std::string("<") + tag + "/>"));
        EXPECT_NE(d.message.find("requires a size"), std::string::npos) << tag;
        EXPECT_EQ(d.line, 4u);
    }
}

TEST(ParserRejects, DoctypeAndEntities) {
    Diagnostic d = parse_error("<?xml version=\"1.0\"?>\n<!DOCTYPE cdi>\n<cdi/>");
    EXPECT_NE(d.message.find("DOCTYPE"), std::string::npos);
    EXPECT_EQ(d.line, 2u);
    std::string laughs = "<?xml version=\"1.0\"?>\n<!DOCTYPE lolz [\n<!ENTITY lol \"lol\">\n";
    for (int i = 1; i < 10; ++i) {
        laughs += "<!ENTITY lol" + std::to_string(i) + " \"";
        for (int j = 0; j < 10; ++j)
            laughs += "&lol" + (i == 1 ? std::string() : std::to_string(i - 1)) + ";";
        laughs += "\">\n";
    }
    laughs += "]>\n<cdi><identification><model>&lol9;</model></identification></cdi>";
    const auto start = std::chrono::steady_clock::now();
    d = parse_error(laughs);
    const auto elapsed = std::chrono::steady_clock::now() - start;
    EXPECT_NE(d.message.find("DOCTYPE"), std::string::npos);
    EXPECT_LT(elapsed, std::chrono::seconds(10));  // generous: catches any expansion
}

TEST(ParserRejects, MalformedXmlWithLine) {
    Diagnostic d = parse_error("<cdi>\n<identification>\n<model>x</identification>\n</cdi>");
    EXPECT_NE(d.message.find("malformed XML"), std::string::npos);
    EXPECT_EQ(d.line, 3u);
    EXPECT_NE(parse_error("<cdi><segment space='1'>").message.find("malformed"), std::string::npos);
    EXPECT_NE(parse_error("not xml at all").message.find("malformed"), std::string::npos);
}

TEST(ParserRejects, WrongRoot) {
    Diagnostic d = parse_error("<?xml version='1.0'?>\n\n<configuration/>");
    EXPECT_NE(d.message.find("<configuration>"), std::string::npos);
    EXPECT_EQ(d.line, 3u);
}

TEST(ParserRejects, GroupNestingBeyondLimit) {
    auto nested = [](std::size_t depth) {
        std::string s = "<cdi><segment space='1'>";
        for (std::size_t i = 0; i < depth; ++i) s += "<group>";
        s += "<int/>";
        for (std::size_t i = 0; i < depth; ++i) s += "</group>";
        return s + "</segment></cdi>";
    };
    Document doc = parse_ok(nested(kMaxGroupDepth));
    const Element* e = &doc.segments[0].children[0];
    for (std::size_t i = 1; i < kMaxGroupDepth; ++i) e = &e->children[0];
    EXPECT_EQ(e->children[0].kind, ElementKind::kInt);
    Diagnostic d = parse_error(nested(kMaxGroupDepth + 1));
    EXPECT_NE(d.message.find("nested deeper"), std::string::npos);
}

TEST(ParserRejects, HostileDeepNestingQuickly) {
    constexpr std::size_t kDepth = 100000;
    std::string groups = "<cdi><segment space='1'>";
    for (std::size_t i = 0; i < kDepth; ++i) groups += "<group>";
    for (std::size_t i = 0; i < kDepth; ++i) groups += "</group>";
    groups += "</segment></cdi>";
    std::string unknown = "<cdi><segment space='1'>";
    for (std::size_t i = 0; i < kDepth; ++i) unknown += "<x size='1'>";
    for (std::size_t i = 0; i < kDepth; ++i) unknown += "</x>";
    unknown += "</segment></cdi>";
    const auto start = std::chrono::steady_clock::now();
    Diagnostic d = parse_error(groups);
    EXPECT_NE(d.message.find("nested deeper"), std::string::npos);
    // Deep nesting anywhere is refused, not only in groups.
    d = parse_error(unknown);
    EXPECT_NE(d.message.find("XML elements nested deeper"), std::string::npos);
    EXPECT_EQ(d.line, 1u);
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(10));
}

TEST(Parser, DepthCheckIgnoresCommentsCdataAndEmptyTags) {
    std::string text = "<?xml version='1.0'?><?pi <a><a>?><cdi><!-- ";
    for (int i = 0; i < 300; ++i) text += "<a>";
    text += " --><segment space='1'><name><![CDATA[";
    for (int i = 0; i < 300; ++i) text += "<b>";
    text += "]]></name>";
    for (int i = 0; i < 300; ++i)
        text += "<int offset='0' size=\"1\"><name>a&gt;b</name></int><int x='>'/>";
    text += "<string size='2'><description x='/>'>q</description></string></segment></cdi>";
    ParseResult r = parse(text);
    ASSERT_TRUE(r.document);
    EXPECT_EQ(r.document->segments[0].children.size(), 601u);
}

TEST(ParserRejects, ErrorsCarryTheElementLine) {
    ParseResult r =
        parse("<cdi>\n<segment space='1'>\n<int/>\n<int size='x'/>\n<string/>\n</segment>\n</cdi>");
    EXPECT_FALSE(r.document);
    ASSERT_EQ(r.diagnostics.size(), 2u);
    EXPECT_EQ(r.diagnostics[0].line, 4u);
    EXPECT_EQ(r.diagnostics[1].line, 5u);
}

// Deep nesting: a valid CDI of 200 or 1,000 nested groups is parsed like any other; nesting
// beyond kMaxGroupDepth, hostile (100,000 and 1,000,000 levels) or not, is refused with a
// diagnostic, quickly and without exhausting the stack (run under the ASan build too). The other
// units' side: layout_test.cpp, render_test.cpp, memory_map_test.cpp, validator_test.cpp,
// rule_finding_test.cpp.
class ParserDeepNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ParserDeepNesting, ParsesEveryLevel) {
    const std::size_t depth = GetParam();
    ParseResult parsed = parse(test::nested_cdi(depth));
    ASSERT_TRUE(parsed.document) << test::first_error_text(parsed.diagnostics);
    const Element* e = &parsed.document->segments.at(0).children.at(0);
    for (std::size_t level = 1; level < depth; ++level) {
        ASSERT_EQ(e->kind, ElementKind::kGroup);
        ASSERT_EQ(e->children.size(), 1u);
        e = &e->children[0];
    }
    ASSERT_EQ(e->children.size(), 1u);
    EXPECT_EQ(e->children[0].name, "Leaf");
}

INSTANTIATE_TEST_SUITE_P(Depths, ParserDeepNesting, ::testing::ValuesIn(test::kValidNestingDepths));

TEST(ParserRejects, GroupsBeyondTheDepthLimit) {
    const ParseResult parsed = parse(test::nested_cdi(kMaxGroupDepth + 1));
    EXPECT_FALSE(parsed.document);
    EXPECT_NE(test::first_error_text(parsed.diagnostics).find("nested deeper"), std::string::npos);
}

class ParserHostileNesting : public ::testing::TestWithParam<std::size_t> {};

TEST_P(ParserHostileNesting, IsRefusedQuicklyWithADiagnostic) {
    const std::string text = test::hostile_cdi(GetParam());
    ASSERT_LE(text.size(), kMaxCdiBytes);
    const auto start = std::chrono::steady_clock::now();
    const ParseResult parsed = parse(text);
    EXPECT_FALSE(parsed.document);
    EXPECT_NE(test::first_error_text(parsed.diagnostics).find("nested deeper"), std::string::npos);
    // Generous for sanitizer builds on a loaded machine; linear work takes well under a second.
    EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
}

INSTANTIATE_TEST_SUITE_P(Depths, ParserHostileNesting,
                         ::testing::ValuesIn(test::kHostileNestingDepths));

}  // namespace
}  // namespace olcb::cdi
