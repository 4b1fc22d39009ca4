// The node run's gate on the session's write ledger: before any write to the node under test goes
// out (a protocol probe, an encoding value, a check's own put-back), the bytes it may change are
// read and saved to the safety backup file, synced to disk; from the first saved byte a
// RestoreGuard owns their restore. A write whose bytes cannot be saved is not sent.
#pragma once

#include <cstddef>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "conformance/link/session.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/link/write_ledger.hpp"
#include "conformance/run/safety_backup.hpp"

namespace olcb::conform {

class WriteCover {
public:
    /// Guards writes through session to node; the backup file is `backup_path`. With read_only
    /// every write is kept back.
    WriteCover(Session& session, const NodeInfo& node, std::string backup_path, bool read_only);
    ~WriteCover();
    WriteCover(const WriteCover&) = delete;
    WriteCover& operator=(const WriteCover&) = delete;

    /// The gate: saves what the write may change, or says why it may not go out.
    GateDecision decide(const PlannedWrite& write, bool past_end_allowed);
    /// Saves ranges ahead of the writes that will change them (the encoding plan); the ranges
    /// that could not be read go to `missing`. False with `error` when the file cannot be
    /// written (then nothing may be written).
    bool capture(const std::vector<RangeRequest>& ranges,
                 std::vector<std::pair<RangeRequest, std::string>>& missing, std::string& error);

    /// Why the backup file could not be written, the first time it could not ("" when every
    /// save succeeded): the writes it was to cover were kept back, so the run is not whole.
    const std::string& save_error() const { return save_error_; }
    /// True once any byte was saved (a restore is owed).
    bool armed() const { return guard_ != nullptr; }
    /// The backup (nullptr before the first saved byte).
    const SafetyBackup* backup() const { return backup_.get(); }
    /// Restores now and reads back; the guard is then done. Only when armed().
    RestoreOutcome finish();
    /// The node is out of reach: nothing more is written, the backup file stays for the user.
    void abandon();
    /// Deletes the backup file (after a verified restore).
    void remove_file();
    /// The file path.
    const std::string& path() const { return path_; }
    /// Memory access to the node (reads and writes go through the session and its ledger).
    MemoryAccess& memory() { return memory_; }

private:
    SafetyBackup& ensure_backup();
    /// Writes the backup file unless it already holds every range; the first failure is kept in
    /// save_error_.
    bool save(std::string& error);
    void arm();

    Session& session_;
    NodeInfo node_;
    std::string path_;
    bool read_only_;
    SessionMemory memory_;
    std::unique_ptr<SafetyBackup> backup_;
    std::unique_ptr<RestoreGuard> guard_;
    std::string save_error_;
    /// How many of the backup's ranges the file holds (none saved yet: never equal).
    std::size_t saved_ranges_ = std::numeric_limits<std::size_t>::max();
};

}  // namespace olcb::conform
