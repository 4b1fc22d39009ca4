// The HTML pages' shell and the CDI page's data: self-contained (nothing to fetch), node and CDI
// text unable to escape the data element, and the CDI's structure as the page script needs it.
#include "cdi/html_page.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "cdi/parser.hpp"
#include "cdi/render_html.hpp"

namespace olcb::cdi {
namespace {

std::size_t count(const std::string& text, const std::string& what) {
    std::size_t n = 0;
    for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

TEST(HtmlPage, AssetsAreEmbeddedAndCannotEndTheirElements) {
    for (const char* name : {"page.css", "map.js", "conform.js", "cdi.js"}) {
        const std::string asset(html_asset(name));
        EXPECT_GT(asset.size(), 1000u) << name;
        EXPECT_EQ(asset.find("</script"), std::string::npos) << name;
        EXPECT_EQ(asset.find("</style"), std::string::npos) << name;
        // Untrusted text goes in with textContent only.
        EXPECT_EQ(asset.find("innerHTML"), std::string::npos) << name;
        EXPECT_EQ(asset.find("://"), std::string::npos) << name;
    }
    EXPECT_TRUE(html_asset("nonexistent.js").empty());
}

TEST(HtmlPage, IsSelfContained) {
    const std::string page = html_page(PageKind::kCdi, nlohmann::json::object());
    EXPECT_NE(page.find("<meta http-equiv=\"Content-Security-Policy\" content=\"default-src "
                        "'none';"),
              std::string::npos);
    for (const char* reference : {"src=", "href=", "url(", "@import", "://"})
        EXPECT_EQ(page.find(reference), std::string::npos) << reference;
    EXPECT_NE(page.find(std::string(html_asset("cdi.js"))), std::string::npos);
    EXPECT_EQ(page.find(std::string(html_asset("conform.js"))), std::string::npos);
    EXPECT_NE(html_page(PageKind::kConformance, {}).find(std::string(html_asset("conform.js"))),
              std::string::npos);
}

TEST(HtmlPage, DataCannotCloseItsElement) {
    const nlohmann::json data = {
        {"name", "</script><script>alert(1)</script><!-- & -->"},
        {"bad", std::string("bad\xff\xfename")},
    };
    const std::string page = html_page(PageKind::kConformance, data);
    EXPECT_EQ(page.find("alert(1)</script>"), std::string::npos);
    EXPECT_EQ(page.find("<!--"), std::string::npos);
    EXPECT_EQ(count(page, "</script>"), 3u);  // the data element and the two scripts
    EXPECT_NE(page.find("\\u003c/script\\u003e\\u003cscript\\u003ealert(1)"), std::string::npos);
    EXPECT_NE(page.find("\\u0026"), std::string::npos);
    EXPECT_NE(page.find("bad\xEF\xBF\xBD\xEF\xBF\xBDname"), std::string::npos);  // U+FFFD each
    // What the page script parses is the data itself.
    const auto begin = page.find("id=\"page-data\">") + 15;
    const auto end = page.find("</script>", begin);
    const auto parsed = nlohmann::json::parse(page.substr(begin, end - begin));
    EXPECT_EQ(parsed["name"], data["name"]);
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
    EXPECT_EQ(last["path"], "Settings/Port[4](Port 4)/Output");
    EXPECT_EQ(last["replicas"], nlohmann::json::array({3}));
    EXPECT_EQ(last["element"], (*port)["children"][3]["id"]);
    const std::string page = render_html(*laid.layout, "default.xml");
    EXPECT_NE(page.find("\"Port 4\""), std::string::npos);
}

}  // namespace
}  // namespace olcb::cdi
