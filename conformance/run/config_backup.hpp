// The whole-configuration backup of `lcc-conform backup` / `restore` / `diff`: every CDI
// variable as one `key=value` line in OpenLCB_Java/JMRI's backup format (docs/backup.md,
// jmri-backup-format.md) with JMRI's own keys and value forms, so files pass between JMRI and
// lcc-conform both ways; floats are written too, and files without them restore fine. The
// pieces: backup_keys (keys), backup_values (value text), config_reader (merged reads),
// backup_file/backup_csv (the two file forms), config_restore (plan and apply), backup_diff.
#pragma once

#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "conformance/backup/backup_diff.hpp"
#include "conformance/backup/backup_file.hpp"
#include "conformance/backup/backup_keys.hpp"
#include "conformance/backup/backup_values.hpp"
#include "conformance/backup/config_reader.hpp"
#include "conformance/backup/config_restore.hpp"
#include "conformance/run/safety_backup.hpp"

namespace olcb::conform {

class Session;
struct NodeInfo;

/// The key=value backup text of a node's configuration read through `memory`; variables that
/// cannot be read are left out and described in `errors` ("KEY: why").
std::string make_config_backup(const cdi::Layout& layout, MemoryAccess& memory,
                               const std::string& node_id, std::vector<std::string>& errors);

/// A node's CDI, downloaded and laid out (the Document outlives the Layout that points into it).
struct NodeConfig {
    std::unique_ptr<cdi::Document> document;
    std::optional<cdi::Layout> layout;
};

/// Downloads space 0xFF, parses it and builds the layout; false with `error` when any step fails.
bool load_node_config(Session& session, const NodeInfo& node, NodeConfig& config,
                      std::string& error);

/// The node a command works on: `node_id` when given, else `file_node` (a backup's header),
/// else the only node answering Verify Node ID (said on `out`); nullopt after saying why on
/// `err` (bad ID, no answer, no node, or several: they are listed).
std::optional<NodeInfo> choose_node(Session& session, const std::string& node_id,
                                    const std::optional<std::string>& file_node, std::ostream& out,
                                    std::ostream& err);

/// Options of `lcc-conform backup [--node ID] [--csv] FILE`.
struct BackupOptions {
    std::string node_id;  ///< --node; empty: the only node on the bus
    std::string path;     ///< FILE
    bool csv = false;     ///< --csv: key,value,type,space,address,size rows
};

/// `lcc-conform backup`: 0 on success, 1 when some variable could not be read, 2 when the node,
/// CDI or file is unusable.
int run_config_backup(Session& session, const BackupOptions& options, std::ostream& out,
                      std::ostream& err);

/// Options of `lcc-conform restore [--node ID] [--dry-run] [--allow-unknown] [--force] FILE`.
struct RestoreOptions {
    std::string path;            ///< FILE: a safety backup, a key=value or a CSV backup
    std::string node_id;         ///< --node; empty: the file's "# node" line, else the only node
    bool dry_run = false;        ///< --dry-run: print what would change, write nothing
    bool allow_unknown = false;  ///< --allow-unknown: unknown keys and malformed lines exit 0
    bool force = false;          ///< --force: also write values the node's CDI forbids
};

/// `lcc-conform restore`: a safety backup goes back byte for byte; a configuration backup
/// writes the values that differ from the node's and that its CDI allows (nothing when the file
/// is unusable or matches less than half of the node's keys; with force also the forbidden
/// values that have bytes). 0 on success; 1 when a write failed, a value was not kept, the file
/// is for another node type, a value was refused, or (without allow_unknown) a key is unknown
/// or a line malformed; 2 when the file or node is unusable (the cause first, one line).
int run_restore(Session& session, const RestoreOptions& options, std::ostream& out,
                std::ostream& err);

/// `lcc-conform diff A B`: the differences of two backup files (either form); needs no link.
/// 0 when they hold the same values, 1 when they differ, 2 when one cannot be read.
int run_diff_files(const std::string& a, const std::string& b, std::ostream& out,
                   std::ostream& err);

/// Options of `lcc-conform diff [--node ID] FILE`.
struct DiffOptions {
    std::string node_id;  ///< --node; empty: the file's "# node" line, else the only node
    std::string path;     ///< FILE
};

/// `lcc-conform diff --node ID FILE`: what a restore of FILE would change on the node, the
/// values its CDI refuses, and what it cannot restore. 0 when nothing would change and every
/// line is known and allowed, 1 otherwise, 2 when the file or node is unusable.
int run_diff_node(Session& session, const DiffOptions& options, std::ostream& out,
                  std::ostream& err);

}  // namespace olcb::conform
