// PIP faults: the Protocol Support Reply misstates what the node serves.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// The protocols of the choices, in the declaration's order (the value is the index + 1).
constexpr Protocol kChoices[] = {Protocol::kCdi,
                                 Protocol::kAcdi,
                                 Protocol::kSnip,
                                 Protocol::kDatagram,
                                 Protocol::kMemoryConfiguration,
                                 Protocol::kEventExchange};

void drop_bit(NodeStackConfig& config, FaultValue v) {
    config.protocols.set(kChoices[v.value - 1], false);
}

}  // namespace

std::vector<FaultDecl> pip_faults() {
    return {
        {
            .name = "pip-missing-bit",
            .order = 40,
            .param = {ParamKind::kChoice,
                      "",
                      1,
                      1,
                      6,
                      {"cdi", "acdi", "snip", "datagram", "memory", "events"}},
            .summary = "Protocol Support Reply lacks a bit for a protocol the node serves",
            .doc_parameter = "`cdi` (default), `acdi`, `snip`, `datagram`, `memory`, `events`",
            .rule_broken = "MsgNet PIP: the reply lists every protocol the node implements; CDI "
                           "5.1.2: ACDI bit iff `<acdi/>` (fact sheet 3.1)",
            .client_sees = "Protocol Support Reply without that bit, although the node serves "
                           "the protocol",
            .verdict = Verdict::kFail,
            .category = "pip",
            .checks = {"pip.cdi-bit"},
            .hooks = {.stack_config = drop_bit},
        },
    };
}

}  // namespace olcb::simnode
