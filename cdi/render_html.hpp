// The CDI as a configuration tool would show it, as one HTML page (lcc-cdi render --html):
// segments as tabs, groups with their names and descriptions, replications numbered by their
// repnames, the 1.4 hints as controls, and each segment's space as a memory map.
#pragma once

#include <string>
#include <string_view>

#include "cdi/layout.hpp"
#include "cdi/memory_map.hpp"

namespace olcb::cdi {

/// The data cdi/html/cdi.js renders: {"source", "identification", "acdi", "segments": [{"name",
/// "description", "space", "origin", "link", "children": [element]}], "memory_map": [...]}; each
/// element has an "id", its "kind", "address" (first replica) and constraints, groups their
/// "replication", "stride" and "replica_names"; memory-map variables name their "element" and
/// the "replicas" of their replicated groups.
/// Written as JSON text (escaped for the page's <script> element, html_page.hpp) onto `out`,
/// element by element: no JSON tree of the whole CDI is built.
void append_cdi_page_data(std::string& out, const Layout& layout, std::string_view source,
                          const MemoryMapOptions& options = {});

/// The whole page with append_cdi_page_data()'s data.
std::string render_html(const Layout& layout, std::string_view source,
                        const MemoryMapOptions& options = {});

}  // namespace olcb::cdi
