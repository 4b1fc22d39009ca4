#include "conformance/run/write_cover.hpp"

#include <utility>

#include "base/hex.hpp"

namespace olcb::conform {
namespace {

GateDecision refuse(std::string why) {
    return {false, std::move(why), 0};
}

}  // namespace

WriteCover::WriteCover(Session& session, const NodeInfo& node, std::string backup_path,
                       bool read_only)
    : session_(session),
      node_(node),
      path_(std::move(backup_path)),
      read_only_(read_only),
      memory_(session, node) {
    session_.ledger().set_gate(
        [this](const PlannedWrite& w, bool past_end) { return decide(w, past_end); });
}

WriteCover::~WriteCover() {
    // The guard restores on the way out (an exception, an early return) before the gate goes.
    {
        WriteLedger::Restoring restoring(session_.ledger());
        guard_.reset();
    }
    session_.ledger().set_gate({});
}

SafetyBackup& WriteCover::ensure_backup() {
    if (!backup_) backup_ = std::make_unique<SafetyBackup>(path_, node_.id.to_string());
    return *backup_;
}

bool WriteCover::save(std::string& error) {
    SafetyBackup& backup = ensure_backup();
    // Ranges are only ever appended: the same count means the file holds them all, so a write
    // over saved bytes costs no file write (a default run saved the file 119 times, now 4).
    if (saved_ranges_ == backup.ranges().size()) return true;
    if (backup.save(error)) {
        saved_ranges_ = backup.ranges().size();
        return true;
    }
    if (save_error_.empty()) save_error_ = error;
    return false;
}

void WriteCover::arm() {
    if (!guard_ && backup_ && !backup_->ranges().empty()) {
        // Saved is not written: bytes saved ahead of writes that never went out (another tool
        // holds the lock, the run stopped) belong to whoever changes them meanwhile.
        guard_ = std::make_unique<RestoreGuard>(*backup_, memory_, [this](const BackupRange& r) {
            return session_.ledger().touched(node_.id, r.space, r.address,
                                             static_cast<std::uint32_t>(r.bytes.size()));
        });
    }
}

GateDecision WriteCover::decide(const PlannedWrite& w, bool past_end_allowed) {
    if (w.node != node_.id) return refuse("not the node under test");
    if (read_only_) return refuse("--read-only");
    if (w.stream) return refuse("a stream write's extent is unknown: no backup can cover it");
    if (w.data.empty()) return {};
    SafetyBackup& backup = ensure_backup();
    const auto length = static_cast<std::uint32_t>(w.data.size());
    std::uint32_t past_end = 0;
    for (const RangeRequest& piece : backup.uncovered(w.space, w.address, length)) {
        const MemResult r = session_.read_range(node_, static_cast<memory::Space>(w.space),
                                                piece.address, piece.length, false);
        if (!r.ok) {
            return refuse(std::string("the bytes it would change do not read (") +
                          (r.timed_out ? "no answer" : "error " + base::hex(r.error, 4)) +
                          "), so they cannot be saved");
        }
        const std::size_t got = std::min<std::size_t>(r.data.size(), piece.length);
        const std::uint64_t piece_end = std::uint64_t{piece.address} + piece.length;
        // Only the write's tail may lie past the end of the space: that is where a space ends.
        if (got < piece.length && piece_end != std::uint64_t{w.address} + length)
            return refuse("the space ends inside the write");
        past_end += static_cast<std::uint32_t>(piece.length - got);
        if (got != 0)
            backup.add({w.space, piece.address,
                        std::vector<std::uint8_t>(
                            r.data.begin(), r.data.begin() + static_cast<std::ptrdiff_t>(got))});
    }
    if (past_end != 0 && !past_end_allowed)
        return refuse(std::to_string(past_end) +
                      " bytes of the write lie past the end of the space (needs --write-past-end)");
    std::string error;
    if (!save(error)) return refuse("the safety backup cannot be saved: " + error);
    arm();
    return {true, {}, past_end};
}

bool WriteCover::capture(const std::vector<RangeRequest>& ranges,
                         std::vector<std::pair<RangeRequest, std::string>>& missing,
                         std::string& error) {
    SafetyBackup& backup = ensure_backup();
    for (const RangeRequest& r : ranges) {
        if (std::string why = backup.save_bytes(memory_, r); !why.empty())
            missing.emplace_back(r, why);
    }
    if (!save(error)) return false;
    arm();
    return true;
}

RestoreOutcome WriteCover::finish() {
    WriteLedger::Restoring restoring(session_.ledger());
    WriteLedger::Origin origin(session_.ledger(), "restore");
    if (!guard_) {
        RestoreOutcome nothing;
        nothing.identical = true;
        return nothing;
    }
    return guard_->finish();
}

void WriteCover::abandon() {
    if (guard_) guard_->abandon();
}

void WriteCover::remove_file() {
    if (backup_) backup_->remove_file();
}

}  // namespace olcb::conform
