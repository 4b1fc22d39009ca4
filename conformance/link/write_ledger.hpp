// Every write lcc-conform sends to a node, recorded before it goes out: what the end-of-run
// restore must cover and what the report's restore line is computed from. A gate (the node run's
// safety backup) sees each planned write first and may refuse it; only then is it sent. Why: a
// protocol probe that wrote outside the safety backup once changed a node's byte and the report
// still said "byte-identical".
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "openlcb/node_id.hpp"

namespace olcb::conform {

/// A write about to be sent: a Write (mask empty) or a Write Under Mask (one mask per data byte).
struct PlannedWrite {
    NodeId node;
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::vector<std::uint8_t> data;
    std::vector<std::uint8_t> mask;
    /// A Write Stream: its length is unknown until the stream ends.
    bool stream = false;
};

/// How a recorded write ended.
enum class WriteOutcome : std::uint8_t {
    kNotSent,   ///< the gate refused it (or sending failed): the node never saw it
    kPending,   ///< sent, no outcome yet
    kAccepted,  ///< Datagram Received OK / Write Reply OK
    kRefused,   ///< Datagram Rejected or Write Reply Fail
    kNoAnswer,  ///< no answer in time: it may have been stored
};

/// What the gate decided for a planned write.
struct GateDecision {
    bool send = true;
    std::string why;  ///< when refused: why, in words
    /// Bytes of the write past the end of the space (no tool can read them back, so no backup
    /// holds them); only a write sent under a PastEndPermit may have any.
    std::uint32_t past_end = 0;
};

/// One recorded write.
struct LedgerEntry {
    PlannedWrite write;
    std::string origin;      ///< the check or phase that sent it
    bool restoring = false;  ///< a put-back of saved bytes (the restore, a check's undo)
    std::uint32_t past_end = 0;
    WriteOutcome outcome = WriteOutcome::kNotSent;
    std::string refused_why;  ///< the gate's reason when kNotSent
};

/// Decides whether a planned write may go out; `past_end_allowed` when a PastEndPermit for its
/// space is held.
using WriteGate = std::function<GateDecision(const PlannedWrite&, bool past_end_allowed)>;

/// Unrestorable bytes a node may keep past the end of one space.
struct PastEndBytes {
    NodeId node;
    std::uint8_t space = 0;
    std::uint32_t address = 0;  ///< the first such byte
    std::uint32_t count = 0;
};

/// The writes of a session, in the order they were planned.
class WriteLedger {
public:
    /// The gate every later write must pass (empty: every write goes out, e.g. a user's restore).
    void set_gate(WriteGate gate) { gate_ = std::move(gate); }
    /// Records the write and asks the gate: the entry's index when it may be sent, else nullopt
    /// with `why`.
    std::optional<std::size_t> open(PlannedWrite write, std::string& why);
    /// The outcome of a sent write.
    void close(std::size_t index, WriteOutcome outcome);
    /// Asks the gate to save the bytes of a write that may come later (nothing is sent or
    /// recorded): a probe that may change bytes it does not address (a write crossing the end)
    /// has them saved first. True when saved or when there is no gate.
    bool save_ahead(NodeId node, std::uint8_t space, std::uint32_t address, std::uint32_t length,
                    std::string& why);

    /// Every write, refused ones included.
    const std::vector<LedgerEntry>& entries() const { return entries_; }
    /// Writes to node that reached it (any outcome but kNotSent), restores excluded.
    std::size_t sent(NodeId node) const;
    /// True when a write that reached node (any outcome but kNotSent, put-backs included) may
    /// have changed a byte of [address, address + length) of space: it overlaps the range, or
    /// some write to the node crossed the end of a space (where its bytes went is unknown).
    bool touched(NodeId node, std::uint8_t space, std::uint32_t address,
                 std::uint32_t length) const;
    /// Bytes a node may hold past the end of a space after the writes it accepted or left
    /// unanswered (restores excluded), one entry per space and first address.
    std::vector<PastEndBytes> unrestorable(NodeId node) const;

    /// While alive, writes are recorded as sent by `origin` (nests; the innermost wins).
    class Origin {
    public:
        Origin(WriteLedger& ledger, std::string origin);
        ~Origin();
        Origin(const Origin&) = delete;
        Origin& operator=(const Origin&) = delete;

    private:
        WriteLedger& ledger_;
        std::string previous_;
    };
    /// While alive, writes put saved bytes back (not counted as the run's writes).
    class Restoring {
    public:
        explicit Restoring(WriteLedger& ledger);
        ~Restoring();
        Restoring(const Restoring&) = delete;
        Restoring& operator=(const Restoring&) = delete;

    private:
        WriteLedger& ledger_;
        bool previous_;
    };
    /// While alive, a write to `space` may cross its end (memory.write-past-end under
    /// --write-past-end): the gate lets bytes past the end go out and the ledger counts them.
    class PastEndPermit {
    public:
        PastEndPermit(WriteLedger& ledger, std::uint8_t space);
        ~PastEndPermit();
        PastEndPermit(const PastEndPermit&) = delete;
        PastEndPermit& operator=(const PastEndPermit&) = delete;

    private:
        WriteLedger& ledger_;
        std::optional<std::uint8_t> previous_;
    };

private:
    WriteGate gate_;
    std::vector<LedgerEntry> entries_;
    std::string origin_;
    bool restoring_ = false;
    std::optional<std::uint8_t> past_end_space_;
};

}  // namespace olcb::conform
