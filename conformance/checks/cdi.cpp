// The CDI as served in space 0xFF: Space Info, the download, its termination, its text and its
// validity, and whether its segments leave the ACDI blocks alone.
#include "cdi/rule_finding.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {

Status status_of(cdi::RuleStatus status) {
    switch (status) {
        case cdi::RuleStatus::kPass:
            return Status::kPass;
        case cdi::RuleStatus::kFail:
            return Status::kFail;
        case cdi::RuleStatus::kWarn:
            return Status::kWarn;
        case cdi::RuleStatus::kSkip:
            return Status::kSkip;
    }
    return Status::kFail;
}

namespace {

// The download's checks judge nothing when it failed: say what they depend on instead.
bool downloaded(CheckRun& run, const CheckSpec& spec) {
    if (run.probe<CdiDownload>().read_ok) return true;
    run.out(spec).skip("depends on cdi.read: space 0xFF returned no data");
    return false;
}

// The text-only checks: each reports cdi::check_rules()' finding for its own ID as it stands (the
// details are cdi.valid's diagnostics), so `lcc-cdi validate` on a file reports what these report
// for the same text served by a node.
void text_rule(CheckRun& run, const CheckSpec& spec) {
    if (!downloaded(run, spec)) return;
    for (const cdi::RuleFinding& f : run.probe<CdiDownload>().rules) {
        if (f.check_id != spec.id) continue;
        std::vector<std::string> details;
        details.reserve(f.diagnostics.size());
        for (const cdi::Diagnostic& d : f.diagnostics) details.push_back(cdi::located(d));
        return run.out(spec).add(status_of(f.status), f.message, f.expected, f.seen,
                                 std::move(details));
    }
    run.out(spec).fail("cdi::check_rules() has no rule for this check", std::string(spec.id),
                       "none");
}

void cdi_space_info(CheckRun& run, const CheckSpec& spec) {
    const SpaceInfo& ff = run.probe<SpaceInfoProbe>(0xFF);
    // Get Address Space Information is not mandatory: unanswered says nothing about 0xFF.
    if (!ff.answered) return run.out(spec).skip("Get Address Space Information not answered");
    if (!ff.present && !run.probe<CdiDownload>().read_ok)
        return run.out(spec).skip("space 0xFF not present and no CDI read: the node has no CDI");
    const std::string seen = ff.present ? "writable" : "not present";
    run.out(spec).judge(ff.present && ff.read_only,
                        ff.present && ff.read_only ? "Space Info for 0xFF: present and read-only"
                                                   : "Space Info says space 0xFF is " + seen,
                        "present, read-only", seen);
}

void cdi_read(CheckRun& run, const CheckSpec& spec) {
    const CdiDownload& d = run.probe<CdiDownload>();
    if (d.by_stream && !d.datagram.ok) {
        return run.out(spec).fail("space 0xFF answered a stream read, but a datagram read of " +
                                      d.sampled + " got " + describe(d.datagram),
                                  "datagram reads of 0xFF answered", describe(d.datagram));
    }
    if (d.by_stream) {
        return run.out(spec).pass("space 0xFF read: " + std::to_string(d.result.data.size()) +
                                  " bytes by one stream, datagram reads of " + d.sampled +
                                  " answered");
    }
    if (d.read_ok) return run.out(spec).pass("space 0xFF read in 64-byte reads");
    // §4.2 asks only a node that has a CDI to serve it; one that claims none owes nothing.
    const auto& pip = run.probe<PipProbe>().reply;
    if (pip && !pip->has(Protocol::kCdi) && d.result.rejected)
        return run.out(spec).skip("the node claims no CDI (PIP) and rejects reads of 0xFF");
    run.out(spec).fail("space 0xFF returned no data", "data",
                       d.result.ok ? "no data" : describe(d.result));
}

void cdi_nul_terminated(CheckRun& run, const CheckSpec& spec) {
    if (!downloaded(run, spec)) return;
    const CdiDownload& d = run.probe<CdiDownload>();
    const std::string seen = "no NUL in " + std::to_string(d.text.size()) + " bytes";
    run.out(spec).judge(d.nul_found,
                        d.nul_found ? "space 0xFF holds a NUL-terminated string"
                                    : "space 0xFF holds " + seen + " read",
                        "a NUL", seen);
}

void cdi_nul_at_highest(CheckRun& run, const CheckSpec& spec) {
    if (!downloaded(run, spec)) return;
    const SpaceInfo& ff = run.probe<SpaceInfoProbe>(0xFF);
    const CdiDownload& d = run.probe<CdiDownload>();
    if (!d.nul_found || !ff.present)
        return run.out(spec).skip(
            "depends on cdi.nul-terminated and cdi.space-info: no NUL or no Space Info");
    const auto size = static_cast<unsigned>(d.text.size());
    if (ff.highest_address == size)
        return run.out(spec).pass("the NUL is at the highest address Space Info gives");
    // Padding after the NUL is legal; a space that ends before the text does is a note.
    if (ff.highest_address > size)
        return run.out(spec).pass("the NUL (at " + hex(size, 8) +
                                  ") lies within space 0xFF (highest " +
                                  hex(ff.highest_address, 8) + ")");
    run.out(spec).warn("Space Info's highest address " + hex(ff.highest_address, 8) +
                       " lies before the CDI's NUL at " + hex(size, 8));
}

}  // namespace

