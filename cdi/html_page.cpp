#include "cdi/html_page.hpp"

#include <stdexcept>

#include <nlohmann/json.hpp>

namespace olcb::cdi {
namespace {

// No request of any kind: inline style and script only, images as data: URLs.
constexpr std::string_view kPolicy =
    "default-src 'none'; style-src 'unsafe-inline'; script-src 'unsafe-inline'; img-src data:";

// JSON that is safe as the text of a <script> element: '<' cannot start "</script" or "<!--",
// and '>' and '&' are escaped too so no HTML parser state can be reached from inside a string.
void append_escaped(std::string& out, std::string_view text) {
    for (const char c : text) {
        switch (c) {
            case '<':
                out += "\\u003c";
                break;
            case '>':
                out += "\\u003e";
                break;
            case '&':
                out += "\\u0026";
                break;
            default:
                out += c;
        }
    }
}

std::string json_text(const nlohmann::json& value) {
    return value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

}  // namespace

void append_script_json(std::string& out, const nlohmann::json& value) {
    append_escaped(out, json_text(value));
}

void append_open_object(std::string& out, const nlohmann::json& object) {
    if (!object.is_object() || object.empty()) {
        throw std::logic_error("append_open_object: not a non-empty object");
    }
    const std::string text = json_text(object);
    append_escaped(out, std::string_view(text).substr(0, text.size() - 1));
}

std::string html_page(PageKind kind, const nlohmann::json& data) {
    return html_page_from(kind, [&data](std::string& out) { append_script_json(out, data); });
}

std::string html_page_from(PageKind kind, const std::function<void(std::string& out)>& write_data) {
    const std::string_view script = kind == PageKind::kCdi ? "cdi.js" : "conform.js";
    std::string page;
    page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
    page += "<meta http-equiv=\"Content-Security-Policy\" content=\"";
    page += kPolicy;
    page += "\">\n<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
    page += kind == PageKind::kCdi ? "<title>CDI</title>\n" : "<title>lcc-conform</title>\n";
    page += "<style>\n";
    page += html_asset("page.css");
    page += "</style>\n</head>\n<body>\n<div id=\"app\"></div>\n";
    page += "<script type=\"application/json\" id=\"page-data\">";
    write_data(page);
    page += "</script>\n<script>\n";
    page += html_asset("map.js");
    page += "\n</script>\n<script>\n";
    page += html_asset(script);
    page += "\n</script>\n</body>\n</html>\n";
    return page;
}

}  // namespace olcb::cdi
