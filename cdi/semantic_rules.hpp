// CDI rules the XML Schemas cannot express (value ranges, hint/map consistency, sizes under
// the older schemas, identification lengths), checked on the typed model.
#pragma once

#include <cstddef>

#include "cdi/diagnostic.hpp"
#include "cdi/document.hpp"

namespace olcb::cdi {

/// Longest identification strings SNIP and ACDI space 252 can carry (bytes, NUL excluded).
inline constexpr std::size_t kMaxManufacturerBytes = 40;
inline constexpr std::size_t kMaxModelBytes = 40;
inline constexpr std::size_t kMaxHardwareVersionBytes = 20;
inline constexpr std::size_t kMaxSoftwareVersionBytes = 20;

/// The ACDI layout versions this library knows (standard 5.1.2: fixed="4", var="2").
inline constexpr unsigned kAcdiFixedVersion = 4;
inline constexpr unsigned kAcdiVarVersion = 2;

/// Checks every semantic rule on a parsed document; each finding names the element, its name
/// if any, and carries the element's line. Errors and warnings, in document order.
Diagnostics check_semantics(const Document& doc);

}  // namespace olcb::cdi
