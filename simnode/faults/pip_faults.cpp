// PIP faults: the Protocol Support Reply misstates what the node serves.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// The choice's index + 1, in the order of PipBit and of the declaration's choices.
void apply_pip_missing(FaultSet& f, FaultValue v) {
    if (v.value == 0) {
        f.pip_missing.reset();
    } else {
        f.pip_missing = static_cast<PipBit>(v.value - 1);
    }
}

FaultValue read_pip_missing(const FaultSet& f) {
    return {f.pip_missing ? static_cast<std::uint32_t>(*f.pip_missing) + 1 : 0U};
}

}  // namespace

std::vector<FaultDecl> pip_faults() {
    return {
        {
            .name = "pip-missing-bit",
            .param = {ParamKind::kChoice,
                      "",
                      1,
                      1,
                      6,
                      {"cdi", "acdi", "snip", "datagram", "memory", "events"}},
            .access = {apply_pip_missing, read_pip_missing},
            .summary = "Protocol Support Reply lacks a bit for a protocol the node serves",
            .doc_parameter = "`cdi` (default), `acdi`, `snip`, `datagram`, `memory`, `events`",
            .rule_broken = "MsgNet PIP: the reply lists every protocol the node implements; CDI "
                           "5.1.2: ACDI bit iff `<acdi/>` (fact sheet 3.1)",
            .client_sees = "Protocol Support Reply without that bit, although the node serves "
                           "the protocol",
            .verdict = Verdict::kFail,
            .category = "pip",
            .checks = {"pip.cdi-bit"},
        },
    };
}

}  // namespace olcb::simnode
