// FDI rules the XML Schema cannot express, checked on the model: the reserved segment attributes,
// the <icon> the published schema lacks, analog ranges, numbers described twice. All warnings:
// the standard's "shall"s are the schema's (docs/validation.md, "FDI").
#pragma once

#include "cdi/diagnostic.hpp"
#include "cdi/fdi_document.hpp"
#include "cdi/schema_validator.hpp"

namespace olcb::cdi {

/// The largest value Train Control's Set Function carries (16 bits; FDI-TN §3.1).
inline constexpr std::int64_t kMaxFunctionValue = 65535;

/// Checks an FDI validated against `schema` (the <icon> warning applies where the schema let the
/// element pass). Each finding names the element, its <name> if any, its line and the clause.
Diagnostics check_fdi_semantics(const FdiDocument& doc, FdiSchemaVersion schema);

}  // namespace olcb::cdi
