// The keys of a configuration backup: every CDI variable OpenLCB_Java (JMRI) backs up, named as
// it names them (docs/backup.md), so files pass between JMRI and lcc-conform both ways.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"

namespace olcb::conform {

/// One backed-up variable: its key and where its bytes lie.
struct ConfigEntry {
    std::string key;                        ///< dotted path, e.g. "Port I/O.Line(3).Event On"
    const cdi::Element* element = nullptr;  ///< the variable (int, string, eventid or float)
    std::uint32_t space = 0;
    std::uint64_t address = 0;
    std::uint64_t size = 0;  ///< bytes of the variable (8 for an eventid)
};

/// The key OpenLCB_Java gives the variable at the cursor (also what the checks report and
/// --exclude/--only match, so a key copied from a backup file selects that variable): names joined
/// by '.', an unnamed segment "seg<N>" and an unnamed group or variable "child<N>", N its index
/// among all XML content nodes of its parent (Element::content_index); replicas of a group "(i)",
/// 0-based.
std::string jmri_backup_key(const cdi::Layout& layout, const cdi::Cursor& cursor);

/// True for the variables a backup holds: int, string and eventid as OpenLCB_Java, and float
/// (which it leaves out); never action, blob, bit or unknown elements.
bool is_backed_up(const cdi::Element& element);

/// Every backed-up variable of the layout in document order, with its OpenLCB_Java key.
std::vector<ConfigEntry> config_entries(const cdi::Layout& layout);

}  // namespace olcb::conform
