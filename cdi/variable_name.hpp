// The one name of a CDI variable wherever a user sees it (lcc-cdi layout, memory maps, check
// messages, backups): the key OpenLCB_Java (JMRI) gives it in a configuration backup. Users
// already know it from JMRI backups, and it must stay byte-identical to JMRI's so backup files
// pass between the tools (docs/backup.md); conformance/backup builds its keys from it.
#pragma once

#include <string>
#include <string_view>

#include "cdi/layout.hpp"

namespace olcb::cdi {

/// Text escaped as in a backup line: `=`, `\` and control characters as \x + 4 lower-case hex.
std::string escape_backup_text(std::string_view text);

/// The part of a name an element contributes: its escaped name, or "child<N>" when unnamed, N
/// its index among all XML content nodes of its parent (Element::content_index).
std::string variable_name_part(const Element& element);

/// The variable's name, as OpenLCB_Java's backup key: names joined by '.', an unnamed segment
/// "seg<N>" and an unnamed group or variable "child<N>"; replicas of a group "(i)", 0-based.
std::string variable_name(const Layout& layout, const Cursor& cursor);

/// The CDI's display names of the replicas enclosing the variable (repname, e.g. "Port 1"),
/// outermost first, joined by " / "; "" when none has one. Not part of the name: shown beside
/// it, since it is what a configuration tool labels the replica with.
std::string replica_names(const Cursor& cursor);

/// True when text names the variable: its name, or the slash path of Cursor::path() that
/// scenario files written before the names were one (watch-variable) still use.
bool names_variable(const Layout& layout, const Cursor& cursor, std::string_view text);

}  // namespace olcb::cdi
