// ACDI: the version bytes of 252/251 against <acdi fixed/var>, and their Space Info.
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

// The ACDI checks apply to a CDI with <acdi/>; the others SKIP saying why.
bool has_acdi(CheckRun& run) {
    if (!run.cdi().read_ok) {
        run.out().skip("depends on cdi.read: the CDI could not be read");
        return false;
    }
    if (!run.ctx().document || !run.ctx().document->acdi) {
        run.out().skip("the CDI has no <acdi/>");
        return false;
    }
    run.acdi_blocks();
    return true;
}

void version_byte(CheckRun& run, const MemResult& r, unsigned want, const char* what) {
    const bool readable = r.ok && !r.data.empty();
    run.out().judge(readable && r.data[0] == want, what, std::to_string(want),
                    readable ? std::to_string(r.data[0]) : "unreadable: " + describe(r));
}

}  // namespace

void acdi_manufacturer_version(CheckRun& run) {
    if (!has_acdi(run)) return;
    version_byte(run, run.acdi_manufacturer_result(), run.ctx().document->acdi->fixed,
                 "space 252 byte 0 equals <acdi fixed>");
}

void acdi_user_version(CheckRun& run) {
    if (!has_acdi(run)) return;
    version_byte(run, run.acdi_user_result(), run.ctx().document->acdi->var,
                 "space 251 byte 0 equals <acdi var>");
}

void acdi_space_info(CheckRun& run) {
    if (!has_acdi(run)) return;
    if (!acdi_conflict(run.ctx()).empty())
        return run.out().skip(
            "depends on cdi.acdi-spaces: the CDI's own segments overlap the ACDI blocks");
    const SpaceInfo fc = run.space_info(0xFC);
    const SpaceInfo fb = run.space_info(0xFB);
    auto seen = [](const SpaceInfo& i) {
        if (!i.present) return std::string(i.answered ? "not present" : "no answer");
        return std::to_string(i.highest_address) + (i.read_only ? " RO" : " RW");
    };
    run.out().judge(fc.present && fc.read_only && fc.highest_address == 124 && fb.present &&
                        fb.highest_address == 127,
                    "Space Info: 252 read-only highest 124, 251 highest 127", "124 RO / 127",
                    seen(fc) + " / " + seen(fb));
}

}  // namespace olcb::conform::checks
