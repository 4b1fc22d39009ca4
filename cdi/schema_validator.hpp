// Validation of CDI text against the official CDI XML Schemas (1.0 to 1.4), compiled into the
// library and run by libxml2. The schema is chosen by the version the CDI itself declares.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string_view>

#include "cdi/diagnostic.hpp"

namespace olcb::cdi {

/// The CDI schema versions compiled into the library (openlcb/documents schema/cdi/1/N).
enum class SchemaVersion : std::uint8_t { kV1_0, kV1_1, kV1_2, kV1_3, kV1_4 };

/// The schema used when a CDI declares no version, or one this library does not know.
inline constexpr SchemaVersion kNewestSchema = SchemaVersion::kV1_4;

/// Inputs larger than this are refused unparsed (space 0xFF of real nodes holds a few 10 KB).
inline constexpr std::size_t kMaxCdiBytes = std::size_t{16} * 1024 * 1024;

/// "1.0" ... "1.4".
std::string_view schema_version_name(SchemaVersion version);

/// The XSD text of a version, as compiled in (empty for an out-of-range value).
std::string_view embedded_schema(SchemaVersion version);

/// The version named by an xsi:noNamespaceSchemaLocation ".../schema/cdi/1/N/cdi.xsd" with N in
/// 0..4; nullopt for anything else (absent, unversioned URL, unknown N such as "1/43").
std::optional<SchemaVersion> schema_version_from_location(std::string_view location);

/// Which schema validate_schema used and why.
struct SchemaChoice {
    SchemaVersion version = kNewestSchema;
    bool declared = false;     ///< the CDI named this version itself
    bool well_formed = false;  ///< libxml2 parsed the text (no schema check happens otherwise)
};

/// Validates CDI text (trailing NUL bytes ignored) against the schema it declares, falling back
/// to the newest with a warning. Parse and validity errors carry their source line. A DOCTYPE is
/// refused unexpanded. `chosen`, when given, receives the choice.
Diagnostics validate_schema(std::string_view bytes, SchemaChoice* chosen = nullptr);

/// Validates CDI text against one given schema version, whatever the CDI declares.
Diagnostics validate_schema_as(std::string_view bytes, SchemaVersion version);

}  // namespace olcb::cdi
