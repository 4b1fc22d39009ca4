#include "cdi/layout.hpp"

#include <algorithm>
#include <limits>

namespace olcb::cdi {
namespace {

using Wide = __int128;

// Intermediate sums saturate here: far beyond any valid address, yet N * value (N < 2^31) and
// sums over 2^32 children still fit in 128 bits.
constexpr Wide kSaturation = Wide{1} << 80;
constexpr Wide kAddressLimit = Wide{1} << 32;
constexpr Wide kTwoPow31 = Wide{1} << 31;
constexpr Wide kMaxVariables = std::numeric_limits<std::int64_t>::max();

Wide sat(Wide v) {
    return v > kSaturation ? kSaturation : (v < -kSaturation ? -kSaturation : v);
}

// Build-time values of one node, kept wide until the address range is proven.
struct Wide4 {
    Wide rel = 0;
    Wide stride = 0;                  // one replica's advance (variables: size)
    Wide one_lo = 0, one_hi = 0;      // variable bytes of replica 0 (relative to own address)
    Wide lo = 0, hi = 0;              // variable bytes over all replicas
    Wide one_amin = 0, one_amax = 0;  // every address (starts and ends) of replica 0
    Wide amin = 0, amax = 0;          // every address over all replicas
    Wide vars = 0;                    // variables per replica
    bool has_vars = false;
};

// What one child contributes to its container.
struct ChildSpan {
    Wide span = 0;            // the advance of the container's cursor
    Wide lo = 0, hi = 0;      // variable bytes (relative to the child's address)
    Wide amin = 0, amax = 0;  // every address
    Wide vars = 0;
    bool has_vars = false;
};

// A container (segment root or group) whose children are being built.
struct BuildFrame {
    std::uint32_t node = 0;
    const std::vector<Element>* children = nullptr;
    std::uint32_t first = 0;  // node index of children[0]
    std::size_t i = 0;        // the child being built
    std::size_t depth = 0;    // group depth of the container
    Wide address = 0;         // of child i
    Wide cursor = 0;
    Wide amin = 0, amax = 0;  // the zero-size element at the start (footnote 3)
    Wide one_lo = 0, one_hi = 0, vars = 0;
    bool has_vars = false;
};

std::string describe(const Element& e) {
    std::string out = "<" + e.tag + ">";
    if (!e.name.empty()) out += " '" + e.name + "'";
    return out;
}

}  // namespace

class LayoutBuilder {
public:
    LayoutBuilder(const Document& doc, const LayoutOptions& options, Diagnostics& diagnostics)
        : doc_(doc), options_(options), diagnostics_(diagnostics) {}

    std::optional<Layout> run();

private:
    void build_children(std::uint32_t node, const std::vector<Element>& children);
    void open_children(std::uint32_t node, const std::vector<Element>& children, std::size_t depth);
    bool start_child(BuildFrame& f);
    ChildSpan group_span(const Element& e, std::uint32_t index);
    void place_child(BuildFrame& f, const ChildSpan& c);
    void close_children(const BuildFrame& f);
    Wide effective_offset(const Element& e);
    bool locate_overflow(std::uint32_t node, Wide address, std::uint32_t space);
    void finish_node(std::uint32_t index);
    void report(Severity severity, std::uint32_t line, std::string message) {
        diagnostics_.push_back({severity, line, std::move(message)});
    }

