// The value text of a configuration backup line, as OpenLCB_Java writes and reads it
// (jmri-backup-format.md): integers in decimal, 8-byte ones signed; event IDs in dotted hex;
// strings up to their NUL with separators and controls escaped; floats in decimal.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/variable_name.hpp"

namespace olcb::conform {

/// A string value escaped for a backup line: `=`, `\` and control characters as \x + 4 hex.
/// In cdi/ because variable names (the backup keys) are escaped the same way.
using cdi::escape_backup_text;
/// The inverse of escape_backup_text (either hex case); malformed escapes are kept as written.
std::string unescape_backup_text(std::string_view text);

/// The text of a variable's bytes (value_size long) as OpenLCB_Java writes it: an int of 1, 2
/// or 4 bytes unsigned and of 8 bytes as a signed 64-bit number; nullopt with error when the
/// bytes do not decode (wrong length, an int size OpenLCB_Java cannot hold). Strings unescaped.
std::optional<std::string> format_backup_value(const cdi::Element& element,
                                               std::span<const std::uint8_t> bytes,
                                               std::string& error);

/// The bytes to write for a value text (strings unescaped): an int in either form, signed or
/// unsigned, as long as it fits the size; nullopt with error ("out of range", unparsable).
std::optional<std::vector<std::uint8_t>> parse_backup_value(const cdi::Element& element,
                                                            std::string_view text,
                                                            std::string& error);

/// The text format_backup_value gives the bytes parse_backup_value makes of text: equal for
/// two texts of one variable exactly when they store the same value ("65413" and "-123" in a
/// 2-byte int); nullopt with error when text is not a value of the element.
std::optional<std::string> canonical_backup_value(const cdi::Element& element,
                                                  std::string_view text, std::string& error);

/// "int", "string", "eventid" or "float": the type column of a CSV backup.
const char* backup_type_name(const cdi::Element& element);

}  // namespace olcb::conform
