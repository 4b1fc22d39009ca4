#include "cdi/memory_map.hpp"

#include <algorithm>
#include <map>
#include <unordered_map>

#include <nlohmann/json.hpp>

#include "cdi/variable_name.hpp"

namespace olcb::cdi {
namespace {

constexpr std::uint64_t kSaturated = std::uint64_t{1} << 63;

std::uint64_t saturating_add(std::uint64_t a, std::uint64_t b) {
    return a >= kSaturated - std::min(b, kSaturated) ? kSaturated : a + b;
}

std::uint64_t saturating_mul(std::uint64_t a, std::uint64_t b) {
    if (a == 0 || b == 0) return 0;
    return a > kSaturated / b ? kSaturated : a * b;
}

// Variables in a list of elements after replication, counted as the layout counts its
// ordinals (every non-group element is one variable), memoized per group.
class VariableCounter {
public:
    std::uint64_t in(const std::vector<Element>& elements) {
        std::uint64_t n = 0;
        for (const Element& e : elements) {
            n = saturating_add(n,
                               e.is_variable() ? 1 : saturating_mul(e.replication, per_replica(e)));
        }
        return n;
    }
    std::uint64_t per_replica(const Element& group) {
        if (auto it = memo_.find(&group); it != memo_.end()) return it->second;
        const std::uint64_t n = in(group.children);
        memo_[&group] = n;
        return n;
    }

private:
    std::unordered_map<const Element*, std::uint64_t> memo_;
};

std::string type_of(const Element& e) {
    return e.kind == ElementKind::kUnknown ? e.tag : kind_name(e.kind);
}

// A bar is too narrow for a whole name: its own name, or for an unnamed variable its innermost
// replica's CDI name, else the part of the name it contributes ("child3").
std::string label_of(const Cursor& c) {
    const Element& e = c.element();
    if (!e.name.empty()) return e.name;
    for (std::size_t level = c.group_depth(); level-- > 0;) {
        const Element& g = c.group(level);
        if (g.replication <= 1) continue;
        std::string name = replica_name(g, c.replica(level));
        if (!name.empty()) return name;
    }
    return variable_name_part(e);
}

class MapBuilder {
public:
    MapBuilder(const Layout& layout, const MemoryMapOptions& options)
        : layout_(layout), options_(options) {
        const Document& doc = layout.document();
        segment_first_.push_back(0);
        for (std::uint32_t i = 0; i < doc.segments.size(); ++i) {
            const Segment& s = doc.segments[i];
            const std::uint64_t count = counter_.in(s.children);
            segment_first_.push_back(saturating_add(segment_first_.back(), count));
            if (count == 0) continue;
            SpaceMap& m = maps_[s.space];
            m.space = s.space;
            m.segments.push_back(i);
            if (!s.name.empty()) m.name += (m.name.empty() ? "" : " / ") + s.name;
            m.variable_count = saturating_add(m.variable_count, count);
            if (auto extent = layout.extent(s.space)) {
                m.begin = extent->begin;
                m.end = extent->end;
            }
        }
    }

    std::vector<SpaceMap> run() {
        for (Cursor c = layout_.begin(); c.valid();) {
            SpaceMap& m = maps_[c.space()];
            if (m.variables.size() >= options_.max_variables) {
                c = skip_segment(c, m);
            } else if (const std::size_t level = unlisted_level(c); level < c.group_depth()) {
                c = skip_replicas(c, level, m);
            } else {
                m.variables.push_back({variable_name(layout_, c), replica_names(c), label_of(c),
                                       type_of(c.element()), c.segment_index(), c.address(),
                                       c.size(), c.ordinal()});
                c.next();
            }
        }
        std::vector<SpaceMap> out;
        for (auto& [space, m] : maps_) {
            find_gaps(m);
            find_overlaps(m);
            out.push_back(std::move(m));
        }
        return out;
    }

private:
    // The first listed replica at or after `from` (count when none is).
    std::uint64_t next_listed(std::uint64_t from, std::uint64_t count) const {
        if (from < options_.replicas) return from;
        // The last replica is listed too: it shows where the group ends.
        std::uint64_t next = from < count ? count - 1 : count;
        if (options_.also_list) next = std::min(next, options_.also_list(from, count));
        return next;
    }

    // The outermost enclosing group whose current replica is not listed (depth when none).
    std::size_t unlisted_level(const Cursor& c) const {
        for (std::size_t level = 0; level < c.group_depth(); ++level) {
            const std::uint64_t count = c.group(level).replication;
            if (count > 1 && next_listed(c.replica(level), count) != c.replica(level)) return level;
        }
        return c.group_depth();
    }

    // The cursor is on the first variable of an unlisted replica (replicas are walked in order
    // and every jump lands on a replica's start): the run up to the next listed one is skipped.
    Cursor skip_replicas(const Cursor& c, std::size_t level, SpaceMap& m) {
        const Element& group = c.group(level);
        const std::uint64_t from = c.replica(level);
        const std::uint64_t to = next_listed(from, group.replication);
        const std::uint64_t skipped = saturating_mul(to - from, counter_.per_replica(group));
        m.summaries.push_back({group.name.empty() ? "(group)" : group.name,
                               variable_name(layout_, c), from, to - from, skipped,
                               replicas_range(c, level, from, to)});
        return layout_.at(saturating_add(c.ordinal(), skipped));
    }

