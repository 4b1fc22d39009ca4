// Address layout of a CDI (standard section 5.1.4) without expanding replication: every element
// gets its address relative to its parent's replica, and replicas are reached by arithmetic.
// Rules and decisions (negative offsets, OpenMRN's unsigned offsets, <bit>, paths, overlaps):
// docs/layout-rules.md.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "cdi/diagnostic.hpp"
#include "cdi/document.hpp"
#include "cdi/parser.hpp"

namespace olcb::cdi {

/// How an offset in [2^31, 2^32) (outside xs:int, as OpenMRN renders negative padding) applies.
enum class UnsignedOffsetRule : std::uint8_t {
    kIgnore,  ///< taken as 0, with a warning: reproduces the firmware's real layout (default)
    kWrap32,  ///< taken as the 32-bit two's complement negative value, with a warning
};

/// Knobs of build_layout(); the defaults suit real CDIs.
struct LayoutOptions {
    UnsignedOffsetRule unsigned_offset = UnsignedOffsetRule::kIgnore;
    /// Variables checked pairwise for overlap; beyond it only replica self-overlap is checked.
    std::uint64_t overlap_budget = std::uint64_t{1} << 16;
};

/// The [begin, end) byte range used by the variables of one memory space.
struct SpaceExtent {
    std::uint32_t space = 0;
    std::uint64_t begin = 0;
    std::uint64_t end = 0;
};

class Layout;

/// Where the first instance of an element (every enclosing replica 0) lies.
struct Placement {
    std::uint32_t space = 0;
    std::uint64_t address = 0;  ///< absolute address of the element (after its offset)
    std::int64_t stride = 0;    ///< group: one replica's advance (may be negative); else size
    std::uint64_t replication = 1;
};

/// A position on one variable (after replication) of a Layout; copyable. Its stack of enclosing
/// groups is allocated once, as deep as the layout's deepest group; moving it never allocates.
class Cursor {
public:
    /// False once iteration has passed the last variable (or for a failed lookup).
    bool valid() const { return var_node_ != kNone; }
    /// Moves to the next variable in document order (depth first, replicas in order).
    void next();

    /// The variable's element in the Document.
    const Element& element() const;
    /// Index of the variable's segment in Document::segments.
    std::uint32_t segment_index() const;
    /// The memory space of the variable's segment.
    std::uint32_t space() const;
    /// Absolute address of the first byte.
    std::uint64_t address() const { return static_cast<std::uint64_t>(address_); }
    /// Bytes occupied (the element's size).
    std::uint64_t size() const { return element().size; }
    /// Position of the variable in document order after replication (0-based).
    std::uint64_t ordinal() const { return ordinal_; }
    /// Number of groups enclosing the variable.
    std::size_t group_depth() const { return depth_ == 0 ? 0 : depth_ - 1; }
    /// The enclosing group at level (0 = outermost).
    const Element& group(std::size_t level) const;
    /// The 0-based replica index of the enclosing group at level (0 = outermost).
    std::uint64_t replica(std::size_t level) const { return frames_[level + 1].replica; }
    /// "Segment/Group[3](repname)/Variable" (1-based indices; docs/layout-rules.md).
    std::string path() const;

private:
    friend class Layout;
    static constexpr std::uint32_t kNone = 0xFFFFFFFFu;
    struct Frame {
        std::uint32_t node = 0;   // group (or segment root) node being walked
        std::uint32_t child = 0;  // next child position to visit
        std::uint64_t replica = 0;
        std::int64_t base = 0;  // absolute address of the current replica
    };
    bool descend_to_variable();

