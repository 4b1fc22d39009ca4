// A configuration backup file as records: key=value lines in OpenLCB_Java's format, or the CSV
// form of `backup --csv` (conformance/backup/backup_csv.hpp); both restore and diff the same way.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "conformance/backup/backup_keys.hpp"
#include "conformance/backup/config_reader.hpp"

namespace olcb::conform {

/// Where a CSV backup says a variable lies (its type, space, address and size columns).
struct BackupPlace {
    std::string type;
    std::uint32_t space = 0;
    std::uint64_t address = 0;
    std::uint64_t size = 0;
    friend bool operator==(const BackupPlace&, const BackupPlace&) = default;
};

/// One key=value line or CSV row of a backup file.
struct BackupRecord {
    std::string key;                   ///< normal_backup_key of the key as written
    std::string value;                 ///< the value, unescaped
    std::size_t line = 0;              ///< 1-based line of the file
    std::optional<BackupPlace> place;  ///< CSV rows only
};

/// A configuration backup read into records.
struct BackupFile {
    std::vector<BackupRecord> records;
    std::optional<std::string> node;  ///< the "# node ID" header line, when present
    bool csv = false;                 ///< read from the CSV form
    std::vector<std::string> errors;  ///< malformed lines ("line N: ...")
};

/// A key as lcc-conform writes it: escapes in either hex case read the same ("\x003D" and
/// "\x003d"; OpenLCB_Java writes lower case).
std::string normal_backup_key(std::string_view key);

/// Reads a backup text: key=value lines ('#' comments and blank lines skipped), or CSV rows
/// when the first line is a CSV header ("key,value,...").
BackupFile parse_backup_file(std::string_view text);

/// Reads a backup file from disk; false with error when it cannot be read or is empty.
bool load_backup_file(const std::string& path, BackupFile& file, std::string& error);

/// The key=value text of a node's values: two '#' header lines naming the node, then one line
/// per value read, in entry order; never a blank line (older OpenLCB_Java throws on one).
std::string backup_text(const std::vector<ConfigEntry>& entries,
                        const std::vector<ConfigValue>& values, const std::string& node_id);

/// The node ID (dotted hex) of the "# node ..." header line of a backup text, if present.
std::optional<std::string> config_backup_node(std::string_view text);

}  // namespace olcb::conform
