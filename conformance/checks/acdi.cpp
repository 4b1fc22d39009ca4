// ACDI: the version bytes of 252/251 against <acdi fixed/var>, and their Space Info.
#include "memory/acdi.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

// The ACDI checks apply to a CDI with <acdi/>: the blocks read, else nullptr with the check
// SKIPped saying why.
const AcdiProbe* has_acdi(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& cdi = run.probe<CdiDownload>();
    if (!cdi.read_ok) {
        run.out(spec).skip("depends on cdi.read: the CDI could not be read");
        return nullptr;
    }
    if (!cdi.document || !cdi.document->acdi) {
        run.out(spec).skip("the CDI has no <acdi/>");
        return nullptr;
    }
    return &run.probe<AcdiProbe>();
}

void version_byte(CheckRun& run, const CheckSpec& spec, const MemResult& r, unsigned want,
                  std::uint8_t space, const char* element) {
    const bool readable = r.ok && !r.data.empty();
    const std::string where = "space " + std::to_string(space) + " byte 0";
    const std::string seen = readable ? std::to_string(r.data[0]) : "unreadable: " + describe(r);
    const bool ok = readable && r.data[0] == want;
    run.out(spec).judge(
        ok,
        ok ? where + " equals " + element
           : where + " is " + seen + ", " + element + " says " + std::to_string(want),
        std::to_string(want), seen);
}

// A string slot of an ACDI block: its bytes up to the NUL (all of them when there is none).
std::string_view slot(const std::vector<std::uint8_t>& block, std::size_t offset,
                      std::size_t size) {
    if (offset >= block.size()) return {};
    const auto* begin = reinterpret_cast<const char*>(block.data()) + offset;
    const std::string_view field(begin, std::min(size, block.size() - offset));
    return field.substr(0, field.find('\0'));
}

void acdi_manufacturer_version(CheckRun& run, const CheckSpec& spec) {
    const AcdiProbe* blocks = has_acdi(run, spec);
    if (!blocks) return;
    version_byte(run, spec, blocks->manufacturer_result, blocks->acdi->fixed, 252, "<acdi fixed>");
}

void acdi_user_version(CheckRun& run, const CheckSpec& spec) {
    const AcdiProbe* blocks = has_acdi(run, spec);
    if (!blocks) return;
    version_byte(run, spec, blocks->user_result, blocks->acdi->var, 251, "<acdi var>");
}

void acdi_space_info(CheckRun& run, const CheckSpec& spec) {
    if (!has_acdi(run, spec)) return;
    if (!acdi_conflict(run.probe<CdiDownload>().layout).empty())
        return run.out(spec).skip(
            "depends on cdi.acdi-spaces: the CDI's own segments overlap the ACDI blocks");
    const SpaceInfo fc = run.probe<SpaceInfoProbe>(0xFC);
    const SpaceInfo fb = run.probe<SpaceInfoProbe>(0xFB);
    auto seen = [](const SpaceInfo& i) {
        if (!i.present) return std::string(i.answered ? "not present" : "no answer");
        return std::to_string(i.highest_address) + (i.read_only ? " RO" : " RW");
    };
    auto said = [](std::uint8_t space, const SpaceInfo& i) {
        const std::string name = "space " + std::to_string(space);
        if (!i.present) return name + (i.answered ? " not present" : " not answered");
        return name + " highest " + std::to_string(i.highest_address) +
               (i.read_only ? " read-only" : " writable");
    };
    const std::string got = seen(fc) + " / " + seen(fb);
    if (!fc.answered || !fb.answered)
        return run.out(spec).skip(
            "Get Address Space Information not answered (an optional "
            "command): " +
            got);
    // §5.1.2 asks for bytes 0-124 of 252 readable and 0-127 of 251 readable and writable; the
    // exact size and the read-only flag of 252 are only what the layout implies.
    const bool room = fc.present && fc.highest_address >= 124 && fb.present &&
                      fb.highest_address >= 127 && !fb.read_only;
    if (!room)
        return run.out(spec).fail("Space Info says " + said(0xFC, fc) + ", " + said(0xFB, fb) +
                                      ": the ACDI blocks need 252 to 124, 251 to 127 writable",
                                  ">= 124 / >= 127 RW", got);
    const bool exact = fc.read_only && fc.highest_address == 124 && fb.highest_address == 127;
    if (exact) return run.out(spec).pass("Space Info: 252 read-only highest 124, 251 highest 127");
    run.out(spec).warn("Space Info: " + got +
                       " (the ACDI blocks end at 124 and 127, 252 is read-only)");
}

void acdi_utf8(CheckRun& run, const CheckSpec& spec) {
    const AcdiProbe* blocks = has_acdi(run, spec);
    if (!blocks) return;
    if (!blocks->manufacturer)
        return run.out(spec).skip(
            "depends on acdi.manufacturer-version: space 252 could not be read (" +
            describe(blocks->manufacturer_result) + ")");
    if (!blocks->user)
        return run.out(spec).skip("depends on acdi.user-version: space 251 could not be read (" +
                                  describe(blocks->user_result) + ")");
    using namespace memory::acdi;
    const auto& m = *blocks->manufacturer;
    const auto& u = *blocks->user;
    judge_utf8(
        run, spec,
        {{"space 252 @1 manufacturer", slot(m, kManufacturerOffset, kManufacturerSize)},
         {"space 252 @42 model", slot(m, kModelOffset, kModelSize)},
         {"space 252 @83 hardware version", slot(m, kHardwareVersionOffset, kHardwareVersionSize)},
         {"space 252 @104 software version", slot(m, kSoftwareVersionOffset, kSoftwareVersionSize)},
         {"space 251 @1 user name", slot(u, kUserNameOffset, kUserNameSize)},
         {"space 251 @64 user description", slot(u, kUserDescriptionOffset, kUserDescriptionSize)}},
        "the six ACDI strings of spaces 252/251 are valid UTF-8", Status::kFail);
}

}  // namespace

std::vector<CheckSpec> acdi_checks() {
    return {
        {"acdi.manufacturer-version", 240, Category::kAcdi,
         "ConfigurationDescriptionInformationS §5.1.2", Strength::kShall,
         "with <acdi/>, byte 0 of space 252 equals the fixed attribute", "cd30",
         "read 252 field by field (with <acdi/>): byte 0 == fixed", acdi_manufacturer_version},
        {"acdi.user-version", 250, Category::kAcdi, "ConfigurationDescriptionInformationS §5.1.2",
         Strength::kShall, "with <acdi/>, byte 0 of space 251 equals the var attribute", "cd30",
         "read 251 field by field (with <acdi/>): byte 0 == var", acdi_user_version},
        {"acdi.utf8", 260, Category::kAcdi, "ConfigurationDescriptionInformationS §5.1.2, §5.1.4.3",
         Strength::kShall, "the ACDI name fields are CDI strings, which are UTF-8", "",
         "(the same reads) each of the six strings of 252/251, up to its NUL, is valid UTF-8; FAIL "
         "names each invalid one with its bytes in hex",
         acdi_utf8},
        {"acdi.space-info", 280, Category::kAcdi,
         "ConfigurationDescriptionInformationS §5.1.2; MemoryConfigurationS §4.16",
         Strength::kShall,
         "252 bytes 0-124 readable, 251 bytes 0-127 readable and writable; an exact size or "
         "read-only "
         "flag is not required (WARN)",
         "cd30",
         "`20 84 FC`, `20 84 FB`: 252 present, read-only, highest 124; 251 present, highest 127",
         acdi_space_info},
    };
}

}  // namespace olcb::conform::checks