    const Layout* layout_ = nullptr;
    std::uint32_t segment_ = 0;
    std::uint32_t var_node_ = kNone;
    std::uint32_t depth_ = 0;  // frames in use
    std::int64_t address_ = 0;
    std::uint64_t ordinal_ = 0;
    std::vector<Frame> frames_;  // [0] the segment root, [d] the group at level d
};

/// Addresses of every variable of a Document; holds pointers into the Document.
class Layout {
public:
    /// Number of variables after replication.
    std::uint64_t variable_count() const { return variable_count_; }
    /// The extent of every space that holds variables, ascending by space.
    std::vector<SpaceExtent> extents() const;
    /// The extent of one space, if it holds variables.
    std::optional<SpaceExtent> extent(std::uint32_t space) const;
    /// A cursor on the first variable (invalid when there is none).
    Cursor begin() const;
    /// A cursor on the variable with this ordinal (invalid when out of range); O(depth log n).
    Cursor at(std::uint64_t ordinal) const;
    /// The variable holding byte (space, address), the first in document order if several do;
    /// invalid cursor on a miss. O(depth * log n) when replicas do not overlap each other.
    Cursor find(std::uint32_t space, std::uint64_t address) const;
    /// Calls f(const Cursor&) for every variable in order; f may return false to stop.
    template <class F>
    void visit(F&& f) const {
        for (Cursor c = begin(); c.valid(); c.next()) {
            if constexpr (std::is_same_v<decltype(f(c)), bool>) {
                if (!f(c)) return;
            } else {
                f(c);
            }
        }
    }
    /// Where the element's first instance lies; nullopt for an element not in this layout.
    std::optional<Placement> placement(const Element& element) const;
    /// The Document this layout was built from.
    const Document& document() const { return *doc_; }

private:
    friend class Cursor;
    friend class LayoutBuilder;
    struct Node {
        const Element* element = nullptr;  // nullptr for a segment root
        std::uint32_t parent = 0xFFFFFFFFu;
        std::uint32_t first_child = 0;
        std::uint32_t child_count = 0;
        std::uint32_t sorted_begin = 0;  // this group's slice of sorted_/prefix_hi_
        std::uint32_t sorted_count = 0;  // children holding variables
        bool is_group = false;
        std::int64_t rel = 0;     // address relative to the parent's replica base
        std::int64_t stride = 0;  // group: one replica's advance; variable: size
        std::uint64_t replication = 1;
        std::uint64_t vars_per_replica = 0;
        std::uint64_t vars_before = 0;        // variables in earlier siblings of one parent replica
        std::int64_t one_lo = 0, one_hi = 0;  // variable bytes of replica 0, relative to rel
        std::int64_t lo = 0, hi = 0;          // variable bytes of all replicas, relative to rel
    };
    struct SegmentInfo {
        std::uint32_t root = 0;
        std::uint32_t space = 0;
        std::int64_t origin = 0;
        std::uint64_t first_ordinal = 0;
    };
    struct ReplicaRange {
        std::int64_t first = 0;
        std::int64_t last = -1;
    };
    bool find_in(Cursor& c, std::uint32_t depth, std::int64_t y, std::uint64_t& budget) const;
    bool try_child(Cursor& c, std::uint32_t depth, std::int64_t x, std::uint32_t index,
                   std::uint64_t& budget) const;
    static ReplicaRange replicas_holding(const Node& n, std::int64_t ya);
    void check_overlaps(const LayoutOptions& options, Diagnostics& diagnostics) const;
    void check_replica_overlaps(Diagnostics& diagnostics) const;

    const Document* doc_ = nullptr;
    std::vector<Node> nodes_;
    std::vector<SegmentInfo> segments_;
    std::vector<std::uint32_t> sorted_;    // per group: child nodes ascending by rel + lo
    std::vector<std::int64_t> prefix_hi_;  // running max of rel + hi over sorted_
    mutable std::unique_ptr<std::once_flag> index_once_ = std::make_unique<std::once_flag>();
    mutable std::vector<std::pair<const Element*, std::uint32_t>> by_element_;  // by pointer
    std::uint64_t variable_count_ = 0;
    std::size_t max_group_depth_ = 0;  // deepest group nesting: the frames a cursor needs
    Cursor new_cursor() const;
};

/// The outcome of build_layout(): a layout when there were no errors, and every finding.
struct LayoutResult {
    std::optional<Layout> layout;
    Diagnostics diagnostics;
};

/// Lays out every segment per standard 5.1.4; errors on address overflow; warnings for overlapping
/// variables and empty groups. The Document must outlive the Layout.
LayoutResult build_layout(const Document& doc, const LayoutOptions& options = {});

/// The name of replica (0-based) of a group from its <repname>s ("" when it has none).
std::string replica_name(const Element& group, std::uint64_t replica);

}  // namespace olcb::cdi
