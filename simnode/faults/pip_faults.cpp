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
                      2,
                      1,
                      6,
                      {"cdi", "acdi", "snip", "datagram", "memory", "events"}},
            .summary = "Protocol Support Reply lacks a bit for a protocol the node serves",
            .doc_parameter = "`cdi`, `acdi` (default), `snip`, `datagram`, `memory`, `events`",
            // Only the ACDI bit (and SNIP's "must") has a "shall": the default breaks it.
            .rule_broken = "CDI 5.1.2: ACDI bit iff `<acdi/>` (shall); SNIP 6.1: a SNIP node "
                           "must set the SNIP bit. MsgNet 3.4.3 says the reply \"will\" list "
                           "the other protocols: `cdi`, `datagram`, `memory` only WARN",
            .client_sees = "Protocol Support Reply without that bit, although the node serves "
                           "the protocol",
            .verdict = Verdict::kFail,
            .category = "pip",
            .checks = {"pip.acdi-bit"},
            .hooks = {.stack_config = drop_bit},
        },
    };
}

}  // namespace olcb::simnode
