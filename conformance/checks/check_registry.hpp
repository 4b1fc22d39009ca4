// The check registry: every check lcc-conform runs is one entry (stable ID, category, standard
// and section, the OlcbChecker checks it covers, summary, and the function that runs it), in
// the order they run. docs/checks.md is tested against it; --list-checks prints it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "conformance/report/check_result.hpp"
#include "openlcb/pip.hpp"

namespace olcb::conform {

class CheckRun;
struct CheckSpec;

/// Runs one protocol check, given its own entry: its results go into the run under the entry's
/// ID (CheckRun::out(spec)).
using CheckFn = void (*)(CheckRun&, const CheckSpec&);

/// Suffix of a per-space check's ID: each result carries the space in two lower-case hex digits
/// in its place ("memory.read-past-end.<sp>" gives "memory.read-past-end.fd").
inline constexpr std::string_view kPerSpace = ".<sp>";

/// How strongly the standard asks for what a check judges: the strongest verdict it may give.
enum class Strength : std::uint8_t {
    kShall,   ///< "shall", "must", "required": a violation FAILs
    kShould,  ///< "should", "recommended": WARN at most
    kMay,     ///< optional behaviour: WARN at most (an optional command rejected 0x1041 SKIPs)
    kNone,    ///< no clause (informative text, a technical note, consistency only): WARN at most
    kRun,     ///< not a verdict on the node: the run itself (the link); makes the run incomplete
};

/// "shall", "should", "may", "none" or "run".
std::string_view strength_name(Strength strength);

/// One check of docs/checks.md.
struct CheckSpec {
    std::string_view id;  ///< stable ID, e.g. "cdi.nul-terminated"; may end in kPerSpace
    /// Where it runs among all checks (the registry is sorted by it): a family file places its
    /// entries between others' without knowing them; gaps of 10 leave room for new ones.
    int order;
    Category category;             ///< its category (the first field of the ID)
    std::string_view section;      ///< standard and section, e.g. "MemoryConfigurationS §4.4"
    Strength strength;             ///< the normative word of the clause it judges
    std::string_view clause;       ///< what the clause asks, in our words (never quoted)
    std::string_view olcbchecker;  ///< OlcbChecker checks it covers, e.g. "mc60"; "" for none
    std::string_view summary;      ///< what is sent and what passes, one line
    /// The check; nullptr when a phase of the node's run produces it (encoding, node, link).
    CheckFn run = nullptr;
    bool thorough = false;  ///< runs only with --thorough (a long soak or a disruptive probe)
    /// Needs the bus to itself: it makes the node change its alias or floods the bus, which would
    /// disturb another lcc-conform run on the segment (and be disturbed by it); SKIP while one is
    /// seen.
    bool exclusive = false;
    /// Writes across the end of a space, which a node without a bounds check keeps for good
    /// where no tool can read or restore it: runs only with --write-past-end.
    bool past_end_writes = false;
    /// The protocol the node's Protocol Support Reply must claim for the check to mean anything
    /// (a train check on an I/O board): SKIPped, saying which, when the reply lacks it or none
    /// came. std::nullopt: every node.
    std::optional<Protocol> needs = std::nullopt;
};

/// Every check, in the order a node's run produces them.
const std::vector<CheckSpec>& check_registry();

/// The entry a result ID belongs to (a per-space result finds its ".<sp>" entry); nullptr when
/// none.
const CheckSpec* find_check(std::string_view result_id);

/// Gives a result its entry's category and section, and holds it to the entry's strength: a FAIL
/// of a check whose clause is no "shall" becomes a WARN saying so (the one place that rule lives).
void cite(CheckResult& result);

/// True when a pattern names checks, not variables: its first dot-separated field is a check
/// category ("memory.*", "frame.collision"). Others select variables by backup key (--only).
bool is_check_pattern(std::string_view pattern);

/// Which checks a run runs: --only PATTERN, --skip PATTERN (fnmatch-style `*`, `?`, `[...]`
/// against check IDs, per-space results by their full ID) and --thorough.
struct CheckSelection {
    std::vector<std::string> only;  ///< empty: every check
    std::vector<std::string> skip;
    bool thorough = false;
    bool write_past_end = false;  ///< --write-past-end: the crossing writes may run
    /// Only checks of these categories (empty: every category): a node that is not a
    /// configurable node gets the protocol checks alone.
    std::vector<Category> categories;

    /// True when some result of the entry can be selected (and, if thorough-only, --thorough).
    bool wants(const CheckSpec& spec) const;
    /// True when a result with this ID is reported.
    bool wants_id(std::string_view id) const;
    /// True when any selected check is produced by the encoding phase (writes are needed).
    bool wants_writes() const;
};

/// The registry as a text table (--list-checks): ID, category, section, strength, OlcbChecker,
/// summary.
std::string format_check_list();

/// One OlcbChecker node check and how lcc-conform covers it.
struct OlcbCheckerCheck {
    std::string_view id;       ///< e.g. "fr30"
    std::string_view title;    ///< what it checks, in a few words
    std::string_view not_why;  ///< "" when a registry entry covers it; else why not
};

/// OlcbChecker's frame, message, snip, events, datagram, memory and cdi checks (and the stream
/// and other sections as one line each), in its order.
const std::vector<OlcbCheckerCheck>& olcbchecker_checks();

/// The markdown docs/checks.md carries between its "registry" markers: every check (ID,
/// category, section, OlcbChecker, summary) and every OlcbChecker check with the lcc-conform
/// checks covering it (or why none does).
std::string format_check_markdown();

}  // namespace olcb::conform
