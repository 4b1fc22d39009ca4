#include "conformance/backup/config_reader.hpp"

#include <algorithm>

#include "base/hex.hpp"
#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

constexpr std::uint64_t kRead = 64;  // bytes of one memory-config read
constexpr std::uint64_t kAddressLimit = 1ull << 32;
constexpr std::uint64_t kMaxVariableRead = 0xFFFF;  // a bigger variable is not read

std::uint64_t reads_for(std::uint64_t bytes) {
    return (bytes + kRead - 1) / kRead;
}

bool readable(const ConfigEntry& e) {
    return e.space <= 0xFF && e.size <= kMaxVariableRead && e.address + e.size <= kAddressLimit;
}

std::string read_error(const AccessResult& r) {
    return "read failed (error " + base::hex(r.error) + ")";
}

void decode_into(const ConfigEntry& e, std::span<const std::uint8_t> bytes, ConfigValue& out) {
    out.text = format_backup_value(*e.element, bytes, out.error);
}

void read_one(const ConfigEntry& e, MemoryAccess& memory, ConfigValue& out) {
    AccessResult r = memory.read(static_cast<std::uint8_t>(e.space),
                                 static_cast<std::uint32_t>(e.address), e.size);
    if (!r.ok || r.data.size() != e.size) {
        out.error = r.ok ? "read returned " + std::to_string(r.data.size()) + " of " +
                               std::to_string(e.size) + " bytes"
                         : read_error(r);
        return;
    }
    decode_into(e, r.data, out);
}

}  // namespace

std::vector<ReadSpan> plan_config_reads(const std::vector<ConfigEntry>& entries) {
    std::vector<ReadSpan> ranges;
    for (const ConfigEntry& e : entries) {
        if (readable(e) && e.size > 0) ranges.push_back({e.space, e.address, e.address + e.size});
    }
    std::sort(ranges.begin(), ranges.end(), [](const ReadSpan& a, const ReadSpan& b) {
        return a.space != b.space ? a.space < b.space : a.begin < b.begin;
    });
    std::vector<ReadSpan> out;
    for (const ReadSpan& r : ranges) {
        if (!out.empty() && out.back().space == r.space) {
            ReadSpan& last = out.back();
            const std::uint64_t end = std::max(last.end, r.end);
            const std::uint64_t apart =
                reads_for(last.end - last.begin) + reads_for(r.end - std::max(r.begin, last.end));
            if (r.begin <= last.end || reads_for(end - last.begin) <= apart) {
                last.end = end;
                continue;
            }
        }
        out.push_back(r);
    }
    return out;
}

std::vector<ConfigValue> read_config_values(const std::vector<ConfigEntry>& entries,
                                            MemoryAccess& memory) {
    std::vector<ConfigValue> out(entries.size());
    // Entries by address, so each span's entries are a contiguous run.
    std::vector<std::size_t> order;
    for (std::size_t i = 0; i < entries.size(); ++i) {
        if (readable(entries[i])) {
            order.push_back(i);
        } else {
            out[i].error = "outside any readable address";
        }
    }
    std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
        const ConfigEntry& x = entries[a];
        const ConfigEntry& y = entries[b];
        return x.space != y.space ? x.space < y.space : x.address < y.address;
    });
    std::size_t next = 0;
    for (const ReadSpan& span : plan_config_reads(entries)) {
        AccessResult r = memory.read(static_cast<std::uint8_t>(span.space),
                                     static_cast<std::uint32_t>(span.begin), span.end - span.begin);
        const std::uint64_t got =
            r.ok ? std::min<std::uint64_t>(r.data.size(), span.end - span.begin) : 0;
        const std::span<const std::uint8_t> data(r.data.data(), got);
        for (; next < order.size(); ++next) {
            const ConfigEntry& e = entries[order[next]];
            ConfigValue& v = out[order[next]];
            const bool before =
                e.space < span.space || (e.space == span.space && e.address < span.begin);
            if (!before && (e.space != span.space || e.address >= span.end)) break;
            if (!before && e.address + e.size <= span.begin + got) {
                decode_into(e, data.subspan(e.address - span.begin, e.size), v);
            } else {
                read_one(e, memory, v);  // in no span (no bytes) or not in what came back
            }
        }
    }
    for (; next < order.size(); ++next) read_one(entries[order[next]], memory, out[order[next]]);
    return out;
}

}  // namespace olcb::conform
