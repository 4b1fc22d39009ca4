// What users review before applying a backup: the differences of two backup files, and what a
// restore of a file would change on a node (`lcc-conform diff`, `restore --dry-run`).
#pragma once

#include <iosfwd>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "conformance/backup/backup_file.hpp"
#include "conformance/backup/config_restore.hpp"

namespace olcb::conform {

/// A key whose value differs between two backups, or that only one of them holds.
struct BackupDifference {
    std::string key;
    std::optional<std::string> a;  ///< nullopt: only in b
    std::optional<std::string> b;  ///< nullopt: only in a
};

/// True when two value texts of one key (no CDI at hand) are the same value: equal text, equal
/// numbers, or an int written signed in one and unsigned in the other ("-123" and "65413": the
/// unsigned one's smallest size of 1, 2, 4 or 8 bytes decides).
bool same_backup_value(std::string_view a, std::string_view b);

/// The differences of two backups: a's keys in order, then the keys only b has; the n-th line
/// of a repeated key is compared with the other file's n-th.
std::vector<BackupDifference> diff_backups(const BackupFile& a, const BackupFile& b);

/// One line per difference ("changed", "only in A", "only in B") and a count line.
void print_differences(const std::vector<BackupDifference>& diffs, std::size_t keys,
                       std::ostream& out);

/// Every unknown key, refused value (with its rule and CDI line) and malformed line of the plan,
/// one per line; with force the refused values --force writes say so. Text from the file and
/// the CDI goes through printable().
void print_problems(const RestorePlan& plan, std::ostream& out, bool force = false);

/// What the plan would change on the node (key, node value, file value), then its problems;
/// with show_missing also the node's keys the file lacks.
void print_plan(const RestorePlan& plan, bool show_missing, std::ostream& out, bool force = false);

}  // namespace olcb::conform
