#include "conformance/backup/backup_keys.hpp"

#include "conformance/backup/backup_values.hpp"

namespace olcb::conform {

namespace {

std::string part_name(const std::string& name, std::size_t index) {
    return name.empty() ? "child" + std::to_string(index) : escape_backup_text(name);
}

}  // namespace

std::string jmri_backup_key(const cdi::Layout& layout, const cdi::Cursor& c) {
    const cdi::Segment& seg = layout.document().segments[c.segment_index()];
    std::string key =
        seg.name.empty() ? "seg" + std::to_string(seg.content_index) : escape_backup_text(seg.name);
    for (std::size_t level = 0; level < c.group_depth(); ++level) {
        const cdi::Element& g = c.group(level);
        key += '.';
        key += part_name(g.name, g.content_index);
        if (g.replication > 1) key += "(" + std::to_string(c.replica(level)) + ")";
    }
    key += '.';
    key += part_name(c.element().name, c.element().content_index);
    return key;
}

bool is_backed_up(const cdi::Element& e) {
    switch (e.kind) {
        case cdi::ElementKind::kInt:
        case cdi::ElementKind::kString:
        case cdi::ElementKind::kEventId:
        case cdi::ElementKind::kFloat:
            return true;
        default:
            return false;
    }
}

std::vector<ConfigEntry> config_entries(const cdi::Layout& layout) {
    std::vector<ConfigEntry> out;
    layout.visit([&](const cdi::Cursor& c) {
        const cdi::Element& e = c.element();
        if (!is_backed_up(e)) return;
        const std::uint64_t size = e.kind == cdi::ElementKind::kEventId ? 8 : e.size;
        out.push_back({jmri_backup_key(layout, c), &e, c.space(), c.address(), size});
    });
    return out;
}

}  // namespace olcb::conform
