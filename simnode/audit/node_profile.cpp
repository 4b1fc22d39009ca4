#include "simnode/audit/node_profile.hpp"

#include <utility>

#include "cdi/layout.hpp"
#include "cdi/variable_name.hpp"
#include "memory/acdi.hpp"
#include "simnode/sim_node.hpp"

namespace olcb::simnode::audit {
namespace {

namespace acdi = memory::acdi;

cdi::Element acdi_string(std::uint64_t size, std::string name) {
    cdi::Element e;
    e.kind = cdi::ElementKind::kString;
    e.tag = "string";
    e.size = size;
    e.name = std::move(name);
    return e;
}

// The user strings of space 251 as CDI §5.1.2 lays them out. Byte 0, the version, is the
// firmware's: not a variable a tool writes.
std::optional<VariableRef> acdi_user_variable(std::uint64_t address) {
    static const cdi::Element name = acdi_string(acdi::kUserNameSize, "User Name");
    static const cdi::Element description =
        acdi_string(acdi::kUserDescriptionSize, "User Description");
    for (const auto& [offset, element] : {std::pair{acdi::kUserNameOffset, &name},
                                          std::pair{acdi::kUserDescriptionOffset, &description}}) {
        if (address >= offset && address < offset + element->size) {
            return VariableRef{offset, element->size, element, "ACDI." + element->name};
        }
    }
    return std::nullopt;
}

}  // namespace

NodeProfile::NodeProfile(NodeId id, std::shared_ptr<const CdiModel> cdi,
                         std::map<std::uint8_t, SpaceShape> spaces)
    : id_(id), cdi_(std::move(cdi)), spaces_(std::move(spaces)) {}

std::optional<SpaceShape> NodeProfile::space(std::uint8_t number) const {
    const auto it = spaces_.find(number);
    if (it == spaces_.end()) return std::nullopt;
    return it->second;
}

std::optional<VariableRef> NodeProfile::variable_at(std::uint8_t space,
                                                    std::uint64_t address) const {
    if (cdi_ && cdi_->layout) {
        const cdi::Cursor c = cdi_->layout->find(space, address);
        if (c.valid())
            return VariableRef{c.address(), c.size(), &c.element(),
                               cdi::variable_name(*cdi_->layout, c)};
    }
    const bool acdi = cdi_ && cdi_->document->acdi.has_value();
    if (acdi && space == memory::to_u8(acdi::kUserSpace)) return acdi_user_variable(address);
    return std::nullopt;
}

NodeProfile profile_of(const SimNode& node) {
    std::map<std::uint8_t, SpaceShape> spaces;
    const NodeMemory& memory = node.memory();
    for (const std::uint8_t number : memory.served_spaces()) {
        const memory::MemorySpace* base = memory.base_space(number);
        if (base != nullptr) spaces[number] = SpaceShape{base->size(), base->read_only()};
    }
    // The model cache hands out the node's own model for its text: shared, not copied.
    std::string error;
    return NodeProfile(node.node_id(), load_cdi_model(node.config().cdi, error), std::move(spaces));
}

}  // namespace olcb::simnode::audit
