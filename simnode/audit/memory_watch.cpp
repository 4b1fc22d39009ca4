#include "simnode/audit/memory_watch.hpp"

#include <string>
#include <variant>

#include "base/hex.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/memory_config_defs.hpp"
#include "simnode/audit/audit_limits.hpp"

namespace olcb::simnode::audit {
namespace {

std::string space_key(std::uint8_t space) {
    return base::hex_digits(space, 2);
}

// "0xFD @0x000000B3"
std::string where(std::uint8_t space, std::uint64_t address) {
    return base::hex(space, 2) + " @" + base::hex(address, 8);
}

}  // namespace

void MemoryWatch::on_datagram(std::uint16_t client, std::uint16_t node,
                              std::span<const std::uint8_t> payload,
                              std::span<const CanFrame> frames, TimePoint now) {
    Pair& p = pairs_[pair_key(client, node)];
    p.last_datagram = now;
    if (payload.empty() || payload[0] != memory::kDatagramType) return;
    const memory::DecodeResult decoded = memory::decode(payload);
    if (!decoded.ok()) return;  // the node rejects it; nothing is read or written
    const auto& m = decoded.message;
    if (const auto* r = std::get_if<memory::Read>(&m)) {
        on_read(client, node, memory::to_u8(r->space), r->address, frames, now);
    } else if (const auto* w = std::get_if<memory::Write>(&m)) {
        const std::uint8_t space = memory::to_u8(w->space);
        if (writable(client, node, space, w->address, w->data.size(), frames, now))
            on_write(p, client, node, space, w->address, w->data, frames, true, now);
    } else if (const auto* wm = std::get_if<memory::WriteUnderMask>(&m)) {
        const std::uint8_t space = memory::to_u8(wm->space);
        if (!writable(client, node, space, wm->address, wm->bytes.size(), frames, now)) return;
        // Only bytes with mask bits set change; the new value depends on the old one, so only
        // what they cover is judged.
        std::size_t first = wm->bytes.size();
        std::size_t last = 0;
        for (std::size_t i = 0; i < wm->bytes.size(); ++i) {
            if (wm->bytes[i].mask == 0) continue;
            first = std::min(first, i);
            last = i;
        }
        if (first > last) return;
        std::vector<std::uint8_t> values;
        for (std::size_t i = first; i <= last; ++i) values.push_back(wm->bytes[i].value);
        on_write(p, client, node, space, wm->address + static_cast<std::uint32_t>(first), values,
                 frames, false, now);
    } else if (std::holds_alternative<memory::UpdateComplete>(m)) {
        flush(p, client, node, now);
        p.wrote_at.reset();
    }
}

void MemoryWatch::on_read(std::uint16_t client, std::uint16_t node, std::uint8_t space,
                          std::uint32_t address, std::span<const CanFrame> frames, TimePoint now) {
    const NodeProfile* profile = ctx_.node_at(node);
    const auto shape = profile ? profile->space(space) : std::nullopt;
    if (!shape || address < shape->size) return;
    ctx_.report(RuleId::kMemoryReadPastEnd, client, node,
                "read at " + where(space, address) + ", at or past the end of the space (" +
                    std::to_string(shape->size) + " bytes)",
                frames, space_key(space), now);
}

bool MemoryWatch::writable(std::uint16_t client, std::uint16_t node, std::uint8_t space,
                           std::uint32_t address, std::size_t length,
                           std::span<const CanFrame> frames, TimePoint now) {
    const NodeProfile* profile = ctx_.node_at(node);
    const auto shape = profile ? profile->space(space) : std::nullopt;
    if (!shape) return false;  // a space the node does not serve: refused as unknown
    if (shape->read_only) {
        ctx_.report(RuleId::kMemoryWriteReadOnly, client, node,
                    "wrote " + std::to_string(length) + " byte(s) at " + where(space, address) +
                        ", a read-only space",
                    frames, space_key(space), now);
        return false;
    }
    if (std::uint64_t{address} + length > shape->size) {
        ctx_.report(RuleId::kMemoryWritePastEnd, client, node,
                    "wrote " + std::to_string(length) + " byte(s) at " + where(space, address) +
                        ", past the end of the space (" + std::to_string(shape->size) + " bytes)",
                    frames, space_key(space), now);
        return false;
    }
    return true;
}

void MemoryWatch::on_write(Pair& p, std::uint16_t client, std::uint16_t node, std::uint8_t space,
                           std::uint32_t address, std::span<const std::uint8_t> data,
                           std::span<const CanFrame> frames, bool judge_values, TimePoint now) {
    if (const NodeProfile* profile = ctx_.node_at(node))
        report(client, node, p.judge.write(*profile, space, address, data, frames, judge_values),
               now);
    p.wrote_at = now;
    p.write_frames.assign(frames.begin(), frames.end());
}

void MemoryWatch::flush(Pair& p, std::uint16_t client, std::uint16_t node, TimePoint now) {
    report(client, node, p.judge.flush(), now);
}

void MemoryWatch::close(Pair& p, std::uint16_t client, std::uint16_t node, const char* why,
                        TimePoint now) {
    flush(p, client, node, now);
    if (!p.wrote_at) return;
    ctx_.report(RuleId::kMemoryNoUpdateComplete, client, node,
                std::string("wrote to the node and sent no Update Complete (20 A8) ") + why,
                p.write_frames, "", now);
    p.wrote_at.reset();
}

void MemoryWatch::report(std::uint16_t client, std::uint16_t node, std::vector<Verdict> verdicts,
                         TimePoint now) {
    for (Verdict& v : verdicts)
        ctx_.report(v.rule, client, node, std::move(v.message), v.frames, v.key, now);
}

void MemoryWatch::node_restarted(std::uint16_t node, TimePoint now) {
    for (auto& [key, p] : pairs_) {
        if (pair_node(key) == node) flush(p, pair_client(key), node, now);
    }
}

void MemoryWatch::client_gone(std::uint16_t client, TimePoint now) {
    for (auto it = pairs_.begin(); it != pairs_.end();) {
        if (pair_client(it->first) != client) {
            ++it;
            continue;
        }
        close(it->second, client, pair_node(it->first), "before its connection ended", now);
        it = pairs_.erase(it);
    }
}

void MemoryWatch::poll(TimePoint now) {
    for (auto& [key, p] : pairs_) {
        if (p.wrote_at && now - p.last_datagram >= kUpdateCompleteQuiet)
            close(p, pair_client(key), pair_node(key), "within 10 s of its last datagram", now);
    }
}

void MemoryWatch::finish(TimePoint now) {
    for (auto& [key, p] : pairs_)
        close(p, pair_client(key), pair_node(key), "before the end of the run", now);
}

std::optional<TimePoint> MemoryWatch::next_deadline() const {
    std::optional<TimePoint> next;
    for (const auto& [key, p] : pairs_) {
        if (!p.wrote_at) continue;
        const TimePoint due = p.last_datagram + kUpdateCompleteQuiet;
        if (!next || due < *next) next = due;
    }
    return next;
}

}  // namespace olcb::simnode::audit
