// The HTML pages' shell: self-contained (nothing to fetch), and node and CDI text unable to escape
// the data element (the CDI page's data: render_html_test.cpp).
#include "cdi/html_page.hpp"

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

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

TEST(HtmlPage, DataWrittenPieceByPieceIsTheSameAsOneValue) {
    const nlohmann::json data = {{"a", "</script>"}, {"b", 1}, {"list", {1, 2}}};
    const std::string page = html_page_from(PageKind::kCdi, [](std::string& out) {
        append_open_object(out, {{"a", "</script>"}, {"b", 1}});
        out += ",\"list\":[";
        append_script_json(out, 1);
        out += ',';
        append_script_json(out, 2);
        out += "]}";
    });
    EXPECT_EQ(page, html_page(PageKind::kCdi, data));
}

TEST(HtmlPage, OnlyANonEmptyObjectCanBeLeftOpen) {
    std::string out;
    EXPECT_THROW(append_open_object(out, nlohmann::json::object()), std::logic_error);
    EXPECT_THROW(append_open_object(out, nlohmann::json::array({1})), std::logic_error);
    EXPECT_TRUE(out.empty());
}

}  // namespace
}  // namespace olcb::cdi
