// One self-contained HTML page (lcc-conform --html, lcc-cdi render --html): the stylesheet and
// scripts of cdi/html/ (embedded at build time) and the page's data as JSON. Nothing is loaded
// from anywhere else: the page's Content-Security-Policy forbids every request.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

namespace olcb::cdi {

/// Which script renders a page's data.
enum class PageKind : std::uint8_t {
    kConformance,  ///< cdi/html/conform.js: a conformance run
    kCdi,          ///< cdi/html/cdi.js: a CDI as a configuration tool shows it
};

/// The page: `data` goes in as JSON inside <script type="application/json"> with every '<',
/// '>' and '&' escaped (node text can never close the element) and invalid UTF-8 replaced by
/// U+FFFD; the scripts put it on screen with textContent only.
std::string html_page(PageKind kind, const nlohmann::json& data);

/// The page with its data written by `write_data` straight into the page text, through
/// append_script_json() and raw JSON punctuation, so a large page's data is never held as a JSON
/// tree (a CDI of 100,000 elements: the tree cost 9x the page's text).
std::string html_page_from(PageKind kind, const std::function<void(std::string& out)>& write_data);

/// Appends `value` as JSON safe inside the page's <script> element (escaped as html_page()
/// describes).
void append_script_json(std::string& out, const nlohmann::json& value);

/// As append_script_json() for a non-empty object, leaving it open: the caller appends further
/// `,"key":value` members and the closing '}'.
void append_open_object(std::string& out, const nlohmann::json& object);

/// An embedded asset of cdi/html/ by file name ("page.css", "map.js", ...); empty when unknown.
std::string_view html_asset(std::string_view name);

}  // namespace olcb::cdi
