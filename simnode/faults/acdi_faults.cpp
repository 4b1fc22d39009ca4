// ACDI faults: the contents of spaces 252/251.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void versions_plus_one(AcdiVersions& v, FaultValue) {
    ++v.fixed;
    ++v.user;
}

}  // namespace

std::vector<FaultDecl> acdi_faults() {
    return {
        {
            .name = "acdi-version",
            .order = 30,
            .summary = "version bytes of spaces 252/251 are fixed+1 and var+1",
            .rule_broken = "CDI 5.1.2: byte 0 of 252 is the `fixed` attribute, byte 0 of 251 the "
                           "`var` attribute (fact sheet 7)",
            .client_sees = "space 252 byte 0 = fixed+1 (5), space 251 byte 0 = var+1 (3)",
            .verdict = Verdict::kFail,
            .category = "acdi",
            .checks = {"acdi.manufacturer-version", "acdi.user-version"},
            .hooks = {.acdi = versions_plus_one},
        },
    };
}

}  // namespace olcb::simnode
