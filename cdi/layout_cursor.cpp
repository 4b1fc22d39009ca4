// Lazy traversal and lookup over a Layout: replicas are visited by arithmetic on the stride,
// never materialised.
#include <algorithm>

#include "cdi/layout.hpp"

namespace olcb::cdi {
namespace {

// Caps the replicas and candidates one find() tries: only hostile documents (replicas that
// overlap each other by millions) get near it.
constexpr std::uint64_t kFindBudget = std::uint64_t{1} << 20;
constexpr std::size_t kMaxCandidates = 32;

std::int64_t floor_div(std::int64_t a, std::int64_t b) {
    std::int64_t q = a / b;
    if ((a % b != 0) && ((a < 0) != (b < 0))) --q;
    return q;
}

std::int64_t ceil_div(std::int64_t a, std::int64_t b) {
    return -floor_div(-a, b);
}

}  // namespace

const Element& Cursor::element() const {
    return *layout_->nodes_[var_node_].element;
}

std::uint32_t Cursor::segment_index() const {
    return segment_;
}

std::uint32_t Cursor::space() const {
    return layout_->segments_[segment_].space;
}

const Element& Cursor::group(std::size_t level) const {
    return *layout_->nodes_[frames_[level + 1].node].element;
}

bool Cursor::descend_to_variable() {
    const auto& nodes = layout_->nodes_;
    while (depth_ > 0) {
        Frame& f = frames_[depth_ - 1];
        const Layout::Node& g = nodes[f.node];
        if (f.child < g.child_count) {
            const std::uint32_t c = g.first_child + f.child++;
            const Layout::Node& n = nodes[c];
            if (!n.is_group) {
                var_node_ = c;
                address_ = f.base + n.rel;
                return true;
            }
            // Groups without variables are skipped whole: replication 10^9 of nothing is free.
            if (n.vars_per_replica != 0) frames_[depth_++] = Frame{c, 0, 0, f.base + n.rel};
            continue;
        }
        if (++f.replica < g.replication) {
            f.child = 0;
            f.base += g.stride;
            continue;
        }
        --depth_;
    }
    return false;
}

void Cursor::next() {
    if (!valid()) return;
    ++ordinal_;
    if (descend_to_variable()) return;
    const auto& segments = layout_->segments_;
    while (++segment_ < segments.size()) {
        frames_[0] = Frame{segments[segment_].root, 0, 0, segments[segment_].origin};
        depth_ = 1;
        if (descend_to_variable()) return;
    }
    var_node_ = kNone;
}

Cursor Layout::new_cursor() const {
    Cursor c;
    c.layout_ = this;
    c.frames_.resize(max_group_depth_ + 2);
    return c;
}

Cursor Layout::begin() const {
    Cursor c = new_cursor();
    for (c.segment_ = 0; c.segment_ < segments_.size(); ++c.segment_) {
        c.frames_[0] =
            Cursor::Frame{segments_[c.segment_].root, 0, 0, segments_[c.segment_].origin};
        c.depth_ = 1;
        if (c.descend_to_variable()) return c;
    }
    c.var_node_ = Cursor::kNone;
    return c;
}

Cursor Layout::at(std::uint64_t ordinal) const {
    Cursor c = new_cursor();
    if (ordinal >= variable_count_) return c;
    auto seg =
        std::upper_bound(segments_.begin(), segments_.end(), ordinal,
                         [](std::uint64_t v, const SegmentInfo& s) { return v < s.first_ordinal; });
    --seg;
    c.segment_ = static_cast<std::uint32_t>(seg - segments_.begin());
    c.ordinal_ = ordinal;
    std::uint64_t rest = ordinal - seg->first_ordinal;
    c.frames_[0] = Cursor::Frame{seg->root, 0, 0, seg->origin};
    c.depth_ = 1;
    while (true) {
        Cursor::Frame& f = c.frames_[c.depth_ - 1];
        const Node& g = nodes_[f.node];
        const Node* first = nodes_.data() + g.first_child;
        const Node* hit =
            std::upper_bound(first, first + g.child_count, rest,
                             [](std::uint64_t v, const Node& n) { return v < n.vars_before; }) -
            1;
        const auto index = static_cast<std::uint32_t>(hit - nodes_.data());
        f.child = index - g.first_child + 1;
        rest -= hit->vars_before;
        if (!hit->is_group) {
            c.var_node_ = index;
            c.address_ = f.base + hit->rel;
            return c;
        }
        const std::uint64_t k = rest / hit->vars_per_replica;
        rest %= hit->vars_per_replica;
        c.frames_[c.depth_++] = Cursor::Frame{
            index, 0, k, f.base + hit->rel + static_cast<std::int64_t>(k) * hit->stride};
    }
}

// Tries child `index` of frame d's group for byte x: the variable itself, or the replicas of a
// group whose span can hold x, in ascending order.
bool Layout::try_child(Cursor& c, std::uint32_t d, std::int64_t x, std::uint32_t index,
                       std::uint64_t& budget) const {
    Cursor::Frame& f = c.frames_[d];
    const Node& g = nodes_[f.node];
    const Node& n = nodes_[index];
    const std::int64_t y = x - f.base;
    if (y < n.rel + n.lo || y >= n.rel + n.hi) return false;
    f.child = index - g.first_child + 1;
    if (!n.is_group) {
        if (y < n.rel || y >= n.rel + n.stride) return false;
        c.var_node_ = index;
        c.address_ = f.base + n.rel;
        c.depth_ = d + 1;
        return true;
    }
    const ReplicaRange range = replicas_holding(n, y - n.rel);
    for (std::int64_t k = range.first; k <= range.last; ++k) {
        if (budget == 0) return false;
        --budget;
        c.frames_[d + 1] =
            Cursor::Frame{index, 0, static_cast<std::uint64_t>(k), f.base + n.rel + k * n.stride};
        if (find_in(c, d + 1, x, budget)) return true;
    }
    return false;
}

// The replicas of group n whose variable bytes can hold offset ya (relative to n.rel); empty
// when last < first.
Layout::ReplicaRange Layout::replicas_holding(const Node& n, std::int64_t ya) {
    const std::int64_t s = n.stride;
    std::int64_t kmin = 0;
    std::int64_t kmax = -1;
    if (s > 0) {
        kmin = ceil_div(ya - n.one_hi + 1, s);
        kmax = floor_div(ya - n.one_lo, s);
    } else if (s < 0) {
        kmin = ceil_div(n.one_lo - ya, -s);
        kmax = floor_div(n.one_hi - 1 - ya, -s);
    } else if (ya >= n.one_lo && ya < n.one_hi) {
        kmax = 0;  // every replica is at the same place; the first one wins
    }
    const auto last = static_cast<std::int64_t>(n.replication - 1);
    return ReplicaRange{std::max<std::int64_t>(kmin, 0), std::min(kmax, last)};
}

// Searches frame d's group (node and base already set) for byte x; children are tried in
// document order among the candidates, replicas in ascending order, so the first hit is the
// first variable in document order holding x.
bool Layout::find_in(Cursor& c, std::uint32_t d, std::int64_t x, std::uint64_t& budget) const {
    const Cursor::Frame& f = c.frames_[d];
    const Node& g = nodes_[f.node];
    if (g.sorted_count == 0) return false;
    const std::int64_t y = x - f.base;
    const std::uint32_t* sorted = sorted_.data() + g.sorted_begin;
    const std::int64_t* prefix_hi = prefix_hi_.data() + g.sorted_begin;
    const std::uint32_t* end = std::upper_bound(
        sorted, sorted + g.sorted_count, y,
        [&](std::int64_t v, std::uint32_t n) { return v < nodes_[n].rel + nodes_[n].lo; });

    std::uint32_t candidates[kMaxCandidates];
    std::size_t count = 0;
    bool too_many = false;
    for (std::ptrdiff_t i = (end - sorted) - 1; i >= 0 && prefix_hi[i] > y; --i) {
        const Node& n = nodes_[sorted[i]];
        if (y >= n.rel + n.hi) continue;
        if (count == kMaxCandidates) {
            too_many = true;
            break;
        }
        candidates[count++] = sorted[i];
    }
    std::sort(candidates, candidates + count);

    if (too_many) {
        for (std::uint32_t i = 0; i < g.child_count; ++i) {
            if (budget == 0) return false;
            --budget;
            if (try_child(c, d, x, g.first_child + i, budget)) return true;
        }
        return false;
    }
    for (std::size_t i = 0; i < count; ++i) {
        if (budget == 0) return false;
        --budget;
        if (try_child(c, d, x, candidates[i], budget)) return true;
    }
    return false;
}

Cursor Layout::find(std::uint32_t space, std::uint64_t address) const {
    Cursor c = new_cursor();
    if (address >= (std::uint64_t{1} << 32)) return c;
    std::uint64_t budget = kFindBudget;
    for (std::uint32_t s = 0; s < segments_.size(); ++s) {
        const SegmentInfo& seg = segments_[s];
        if (seg.space != space) continue;
        c.frames_[0] = Cursor::Frame{seg.root, 0, 0, seg.origin};
        if (!find_in(c, 0, static_cast<std::int64_t>(address), budget)) continue;
        c.segment_ = s;
        std::uint64_t ordinal = seg.first_ordinal;
        for (std::uint32_t d = 0; d < c.depth_; ++d) {
            const Node& g = nodes_[c.frames_[d].node];
            const Node& child = nodes_[g.first_child + c.frames_[d].child - 1];
            ordinal += child.vars_before;
            if (d + 1 < c.depth_) ordinal += c.frames_[d + 1].replica * child.vars_per_replica;
        }
        c.ordinal_ = ordinal;
        return c;
    }
    c.var_node_ = Cursor::kNone;
    c.depth_ = 0;
    return c;
}

}  // namespace olcb::cdi
