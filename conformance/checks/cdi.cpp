// The CDI as served in space 0xFF: Space Info, the download, its termination, its text and its
// validity, and whether its segments leave the ACDI blocks alone.
#include "cdi/validator.hpp"
#include "conformance/checks/checks.hpp"

namespace olcb::conform::checks {
namespace {

std::string_view cdi_text(CheckRun& run) {
    const auto& b = run.ctx().cdi_bytes;
    return {reinterpret_cast<const char*>(b.data()), b.size()};
}

// The download's checks judge nothing when it failed: say what they depend on instead.
bool downloaded(CheckRun& run) {
    if (run.cdi().read_ok) return true;
    run.out().skip("depends on cdi.read: space 0xFF returned no data");
    return false;
}

}  // namespace

void cdi_space_info(CheckRun& run) {
    const SpaceInfo& ff = run.space_info(0xFF);
    run.out().judge(ff.present && ff.read_only, "Space Info for 0xFF: present and read-only",
                    "present, read-only",
                    ff.present ? "writable" : (ff.answered ? "not present" : "no answer"));
}

void cdi_read(CheckRun& run) {
    const CdiDownload& d = run.cdi();
    run.out().judge(d.read_ok, "space 0xFF read in 64-byte reads", "data",
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
    run.out().judge(ff.highest_address == size,
                    "the NUL is at the highest address Space Info gives", hex(size, 8),
                    hex(ff.highest_address, 8));
}

void cdi_no_bom(CheckRun& run) {
    if (!downloaded(run)) return;
    const bool bom = cdi_text(run).starts_with("\xEF\xBB\xBF");
    run.out().judge(!bom, "no byte-order mark", "no BOM", "EF BB BF at offset 0");
}

void cdi_utf8(CheckRun& run) {
    if (!downloaded(run)) return;
    run.out().judge(is_valid_utf8(run.ctx().cdi_bytes), "valid UTF-8", "UTF-8",
                    "invalid byte sequence");
}

// Judges the first line only: a one-line CDI goes on with <cdi ...> after the declaration.
void cdi_xml_declaration(CheckRun& run) {
    if (!downloaded(run)) return;
    static constexpr std::string_view kDeclaration = "<?xml version=\"1.0\"?>";
    const std::string_view text = cdi_text(run);
    const std::string_view first = text.substr(0, text.find('\n'));
    if (first.starts_with(kDeclaration))
        return run.out().pass("first line starts with the XML declaration <?xml version=\"1.0\"?>");
    const bool declaration =
        first.starts_with("<?xml") &&
        (first.size() == 5 || std::string_view(" \t\r?").find(first[5]) != std::string_view::npos);
    if (declaration) {
        const std::size_t end = first.find("?>");
        const std::string_view decl =
            end == std::string_view::npos ? first : first.substr(0, end + 2);
        return run.out().warn(
            "first line is an XML declaration other than <?xml version=\"1.0\"?>: " + clip(decl));
    }
    std::string_view line = first;
    if (line.ends_with('\r')) line.remove_suffix(1);
    run.out().fail("first line is not the XML declaration <?xml version=\"1.0\"?>",
                   std::string(kDeclaration), quoted(line));
}

void cdi_well_formed(CheckRun& run) {
    if (!downloaded(run)) return;
    const cdi::ValidationReport& report = run.validation();
    run.out().judge(report.schema.well_formed, "well-formed XML", "well-formed", "not well-formed");
}

void cdi_valid(CheckRun& run) {
    if (!downloaded(run)) return;
    const cdi::ValidationReport& report = run.validation();
    std::vector<std::string> errors, warnings;
    for (const auto& d : report.diagnostics) {
        const std::string where = d.line ? "line " + std::to_string(d.line) + ": " : "";
        (d.severity == cdi::Severity::kError ? errors : warnings).push_back(where + d.message);
    }
    if (!errors.empty()) {
        std::vector<std::string> details = errors;
        details.insert(details.end(), warnings.begin(), warnings.end());
        return run.out().add(Status::kFail,
                             std::to_string(errors.size()) + " error(s), " +
                                 std::to_string(warnings.size()) +
                                 " warning(s); first: " + errors.front(),
                             "no error", errors.front(), std::move(details));
    }
    if (!warnings.empty())
        return run.out().warn(
            std::to_string(warnings.size()) + " warning(s); first: " + warnings.front(), warnings);
    run.out().pass("valid against the declared schema and the semantic rules");
}

void cdi_schema_location(CheckRun& run) {
    if (!downloaded(run)) return;
    if (!run.ctx().document) return run.out().skip("depends on cdi.well-formed: no document");
    const std::string& loc = run.ctx().document->schema_location;
    if (loc.empty()) return run.out().warn("no xsi:noNamespaceSchemaLocation");
    const bool sane = (loc.starts_with("http://openlcb.org/schema/cdi/") ||
                       loc.starts_with("https://openlcb.org/schema/cdi/")) &&
                      loc.ends_with(".xsd");
    run.out().judge(sane, "schema location names an openlcb.org CDI schema",
                    "http://openlcb.org/schema/cdi/.../cdi.xsd", clip(loc));
}

void cdi_acdi_spaces(CheckRun& run) {
    if (!downloaded(run)) return;
    const CheckContext& ctx = run.ctx();
    if (!ctx.document || !ctx.document->acdi) return run.out().skip("the CDI has no <acdi/>");
    const std::string conflict = acdi_conflict(ctx);
    run.out().judge(conflict.empty(),
                    "CDI segments leave the ACDI blocks of spaces 252/251 to <acdi/>",
                    "no variable in 252; 251 variables within 1..127", conflict);
}

// A CDI that lays its own variables over the ACDI blocks (some real devices put configuration
// in space 252) makes the node disagree with ACDI whatever it does: that is the CDI's fault.
std::string acdi_conflict(const CheckContext& ctx) {
    std::string conflict;
    if (!ctx.layout) return conflict;
    for (const auto& ext : ctx.layout->extents()) {
        if (ext.begin == ext.end) continue;
        if (ext.space == 0xFC || (ext.space == 0xFB && (ext.begin < 1 || ext.end > 128))) {
            conflict += (conflict.empty() ? "" : ", ") + std::string("space ") +
                        std::to_string(ext.space) + " bytes " + std::to_string(ext.begin) + ".." +
                        std::to_string(ext.end - 1);
        }
    }
    return conflict;
}

}  // namespace olcb::conform::checks
