#include "cdi/rule_finding.hpp"

#include <algorithm>
#include <cstdint>
#include <iterator>
#include <optional>
#include <utility>

#include "base/hex.hpp"
#include "base/utf8.hpp"
#include "cdi/decimal.hpp"
#include "cdi/fdi_validator.hpp"
#include "cdi/string_codec.hpp"
#include "cdi/validator.hpp"
#include "cdi/variable_name.hpp"

namespace olcb::cdi {
namespace {

constexpr std::string_view kBom = "\xEF\xBB\xBF";

/// Which text the rules judge: their IDs' prefix and how messages name it.
struct TextKind {
    std::string_view prefix;        ///< "cdi": the checks are cdi.*
    std::string_view with_article;  ///< "a CDI"
    std::string_view clause;        ///< §5's standard, for a finding's clause ("" for a CDI)
    std::string id(std::string_view rule) const {
        return std::string(prefix) + "." + std::string(rule);
    }
};

// A cdi.* finding's clause is its lcc-conform registry entry's; an fdi.* finding carries its own.
constexpr TextKind kCdi{"cdi", "a CDI", ""};
constexpr TextKind kFdi{"fdi", "an FDI", "FunctionDescriptionInformationS §5"};
constexpr std::string_view kDeclaration = "<?xml version=\"1.0\"?>";
/// Longest quote of the text in a finding: a first line can be a whole one-line CDI.
constexpr std::size_t kMaxQuote = 80;
/// Bytes shown from the first invalid UTF-8 sequence on.
constexpr std::size_t kShownBytes = 4;

RuleFinding finding(std::string_view id, RuleStatus status, std::string message,
                    std::string expected = {}, std::string seen = {}, std::uint32_t line = 0) {
    RuleFinding f;
    f.check_id = std::string(id);
    f.status = status;
    f.message = std::move(message);
    f.expected = std::move(expected);
    f.seen = std::move(seen);
    f.line = line;
    return f;
}

std::string clip(std::string_view text) {
    if (text.size() <= kMaxQuote) return std::string(text);
    return std::string(base::truncate_utf8(text, kMaxQuote)) + "...";
}

std::string quoted(std::string_view text) {
    return "\"" + clip(text) + "\"";
}

std::uint32_t line_at(std::string_view text, std::size_t offset) {
    return 1 + static_cast<std::uint32_t>(std::count(text.begin(), text.begin() + offset, '\n'));
}

std::string hex_bytes(std::string_view bytes) {
    return base::hex_bytes({reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size()});
}

// CDI and FDI standards §5: "There is no byte-order mark (BOM) at the start of the string."
RuleFinding no_bom(std::string_view text, const TextKind& kind) {
    if (!text.starts_with(kBom))
        return finding(kind.id("no-bom"), RuleStatus::kPass, "no byte-order mark");
    return finding(kind.id("no-bom"), RuleStatus::kFail, "byte-order mark at the start", "no BOM",
                   "EF BB BF at offset 0", 1);
}

// CDI and FDI standards §5: "The bytes encode UTF-8 characters."
RuleFinding utf8(std::string_view text, const TextKind& kind) {
    const std::optional<std::size_t> bad = base::find_invalid_utf8(text);
    if (!bad) return finding(kind.id("utf8"), RuleStatus::kPass, "valid UTF-8");
    const std::uint32_t line = line_at(text, *bad);
    return finding(
        kind.id("utf8"), RuleStatus::kFail,
        "invalid UTF-8 at offset " + std::to_string(*bad) + " (line " + std::to_string(line) + ")",
        "UTF-8", hex_bytes(text.substr(*bad, kShownBytes)) + " at offset " + std::to_string(*bad),
        line);
}

/// The pseudo-attributes of an XML declaration ("version", "encoding", "standalone"), as far as
/// they read as name="value" or name='value'; a malformed rest is left to cdi.well-formed.
std::vector<std::pair<std::string_view, std::string_view>> pseudo_attributes(
    std::string_view decl) {
    std::vector<std::pair<std::string_view, std::string_view>> out;
    constexpr std::string_view kSpace = " \t\r\n";
    std::string_view rest = decl.substr(std::string_view("<?xml").size());
    for (;;) {
        rest.remove_prefix(std::min(rest.size(), rest.find_first_not_of(kSpace)));
        const std::size_t eq = rest.find('=');
        if (rest.empty() || rest.starts_with("?>") || eq == std::string_view::npos) break;
        std::string_view name = rest.substr(0, eq);
        name.remove_suffix(name.size() - std::min(name.size(), name.find_last_not_of(kSpace) + 1));
        rest.remove_prefix(eq + 1);
        rest.remove_prefix(std::min(rest.size(), rest.find_first_not_of(kSpace)));
        if (rest.empty() || (rest.front() != '"' && rest.front() != '\'')) break;
        const std::size_t close = rest.find(rest.front(), 1);
        if (close == std::string_view::npos) break;
        out.emplace_back(name, rest.substr(1, close - 1));
        rest.remove_prefix(close + 1);
    }
    return out;
}

bool iequals(std::string_view a, std::string_view b) {
    return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](char x, char y) {
        return (x >= 'A' && x <= 'Z' ? x + 32 : x) == (y >= 'A' && y <= 'Z' ? y + 32 : y);
    });
}

