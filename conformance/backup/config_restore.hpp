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
#include "conformance/backup/value_rules.hpp"
#include "conformance/link/memory_access.hpp"

namespace olcb::conform {

/// A variable whose file value differs from the node's.
struct ValueChange {
    const ConfigEntry* entry = nullptr;
    std::optional<std::string> node_value;  ///< nullopt when the node's value could not be read
    std::string file_value;                 ///< as written in the file (unescaped)
    std::vector<std::uint8_t> bytes;        ///< what a restore writes
};

/// A value of the file that differs from the node's and that the node's CDI forbids writing
/// (CDI §5.1.4.2-§5.1.4.5: "shall not be written"): nothing is written for its key unless
/// `restore --force` writes it anyway (only when it has bytes).
struct RefusedValue {
    const ConfigEntry* entry = nullptr;
    std::size_t line = 0;                   ///< the file's line
    std::string file_value;                 ///< as written in the file (unescaped)
    std::optional<std::string> node_value;  ///< nullopt when the node's value could not be read
    ValueVerdict verdict;                   ///< the rule broken, why, and the bytes (if any)
};

/// One line for a refused value, safe for a terminal (printable()): "line 12:
/// Settings.Trim="2000": out-of-range: value 2000 above max 1000 of 'Trim' (<int> at CDI line
/// 24; CDI §5.1.4.2: invalid values shall not be written)".
std::string refused_text(const RefusedValue& refused);

/// What restoring a file onto a node would do.
struct RestorePlan {
    std::size_t node_keys = 0;  ///< the node's keys OpenLCB_Java writes (floats aside)
    std::size_t matched = 0;    ///< of those, how many the file holds
    std::size_t unchanged = 0;  ///< file values the node already holds
    std::vector<ValueChange> changes;
    std::vector<std::string> unknown_keys;    ///< "line N: KEY": no such variable in the CDI
    std::vector<RefusedValue> refused;        ///< values the CDI forbids (or not values at all)
    std::vector<std::string> file_errors;     ///< malformed lines
    std::vector<const ConfigEntry*> missing;  ///< the node's variables the file lacks

    /// True when the file matches less than half of the node's keys: it is for another node
    /// type (or no backup at all), and nothing may be written.
    bool for_another_node() const { return node_keys > 0 && matched * 2 < node_keys; }
    /// True when every line of the file is a value of this node the CDI allows.
    bool clean() const { return unknown_keys.empty() && refused.empty() && file_errors.empty(); }
    /// How many refused values have bytes --force could write.
    std::size_t forcible() const;
};

/// Matches the file's records to entries (the n-th line of a repeated key is its n-th
/// variable) and compares each value with node_values (read_config_values of entries). A CSV
/// row whose type, space, address or size disagree with the CDI is a key of another CDI. A value
/// that differs from the node's is judged by the CDI's rules (judge_backup_value): a change when
/// allowed, refused otherwise; a value the node already holds is never written, so not judged.
RestorePlan plan_restore(const std::vector<ConfigEntry>& entries, const BackupFile& file,
                         const std::vector<ConfigValue>& node_values);

/// What a restore did.
struct ConfigRestoreOutcome {
    std::size_t written = 0;                ///< variables written and read back equal
    std::size_t forced = 0;                 ///< of those, values the CDI forbids (--force)
    std::vector<std::string> unknown_keys;  ///< keys of the file the CDI does not have
    std::vector<std::string> errors;        ///< bad values, failed writes, values not kept
    /// True when every known value was written.
    bool ok() const { return errors.empty(); }
    /// One line: counts, then the unknown keys and errors.
    std::string summary() const;
};

/// Writes every change of the plan (with force also every refused value that has bytes), then
/// reads each back to prove the node kept it.
ConfigRestoreOutcome apply_restore(const RestorePlan& plan, MemoryAccess& memory,
                                   bool force = false);

/// plan_restore + apply_restore of a backup text onto the layout's variables, whatever share
/// of the node's keys the text matches (the command refuses files for another node first);
/// refused values not written are errors.
ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text, bool force = false);

/// The value as shown in reports: escaped as in a backup line, "(unreadable)" for nullopt.
std::string shown_value(const std::optional<std::string>& value);

}  // namespace olcb::conform