std::string acdi_conflict(const std::optional<cdi::Layout>& layout) {
    return layout ? cdi::acdi_block_conflict(*layout) : std::string();
}

std::vector<CheckSpec> cdi_checks() {
    return {
        {"cdi.space-info", 110, Category::kCdi, "MemoryConfigurationS §4.2, §4.16",
         Strength::kShall,
         "space 0xFF is the read-only space holding the CDI; a rejected Get Address Space "
         "Information "
         "is a SKIP",
         "mc20", "`20 84 FF`: present (0x87) and read-only", cdi_space_info},
        {"cdi.read", 120, Category::kCdi, "MemoryConfigurationS §4.2, §4.4, §4.5", Strength::kShall,
         "a node that has a CDI makes it readable through space 0xFF", "cd20",
         "reads of up to 64 bytes of 0xFF, each going on where the previous reply's data ended, up "
         "to Space Info's highest address, a NUL or 0x1082 (at the highest address without a NUL "
         "it reads on: a CDI cut short by a too-small highest address is judged whole, the address "
         "by cdi.nul-at-highest): data returned. A node that offers streams is read once, by one "
         "stream up to the NUL; then datagram reads of its first and last 64 bytes must answer "
         "(stream.cdi-read compares them)",
         cdi_read},
        {"cdi.nul-terminated", 160, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kShall, "the CDI is provided as a NUL-terminated string", "cd20",
         "(CDI download) a NUL ends the text", cdi_nul_terminated},
        {"cdi.nul-at-highest", 170, Category::kCdi, "MemoryConfigurationS §4.16", Strength::kNone,
         "no clause ties the highest address to the NUL: padding after it is legal; a highest "
         "address "
         "before the NUL WARNs",
         "", "(CDI download) offset of the NUL == Space Info highest address", cdi_nul_at_highest},
        {"cdi.no-bom", 180, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kShall, "the CDI string carries no byte-order mark", "",
         "no UTF-8 byte-order mark", text_rule},
        {"cdi.utf8", 190, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kShall, "the CDI string is UTF-8", "",
         "the CDI is valid UTF-8 (FAIL: offset, line and bytes of the first invalid sequence)",
         text_rule},
        {"cdi.xml-declaration", 200, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kShall, "the first line is the XML 1.0 declaration", "cd10",
         "the first line (after a BOM, which is cdi.no-bom's) starts with exactly <?xml "
         "version=\"1.0\"?> (another declaration of XML 1.0 in UTF-8, e.g. encoding=\"utf-8\": "
         "WARN quoting it; another version or encoding, or none: FAIL quoting at most 80 bytes)",
         text_rule},
        {"cdi.well-formed", 210, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kShall, "the CDI is XML 1.0", "cd10",
         "libxml2's parse (FAIL quotes its first parse error and lists all; stopped at the invalid "
         "UTF-8: SKIP depends on cdi.utf8)",
         text_rule},
        {"cdi.valid", 220, Category::kCdi, "ConfigurationDescriptionInformationS §5, §5.1.4",
         Strength::kShall,
         "the CDI validates against the schema it names and follows the element rules of §5.1.4",
         "cd10",
         "cdi::validate: FAIL with every error (details), WARN with every warning, PASS when "
         "none (not well-formed: SKIP depends on cdi.well-formed)",
         text_rule},
        {"cdi.schema-location", 230, Category::kCdi, "ConfigurationDescriptionInformationS §5",
         Strength::kNone,
         "the standard shows the root naming the schema URL but sets no rule for other spellings",
         "",
         "xsi:noNamespaceSchemaLocation names http(s)://openlcb.org/schema/cdi/...xsd (absent: "
         "WARN)",
         text_rule},
        {"cdi.acdi-spaces", 270, Category::kCdi,
         "ConfigurationDescriptionInformationS §5.1.2; ConfigurationDescriptionInformationTN "
         "§2.5.1.2",
         Strength::kMay,
         "a node may also describe spaces 252/251 as segments; variables that contradict the ACDI "
         "layout WARN",
         "", "with <acdi/>: no CDI variable in 252, space-251 variables within bytes 1..127",
         text_rule},
    };
}

}  // namespace olcb::conform::checks
