// Validation of CDI text against the official CDI XML Schemas (1.0 to 1.4), and of FDI text
// (Function Description Information, a train node's space 0xFA) against the FDI schemas (1.0,
// 1.1), compiled into the library and run by libxml2. The schema is chosen by the version the
// text itself declares.
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

/// The FDI schema versions compiled into the library (openlcb/documents schema/fdi/1/N). The
/// published 1.0 and 1.1 files are the same; the embedded 1.1 adds the <icon> element the
/// standard defines (FunctionDescriptionInformationS §5.1.4, Appendix A; docs/validation.md).
enum class FdiSchemaVersion : std::uint8_t { kV1_0, kV1_1 };

/// The FDI schema used when an FDI declares no version, or one this library does not know.
inline constexpr FdiSchemaVersion kNewestFdiSchema = FdiSchemaVersion::kV1_1;

/// "1.0" or "1.1".
std::string_view fdi_schema_version_name(FdiSchemaVersion version);

/// The FDI XSD text of a version, as compiled in (empty for an out-of-range value).
std::string_view embedded_fdi_schema(FdiSchemaVersion version);

/// The version named by an xsi:noNamespaceSchemaLocation ".../schema/fdi/1/N/fdi.xsd" with N in
/// 0..1; nullopt for anything else.
std::optional<FdiSchemaVersion> fdi_schema_version_from_location(std::string_view location);

/// Which FDI schema validate_fdi_schema used and why.
struct FdiSchemaChoice {
    FdiSchemaVersion version = kNewestFdiSchema;
    bool declared = false;     ///< the FDI named this version itself
    bool well_formed = false;  ///< libxml2 parsed the text (no schema check happens otherwise)
};

/// validate_schema() for an FDI: the schema the FDI declares, else the newest with a warning.
/// The same limits apply (kMaxCdiBytes, no DOCTYPE, trailing NULs ignored).
Diagnostics validate_fdi_schema(std::string_view bytes, FdiSchemaChoice* chosen = nullptr);

/// Validates FDI text against one given FDI schema version, whatever the FDI declares.
Diagnostics validate_fdi_schema_as(std::string_view bytes, FdiSchemaVersion version);

}  // namespace olcb::cdi
