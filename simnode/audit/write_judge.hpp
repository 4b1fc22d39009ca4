// Judges one client's writes to one node against the node's CDI: writes that cut a variable,
// bytes no variable covers, and the value of every variable written whole (the CDI's rules,
// through cdi::decode and cdi::check_value). Consecutive writes, each starting where the last
// ended, are one write: a long string or a restored range goes in several datagrams.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "simnode/audit/audit_rule.hpp"
#include "simnode/audit/node_profile.hpp"

namespace olcb::simnode::audit {

/// One violation found in a write.
struct Verdict {
    RuleId rule = RuleId::kMemoryWriteStraddles;  ///< which rule
    std::string message;                          ///< what was wrong
    std::string key;                              ///< the place: "FD:00000001"
    std::vector<CanFrame> frames;                 ///< the writes involved
};

/// The write rules for one (client, node) pair.
class WriteJudge {
public:
    /// Judges a write of data at address in space, carried by frames. With judge_values false
    /// (a write under mask, whose result depends on the old bytes) only coverage is judged. A
    /// variable the write leaves cut at its end waits for the next write to go on with it.
    std::vector<Verdict> write(const NodeProfile& node, std::uint8_t space, std::uint32_t address,
                               std::span<const std::uint8_t> data, std::span<const CanFrame> frames,
                               bool judge_values = true);
    /// Judges the variable still waiting for the rest of its bytes, as it is.
    std::vector<Verdict> flush();

private:
    struct Piece {
        std::uint8_t space = 0;
        VariableRef variable;
        std::uint64_t covered = 0;        // bytes written from the variable's first one
        std::vector<std::uint8_t> bytes;  // those bytes (kept for judged sizes only)
        std::vector<CanFrame> frames;
        bool judge_values = true;
        std::uint64_t next() const { return variable.address + covered; }
    };

    void take(std::vector<Verdict>& out, const VariableRef& v, std::uint8_t space, std::uint64_t at,
              std::span<const std::uint8_t> bytes, std::span<const CanFrame> frames,
              bool judge_values);
    void finish(std::vector<Verdict>& out, Piece piece);

    std::optional<Piece> pending_;
};

}  // namespace olcb::simnode::audit
