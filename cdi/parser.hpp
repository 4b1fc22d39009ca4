// Parses the CDI XML a node serves (memory space 0xFF) into the typed model of document.hpp.
#pragma once

#include <cstddef>
#include <optional>
#include <string_view>

#include "cdi/decimal.hpp"
#include "cdi/diagnostic.hpp"
#include "cdi/document.hpp"
#include "cdi/loaded_xml.hpp"

namespace olcb::cdi {

/// The outcome of parse(): a document when there were no errors, and every finding.
struct ParseResult {
    std::optional<Document> document;
    Diagnostics diagnostics;
};

/// Deepest group nesting accepted. Every walk over groups (parser, layout, rules, renderers) is
/// iterative, so this bounds no stack: it refuses hostile nesting with a clear diagnostic.
inline constexpr std::size_t kMaxGroupDepth = 1024;

/// Parses CDI bytes as a node serves them; document is empty when diagnostics has errors.
ParseResult parse(std::string_view bytes);

/// The same, from a text already loaded (validate() shares one load with the schema check).
ParseResult parse(const LoadedXml& loaded);

}  // namespace olcb::cdi
