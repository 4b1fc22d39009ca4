// The whole check of an FDI, as `lcc-cdi validate` runs it: well-formedness and the declared FDI
// schema (libxml2), the model (fdi_parser) and the rules no schema expresses
// (fdi_semantic_rules). What a throttle, a train node or lcc-conform calls to read an FDI.
#pragma once

#include <optional>
#include <string_view>

#include "cdi/diagnostic.hpp"
#include "cdi/fdi_document.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {

/// Every finding about one FDI text, the schema it was judged by and the model read from it.
struct ValidatedFdi {
    Diagnostics diagnostics;  ///< sorted by line (0 = whole document first), duplicates removed
    FdiSchemaChoice schema;   ///< the schema version used and whether the FDI declared it
    /// The functions, whenever the text is XML with an <fdi> root (also when it has errors: a
    /// function whose <number> cannot be read is left out).
    std::optional<FdiDocument> document;

    /// True when no finding is an error (warnings allowed): the FDI conforms.
    bool ok() const { return !has_errors(diagnostics); }
};

/// Parses and checks FDI bytes (trailing NULs ignored): schema, model and semantic findings
/// merged into one list. The model parser's errors restate what the schema refuses in other
/// words, so they are kept only when the schema pass found no error.
ValidatedFdi validate_fdi(std::string_view bytes);

}  // namespace olcb::cdi
