// CDI faults: the text served in space 0xFF.
#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

std::vector<FaultDecl> cdi_faults() {
    return {
        {
            .name = "cdi-unterminated",
            .order = 50,
            .access = flag_field<&FaultSet::cdi_unterminated>(),
            .summary = "space 0xFF holds the CDI without its terminating NUL",
            .rule_broken = "CDI: the CDI is a NUL-terminated string in space 0xFF (fact sheet "
                           "5.3)",
            .client_sees = "no NUL anywhere in 0xFF; Space Info highest address = last `>`; a "
                           "client must stop on the short read",
            .verdict = Verdict::kFail,
            .category = "cdi",
            .checks = {"cdi.nul-terminated"},
        },
        {
            .name = "cdi-padding",
            .order = 60,
            .access = flag_field<&FaultSet::cdi_padding>(),
            .summary = "space 0xFF has extra NULs and garbage after the NUL",
            .rule_broken = "none broken: a space may be larger than the text it holds (MemCfg "
                           "§4.16 ties no highest address to the NUL); only the CDI's "
                           "NUL-terminated string is required (CDI §5)",
            .client_sees = "after the NUL: 7 more NULs, `PADDING`, `FF FE`; highest address 16 "
                           "bytes too big. A careful client stops at the NUL and sees nothing "
                           "wrong",
            .verdict = Verdict::kNone,
        },
        {
            .name = "cdi-invalid",
            .order = 70,
            .access = flag_field<&FaultSet::cdi_invalid>(),
            .summary = "served CDI violates the schema (no XML declaration, unknown element)",
            .rule_broken = "CDI 5.1 / schema: the served XML declares and follows the CDI schema",
            .client_sees = "served CDI has no `<?xml …?>` declaration and an unknown "
                           "`<simnodeUnknownElement/>` as first child of `<cdi>`; with this "
                           "fault the node also *starts* from a CDI file that fails validation "
                           "(it must still parse and lay out)",
            .verdict = Verdict::kFail,
            .category = "cdi",
            .checks = {"cdi.xml-declaration", "cdi.valid"},
        },
    };
}

}  // namespace olcb::simnode
