// Which variables lcc-conform never writes by default: settings a node's CDI marks as not to be
// changed (OpenMRN's "Internal data" group, CDI 1.4 <hints><readOnly/>), <action> elements, and
// what the user excludes with --exclude / --only. See docs/checks.md "Safety".
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "cdi/layout.hpp"

namespace olcb::conform {

/// What the user asked about protected and selected variables.
struct ProtectionRules {
    std::vector<std::string> exclude;  ///< --exclude GLOB: never write matching keys
    std::vector<std::string> only;     ///< --only GLOB: write only matching keys (empty: all)
    bool write_protected = false;      ///< --write-protected: probe protected settings too
};

/// Why the variable at the cursor must not be written by default, or "" when it may be:
/// "<action> triggers a command", "read-only hint of group X", "'do not change' in Y".
std::string protection_reason(const cdi::Layout& layout, const cdi::Cursor& cursor);

/// True when `text` (e.g. "do not change these settings") asks a tool to leave a value alone.
bool says_do_not_change(std::string_view text);

/// Shell-style match of a backup key: `*` any run (dots included), `?` one character,
/// `[...]` a set; e.g. `Internal data.*`.
bool key_matches(std::string_view pattern, std::string_view key);

/// "" when rules let a key be written, else why not ("--exclude 'X'", "not matched by --only").
std::string selection_reason(const ProtectionRules& rules, std::string_view key);

}  // namespace olcb::conform
