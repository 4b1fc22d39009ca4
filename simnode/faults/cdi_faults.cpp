// CDI faults: the text served in space 0xFF.
#include <iterator>
#include <string>

#include "simnode/faults/fault_families.hpp"

namespace olcb::simnode {

namespace {

void unterminated(ServedCdi& cdi, FaultValue) {
    cdi.terminated = false;
}

void padded(ServedCdi& cdi, FaultValue) {
    static constexpr std::uint8_t kPadding[] = {0,   0,   0,   0,   0,   0,   0,    'P',
                                                'A', 'D', 'D', 'I', 'N', 'G', 0xFF, 0xFE};
    cdi.trailer.insert(cdi.trailer.end(), std::begin(kPadding), std::end(kPadding));
}

// Two schema violations a reader notices at once: no declaration, an unknown element.
void invalid(ServedCdi& cdi, FaultValue) {
    std::string& xml = cdi.xml;
    if (xml.rfind("<?xml", 0) == 0) {
        auto end = xml.find("?>");
        end = end == std::string::npos ? 0 : end + 2;
        while (end < xml.size() && (xml[end] == '\n' || xml[end] == '\r')) ++end;
        xml.erase(0, end);
    }
    if (auto root = xml.find("<cdi"); root != std::string::npos) {
        if (auto close = xml.find('>', root); close != std::string::npos) {
            xml.insert(close + 1, "\n<simnodeUnknownElement/>");
        }
    }
}

}  // namespace

std::vector<FaultDecl> cdi_faults() {
    return {
        {
            .name = "cdi-unterminated",
            .order = 50,
            .summary = "space 0xFF holds the CDI without its terminating NUL",
            .rule_broken = "CDI: the CDI is a NUL-terminated string in space 0xFF (fact sheet "
                           "5.3)",
            .client_sees = "no NUL anywhere in 0xFF; Space Info highest address = last `>`; a "
                           "client must stop on the short read",
            .verdict = Verdict::kFail,
            .category = "cdi",
            .checks = {"cdi.nul-terminated"},
            .hooks = {.cdi = unterminated},
        },
        {
            .name = "cdi-padding",
            .order = 60,
            .summary = "space 0xFF has extra NULs and garbage after the NUL",
            .rule_broken = "none broken: a space may be larger than the text it holds (MemCfg "
                           "§4.16 ties no highest address to the NUL); only the CDI's "
                           "NUL-terminated string is required (CDI §5)",
            .client_sees = "after the NUL: 7 more NULs, `PADDING`, `FF FE`; highest address 16 "
                           "bytes too big. A careful client stops at the NUL and sees nothing "
                           "wrong",
            .verdict = Verdict::kNone,
            .hooks = {.cdi = padded},
        },
        {
            .name = "cdi-invalid",
            .order = 70,
            .summary = "served CDI violates the schema (no XML declaration, unknown element)",
            .rule_broken = "CDI 5.1 / schema: the served XML declares and follows the CDI schema",
            .client_sees = "served CDI has no `<?xml …?>` declaration and an unknown "
                           "`<simnodeUnknownElement/>` as first child of `<cdi>`; with this "
                           "fault the node also *starts* from a CDI file that fails validation "
                           "(it must still parse and lay out)",
            .verdict = Verdict::kFail,
            .category = "cdi",
            .checks = {"cdi.xml-declaration", "cdi.valid"},
            .hooks = {.cdi = invalid},
        },
    };
}

}  // namespace olcb::simnode
