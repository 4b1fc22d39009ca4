// One self-contained HTML page (lcc-conform --html, lcc-cdi render --html): the stylesheet and
// scripts of cdi/html/ (embedded at build time) and the page's data as JSON. Nothing is loaded
// from anywhere else: the page's Content-Security-Policy forbids every request.
#pragma once

#include <cstdint>
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

/// An embedded asset of cdi/html/ by file name ("page.css", "map.js", ...); empty when unknown.
std::string_view html_asset(std::string_view name);

}  // namespace olcb::cdi
