#include "cdi/fdi_document.hpp"

#include <algorithm>
#include <vector>

namespace olcb::cdi {

std::string_view function_kind_name(FunctionKind kind) {
    switch (kind) {
        case FunctionKind::kBinary:
            return "binary";
        case FunctionKind::kMomentary:
            return "momentary";
        case FunctionKind::kAnalog:
            return "analog";
    }
    return "?";
}

const FdiFunction* FdiDocument::find(std::uint32_t number) const {
    const auto it = std::find_if(functions.begin(), functions.end(),
                                 [number](const FdiFunction& f) { return f.number == number; });
    return it == functions.end() ? nullptr : &*it;
}

void FdiDocument::walk(const std::function<void(const FdiStep&)>& visit) const {
    // Container 0 is the segment, container g + 1 the group g.
    const std::size_t containers = groups.size() + 1;
    std::vector<std::vector<std::size_t>> child_groups(containers);
    std::vector<std::vector<std::size_t>> child_functions(containers);
    for (std::size_t g = 0; g < groups.size(); ++g) {
        const auto& parent = groups[g].parent;
        child_groups[parent && *parent < g ? *parent + 1 : 0].push_back(g);
    }
    for (std::size_t f = 0; f < functions.size(); ++f) {
        const auto& group = functions[f].group;
        child_functions[group && *group < groups.size() ? *group + 1 : 0].push_back(f);
    }
    struct Frame {
        std::size_t container;
        std::size_t next_group = 0;
        std::size_t next_function = 0;
    };
    std::vector<Frame> open{{0}};
    while (!open.empty()) {
        Frame& top = open.back();
        const auto& subgroups = child_groups[top.container];
        const auto& own = child_functions[top.container];
        const std::size_t depth = open.size() - 1;
        const bool group_left = top.next_group < subgroups.size();
        const bool function_left = top.next_function < own.size();
        if (group_left && (!function_left || groups[subgroups[top.next_group]].first_function <=
                                                 own[top.next_function])) {
            const std::size_t g = subgroups[top.next_group++];
            visit({FdiStep::Kind::kOpenGroup, g, depth});
            open.push_back({g + 1});
        } else if (function_left) {
            visit({FdiStep::Kind::kFunction, own[top.next_function++], depth});
        } else {
            const std::size_t container = top.container;
            open.pop_back();
            if (container != 0) visit({FdiStep::Kind::kCloseGroup, container - 1, depth - 1});
        }
    }
}

}  // namespace olcb::cdi