    const Document& doc_;
    const LayoutOptions& options_;
    Diagnostics& diagnostics_;
    Layout layout_;
    std::vector<Wide4> wide_;
    std::vector<BuildFrame> open_;  // build_children's stack, outermost first
    std::size_t max_depth_ = 0;     // deepest group nesting seen
    bool failed_ = false;
};

Wide LayoutBuilder::effective_offset(const Element& e) {
    Wide offset = e.offset;
    if (offset < kTwoPow31) return offset;
    const std::string negative = to_string(offset - kAddressLimit);
    if (options_.unsigned_offset == UnsignedOffsetRule::kIgnore) {
        report(Severity::kWarning, e.pos.line,
               "offset=" + to_string(offset) + " of " + describe(e) +
                   " is not an xs:int; read as an unsigned rendering of " + negative +
                   " (OpenMRN padding bug) and ignored");
        return 0;
    }
    report(Severity::kWarning, e.pos.line,
           "offset=" + to_string(offset) + " of " + describe(e) +
               " is not an xs:int; applied as the 32-bit wrap-around value " + negative);
    return offset - kAddressLimit;
}

// Allocates the nodes of a container's children and opens it on the build stack.
void LayoutBuilder::open_children(std::uint32_t node, const std::vector<Element>& children,
                                  std::size_t depth) {
    const auto first = static_cast<std::uint32_t>(layout_.nodes_.size());
    layout_.nodes_.resize(first + children.size());
    wide_.resize(first + children.size());
    layout_.nodes_[node].first_child = first;
    layout_.nodes_[node].child_count = static_cast<std::uint32_t>(children.size());
    BuildFrame frame;
    frame.node = node;
    frame.children = &children;
    frame.first = first;
    frame.depth = depth;
    open_.push_back(frame);
    max_depth_ = std::max(max_depth_, depth);
}

// The span of a group whose children are built, from its replica 0 and its last replica.
ChildSpan LayoutBuilder::group_span(const Element& e, std::uint32_t index) {
    layout_.nodes_[index].replication = e.replication;
    const Wide4& w = wide_[index];
    const Wide last = sat(Wide(e.replication - 1) * w.stride);
    ChildSpan c;
    c.span = sat(Wide(e.replication) * w.stride);
    c.has_vars = w.has_vars;
    c.lo = std::min(w.one_lo, sat(last + w.one_lo));
    c.hi = std::max(w.one_hi, sat(last + w.one_hi));
    c.amin = std::min(w.one_amin, sat(last + w.one_amin));
    c.amax = std::max(w.one_amax, sat(last + w.one_amax));
    c.vars = std::min(sat(Wide(e.replication) * w.vars), kMaxVariables + 1);
    return c;
}

// Records child f.i (at address) in its own node and in the running values of its container.
void LayoutBuilder::place_child(BuildFrame& f, const ChildSpan& c) {
    const Element& e = (*f.children)[f.i];
    const auto index = static_cast<std::uint32_t>(f.first + f.i);
    const Wide address = f.address;
    Wide4& w = wide_[index];
    w.rel = address;
    w.lo = c.lo;
    w.hi = c.hi;
    w.amin = c.amin;
    w.amax = c.amax;
    if (e.is_variable()) {
        w.one_lo = c.lo;
        w.one_hi = c.hi;
        w.one_amin = c.amin;
        w.one_amax = c.amax;
        w.vars = 1;
        w.has_vars = true;
    }
    f.amin = std::min(f.amin, sat(address + c.amin));
    f.amax = std::max(f.amax, sat(address + c.amax));
    if (c.has_vars) {
        f.one_lo = f.has_vars ? std::min(f.one_lo, sat(address + c.lo)) : sat(address + c.lo);
        f.one_hi = f.has_vars ? std::max(f.one_hi, sat(address + c.hi)) : sat(address + c.hi);
        f.has_vars = true;
    }
    layout_.nodes_[index].vars_before = static_cast<std::uint64_t>(std::min(f.vars, kMaxVariables));
    f.vars = std::min(f.vars + c.vars, kMaxVariables + 1);
    f.cursor = sat(address + c.span);
    ++f.i;
}

// The container's own values, once every child is placed.
void LayoutBuilder::close_children(const BuildFrame& f) {
    Wide4& w = wide_[f.node];
    w.stride = f.cursor;
    w.one_amin = std::min(f.amin, f.cursor);
    w.one_amax = std::max(f.amax, f.cursor);
    w.one_lo = f.one_lo;
    w.one_hi = f.one_hi;
    w.has_vars = f.has_vars;
    w.vars = f.vars;
}

// Starts child f.i: places a variable (or a refused group) at once; opens a group's children,
// placed by build_children when they are done. Returns true when it opened a group.
bool LayoutBuilder::start_child(BuildFrame& f) {
    const Element& e = (*f.children)[f.i];
    const auto index = static_cast<std::uint32_t>(f.first + f.i);
    layout_.nodes_[index].element = &e;
    layout_.nodes_[index].parent = f.node;
    layout_.nodes_[index].is_group = !e.is_variable();
    f.address = sat(f.cursor + effective_offset(e));
    ChildSpan c;
    if (e.is_variable()) {
        c.span = e.size;
        c.hi = c.span;
        c.amax = c.span;
        c.vars = 1;
        c.has_vars = true;
        wide_[index].stride = c.span;
    } else if (e.replication < 1) {
        report(Severity::kError, e.pos.line, describe(e) + " has replication 0");
        failed_ = true;
    } else if (f.depth + 1 > kMaxGroupDepth) {
        report(Severity::kError, e.pos.line,
               "groups nested deeper than " + std::to_string(kMaxGroupDepth) + " levels");
        failed_ = true;
    } else {
        if (e.children.empty() && e.name.empty() && e.description.empty() && !e.link &&
            e.offset == 0) {
            report(Severity::kWarning, e.pos.line,
                   "empty <group> (no name, description, link, data elements or offset) has "
                   "no effect and is not rendered");
        }
        open_children(index, e.children, f.depth + 1);  // f may move: nothing after this
        return true;
    }
    place_child(f, c);
    return false;
}

// Builds the nodes under node in document order, depth first, with an explicit stack (heap in
// proportion to the document, never the call stack).
void LayoutBuilder::build_children(std::uint32_t node, const std::vector<Element>& children) {
    open_children(node, children, 0);
    while (!open_.empty()) {
        BuildFrame& f = open_.back();
        if (f.i < f.children->size()) {
            start_child(f);
            continue;
        }
        close_children(f);
        const std::uint32_t group = f.node;
        open_.pop_back();
        if (open_.empty()) break;
        BuildFrame& parent = open_.back();
        place_child(parent, group_span((*parent.children)[parent.i], group));
    }
}

// Reports the first element (document order, replica 0 then the last replica) whose address
// range leaves [0, 2^32]; the ranges are linear in the replica index, so these two suffice.
bool LayoutBuilder::locate_overflow(std::uint32_t node, Wide address, std::uint32_t space) {
    const Wide4& w = wide_[node];
    if (address + w.amin >= 0 && address + w.amax <= kAddressLimit) return false;
    const Layout::Node& n = layout_.nodes_[node];
    const Element* e = n.element;
    if (e == nullptr || n.is_group) {
        const std::uint64_t replication = e ? e->replication : 1;
        for (std::uint64_t k : {std::uint64_t{0}, replication - 1}) {
            const Wide base = sat(address + sat(Wide(k) * w.stride));
            for (std::uint32_t c = 0; c < n.child_count; ++c) {
                const std::uint32_t child = n.first_child + c;
                if (locate_overflow(child, sat(base + wide_[child].rel), space)) return true;
            }
            if (replication == 1) break;
        }
    }
    const std::string where = " (space " + std::to_string(space) + ")";
    if (e == nullptr) {
        report(Severity::kError, 0, "segment addresses leave 0..2^32" + where);
    } else if (address + w.amin < 0) {
        report(Severity::kError, e->pos.line,
               describe(*e) + " starts at address " + to_string(address + w.amin) + ", below 0" +
                   where);
    } else {
        report(Severity::kError, e->pos.line,
               describe(*e) + " ends at address " + to_string(address + w.amax) +
                   ", beyond the 32-bit address space" + where);
    }
    return true;
}

// Narrows the proven values and builds the per-group index that find() searches.
void LayoutBuilder::finish_node(std::uint32_t index) {
    Layout::Node& n = layout_.nodes_[index];
    const Wide4& w = wide_[index];
    n.rel = static_cast<std::int64_t>(w.rel);
    n.stride = static_cast<std::int64_t>(w.stride);
    n.vars_per_replica = static_cast<std::uint64_t>(w.vars);
    n.one_lo = static_cast<std::int64_t>(w.one_lo);
    n.one_hi = static_cast<std::int64_t>(w.one_hi);
    n.lo = static_cast<std::int64_t>(w.lo);
    n.hi = static_cast<std::int64_t>(w.hi);
    if (n.element != nullptr && !n.is_group) return;
    n.sorted_begin = static_cast<std::uint32_t>(layout_.sorted_.size());
    for (std::uint32_t c = 0; c < n.child_count; ++c) {
        if (wide_[n.first_child + c].has_vars) layout_.sorted_.push_back(n.first_child + c);
    }
    n.sorted_count = static_cast<std::uint32_t>(layout_.sorted_.size()) - n.sorted_begin;
    auto begin = layout_.sorted_.begin() + n.sorted_begin;
    const auto by_start = [&](std::uint32_t a, std::uint32_t b) {
        const Wide ka = wide_[a].rel + wide_[a].lo;
        const Wide kb = wide_[b].rel + wide_[b].lo;
        return ka != kb ? ka < kb : a < b;
    };
    // Children usually follow each other in memory; checking is cheaper than sorting.
    if (!std::is_sorted(begin, layout_.sorted_.end(), by_start)) {
        std::sort(begin, layout_.sorted_.end(), by_start);
    }
    Wide running = std::numeric_limits<std::int64_t>::min();
    for (auto it = begin; it != layout_.sorted_.end(); ++it) {
        running = std::max(running, wide_[*it].rel + wide_[*it].hi);
        layout_.prefix_hi_.push_back(static_cast<std::int64_t>(running));
    }
}

namespace {

// A reservation hint only: every element under the segments, without recursion.
std::size_t count_elements(const std::vector<Segment>& segments) {
    std::size_t n = 0;
    std::vector<const std::vector<Element>*> todo;
    todo.reserve(segments.size());
    for (const Segment& segment : segments) todo.push_back(&segment.children);
    while (!todo.empty()) {
        const std::vector<Element>& elements = *todo.back();
        todo.pop_back();
        n += elements.size();
        for (const Element& e : elements) {
            if (!e.children.empty()) todo.push_back(&e.children);
        }
    }
    return n;
}

}  // namespace

std::optional<Layout> LayoutBuilder::run() {
    layout_.doc_ = &doc_;
    const std::size_t nodes = doc_.segments.size() + count_elements(doc_.segments);
    layout_.nodes_.reserve(nodes);
    wide_.reserve(nodes);
    Wide total = 0;
    for (const Segment& segment : doc_.segments) {
        const auto root = static_cast<std::uint32_t>(layout_.nodes_.size());
        layout_.nodes_.emplace_back();
        wide_.emplace_back();
        build_children(root, segment.children);
        Wide4& w = wide_[root];
        w.rel = segment.origin;
        w.lo = w.one_lo;
        w.hi = w.one_hi;
        w.amin = w.one_amin;
        w.amax = w.one_amax;
        layout_.segments_.push_back(
            Layout::SegmentInfo{root, segment.space, segment.origin,
                                static_cast<std::uint64_t>(std::min(total, kMaxVariables))});
        total = std::min(total + w.vars, kMaxVariables + 1);
    }
    if (failed_) return std::nullopt;
    for (std::size_t i = 0; i < layout_.segments_.size(); ++i) {
        const Layout::SegmentInfo& s = layout_.segments_[i];
        if (locate_overflow(s.root, s.origin, s.space)) failed_ = true;
    }
    if (total > kMaxVariables) {
        report(Severity::kError, 0,
               "more than 2^63 variables after replication; the layout is refused");
        failed_ = true;
    }
    if (failed_) return std::nullopt;
    layout_.variable_count_ = static_cast<std::uint64_t>(total);
    layout_.max_group_depth_ = max_depth_;
    for (std::uint32_t i = 0; i < layout_.nodes_.size(); ++i) finish_node(i);
    wide_.clear();
    wide_.shrink_to_fit();
    layout_.check_overlaps(options_, diagnostics_);
    return std::move(layout_);
}

LayoutResult build_layout(const Document& doc, const LayoutOptions& options) {
    LayoutResult result;
    LayoutBuilder builder(doc, options, result.diagnostics);
    result.layout = builder.run();
    if (has_errors(result.diagnostics)) result.layout.reset();
    return result;
}

std::vector<SpaceExtent> Layout::extents() const {
    std::vector<SpaceExtent> out;
    for (const SegmentInfo& s : segments_) {
        const Node& root = nodes_[s.root];
        if (root.vars_per_replica == 0) continue;
        const auto begin = static_cast<std::uint64_t>(s.origin + root.one_lo);
        const auto end = static_cast<std::uint64_t>(s.origin + root.one_hi);
        auto it = std::find_if(out.begin(), out.end(),
                               [&](const SpaceExtent& e) { return e.space == s.space; });
        if (it == out.end()) {
            out.push_back({s.space, begin, end});
        } else {
            it->begin = std::min(it->begin, begin);
            it->end = std::max(it->end, end);
        }
    }
    std::sort(out.begin(), out.end(),
              [](const SpaceExtent& a, const SpaceExtent& b) { return a.space < b.space; });
    return out;
}

std::optional<Placement> Layout::placement(const Element& element) const {
    // Built on first use: only renderers need it, and sorting costs a few % of a parse.
    std::call_once(*index_once_, [this] {
        by_element_.reserve(nodes_.size() - segments_.size());
        for (std::uint32_t i = 0; i < nodes_.size(); ++i) {
            if (nodes_[i].element) by_element_.emplace_back(nodes_[i].element, i);
        }
        std::sort(by_element_.begin(), by_element_.end());
    });
    auto it = std::lower_bound(by_element_.begin(), by_element_.end(),
                               std::pair<const Element*, std::uint32_t>(&element, 0));
    if (it == by_element_.end() || it->first != &element) return std::nullopt;
    const Node& n = nodes_[it->second];
    std::int64_t address = 0;
    std::uint32_t i = it->second;
    while (nodes_[i].parent != 0xFFFFFFFFu) {
        address += nodes_[i].rel;
        i = nodes_[i].parent;
    }
    auto seg = std::find_if(segments_.begin(), segments_.end(),
                            [&](const SegmentInfo& s) { return s.root == i; });
    Placement p;
    p.space = seg->space;
    p.address = static_cast<std::uint64_t>(address + seg->origin);
    p.stride = n.stride;
    p.replication = n.replication;
    return p;
}

std::optional<SpaceExtent> Layout::extent(std::uint32_t space) const {
    for (const SpaceExtent& e : extents()) {
        if (e.space == space) return e;
    }
    return std::nullopt;
}

}  // namespace olcb::cdi
