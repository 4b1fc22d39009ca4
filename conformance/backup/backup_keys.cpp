#include "conformance/backup/backup_keys.hpp"

#include "cdi/variable_name.hpp"

namespace olcb::conform {

// The name every tool shows (cdi/variable_name.hpp) is the backup key: one function, so they
// cannot drift apart.
std::string jmri_backup_key(const cdi::Layout& layout, const cdi::Cursor& c) {
    return cdi::variable_name(layout, c);
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
