// Restoring a configuration backup: which file values a node's CDI knows, which differ from
// what the node holds (the only ones written), and what the file has that the CDI has not.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "conformance/backup/backup_file.hpp"
#include "conformance/backup/backup_keys.hpp"
#include "conformance/backup/config_reader.hpp"
#include "conformance/link/memory_access.hpp"

namespace olcb::conform {

/// A variable whose file value differs from the node's.
struct ValueChange {
    const ConfigEntry* entry = nullptr;
    std::optional<std::string> node_value;  ///< nullopt when the node's value could not be read
    std::string file_value;                 ///< as written in the file (unescaped)
    std::vector<std::uint8_t> bytes;        ///< what a restore writes
};

/// What restoring a file onto a node would do.
struct RestorePlan {
    std::size_t node_keys = 0;  ///< the node's keys OpenLCB_Java writes (floats aside)
    std::size_t matched = 0;    ///< of those, how many the file holds
    std::size_t unchanged = 0;  ///< file values the node already holds
    std::vector<ValueChange> changes;
    std::vector<std::string> unknown_keys;    ///< "line N: KEY": no such variable in the CDI
    std::vector<std::string> bad_values;      ///< "line N: KEY: why": out of range, unparsable
    std::vector<std::string> file_errors;     ///< malformed lines
    std::vector<const ConfigEntry*> missing;  ///< the node's variables the file lacks

    /// True when the file matches less than half of the node's keys: it is for another node
    /// type (or no backup at all), and nothing may be written.
    bool for_another_node() const { return node_keys > 0 && matched * 2 < node_keys; }
    /// True when every line of the file is a value of this node.
    bool clean() const { return unknown_keys.empty() && bad_values.empty() && file_errors.empty(); }
};

/// Matches the file's records to entries (the n-th line of a repeated key is its n-th
/// variable) and compares each value with node_values (read_config_values of entries). A CSV
/// row whose type, space, address or size disagree with the CDI is a key of another CDI.
RestorePlan plan_restore(const std::vector<ConfigEntry>& entries, const BackupFile& file,
                         const std::vector<ConfigValue>& node_values);

/// What a restore did.
struct ConfigRestoreOutcome {
    std::size_t written = 0;                ///< variables written and read back equal
    std::vector<std::string> unknown_keys;  ///< keys of the file the CDI does not have
    std::vector<std::string> errors;        ///< bad values, failed writes, values not kept
    /// True when every known value was written.
    bool ok() const { return errors.empty(); }
    /// One line: counts, then the unknown keys and errors.
    std::string summary() const;
};

/// Writes every change of the plan, then reads each back to prove the node kept it.
ConfigRestoreOutcome apply_restore(const RestorePlan& plan, MemoryAccess& memory);

/// plan_restore + apply_restore of a backup text onto the layout's variables, whatever share
/// of the node's keys the text matches (the command refuses files for another node first).
ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text);

/// The value as shown in reports: escaped as in a backup line, "(unreadable)" for nullopt.
std::string shown_value(const std::optional<std::string>& value);

}  // namespace olcb::conform
