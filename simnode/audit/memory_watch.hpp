// The Memory Configuration rules of the client audit: reads past the end, writes to read-only
// spaces or past the end, the write rules of WriteJudge, and writes left without Update
// Complete.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

#include "openlcb/can_frame.hpp"
#include "openlcb/clock.hpp"
#include "simnode/audit/audit_context.hpp"
#include "simnode/audit/write_judge.hpp"

namespace olcb::simnode::audit {

/// Follows the Memory Configuration requests of every (client alias, node alias) pair.
class MemoryWatch {
public:
    /// A watch reporting to ctx.
    explicit MemoryWatch(AuditContext& ctx) : ctx_(ctx) {}

    /// A complete datagram client sent node (any content type; only 0x20 is looked into).
    void on_datagram(std::uint16_t client, std::uint16_t node,
                     std::span<const std::uint8_t> payload, std::span<const CanFrame> frames,
                     TimePoint now);
    /// The node at alias restarted or gave it up: writes waiting for a continuation are judged
    /// as they are; Update Complete is still owed.
    void node_restarted(std::uint16_t node, TimePoint now);
    /// A client alias is gone (its connection ended): what it left open is judged.
    void client_gone(std::uint16_t client, TimePoint now);
    /// Judges the quiet time after writes.
    void poll(TimePoint now);
    /// The end of the run: everything still open is judged.
    void finish(TimePoint now);
    /// When poll() next has something to judge.
    std::optional<TimePoint> next_deadline() const;

private:
    struct Pair {
        WriteJudge judge;
        std::optional<TimePoint> wrote_at;   // writes since the last Update Complete
        std::vector<CanFrame> write_frames;  // the last of them
        TimePoint last_datagram{};
    };

    void on_read(std::uint16_t client, std::uint16_t node, std::uint8_t space,
                 std::uint32_t address, std::span<const CanFrame> frames, TimePoint now);
    bool writable(std::uint16_t client, std::uint16_t node, std::uint8_t space,
                  std::uint32_t address, std::size_t length, std::span<const CanFrame> frames,
                  TimePoint now);
    void on_write(Pair& p, std::uint16_t client, std::uint16_t node, std::uint8_t space,
                  std::uint32_t address, std::span<const std::uint8_t> data,
                  std::span<const CanFrame> frames, bool judge_values, TimePoint now);
    void flush(Pair& p, std::uint16_t client, std::uint16_t node, TimePoint now);
    void close(Pair& p, std::uint16_t client, std::uint16_t node, const char* why, TimePoint now);
    void report(std::uint16_t client, std::uint16_t node, std::vector<Verdict> verdicts,
                TimePoint now);

    AuditContext& ctx_;
    std::unordered_map<std::uint32_t, Pair> pairs_;  // by pair_key(client, node)
};

}  // namespace olcb::simnode::audit