// CDI and FDI standards §5: "The first line of the CDI [FDI] is: <?xml version="1.0"?> to define
// the XML version of the content." Another version breaks "XML 1.0 format ... No extensions to
// XML 1.0 are permitted", another encoding "The bytes encode UTF-8 characters": FAIL. A declaration
// that still says XML 1.0 in UTF-8 (single quotes, encoding="utf-8", standalone) defines what the
// standard's line defines, only not in its words: WARN. A BOM is cdi.no-bom's finding, so the
// line is judged after it rather than failed a second time for it.
RuleFinding xml_declaration(std::string_view text, const TextKind& kind) {
    const std::string kId = kind.id("xml-declaration");
    if (text.starts_with(kBom)) text.remove_prefix(kBom.size());
    std::string_view first = text.substr(0, text.find('\n'));
    if (first.starts_with(kDeclaration))
        return finding(kId, RuleStatus::kPass,
                       "first line starts with the XML declaration <?xml version=\"1.0\"?>");
    if (first.ends_with('\r')) first.remove_suffix(1);
    const bool declaration =
        first.starts_with("<?xml") &&
        (first.size() == 5 || std::string_view(" \t\r?").find(first[5]) != std::string_view::npos);
    if (!declaration)
        return finding(kId, RuleStatus::kFail,
                       "first line is not the XML declaration <?xml version=\"1.0\"?>",
                       std::string(kDeclaration), quoted(first), 1);
    const std::size_t end = first.find("?>");
    const std::string_view decl = end == std::string_view::npos ? first : first.substr(0, end + 2);
    std::optional<std::string_view> version, encoding;
    for (const auto& [name, value] : pseudo_attributes(decl)) {
        if (name == "version") version = value;
        if (name == "encoding") encoding = value;
    }
    if (version != "1.0")
        return finding(kId, RuleStatus::kFail,
                       (version ? "the XML declaration names XML " + clip(*version)
                                : std::string("the XML declaration names no XML version")) +
                           "; " + std::string(kind.with_article) + " is XML 1.0",
                       std::string(kDeclaration), quoted(decl), 1);
    if (encoding && !iequals(*encoding, "UTF-8"))
        return finding(kId, RuleStatus::kFail,
                       "the XML declaration names encoding " + clip(*encoding) + "; " +
                           std::string(kind.with_article) + "'s bytes are UTF-8",
                       std::string(kDeclaration), quoted(decl), 1);
    return finding(
        kId, RuleStatus::kWarn,
        "first line is an XML declaration other than <?xml version=\"1.0\"?>: " + clip(decl),
        std::string(kDeclaration), quoted(decl), 1);
}

// Errors first, then warnings, each in line order: how a finding lists its diagnostics.
Diagnostics errors_then_warnings(const Diagnostics& all) {
    Diagnostics out;
    out.reserve(all.size());
    for (const Severity severity : {Severity::kError, Severity::kWarning})
        std::copy_if(all.begin(), all.end(), std::back_inserter(out),
                     [severity](const Diagnostic& d) { return d.severity == severity; });
    return out;
}

// Text that is not XML has no validity to judge: its parse errors are this finding's, and
// cdi.valid says it depends on it instead of failing a second time for the same cause.
RuleFinding well_formed(bool xml, const Diagnostics& diagnostics, const TextKind& kind) {
    const std::string kId = kind.id("well-formed");
    if (xml) return finding(kId, RuleStatus::kPass, "well-formed XML");
    RuleFinding f =
        finding(kId, RuleStatus::kFail, "not well-formed XML", "well-formed", "not well-formed");
    f.diagnostics = errors_then_warnings(diagnostics);
    if (!f.diagnostics.empty() && f.diagnostics.front().severity == Severity::kError) {
        f.seen = clip(located(f.diagnostics.front()));
        f.line = f.diagnostics.front().line;
    }
    return f;
}

