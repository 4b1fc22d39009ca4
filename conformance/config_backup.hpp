// The whole-configuration backup of `lcc-conform backup` / `restore`: every CDI variable as one
// `key=value` line in OpenLCB_Java/JMRI's backup format (docs: jmri-backup-format.md), so JMRI
// users can load the file; floats are written too, and files without them restore fine.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "conformance/backup.hpp"

namespace olcb::conform {

class Session;
struct NodeInfo;

/// One backed-up variable: its key and where its bytes lie.
struct ConfigEntry {
    std::string key;                        ///< dotted path, e.g. "Port I/O.Line(3).Event On"
    const cdi::Element* element = nullptr;  ///< the variable (int, float, string or eventid)
    std::uint32_t space = 0;
    std::uint64_t address = 0;
};

/// The JMRI backup key of the variable at the cursor (also what --exclude/--only match).
std::string backup_key(const cdi::Layout& layout, const cdi::Cursor& cursor);

/// Every value variable of the layout in document order, with its JMRI key (actions, blobs and
/// unknown elements are left out).
std::vector<ConfigEntry> config_entries(const cdi::Layout& layout);

/// A string value escaped for a backup line: `=`, `\` and control characters as \x + 4 hex.
std::string escape_backup_text(std::string_view text);
/// The inverse of escape_backup_text; malformed escapes are kept as written.
std::string unescape_backup_text(std::string_view text);

/// The backup file text of a node's configuration read through `memory`; variables that
/// cannot be read are left out and described in `errors`.
std::string make_config_backup(const cdi::Layout& layout, MemoryAccess& memory,
                               const std::string& node_id, std::vector<std::string>& errors);

/// What a configuration restore did.
struct ConfigRestoreOutcome {
    std::size_t written = 0;                ///< variables written
    std::vector<std::string> unknown_keys;  ///< keys of the file the CDI does not have
    std::vector<std::string> errors;        ///< unparsable values and failed writes
    /// True when every known value was written.
    bool ok() const { return errors.empty(); }
    /// One line: counts, then the unknown keys and errors.
    std::string summary() const;
};

/// Writes every value of a backup file text that the layout knows; unknown keys are reported,
/// not fatal. Integers are accepted signed or unsigned (OpenLCB_Java writes them unsigned).
ConfigRestoreOutcome restore_config(const cdi::Layout& layout, MemoryAccess& memory,
                                    std::string_view text);

/// The node ID (dotted hex) of the "# node ..." header line of a backup file, if present.
std::optional<std::string> config_backup_node(std::string_view text);

/// A node's CDI, downloaded and laid out (the Document outlives the Layout that points into it).
struct NodeConfig {
    std::unique_ptr<cdi::Document> document;
    std::optional<cdi::Layout> layout;
};

/// Downloads space 0xFF, parses it and builds the layout; false with `error` when any step fails.
bool load_node_config(Session& session, const NodeInfo& node, NodeConfig& config,
                      std::string& error);

/// `lcc-conform backup --node ID FILE`: 0 on success, 1 when some variable could not be read,
/// 2 when the node, CDI or file is unusable.
int run_config_backup(Session& session, const std::string& node_id, const std::string& path,
                      std::ostream& out, std::ostream& err);

/// `lcc-conform restore FILE`: a safety backup goes back byte for byte, a JMRI configuration
/// backup variable by variable (node from `node_id`, else from the file's header). 0 on success,
/// 1 when something differs or failed, 2 when the file or node is unusable.
int run_restore(Session& session, const std::string& path, const std::string& node_id,
                std::ostream& out, std::ostream& err);

}  // namespace olcb::conform
