// The whole check of a CDI, as `lcc-cdi validate` runs it: well-formedness and the declared XML
// Schema (libxml2), the typed model (parser), the semantic rules and the address layout.
#pragma once

#include <memory>
#include <optional>
#include <string_view>

#include "cdi/diagnostic.hpp"
#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {

/// Every finding about one CDI plus what was checked.
struct ValidationReport {
    Diagnostics diagnostics;  ///< sorted by line (0 = whole document first), duplicates removed
    SchemaChoice schema;      ///< the schema version used and whether the CDI declared it
    bool parsed = false;      ///< the model parser produced a document (semantics/layout ran)

    /// True when no finding is an error (warnings allowed).
    bool ok() const { return !has_errors(diagnostics); }
};

/// Parses and checks CDI bytes (trailing NULs ignored): schema, parse, semantic and layout
/// diagnostics merged into one list.
ValidationReport validate(std::string_view bytes);

/// validate()'s report with the model it checked, for rules judged on the model. The document
/// is on the heap because the layout points into it.
struct ValidatedCdi {
    ValidationReport report;
    std::unique_ptr<Document> document;  ///< when the model parser produced one
    std::optional<Layout> layout;        ///< when the layout has no errors
};

/// validate() keeping the parsed document and its layout.
ValidatedCdi validate_model(std::string_view bytes);

}  // namespace olcb::cdi
