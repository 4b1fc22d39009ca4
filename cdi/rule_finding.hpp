// The rules a CDI's text alone decides (byte-order mark, UTF-8, the XML declaration, schema
// validity and the semantic rules, the schema location, the ACDI blocks), each under the ID of the
// lcc-conform check that reports it: `lcc-cdi validate` and lcc-conform's cdi.* checks both call
// check_rules(), so a file and the same text served by a node get the same verdicts. The same
// rules of an FDI text (FunctionDescriptionInformationS §5) are check_fdi_rules()'s, under fdi.*
// IDs.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/diagnostic.hpp"
#include "cdi/layout.hpp"

namespace olcb::cdi {

struct ValidatedCdi;  // cdi/validator.hpp

/// A rule's verdict, as lcc-conform reports the check (FAIL and WARN are findings).
enum class RuleStatus : std::uint8_t { kPass, kFail, kWarn, kSkip };

/// One rule's verdict on a CDI text.
struct RuleFinding {
    std::string check_id;  ///< the lcc-conform check, e.g. "cdi.xml-declaration"
    RuleStatus status = RuleStatus::kPass;
    std::string message;      ///< one line: what was judged and, for a finding, what is wrong
    std::string expected;     ///< FAIL/WARN: what the standard wants (may be empty)
    std::string seen;         ///< FAIL/WARN: what the text holds (may be empty)
    std::uint32_t line = 0;   ///< 1-based line the finding is about (0: the whole text)
    Diagnostics diagnostics;  ///< cdi.valid: every error, then every warning
    /// fdi.* only: the clause judged, e.g. "FunctionDescriptionInformationS §5" (a cdi.* rule's
    /// clause is its lcc-conform registry entry's).
    std::string clause;
};

/// The checks check_rules() judges, in the order it returns them (lcc-conform's registry order).
inline constexpr std::array<std::string_view, 7> kRuleCheckIds = {
    "cdi.no-bom",          "cdi.utf8",       "cdi.xml-declaration", "cdi.well-formed", "cdi.valid",
    "cdi.schema-location", "cdi.acdi-spaces"};

/// "PASS", "FAIL", "WARN" or "SKIP".
std::string_view rule_status_name(RuleStatus status);

/// Judges a CDI text (the bytes before its terminating NUL; trailing NULs are ignored): one
/// finding per entry of kRuleCheckIds, in that order, PASS and SKIP included.
std::vector<RuleFinding> check_rules(std::string_view text);

/// check_rules() of a text whose validate_model() the caller already has (and keeps, for the
/// model): the text is parsed once, not twice.
std::vector<RuleFinding> check_rules(std::string_view text, const ValidatedCdi& cdi);

struct ValidatedFdi;  // cdi/fdi_validator.hpp

/// The checks check_fdi_rules() judges, in the order it returns them.
inline constexpr std::array<std::string_view, 6> kFdiRuleCheckIds = {
    "fdi.no-bom",      "fdi.utf8",  "fdi.xml-declaration",
    "fdi.well-formed", "fdi.valid", "fdi.schema-location"};

/// check_rules() of an FDI text (trailing NULs ignored): one finding per entry of
/// kFdiRuleCheckIds, in that order, PASS and SKIP included, each with its clause.
std::vector<RuleFinding> check_fdi_rules(std::string_view text);

/// check_fdi_rules() of a text whose validate_fdi() the caller already has.
std::vector<RuleFinding> check_fdi_rules(std::string_view text, const ValidatedFdi& fdi);

/// The CDI variables in spaces 252/251 that contradict the ACDI layout (crossing one of its
/// fields, past its block, or of another type than the field), as "Path (space 252 bytes 0..7),
/// ..." (at most 8); "" when none.
std::string acdi_block_conflict(const Layout& layout);

}  // namespace olcb::cdi
