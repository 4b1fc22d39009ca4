#include "conformance/link/write_ledger.hpp"

#include <set>
#include <utility>

namespace olcb::conform {

std::optional<std::size_t> WriteLedger::open(PlannedWrite write, std::string& why) {
    LedgerEntry e;
    e.origin = origin_;
    e.restoring = restoring_;
    const bool past_end_allowed = past_end_space_ && *past_end_space_ == write.space;
    e.write = std::move(write);
    GateDecision d;
    if (gate_) d = gate_(e.write, past_end_allowed);
    if (d.send && d.past_end != 0 && !past_end_allowed) {
        // A gate that found bytes past the end must not let them out without the permit.
        d.send = false;
        d.why = "the write crosses the end of its space (needs --write-past-end)";
    }
    e.past_end = d.send ? d.past_end : 0;
    e.outcome = d.send ? WriteOutcome::kPending : WriteOutcome::kNotSent;
    e.refused_why = d.send ? std::string() : d.why;
    entries_.push_back(std::move(e));
    if (!d.send) {
        why = d.why;
        return std::nullopt;
    }
    return entries_.size() - 1;
}

bool WriteLedger::save_ahead(NodeId node, std::uint8_t space, std::uint32_t address,
                             std::uint32_t length, std::string& why) {
    if (!gate_) return true;
    PlannedWrite w{node, space, address, std::vector<std::uint8_t>(length), {}, false};
    const GateDecision d = gate_(w, false);
    if (!d.send) why = d.why;
    return d.send;
}

void WriteLedger::close(std::size_t index, WriteOutcome outcome) {
    if (index < entries_.size()) entries_[index].outcome = outcome;
}

std::size_t WriteLedger::sent(NodeId node) const {
    std::size_t n = 0;
    for (const LedgerEntry& e : entries_)
        n += e.write.node == node && !e.restoring && e.outcome != WriteOutcome::kNotSent;
    return n;
}

bool WriteLedger::touched(NodeId node, std::uint8_t space, std::uint32_t address,
                          std::uint32_t length) const {
    const std::uint64_t end = std::uint64_t{address} + length;
    for (const LedgerEntry& e : entries_) {
        if (e.write.node != node || e.outcome == WriteOutcome::kNotSent) continue;
        if (e.past_end != 0) return true;
        const std::uint64_t first = e.write.address;
        const std::uint64_t last = first + e.write.data.size();
        if (e.write.space == space && first < end && address < last) return true;
    }
    return false;
}

std::vector<PastEndBytes> WriteLedger::unrestorable(NodeId node) const {
    // Distinct bytes: the same byte past the end written twice is still one byte kept.
    std::set<std::pair<std::uint8_t, std::uint64_t>> bytes;
    for (const LedgerEntry& e : entries_) {
        if (e.write.node != node || e.restoring || e.past_end == 0) continue;
        if (e.outcome != WriteOutcome::kAccepted && e.outcome != WriteOutcome::kNoAnswer) continue;
        const std::uint64_t end = std::uint64_t{e.write.address} + e.write.data.size();
        for (std::uint64_t a = end - e.past_end; a < end; ++a) bytes.insert({e.write.space, a});
    }
    std::vector<PastEndBytes> out;
    for (const auto& [space, address] : bytes) {
        if (!out.empty() && out.back().space == space &&
            std::uint64_t{out.back().address} + out.back().count == address) {
            ++out.back().count;
            continue;
        }
        out.push_back({node, space, static_cast<std::uint32_t>(address), 1});
    }
    return out;
}

WriteLedger::Origin::Origin(WriteLedger& ledger, std::string origin)
    : ledger_(ledger), previous_(std::exchange(ledger.origin_, std::move(origin))) {}

WriteLedger::Origin::~Origin() {
    ledger_.origin_ = std::move(previous_);
}

WriteLedger::Restoring::Restoring(WriteLedger& ledger)
    : ledger_(ledger), previous_(std::exchange(ledger.restoring_, true)) {}

WriteLedger::Restoring::~Restoring() {
    ledger_.restoring_ = previous_;
}

WriteLedger::PastEndPermit::PastEndPermit(WriteLedger& ledger, std::uint8_t space)
    : ledger_(ledger), previous_(std::exchange(ledger.past_end_space_, space)) {}

WriteLedger::PastEndPermit::~PastEndPermit() {
    ledger_.past_end_space_ = previous_;
}

}  // namespace olcb::conform
