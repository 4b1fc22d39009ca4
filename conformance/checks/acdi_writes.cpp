// Writes the ACDI version byte of space 251 must refuse (OlcbChecker cd40; the 252 half of cd40
// is memory.readonly-refused.fc). The byte written is the one read, so an accepting node still
// holds what it held: this runs before the safety backup exists.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "conformance/checks/checks.hpp"
#include "memory/memory_config_codec.hpp"

namespace olcb::conform::checks {
namespace {

using memory::Space;

constexpr std::uint8_t kAcdiUser = 0xFB;
constexpr std::uint16_t kReadOnly = base::to_u16(base::ErrorCode::kReadOnly);

MemResult read_version(CheckRun& run) {
    MemResult r = run.session().read(run.node(), Space::kAcdiUser, 0, 1);
    run.note(r);
    return r;
}

MemResult write_version(CheckRun& run, std::uint8_t value) {
    MemResult r = run.session().write(run.node(), Space::kAcdiUser, 0, std::span(&value, 1));
    run.note(r);
    return r;
}

// After a write the node did not refuse: "" when byte 0 still holds original, else what was
// found (the original already written back once more).
std::string version_unchanged(CheckRun& run, std::uint8_t original) {
    const MemResult back = read_version(run);
    if (back.ok && !back.data.empty() && back.data[0] == original) return {};
    std::string found = "byte 0 then read " +
                        (back.ok && !back.data.empty() ? hex(back.data[0], 2) : describe(back));
    write_version(run, original);
    const MemResult again = read_version(run);
    if (again.ok && !again.data.empty() && again.data[0] == original) return found + "; restored";
    return found + "; original not restored (" + hex(original, 2) + " written back, it reads " +
           (again.ok && !again.data.empty() ? hex(again.data[0], 2) : describe(again)) + ")";
}

void version_write_refused(CheckRun& run) {
    Verdict out = run.out();
    run.cdi();
    const bool acdi = run.ctx().document && run.ctx().document->acdi;
    if (!acdi && !run.space_info(kAcdiUser).present)
        return out.skip("no <acdi/> in the CDI and Space Info says 0xFB is not present");
    // A CDI laying its own variable over the version byte is reported by cdi.acdi-spaces; such
    // a byte is a setting of the node, and may be protected: it is left alone.
    if (const auto& layout = run.ctx().layout) {
        if (const cdi::Cursor c = layout->find(kAcdiUser, 0); c.valid())
            return out.skip("depends on cdi.acdi-spaces: the CDI lays " + c.path() +
                            " over 0xFB byte 0");
    }
    if (run.options().read_only) return out.skip("--read-only");
    const MemResult r = read_version(run);
    if (!r.ok || r.data.empty())
        return out.skip("space 0xFB byte 0 does not read (" + describe(r) + "): nothing written");
    const std::uint8_t version = r.data[0];
    const std::string what =
        "write of 0xFB byte 0 (the ACDI user version " + hex(version, 2) + ", its own value)";
    const MemResult w = write_version(run, version);
    if (w.ok || w.timed_out) {
        const std::string changed = version_unchanged(run, version);
        const std::string seen = w.ok ? "accepted" : "no answer";
        return out.fail(what + (w.ok ? " accepted" : ": no answer") +
                            (changed.empty() ? "; the byte is unchanged" : "; " + changed),
                        "refused with 0x1083", seen);
    }
    const std::string code = w.error ? hex(w.error) : "no error code";
    out.pass(what + " refused with " + code +
             (w.error == kReadOnly ? "" : " (the standard gives 0x1083)"));
}

}  // namespace

std::vector<CheckSpec> acdi_write_checks() {
    return {
        {"acdi.version-write-refused", Category::kAcdi,
         "ConfigurationDescriptionInformationS §5.1.2; MemoryConfigurationS §4.8", "cd40",
         "with <acdi/> or 0xFB present: 0xFB byte 0 (the version) read, then written with that "
         "value: refused (0x1083 preferred); writes to 0xFC (cd40's other half) are "
         "memory.readonly-refused.fc",
         version_write_refused},
    };
}

}  // namespace olcb::conform::checks