// CDI and FDI standards §5: "The CDI [FDI] content shall pass validation against its referenced
// schema." The semantic rules (and a CDI's layout) add what no schema can express
// (docs/validation.md).
RuleFinding valid(bool xml, const Diagnostics& diagnostics, const TextKind& kind) {
    const std::string kId = kind.id("valid");
    if (!xml)
        return finding(kId, RuleStatus::kSkip,
                       "depends on " + kind.id("well-formed") + ": the text is not XML");
    Diagnostics all = errors_then_warnings(diagnostics);
    if (all.empty())
        return finding(kId, RuleStatus::kPass,
                       "valid against the declared schema and the semantic rules");
    const auto errors =
        static_cast<std::size_t>(std::count_if(all.begin(), all.end(), [](const Diagnostic& d) {
            return d.severity == Severity::kError;
        }));
    const std::size_t warnings = all.size() - errors;
    const std::string first = located(all.front());
    RuleFinding f = errors == 0
                        ? finding(kId, RuleStatus::kWarn,
                                  std::to_string(warnings) + " warning(s); first: " + first)
                        : finding(kId, RuleStatus::kFail,
                                  std::to_string(errors) + " error(s), " +
                                      std::to_string(warnings) + " warning(s); first: " + first,
                                  "no error", first);
    f.line = all.front().line;
    f.diagnostics = std::move(all);
    return f;
}

// `location`: the root's xsi:noNamespaceSchemaLocation, null when there is no document.
RuleFinding schema_location(const std::string* location, const TextKind& kind) {
    const std::string kId = kind.id("schema-location");
    if (location == nullptr)
        return finding(kId, RuleStatus::kSkip,
                       "depends on " + kind.id("well-formed") + ": no document");
    // xs:anyURI collapses whitespace: " http://..." names the same location as "http://...".
    const std::string_view loc = trim_xml_space(*location);
    if (loc.empty()) return finding(kId, RuleStatus::kWarn, "no xsi:noNamespaceSchemaLocation");
    const std::string stem = "openlcb.org/schema/" + std::string(kind.prefix) + "/";
    const bool sane = (loc.starts_with("http://" + stem) || loc.starts_with("https://" + stem)) &&
                      loc.ends_with(".xsd");
    std::string upper(kind.prefix);
    for (char& c : upper) c = static_cast<char>(c - 'a' + 'A');
    if (sane)
        return finding(kId, RuleStatus::kPass,
                       "schema location names an openlcb.org " + upper + " schema");
    // The standard shows the URL but sets no rule for other spellings: a note, not a failure.
    return finding(kId, RuleStatus::kWarn,
                   "schema location " + clip(loc) + " does not name http(s)://" + stem + ".../" +
                       std::string(kind.prefix) + ".xsd");
}

// A CDI may describe spaces 252/251 as segments too (§5.1.2 "may"); one whose variables there
// contradict the ACDI layout (some real devices put configuration in 252) is worth a WARN.
RuleFinding acdi_spaces(const ValidatedCdi& cdi) {
    static constexpr std::string_view kId = "cdi.acdi-spaces";
    if (!cdi.document)
        return finding(kId, RuleStatus::kSkip, "depends on cdi.well-formed: no document");
    if (!cdi.document->acdi) return finding(kId, RuleStatus::kSkip, "the CDI has no <acdi/>");
    const std::string conflict = cdi.layout ? acdi_block_conflict(*cdi.layout) : std::string();
    if (conflict.empty())
        return finding(kId, RuleStatus::kPass,
                       "CDI variables in spaces 252/251 (if any) agree with the ACDI layout");
    return finding(kId, RuleStatus::kWarn,
                   "CDI variables contradict the ACDI layout of spaces 252/251: " + conflict);
}

