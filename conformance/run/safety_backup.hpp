// The safety backup of lcc-conform: every byte a run will write is saved to a file before the
// first write, put back at the end (or on SIGINT/SIGTERM, or later by `lcc-conform restore FILE`)
// and read again to prove the node's memory is byte-identical to before.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "conformance/link/memory_access.hpp"

namespace olcb::conform {

/// A run of bytes of one space, as they were before the run touched them.
struct BackupRange {
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::vector<std::uint8_t> bytes;
    friend bool operator==(const BackupRange&, const BackupRange&) = default;
};

/// Where a range to save lies, before its bytes are known.
struct RangeRequest {
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::uint32_t length = 0;
};

/// Sorts requests and merges the overlapping or adjacent ones of the same space.
std::vector<RangeRequest> merge_ranges(std::vector<RangeRequest> requests);

/// The saved bytes of one node, and their file.
class SafetyBackup {
public:
    /// An empty backup of node `node_id` (dotted hex) kept in `path`.
    SafetyBackup(std::string path, std::string node_id)
        : path_(std::move(path)), node_id_(std::move(node_id)) {}

    /// Reads every requested range from the node and saves the file (synced to disk) before
    /// returning; false with `error` set when a read fails or the file cannot be written, in
    /// which case nothing may be written to the node.
    bool capture(MemoryAccess& memory, const std::vector<RangeRequest>& requests,
                 std::string& error);
    /// Reads every requested range it can, appends those ranges and saves the file (synced)
    /// before returning; the ranges that could not be read go to `missing` with why. False with
    /// `error` only when the file cannot be written (then nothing may be written to the node).
    bool capture_available(MemoryAccess& memory, const std::vector<RangeRequest>& requests,
                           std::vector<std::pair<RangeRequest, std::string>>& missing,
                           std::string& error);
    /// The parts of [address, address + length) of space no saved range holds yet.
    std::vector<RangeRequest> uncovered(std::uint8_t space, std::uint32_t address,
                                        std::uint32_t length) const;
    /// Reads and keeps the parts of r not saved yet (saved bytes keep their first value); ""
    /// when all came, else why not (the file is not written: save() does that).
    std::string save_bytes(MemoryAccess& memory, const RangeRequest& r);
    /// Writes the file atomically (base::write_file: a new temporary file created exclusively,
    /// synced, renamed over path()); false with `error` "cannot open PATH for writing: REASON"
    /// or "cannot write PATH: REASON".
    bool save(std::string& error) const;
    /// Loads a backup file; nullopt with `error` set when it is missing or malformed.
    static std::optional<SafetyBackup> load(const std::string& path, std::string& error);
    /// True when the file text is a safety backup (first line is the header).
    static bool is_safety_backup(const std::string& text);
    /// Deletes the file (after a verified restore).
    void remove_file() const;

    /// The saved ranges.
    const std::vector<BackupRange>& ranges() const { return ranges_; }
    /// Adds a range already read by the caller.
    void add(BackupRange range) { ranges_.push_back(std::move(range)); }
    /// The node this backup belongs to (dotted hex).
    const std::string& node_id() const { return node_id_; }
    /// The file path.
    const std::string& path() const { return path_; }
    /// The whole file text.
    std::string to_text() const;

private:
    std::string path_;
    std::string node_id_;
    std::vector<BackupRange> ranges_;
};

/// What a restore found when reading the bytes back.
struct RestoreOutcome {
    bool identical = false;                ///< every saved byte reads back as saved
    std::size_t bytes = 0;                 ///< saved bytes read back
    std::size_t rewritten = 0;             ///< of them, bytes that differed and were written
    std::vector<std::string> differences;  ///< one line per range that differs or failed
    /// A saved range that changed during the run though none of the run's writes reached it
    /// (another tool's writes): not written back.
    struct LeftAsFound {
        RangeRequest range;
        std::string difference;  ///< what reads back now, in words
    };
    std::vector<LeftAsFound> left_as_found;
    /// "node memory byte-identical to before (N bytes in M ranges restored)" or what differs.
    std::string summary() const;
};

/// Which saved ranges a restore may write back: those the run's own writes may have changed. A
/// range only another tool wrote is left as that tool left it. Empty: every range (a user's
/// `lcc-conform restore FILE`).
using RestoreScope = std::function<bool(const BackupRange&)>;

/// Reads every saved range; writes back those that differ and are in scope, and reads them again.
RestoreOutcome restore(const SafetyBackup& backup, MemoryAccess& memory,
                       const RestoreScope& scope = {});

/// Restores a backup when the run leaves without finish() (an exception, an early return):
/// the "nothing is lost" rule made structural.
class RestoreGuard {
public:
    /// Guards `backup` (restored through `memory`, within `scope`); both must outlive the guard.
    RestoreGuard(const SafetyBackup& backup, MemoryAccess& memory, RestoreScope scope = {})
        : backup_(backup), memory_(memory), scope_(std::move(scope)) {}
    RestoreGuard(const RestoreGuard&) = delete;
    RestoreGuard& operator=(const RestoreGuard&) = delete;
    ~RestoreGuard();
    /// Restores now and reads everything back; the guard is then done.
    RestoreOutcome finish();
    /// The node is out of reach: nothing is written, the backup file stays for the user.
    void abandon() { armed_ = false; }

private:
    const SafetyBackup& backup_;
    MemoryAccess& memory_;
    RestoreScope scope_;
    bool armed_ = true;
};

/// The default backup file name for a node: ./lcc-conform-backup-<node id without dots>.txt.
std::string default_backup_path(const std::string& node_id);

}  // namespace olcb::conform