    // The rest of the cursor's segment, once its space has max_variables listed.
    Cursor skip_segment(const Cursor& c, SpaceMap& m) {
        const std::uint64_t end = segment_first_[c.segment_index() + 1];
        const std::uint64_t address = std::min(c.address(), m.end);
        m.summaries.push_back(
            {"", variable_name(layout_, c), 0, 0, end - c.ordinal(), {address, m.end - address}});
        return layout_.at(end);
    }

    // Replicas [from, to) of the group at level, within the cursor's enclosing replicas.
    MapRange replicas_range(const Cursor& c, std::size_t level, std::uint64_t from,
                            std::uint64_t to) const {
        auto placement = layout_.placement(c.group(level));
        if (!placement) return {};
        __int128 base = placement->address;
        for (std::size_t outer = 0; outer < level; ++outer) {
            if (auto p = layout_.placement(c.group(outer)))
                base += __int128(c.replica(outer)) * p->stride;
        }
        const __int128 a = base + __int128(from) * placement->stride;
        const __int128 b = base + __int128(to) * placement->stride;
        const __int128 lo = std::max<__int128>(0, std::min(a, b));
        const __int128 hi = std::max(lo, std::max(a, b));
        return {static_cast<std::uint64_t>(lo), static_cast<std::uint64_t>(hi - lo)};
    }

    static void find_gaps(SpaceMap& m) {
        std::vector<MapRange> used;
        used.reserve(m.variables.size() + m.summaries.size());
        for (const MapVariable& v : m.variables) used.push_back({v.address, v.size});
        for (const MapSummary& s : m.summaries) {
            if (s.range.size != 0) used.push_back(s.range);
        }
        std::sort(used.begin(), used.end(),
                  [](const MapRange& a, const MapRange& b) { return a.address < b.address; });
        std::uint64_t at = m.begin;
        for (const MapRange& r : used) {
            if (r.address > at) m.gaps.push_back({at, r.address - at});
            at = std::max(at, r.address + r.size);
        }
        if (at < m.end) m.gaps.push_back({at, m.end - at});
    }

    static void find_overlaps(SpaceMap& m) {
        std::vector<MapRange> vars;
        vars.reserve(m.variables.size());
        for (const MapVariable& v : m.variables) vars.push_back({v.address, v.size});
        std::sort(vars.begin(), vars.end(),
                  [](const MapRange& a, const MapRange& b) { return a.address < b.address; });
        std::uint64_t reach = 0;  // one past the last byte of the variables so far
        for (const MapRange& v : vars) {
            const std::uint64_t end = v.address + v.size;
            if (v.address < reach) {
                const std::uint64_t shared_end = std::min(end, reach);
                if (!m.overlaps.empty() &&
                    v.address <= m.overlaps.back().address + m.overlaps.back().size) {
                    MapRange& last = m.overlaps.back();
                    last.size = std::max(last.address + last.size, shared_end) - last.address;
                } else {
                    m.overlaps.push_back({v.address, shared_end - v.address});
                }
            }
            reach = std::max(reach, end);
        }
    }

    const Layout& layout_;
    const MemoryMapOptions& options_;
    VariableCounter counter_;
    std::vector<std::uint64_t> segment_first_;  // first ordinal of each segment, then the total
    std::map<std::uint32_t, SpaceMap> maps_;
};

nlohmann::json range_json(const MapRange& r) {
    return {{"address", r.address}, {"size", r.size}};
}

}  // namespace

std::vector<SpaceMap> build_memory_map(const Layout& layout, const MemoryMapOptions& options) {
    return MapBuilder(layout, options).run();
}

nlohmann::json memory_map_json(const SpaceMap& map) {
    nlohmann::json variables = nlohmann::json::array();
    for (const MapVariable& v : map.variables) {
        variables.push_back({{"name", v.name},
                             {"replica", v.replica},
                             {"label", v.label},
                             {"type", v.type},
                             {"segment", v.segment},
                             {"address", v.address},
                             {"size", v.size},
                             {"ordinal", v.ordinal}});
    }
    nlohmann::json summaries = nlohmann::json::array();
    for (const MapSummary& s : map.summaries) {
        summaries.push_back({{"group", s.group},
                             {"first_name", s.first_name},
                             {"first_replica", s.first_replica},
                             {"replicas", s.replicas},
                             {"variables", s.variables},
                             {"address", s.range.address},
                             {"size", s.range.size}});
    }
    nlohmann::json gaps = nlohmann::json::array();
    for (const MapRange& r : map.gaps) gaps.push_back(range_json(r));
    nlohmann::json overlaps = nlohmann::json::array();
    for (const MapRange& r : map.overlaps) overlaps.push_back(range_json(r));
    return {{"space", map.space},
            {"segments", map.segments},
            {"name", map.name},
            {"begin", map.begin},
            {"end", map.end},
            {"variable_count", map.variable_count},
            {"variables", std::move(variables)},
            {"summaries", std::move(summaries)},
            {"gaps", std::move(gaps)},
            {"overlaps", std::move(overlaps)}};
}

nlohmann::json memory_map_json(const std::vector<SpaceMap>& maps) {
    nlohmann::json out = nlohmann::json::array();
    for (const SpaceMap& m : maps) out.push_back(memory_map_json(m));
    return out;
}

}  // namespace olcb::cdi
