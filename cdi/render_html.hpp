// The CDI as a configuration tool would show it, as one HTML page (lcc-cdi render --html):
// segments as tabs, groups with their names and descriptions, replications numbered by their
// repnames, the 1.4 hints as controls, and each segment's space as a memory map.
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json_fwd.hpp>

#include "cdi/layout.hpp"
#include "cdi/memory_map.hpp"

namespace olcb::cdi {

/// The data cdi/html/cdi.js renders: {"source", "identification", "acdi", "segments": [{"name",
/// "description", "space", "origin", "link", "children": [element]}], "memory_map": [...]}; each
/// element has an "id", its "kind", "address" (first replica) and constraints, groups their
/// "replication", "stride" and "replica_names"; memory-map variables name their "element" and
/// the "replicas" of their replicated groups.
nlohmann::json cdi_page_json(const Layout& layout, std::string_view source,
                             const MemoryMapOptions& options = {});

/// The whole page of cdi_page_json().
std::string render_html(const Layout& layout, std::string_view source,
                        const MemoryMapOptions& options = {});

}  // namespace olcb::cdi
