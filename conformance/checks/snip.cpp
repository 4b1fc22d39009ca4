// SNIP: its version bytes, and its strings against the ACDI spaces and the CDI.
#include <span>
#include <vector>

#include "base/utf8.hpp"
#include "conformance/checks/checks.hpp"
#include "conformance/report/report.hpp"
#include "memory/acdi.hpp"

namespace olcb::conform::checks {
namespace {

// One string both sides should hold, named for the message.
struct Field {
    const char* name;
    const std::string* want;
    const std::string* got;
};

// "SNIP model "B" differs from <source> "A"" for the first field that differs; "" when none.
std::string first_difference(std::span<const Field> fields, const std::string& source,
                             std::string& want, std::string& got) {
    for (const Field& f : fields) {
        if (*f.want == *f.got) continue;
        want = quoted(*f.want);
        got = quoted(*f.got);
        std::string message = std::string("SNIP ") + f.name;
        message.append(" ").append(got).append(" differs from ");
        message.append(source).append(" ").append(want);
        return message;
    }
    return {};
}

void snip_version_bytes(CheckRun& run, const CheckSpec& spec) {
    const SnipProbe& snip = run.probe<SnipProbe>();
    const auto& raw = snip.raw;
    if (!raw || raw->empty() || !snip.snip) return run.out(spec).skip("no SNIP reply");
    // SimpleNodeInformationS §5.1: 0x01 counts as the current version; §5.2: higher ones are
    // later versions with more strings.
    const unsigned fixed = (*raw)[0];
    const unsigned user = snip.snip->user_version;
    const std::string seen = std::to_string(fixed) + ", " + std::to_string(user);
    if ((fixed == 1 || fixed == 4) && (user == 1 || user == 2))
        return run.out(spec).pass("SNIP version bytes " + seen);
    if (fixed >= 4 && user >= 2)
        return run.out(spec).warn(
            "SNIP version bytes " + seen +
            ": a later version than the standard knows (tools ignore the extra "
            "strings)");
    run.out(spec).fail("SNIP version bytes " + seen + ": not a valid version", "1 or 4, 1 or 2",
                       seen);
}

}  // namespace

void judge_utf8(CheckRun& run, const CheckSpec& spec, const std::vector<NamedText>& texts,
                const std::string& what, Status bad_status) {
    std::vector<const NamedText*> bad;
    for (const NamedText& t : texts)
        if (!base::is_valid_utf8(t.text)) bad.push_back(&t);
    if (bad.empty()) return run.out(spec).pass(what);
    // The bytes themselves, in hex: what U+FFFD stands for is what the firmware author needs.
    const auto shown = [](const NamedText& t) {
        return t.name + " " + show_node_text(t.text, true, t.text.size());
    };
    std::string message = bad.front()->name + " is not valid UTF-8";
    std::vector<std::string> details;
    if (bad.size() > 1) {
        message += " (and " + std::to_string(bad.size() - 1) + " more: see the details)";
        for (const NamedText* t : bad) details.push_back(shown(*t));
    }
    run.out(spec).add(bad_status, std::move(message), "valid UTF-8", shown(*bad.front()),
                      std::move(details));
}

namespace {

void snip_utf8(CheckRun& run, const CheckSpec& spec) {
    const auto& snip = run.probe<SnipProbe>().snip;
    if (!snip) return run.out(spec).skip("depends on snip.version-bytes: no SNIP reply");
    const memory::Snip& sn = *snip;
    judge_utf8(run, spec,
               {{"manufacturer", sn.manufacturer},
                {"model", sn.model},
                {"hardware version", sn.hardware_version},
                {"software version", sn.software_version},
                {"user name", sn.user_name},
                {"user description", sn.user_description}},
               "the six SNIP strings are valid UTF-8",
               Status::kWarn);  // only CommonInformationTN §2.5 says SNIP text is UTF-8
}

void snip_matches_acdi(CheckRun& run, const CheckSpec& spec) {
    const auto& snip = run.probe<SnipProbe>().snip;
    const AcdiProbe& acdi = run.probe<AcdiProbe>();
    if (!snip) return run.out(spec).skip("depends on snip.version-bytes: no SNIP reply");
    if (!acdi.manufacturer || !acdi.user)
        return run.out(spec).skip("spaces 252/251 not read (no <acdi/> in the CDI, or unreadable)");
    const memory::Snip from = memory::snip_from_acdi(*acdi.manufacturer, *acdi.user);
    const memory::Snip& sn = *snip;
    std::string want, got;
    const Field fixed[] = {{"manufacturer", &from.manufacturer, &sn.manufacturer},
                           {"model", &from.model, &sn.model},
                           {"hardware version", &from.hardware_version, &sn.hardware_version},
                           {"software version", &from.software_version, &sn.software_version}};
    const Field user[] = {{"user name", &from.user_name, &sn.user_name},
                          {"user description", &from.user_description, &sn.user_description}};
    std::string diff = first_difference(fixed, "ACDI 252", want, got);
    if (diff.empty()) diff = first_difference(user, "ACDI 251", want, got);
    run.out(spec).judge(diff.empty(),
                        diff.empty() ? "SNIP strings equal the ACDI 252/251 strings" : diff, want,
                        got);
}

void snip_matches_cdi(CheckRun& run, const CheckSpec& spec) {
    const auto& snip = run.probe<SnipProbe>().snip;
    const CdiDownload& cdi = run.probe<CdiDownload>();
    if (!snip) return run.out(spec).skip("depends on snip.version-bytes: no SNIP reply");
    if (!cdi.document || !cdi.document->identification)
        return run.out(spec).skip("the CDI has no <identification> (or did not parse)");
    const auto& id = *cdi.document->identification;
    const memory::Snip& sn = *snip;
    // §5.1.1 compares the tags the CDI has: all four are optional in the schema.
    std::vector<Field> present;
    for (const Field& f : {Field{"manufacturer", &id.manufacturer, &sn.manufacturer},
                           Field{"model", &id.model, &sn.model},
                           Field{"hardware version", &id.hardware_version, &sn.hardware_version},
                           Field{"software version", &id.software_version, &sn.software_version}})
        if (!f.want->empty()) present.push_back(f);
    if (present.empty())
        return run.out(spec).skip("the CDI's <identification> names none of the four strings");
    std::string want, got;
    const std::string diff = first_difference(present, "CDI <identification>", want, got);
    run.out(spec).judge(diff.empty(),
                        diff.empty() ? "SNIP strings equal the CDI <identification>" : diff, want,
                        got);
}

}  // namespace

std::vector<CheckSpec> snip_checks() {
    return {
        {"snip.version-bytes", 80, Category::kSnip, "SimpleNodeInformationS §5.1, §5.2",
         Strength::kShall,
         "the section version bytes are 0x01 or 0x04 (manufacturer) and 0x01 or 0x02 (user); "
         "higher "
         "values are future versions",
         "sn10", "SNIP request: version bytes 4 and 2", snip_version_bytes},
        {"snip.utf8", 90, Category::kSnip, "SimpleNodeInformationS §5.1; CommonInformationTN §2.5",
         Strength::kNone,
         "OpenLCB text is UTF-8 (a technical note; SNIP itself only says NUL-terminated strings)",
         "",
         "(the same reply) each of the six strings is valid UTF-8; FAIL names each invalid one "
         "with "
         "its bytes in hex",
         snip_utf8},
        {"snip.matches-acdi", 340, Category::kSnip, "ConfigurationDescriptionInformationS §5.1.2",
         Strength::kShall, "with <acdi/> and SNIP, the SNIP strings equal the ACDI spaces", "",
         "all six SNIP strings equal the ACDI strings; FAIL names the first differing field",
         snip_matches_acdi},
        {"snip.matches-cdi", 350, Category::kSnip, "ConfigurationDescriptionInformationS §5.1.1",
         Strength::kShall,
         "with <identification> and SNIP, the SNIP strings equal the tags present", "",
         "the four manufacturer strings equal <identification>; FAIL names the first differing "
         "field",
         snip_matches_cdi},
        {"snip.follows-acdi-user-write", 890, Category::kSnip,
         "ConfigurationDescriptionInformationS §5.1.2; SimpleNodeInformationS §6.3",
         Strength::kShall, "the SNIP user strings equal space 251, which is writable", "",
         "write of a UTF-8 user name to 251 @1, a SNIP request, the original back: the reply "
         "carries the name"},
    };
}

}  // namespace olcb::conform::checks