// The text rules both standards share (§5): BOM, UTF-8, the first line, well-formedness and
// validity, the schema location; `location` as schema_location() takes it.
std::vector<RuleFinding> text_rules(std::string_view text, bool xml, const Diagnostics& found,
                                    const std::string* location, const TextKind& kind) {
    while (text.ends_with('\0')) text.remove_suffix(1);
    std::vector<RuleFinding> out;
    out.reserve(kRuleCheckIds.size());
    out.push_back(no_bom(text, kind));
    out.push_back(utf8(text, kind));
    const bool utf8_failed = out.back().status == RuleStatus::kFail;
    const std::uint32_t utf8_line = out.back().line;
    out.push_back(xml_declaration(text, kind));
    RuleFinding parsed = well_formed(xml, found, kind);
    if (utf8_failed && parsed.status == RuleStatus::kFail && parsed.line >= utf8_line) {
        // libxml2 stops where the text leaves its declared encoding: the cause is cdi.utf8's
        // (a parse error before that line is a cause of its own and stays a FAIL).
        parsed.status = RuleStatus::kSkip;
        parsed.message =
            "depends on " + kind.id("utf8") + ": libxml2 refused the text (" + parsed.seen + ")";
        parsed.expected.clear();
        parsed.seen.clear();
    }
    out.push_back(std::move(parsed));
    out.push_back(valid(xml, found, kind));
    out.push_back(schema_location(location, kind));
    if (!kind.clause.empty()) {
        for (RuleFinding& f : out) f.clause = std::string(kind.clause);
    }
    return out;
}

}  // namespace

std::string_view rule_status_name(RuleStatus status) {
    switch (status) {
        case RuleStatus::kPass:
            return "PASS";
        case RuleStatus::kFail:
            return "FAIL";
        case RuleStatus::kWarn:
            return "WARN";
        case RuleStatus::kSkip:
            return "SKIP";
    }
    return "?";
}

std::vector<RuleFinding> check_rules(std::string_view text) {
    return check_rules(text, validate_model(text));
}

std::vector<RuleFinding> check_rules(std::string_view text, const ValidatedCdi& cdi) {
    std::vector<RuleFinding> out =
        text_rules(text, cdi.report.schema.well_formed, cdi.report.diagnostics,
                   cdi.document ? &cdi.document->schema_location : nullptr, kCdi);
    out.push_back(acdi_spaces(cdi));
    return out;
}

std::vector<RuleFinding> check_fdi_rules(std::string_view text) {
    return check_fdi_rules(text, validate_fdi(text));
}

std::vector<RuleFinding> check_fdi_rules(std::string_view text, const ValidatedFdi& fdi) {
    return text_rules(text, fdi.schema.well_formed, fdi.diagnostics,
                      fdi.document ? &fdi.document->schema_location : nullptr, kFdi);
}

namespace {

// One field of an ACDI block (ConfigurationDescriptionInformationS §5.1.2).
struct AcdiField {
    std::uint32_t space;
    std::uint64_t offset, size;
    bool version;  // the 1-byte version int; the others are strings
};

constexpr AcdiField kAcdiFields[] = {
    {0xFC, 0, 1, true},     {0xFC, 1, 41, false}, {0xFC, 42, 41, false}, {0xFC, 83, 21, false},
    {0xFC, 104, 21, false}, {0xFB, 0, 1, true},   {0xFB, 1, 63, false},  {0xFB, 64, 64, false},
};

// True when the variable lies inside one ACDI field and has its type.
bool fits_acdi_field(const Cursor& c) {
    for (const AcdiField& f : kAcdiFields) {
        if (f.space != c.space() || c.address() < f.offset ||
            c.address() + c.size() > f.offset + f.size)
            continue;
        const ElementKind k = c.element().kind;
        return f.version ? k == ElementKind::kInt : k == ElementKind::kString;
    }
    return false;
}

}  // namespace

std::string acdi_block_conflict(const Layout& layout) {
    // Segments may describe the ACDI blocks too (§5.1.2; CDI-TN §2.5.1.2): only variables that
    // cross a field, lie past a block or have another type contradict it.
    std::string conflict;
    std::size_t listed = 0;
    layout.visit([&](const Cursor& c) {
        if ((c.space() != 0xFC && c.space() != 0xFB) || c.size() == 0 || fits_acdi_field(c))
            return true;
        conflict += (conflict.empty() ? "" : ", ") + variable_name(layout, c) + " (space " +
                    std::to_string(c.space()) + " bytes " + std::to_string(c.address()) + ".." +
                    std::to_string(c.address() + c.size() - 1) + ")";
        return ++listed < 8;
    });
    return conflict;
}

}  // namespace olcb::cdi
