// The CSV form of a configuration backup (`lcc-conform backup --csv`): one row per variable
// with its key, value, type, space, address and size, for spreadsheets and scripts (RFC 4180:
// comma separated, fields with a comma, quote, line end or edge space quoted). Restore reads it
// like the key=value form and also checks each row's place against the node's CDI.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "conformance/backup/backup_file.hpp"

namespace olcb::conform {

/// The first line of a CSV backup.
inline constexpr std::string_view kBackupCsvHeader = "key,value,type,space,address,size";

/// True when the text starts like the CSV header line ("key,value").
bool is_backup_csv(std::string_view text);

/// One CSV field, quoted when it must be.
std::string csv_field(std::string_view text);

/// The CSV text of a node's values: the header, then one row per value read, in entry order.
/// Values are raw (not backslash-escaped); space, address and size are decimal.
std::string backup_csv(const std::vector<ConfigEntry>& entries,
                       const std::vector<ConfigValue>& values);

/// Reads a CSV backup (columns found by the header's names; key and value required, the others
/// optional); malformed rows go to errors with their line.
BackupFile parse_backup_csv(std::string_view text);

}  // namespace olcb::conform
