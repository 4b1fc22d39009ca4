// SNIP faults: the Simple Node Information reply disagrees with the node's other identity data.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

std::vector<FaultDecl> snip_faults() {
    return {
        {
            .name = "snip-mismatch",
            .access = flag_field<&FaultSet::snip_mismatch>(),
            .summary = "SNIP model string differs from ACDI space 252 and the CDI",
            .rule_broken = "CDI 5.1.1/5.1.2 and SNIP: SNIP strings equal the CDI "
                           "`<identification>` and the ACDI space contents (fact sheet 6, 7)",
            .client_sees = "SNIP model is `<model> (SNIP)`, space 252 and the CDI say `<model>`",
            .verdict = Verdict::kFail,
            .category = "snip",
            .checks = {"snip.matches-acdi", "snip.matches-cdi"},
        },
        {
            .name = "snip-invalid-utf8",
            .access = flag_field<&FaultSet::snip_invalid_utf8>(),
            .summary = "SNIP user name ends in the bytes FF FE, which are not UTF-8 (space 251 "
                       "stays valid)",
            .rule_broken = "SNIP: the strings of the reply are UTF-8 text (fact sheet 6; CDI "
                           "5.1.4.3 for the ACDI strings they mirror)",
            .client_sees = "the SNIP user name is space 251's name followed by the bytes `FF FE` "
                           "(`simnode default` + `FF FE`), which no UTF-8 text holds; space 251 "
                           "itself stays valid, so `snip.matches-acdi` fails too",
            .verdict = Verdict::kFail,
            .category = "snip",
            .checks = {"snip.matches-acdi", "snip.follows-acdi-user-write"},
        },
    };
}

}  // namespace olcb::simnode
