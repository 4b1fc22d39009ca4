// Overlap warnings. Real firmware overlaps variables on purpose (two views of one byte), so
// overlaps are warnings. The pairwise sweep is bounded by LayoutOptions::overlap_budget; past it,
// replicas are still checked against each other by arithmetic (docs/layout-rules.md).
#include <algorithm>

#include "base/run_sort.hpp"
#include "cdi/layout.hpp"
#include "cdi/variable_name.hpp"

namespace olcb::cdi {
namespace {

struct Span {
    std::uint32_t space;
    std::uint64_t begin;
    std::uint64_t end;
    std::uint64_t ordinal;
};

// The first `budget` variables with bytes, ascending by space, address, then document order.
std::vector<Span> sorted_spans(const Layout& layout, std::uint64_t budget) {
    std::vector<Span> spans;
    spans.reserve(static_cast<std::size_t>(budget));
    for (Cursor c = layout.begin(); c.valid() && spans.size() < budget; c.next()) {
        if (c.size() == 0) continue;
        spans.push_back({c.space(), c.address(), c.address() + c.size(), c.ordinal()});
    }
    const auto by_address = [](const Span& a, const Span& b) {
        if (a.space != b.space) return a.space < b.space;
        if (a.begin != b.begin) return a.begin < b.begin;
        return a.ordinal < b.ordinal;
    };
    // Document order is usually address order already, or a few ascending runs.
    base::run_sort(spans.begin(), spans.end(), by_address);
    return spans;
}

// One warning per space whose sorted spans overlap, naming the first overlapping pair.
void warn_span_overlaps(const Layout& layout, const std::vector<Span>& spans,
                        Diagnostics& diagnostics) {
    for (std::size_t i = 0; i < spans.size();) {
        const std::uint32_t space = spans[i].space;
        std::uint64_t overlaps = 0;
        const Span* widest = &spans[i];
        const Span* first_a = nullptr;
        const Span* first_b = nullptr;
        for (++i; i < spans.size() && spans[i].space == space; ++i) {
            if (spans[i].begin < widest->end && overlaps++ == 0) {
                first_a = widest;
                first_b = &spans[i];
            }
            if (spans[i].end > widest->end) widest = &spans[i];
        }
        if (overlaps == 0) continue;
        const Cursor a = layout.at(first_a->ordinal);
        const Cursor b = layout.at(first_b->ordinal);
        diagnostics.push_back(
            {Severity::kWarning, b.element().pos.line,
             std::to_string(overlaps) + " variable(s) overlap an earlier one in space " +
                 std::to_string(space) + ", e.g. '" + variable_name(layout, b) + "' at " +
                 std::to_string(b.address()) + " overlaps '" + variable_name(layout, a) + "' at " +
                 std::to_string(a.address()) + ".." + std::to_string(a.address() + a.size())});
    }
}

}  // namespace

void Layout::check_overlaps(const LayoutOptions& options, Diagnostics& diagnostics) const {
    const std::uint64_t budget = std::min(options.overlap_budget, variable_count_);
    warn_span_overlaps(*this, sorted_spans(*this, budget), diagnostics);
    if (budget != variable_count_) check_replica_overlaps(diagnostics);
}

// Beyond the budget: a group's replicas collide when one replica's variables span more bytes
// than the stride.
void Layout::check_replica_overlaps(Diagnostics& diagnostics) const {
    for (const Node& n : nodes_) {
        if (!n.is_group || n.replication < 2 || n.vars_per_replica == 0) continue;
        const std::int64_t width = n.one_hi - n.one_lo;
        const std::int64_t stride = n.stride < 0 ? -n.stride : n.stride;
        if (width <= stride) continue;
        diagnostics.push_back(
            {Severity::kWarning, n.element->pos.line,
             "replicas of <group>" + (n.element->name.empty() ? "" : " '" + n.element->name + "'") +
                 " overlap each other: one replica spans " + std::to_string(width) +
                 " bytes but the stride is " + std::to_string(n.stride)});
    }
}

}  // namespace olcb::cdi
