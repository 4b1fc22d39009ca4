// A configuration backup file as records: key=value lines in OpenLCB_Java's format, or the CSV
// form of `backup --csv` (conformance/backup/backup_csv.hpp); both restore and diff the same way.
#pragma once

#include <cstdint>
#include <iosfwd>
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

/// The most examples a message about a bad backup file lists; a count gives the rest.
inline constexpr std::size_t kMaxBackupExamples = 10;

/// Why a file is no usable backup at all (empty, not text, cut short, no key=value line, or for
/// another node type): one line of cause, then a few examples and how many there are.
struct UnusableBackup {
    std::string cause;                  ///< follows the file's name: "is empty (0 bytes)"
    std::vector<std::string> examples;  ///< at most kMaxBackupExamples, printable()
    std::size_t count = 0;              ///< examples in all

    /// Counts one more example and keeps it (printable) while fewer than the most are kept.
    void add(std::string_view example);
};

/// "lcc-conform: PATH CAUSE[CONSEQUENCE]" on one line (printable), then each example indented
/// and "... and N more" when not all were kept: the cause first, so it is never lost in a list.
void print_unusable(std::string_view path, const UnusableBackup& unusable,
                    std::string_view consequence, std::ostream& out);

/// A configuration backup read into records.
struct BackupFile {
    std::vector<BackupRecord> records;
    std::optional<std::string> node;  ///< the "# node ID" header line, when present
    bool csv = false;                 ///< read from the CSV form
    std::vector<std::string> errors;  ///< malformed lines ("line N: ...")
    /// Set when the text is no backup to use at all: empty, not text (a control or NUL byte
    /// outside a CSV value, invalid UTF-8 outside a value), cut short (a last line without its
    /// line end, a quote never closed), or no key=value line. Nothing may be written then.
    std::optional<UnusableBackup> unusable;
};

/// The largest backup file read (a node of thousands of variables writes a few MB).
inline constexpr std::size_t kMaxBackupBytes = std::size_t{64} << 20;

/// A key as lcc-conform writes it: escapes in either hex case read the same ("\x003D" and
/// "\x003d"; OpenLCB_Java writes lower case).
std::string normal_backup_key(std::string_view key);

/// Reads a backup text: key=value lines ('#' comments and blank lines skipped), or CSV rows
/// when the first line is a CSV header ("key,value,..."); `unusable` says when it is no backup.
BackupFile parse_backup_file(std::string_view text);

/// The text of a backup file named by a user: at most `limit` bytes (a FIFO or /dev/stdin read
/// within that bound); nullopt with error ("cannot read PATH: REASON") otherwise.
std::optional<std::string> read_backup_text(const std::string& path, std::string& error,
                                            std::size_t limit = kMaxBackupBytes);

/// Reads a backup file from disk; false with error when it cannot be read. A file read but
/// unusable (BackupFile::unusable) returns true: the caller says why.
bool load_backup_file(const std::string& path, BackupFile& file, std::string& error);

/// The key=value text of a node's values: two '#' header lines naming the node, then one line
/// per value read, in entry order; never a blank line (older OpenLCB_Java throws on one).
std::string backup_text(const std::vector<ConfigEntry>& entries,
                        const std::vector<ConfigValue>& values, const std::string& node_id);

/// The node ID (dotted hex) of the "# node ..." header line of a backup text, if present.
std::optional<std::string> config_backup_node(std::string_view text);

}  // namespace olcb::conform
