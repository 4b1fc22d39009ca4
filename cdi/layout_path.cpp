// Human-readable paths of laid-out variables ("Segment/Group[3](repname)/Variable").
#include "cdi/layout.hpp"

namespace olcb::cdi {

std::string replica_name(const Element& group, std::uint64_t replica) {
    const std::vector<std::string>& names = group.repnames;
    if (names.empty()) return {};
    // One repname is a template numbered per replica; several name the replicas one by one,
    // and replicas beyond the list reuse the last name with the replica's 1-based number.
    if (names.size() == 1) return names[0] + " " + std::to_string(replica + 1);
    if (replica < names.size()) return names[replica];
    return names.back() + " " + std::to_string(replica + 1);
}

std::string Cursor::path() const {
    const Document& doc = layout_->document();
    const Segment& segment = doc.segments[segment_];
    std::string out =
        segment.name.empty() ? "(space " + std::to_string(segment.space) + ")" : segment.name;
    for (std::size_t level = 0; level < group_depth(); ++level) {
        const Element& g = group(level);
        out += '/';
        if (!g.name.empty()) {
            out += g.name;
        } else if (g.replication <= 1) {
            out += "(group)";
        }
        if (g.replication > 1) {
            out += '[' + std::to_string(replica(level) + 1) + ']';
            const std::string name = replica_name(g, replica(level));
            if (!name.empty()) out += '(' + name + ')';
        }
    }
    const Element& e = element();
    out += '/';
    out += e.name.empty() ? "(" + e.tag + ")" : e.name;
    return out;
}

}  // namespace olcb::cdi
