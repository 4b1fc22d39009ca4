// The CDI as one HTML page (cdi/render_html.cpp, lcc-cdi render --html): the data the page script
// renders, with the CDI's structure, constraints, hints, replicas and memory map.
#include "cdi/render_html.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cdi/cdi_test_util.hpp"
#include "cdi/html_page.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {
namespace {

using test::first_error_text;
using test::lay;

// The page's data as the page script reads it.
nlohmann::json cdi_page_json(const Layout& layout, std::string_view source) {
    std::string text;
    append_cdi_page_data(text, layout, source);
    return nlohmann::json::parse(text);
}

// The data inside a whole page's <script id="page-data"> element.
nlohmann::json data_of_page(const std::string& page) {
    const std::string open = "id=\"page-data\">";
    const std::size_t begin = page.find(open);
    const std::size_t end = page.find("</script>", begin);
    if (begin == std::string::npos || end == std::string::npos) return nullptr;
    return nlohmann::json::parse(page.substr(begin + open.size(), end - begin - open.size()));
}

TEST(RenderHtml, CdiPageDataCarriesStructureHintsAndReplicas) {
    std::ifstream in(std::filesystem::path(OLCB_SOURCE_DIR) / "scenarios" / "default.xml");
    std::stringstream text;
    text << in.rdbuf();
    ParseResult parsed = parse(text.str());
    ASSERT_TRUE(parsed.document);
    auto laid = build_layout(*parsed.document);
    ASSERT_TRUE(laid.layout);
    const nlohmann::json j = cdi_page_json(*laid.layout, "default.xml");
    EXPECT_EQ(j["source"], "default.xml");
    EXPECT_EQ(j["identification"]["model"], "simnode default");
    ASSERT_EQ(j["segments"].size(), 2u);
    const nlohmann::json& settings = j["segments"][1];
    EXPECT_EQ(settings["space"], 253);
    const nlohmann::json& children = settings["children"];
    EXPECT_TRUE(children[0]["hints"]["checkbox"].get<bool>());
    EXPECT_EQ(children[0]["map"][1]["value"], "On");
    EXPECT_EQ(children[1]["hints"]["slider"]["tick_spacing"], 100);
    EXPECT_EQ(children[1]["min"], "-1000");
    EXPECT_TRUE(children[4]["hints"]["radiobutton"].get<bool>());
    const nlohmann::json* port = nullptr;
    for (const auto& c : children) {
        if (c["kind"] == "group") port = &c;
    }
    ASSERT_NE(port, nullptr);
    EXPECT_EQ((*port)["replication"], 4);
    EXPECT_EQ((*port)["stride"], 33);
    EXPECT_EQ((*port)["replica_names"],
              nlohmann::json::array({"Port 1", "Port 2", "Port 3", "Port 4"}));
    // The memory map's variables point back at the form's elements and replicas.
    const nlohmann::json& map = j["memory_map"];
    ASSERT_EQ(map.size(), 2u);
    const nlohmann::json& last = map[1]["variables"][map[1]["variables"].size() - 2];
    EXPECT_EQ(last["name"], "Settings.Port(3).Output");
    EXPECT_EQ(last["replica"], "Port 4");
    EXPECT_EQ(last["replicas"], nlohmann::json::array({3}));
    EXPECT_EQ(last["element"], (*port)["children"][3]["id"]);
    const std::string page = render_html(*laid.layout, "default.xml");
    EXPECT_NE(page.find("\"Port 4\""), std::string::npos);
}

TEST(RenderHtml, AbsentIdentificationAndAcdiAreNull) {
    auto l = lay(R"(<cdi><segment space="1"><name>S</name><description>d</description>
<link ref="https://example.com">home</link><int size="1"><name>A</name></int></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    const nlohmann::json j = cdi_page_json(l->layout(), "x.xml");
    EXPECT_TRUE(j["identification"].is_null());
    EXPECT_TRUE(j["acdi"].is_null());
    ASSERT_EQ(j["segments"].size(), 1u);
    const nlohmann::json& s = j["segments"][0];
    EXPECT_EQ(s["name"], "S");
    EXPECT_EQ(s["description"], "d");
    EXPECT_EQ(s["space"], 1);
    EXPECT_EQ(s["origin"], 0);
    EXPECT_EQ(s["link"], (nlohmann::json{{"ref", "https://example.com"}, {"text", "home"}}));
    const nlohmann::json& a = s["children"][0];
    EXPECT_EQ(a["id"], 0);
    EXPECT_EQ(a["kind"], "int");
    EXPECT_EQ(a["tag"], "int");
    EXPECT_EQ(a["address"], 0);
    EXPECT_EQ(a["size"], 1);
    EXPECT_FALSE(a["signed"].get<bool>());
    EXPECT_EQ(a["hints"], nlohmann::json::object());
}

TEST(RenderHtml, IntegersGoAsDecimalTextAndEveryConstraintIsCarried) {
    auto l = lay(R"(<cdi><acdi/><segment space="253">
<int size="8"><min>-9223372036854775808</min><max>9223372036854775807</max>
<default>-9007199254740993</default></int>
<float size="4" formatting="%.3f"><min>-1</min><max>1</max><default>0.25</default></float>
<string size="4"><default>ab</default></string>
<action size="1"><buttonText>Go</buttonText><dialogText>Sure?</dialogText><value>7</value></action>
<blob size="2" mode="readwrite"/>
</segment></cdi>)");
    ASSERT_TRUE(l->result.layout) << first_error_text(l->result.diagnostics);
    const nlohmann::json j = cdi_page_json(l->layout(), "x.xml");
    EXPECT_EQ(j["acdi"], (nlohmann::json{{"fixed", 4}, {"var", 2}}));
    const nlohmann::json& c = j["segments"][0]["children"];
    // Beyond 2^53: a JavaScript number would round it.
    EXPECT_EQ(c[0]["min"], "-9223372036854775808");
    EXPECT_EQ(c[0]["max"], "9223372036854775807");
    EXPECT_EQ(c[0]["default"], "-9007199254740993");
    EXPECT_TRUE(c[0]["signed"].get<bool>());
    EXPECT_EQ(c[1]["min"], -1.0);
    EXPECT_EQ(c[1]["default"], 0.25);
    EXPECT_EQ(c[1]["formatting"], "%.3f");
    EXPECT_EQ(c[2]["default"], "ab");
    EXPECT_EQ(c[3]["button"], "Go");
    EXPECT_EQ(c[3]["dialog"], "Sure?");
    EXPECT_EQ(c[3]["value"], "7");
    EXPECT_EQ(c[4]["mode"], "readwrite");
    EXPECT_EQ(c[4]["address"], 8 + 4 + 4 + 1);
}

TEST(RenderHtml, ReplicaNamesAreListedForTheFirst256Replicas) {
    auto l = lay(R"(<cdi><segment space="253"><group replication="1000" offset="2">
<repname>Line</repname><int size="1"/></group></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    const nlohmann::json j = cdi_page_json(l->layout(), "x.xml");
    const nlohmann::json& g = j["segments"][0]["children"][0];
    EXPECT_EQ(g["kind"], "group");
    EXPECT_EQ(g["replication"], 1000);
    EXPECT_EQ(g["stride"], 1);
    EXPECT_EQ(g["address"], 2);
    ASSERT_EQ(g["replica_names"].size(), 256u);
    EXPECT_EQ(g["replica_names"][0], "Line 1");
    EXPECT_EQ(g["replica_names"][255], "Line 256");
    EXPECT_EQ(g["children"][0]["id"], 1);
}

TEST(RenderHtml, ThePageCarriesTheDataAndTheCdiScript) {
    auto l =
        lay(R"(<cdi><segment space="1"><int size="1"><name>Knob</name></int></segment></cdi>)");
    ASSERT_TRUE(l->result.layout);
    const std::string page = render_html(l->layout(), "knob.xml");
    EXPECT_EQ(data_of_page(page), cdi_page_json(l->layout(), "knob.xml"));
    EXPECT_NE(page.find("\"Knob\""), std::string::npos);
    EXPECT_NE(page.find("\"knob.xml\""), std::string::npos);
    EXPECT_NE(page.find(std::string(html_asset("cdi.js"))), std::string::npos);
}

TEST(RenderHtml, StreamedDataNestsGroupsAndKeepsMarkupOutOfTheScript) {
    auto l = lay(R"(<cdi><segment space="253"><name>&lt;/script&gt;&lt;!--</name>
<group replication="2"><name>Outer &amp; more</name><repname>R</repname>
<group><name>Inner</name><int size="1"><name>A</name></int></group>
<string size="4"><name>B</name></string></group>
<int size="2"><name>C</name></int></segment></cdi>)");
    ASSERT_TRUE(l->result.layout) << first_error_text(l->result.diagnostics);
    const std::string page = render_html(l->layout(), "x.xml");
    const std::size_t data = page.find("id=\"page-data\">");
    ASSERT_NE(data, std::string::npos);
    // The first "</script>" after the data's start closes the data element itself.
    EXPECT_EQ(page.find("</script>", data), page.find("</script>\n<script>\n", data));
    EXPECT_EQ(page.find("<!--"), std::string::npos);
    const nlohmann::json j = data_of_page(page);
    const nlohmann::json& s = j["segments"][0];
    EXPECT_EQ(s["name"], "</script><!--");
    const nlohmann::json& outer = s["children"][0];
    EXPECT_EQ(outer["name"], "Outer & more");
    EXPECT_EQ(outer["children"][0]["children"][0]["name"], "A");
    EXPECT_EQ(outer["children"][0]["children"][0]["id"], 2);
    EXPECT_EQ(outer["children"][1]["name"], "B");
    EXPECT_EQ(s["children"][1]["name"], "C");
    EXPECT_EQ(s["children"][1]["id"], 4);
    EXPECT_EQ(s["children"][1]["address"], 10);
    // Every listed variable points back at its element.
    for (const nlohmann::json& v : j["memory_map"][0]["variables"])
        EXPECT_TRUE(v.contains("element"));
}

}  // namespace
}  // namespace olcb::cdi
