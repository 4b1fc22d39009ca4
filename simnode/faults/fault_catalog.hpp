// The declarations every fault is made of (issue 29): one entry per fault, kept in its family's
// file (simnode/faults/*_faults.cpp). Parsing, --list-faults, docs/faults.md's table and the
// end-to-end matrix's oracle are all generated from these, so a fault is described once.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "simnode/faults.hpp"
#include "simnode/faults/fault_hooks.hpp"

namespace olcb::simnode {

/// The syntax of a fault's parameter.
enum class ParamKind : std::uint8_t {
    kNone,      ///< "name" only
    kNumber,    ///< "name[=N]", a whole number in min..max
    kChoice,    ///< "name[=WORD]", one of choices
    kMsJitter,  ///< "name[=MS[:JITTER]]", both 0..max, not both 0
    /// "name[=N[:MS]]": a timeout exponent N in min..max (the time promised, 2^N s) and a delay MS
    /// within it (0..2^N s - 1 ms, at most kMaxDelayMs; default half of 2^N s, at most
    /// kMaxDelayMs), kept as FaultValue{N, MS}
    kExponentMs,
};

struct FaultParam {
    ParamKind kind = ParamKind::kNone;
    std::string_view value_name;  ///< "MS", "N", "MS[:JITTER]", "N[:MS]" (kChoice: unused)
    std::uint32_t fallback = 0;   ///< when no "=": the number, or the choice's index + 1
    std::uint32_t min = 0;
    std::uint32_t max = 0;
    std::vector<std::string_view> choices;  ///< kChoice: the words, in parse order
};

/// What a careful checker (lcc-conform) must conclude about a node with only this fault.
enum class Verdict : std::uint8_t {
    kFail,        ///< a FAIL in the category; exit 1
    kWarn,        ///< a WARN in the category, no FAIL anywhere; exit 0
    kIncomplete,  ///< the node restarts or stops mid-run: flagged in the category, exit 2
    kNone,        ///< nothing wrong: every check passes, exit 0
};

/// One fault, declared once.
struct FaultDecl {
    std::string_view name;  ///< e.g. "reject-temporary"
    /// Where it stands among all faults (--list-faults, docs/faults.md's rows, to_names() and the
    /// order hooks run in); gaps of 10 leave room, as CheckSpec::order does for checks.
    int order = 0;
    FaultParam param;          ///< its "=..." syntax, default and bounds
    std::string_view summary;  ///< one line for --help / --list-faults
    // docs/faults.md's columns, as written there (markdown).
    std::string_view doc_parameter;  ///< "Parameter" ("" prints as "–")
    std::string_view rule_broken;    ///< "Rule broken"
    std::string_view client_sees;    ///< "What a client sees"
    Verdict verdict = Verdict::kFail;
    /// The lcc-conform category that flags it; for kNone "" or the category whose checks a
    /// careless client would trip on.
    std::string_view category;
    std::string_view category_note;  ///< appended in parentheses, e.g. "above 750 ms: message"
    /// Check IDs (as reports name them) seen to flag it with the verdict's status.
    std::vector<std::string_view> checks;
    FaultHooks hooks;  ///< what it changes in the node, at which points
    /// It reads the watched variable (NodeConfig::watch_variable), which the node then finds.
    bool watches = false;
};

/// The value of fault d in faults ({0, 0}: off).
FaultValue fault_value(const FaultSet& faults, const FaultDecl& d);

/// Sets fault d of faults to v.
void set_fault(FaultSet& faults, const FaultDecl& d, FaultValue v);

/// Every fault with its whole declaration, in catalogue order (docs/faults.md's rows).
const std::vector<FaultDecl>& fault_decls();

/// The declaration of `name`; nullptr when there is none.
const FaultDecl* find_fault(std::string_view name);

/// "cdi", "memory (warn)", "none": docs/faults.md's Category column of d.
std::string category_column(const FaultDecl& d);

/// The parameter as --help shows it: "" or e.g. "N (default 3)".
std::string help_parameter(const FaultDecl& d);

/// docs/faults.md's table (header, separator, one row per fault), each line ending in '\n'.
std::string format_fault_markdown();

/// Every declaration as a JSON array (name, parameter, summary, verdict, category, checks).
std::string format_fault_json();

}  // namespace olcb::simnode
