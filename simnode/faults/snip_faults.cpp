// SNIP faults: the Simple Node Information reply disagrees with the node's other identity data.
#include <string>
#include <string_view>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

// Still a valid SNIP string, just not the one ACDI and the CDI hold.
void mismatch_model(memory::Snip& s, FaultValue) {
    constexpr std::string_view kSuffix = " (SNIP)";
    s.model = std::string(memory::clamp_utf8(s.model, memory::kSnipModelMax - 1 - kSuffix.size())) +
              std::string(kSuffix);
}

// Bytes no UTF-8 text holds anywhere: a client must not trust SNIP strings blindly.
void invalid_user_name(memory::Snip& s, FaultValue) {
    constexpr std::string_view kInvalid = "\xFF\xFE";
    s.user_name = std::string(memory::clamp_utf8(s.user_name,
                                                 memory::kSnipUserNameMax - 1 - kInvalid.size())) +
                  std::string(kInvalid);
}

}  // namespace

std::vector<FaultDecl> snip_faults() {
    return {
        {
            .name = "snip-mismatch",
            .order = 10,
            .summary = "SNIP model string differs from ACDI space 252 and the CDI",
            .rule_broken = "CDI 5.1.1/5.1.2 and SNIP: SNIP strings equal the CDI "
                           "`<identification>` and the ACDI space contents (fact sheet 6, 7)",
            .client_sees = "SNIP model is `<model> (SNIP)`, space 252 and the CDI say `<model>`",
            .verdict = Verdict::kFail,
            .category = "snip",
            .checks = {"snip.matches-acdi", "snip.matches-cdi"},
            .hooks = {.snip = mismatch_model},
        },
        {
            .name = "snip-invalid-utf8",
            .order = 20,
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
            .hooks = {.snip = invalid_user_name},
        },
    };
}

}  // namespace olcb::simnode
