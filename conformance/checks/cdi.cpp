// The CDI as served in space 0xFF: Space Info, the download, its termination, its text and its
// validity, and whether its segments leave the ACDI blocks alone.
#include "cdi/rule_finding.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

// The download's checks judge nothing when it failed: say what they depend on instead.
bool downloaded(CheckRun& run) {
    if (run.cdi().read_ok) return true;
    run.out().skip("depends on cdi.read: space 0xFF returned no data");
    return false;
}

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

// Reports check_rules()' finding for `id` as it stands; the details are cdi.valid's diagnostics.
void text_rule(CheckRun& run, std::string_view id) {
    if (!downloaded(run)) return;
    for (const cdi::RuleFinding& f : run.rules()) {
        if (f.check_id != id) continue;
        std::vector<std::string> details;
        details.reserve(f.diagnostics.size());
        for (const cdi::Diagnostic& d : f.diagnostics) details.push_back(cdi::located(d));
        return run.out().add(status_of(f.status), f.message, f.expected, f.seen,
                             std::move(details));
    }
    run.out().fail("cdi::check_rules() has no rule for this check", std::string(id), "none");
}

}  // namespace

void cdi_space_info(CheckRun& run) {
    const SpaceInfo& ff = run.space_info(0xFF);
    // Get Address Space Information is not mandatory: unanswered says nothing about 0xFF.
    if (!ff.answered) return run.out().skip("Get Address Space Information not answered");
    if (!ff.present && !run.cdi().read_ok)
        return run.out().skip("space 0xFF not present and no CDI read: the node has no CDI");
    run.out().judge(ff.present && ff.read_only, "Space Info for 0xFF: present and read-only",
                    "present, read-only", ff.present ? "writable" : "not present");
}

void cdi_read(CheckRun& run) {
    const CdiDownload& d = run.cdi();
    if (d.read_ok) return run.out().pass("space 0xFF read in 64-byte reads");
    // §4.2 asks only a node that has a CDI to serve it; one that claims none owes nothing.
    const auto& pip = run.pip();
    if (pip && !pip->has(Protocol::kCdi) && d.result.rejected)
        return run.out().skip("the node claims no CDI (PIP) and rejects reads of 0xFF");
    run.out().fail("space 0xFF returned no data", "data",
                   d.result.ok ? "no data" : describe(d.result));
}

void cdi_nul_terminated(CheckRun& run) {
    if (!downloaded(run)) return;
    run.out().judge(run.ctx().cdi_nul_found, "space 0xFF holds a NUL-terminated string", "a NUL",
                    "no NUL in " + std::to_string(run.ctx().cdi_bytes.size()) + " bytes");
}

void cdi_nul_at_highest(CheckRun& run) {
    if (!downloaded(run)) return;
    const SpaceInfo& ff = run.space_info(0xFF);
    if (!run.ctx().cdi_nul_found || !ff.present)
        return run.out().skip(
            "depends on cdi.nul-terminated and cdi.space-info: no NUL or no Space Info");
    const auto size = static_cast<unsigned>(run.ctx().cdi_bytes.size());
    if (ff.highest_address == size)
        return run.out().pass("the NUL is at the highest address Space Info gives");
    // Padding after the NUL is legal; a space that ends before the text does is a note.
    if (ff.highest_address > size)
        return run.out().pass("the NUL (at " + hex(size, 8) + ") lies within space 0xFF (highest " +
                              hex(ff.highest_address, 8) + ")");
    run.out().warn("Space Info's highest address " + hex(ff.highest_address, 8) +
                   " lies before the CDI's NUL at " + hex(size, 8));
}

// The text-only checks: their verdicts are cdi::check_rules()', so `lcc-cdi validate` on a file
// reports what these report for the same text served by a node.
void cdi_no_bom(CheckRun& run) {
    text_rule(run, "cdi.no-bom");
}

void cdi_utf8(CheckRun& run) {
    text_rule(run, "cdi.utf8");
}

void cdi_xml_declaration(CheckRun& run) {
    text_rule(run, "cdi.xml-declaration");
}

void cdi_well_formed(CheckRun& run) {
    text_rule(run, "cdi.well-formed");
}

void cdi_valid(CheckRun& run) {
    text_rule(run, "cdi.valid");
}

void cdi_schema_location(CheckRun& run) {
    text_rule(run, "cdi.schema-location");
}

void cdi_acdi_spaces(CheckRun& run) {
    text_rule(run, "cdi.acdi-spaces");
}

std::string acdi_conflict(const CheckContext& ctx) {
    return ctx.layout ? cdi::acdi_block_conflict(*ctx.layout) : std::string();
}

}  // namespace olcb::conform::checks
