// What a run concluded about each variable of a node's memory map (verified, failed, skipped,
// protected) with the values written and read back: the vocabulary the reports and the HTML page
// show (run/memory_map.hpp builds it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "cdi/memory_map.hpp"

namespace olcb::conform {

/// What the run concluded about one variable.
enum class MapVerdict : std::uint8_t {
    kVerified,   ///< every test value read back exactly as written, and the original went back
    kFailed,     ///< a test value was refused or read back differently, or the original did not
    kSkipped,    ///< not tested (not sampled, deselected, --read-only, the run stopped, ...)
    kProtected,  ///< left alone as a protected setting (docs/checks.md "Safety")
};

/// "verified", "failed", "skipped" or "protected".
std::string_view map_verdict_name(MapVerdict verdict);

/// One test value written to a variable and what came back.
struct TestedValue {
    std::string value;       ///< the value as text ("-1000", "\"AB...\"", "pattern")
    std::string written;     ///< its bytes in hex
    std::string read;        ///< the bytes read back in hex ("" when the read failed)
    std::string read_value;  ///< what they decode to ("" when they do not decode)
    std::string error;       ///< why the write or the read-back failed ("" when both worked)
    bool ok = false;         ///< read back exactly as written
};

/// The verdict on one variable with its evidence.
struct VariableVerdict {
    MapVerdict verdict = MapVerdict::kSkipped;
    std::string reason;               ///< why it was skipped or protected, or what failed first
    std::string original_value;       ///< what the node held before the test ("" when not read)
    std::string original_bytes;       ///< the same in hex
    std::vector<TestedValue> values;  ///< the values written, in order (the first 32)
};

/// A variable the encoding checks reached, by its position in the layout (Cursor::ordinal()).
struct TestedVariable {
    std::uint64_t ordinal = 0;
    VariableVerdict verdict;
};

/// The map of one space of a node.
struct MemoryMapSpace {
    cdi::SpaceMap map;                      ///< the layout's variables, gaps and overlaps
    std::vector<VariableVerdict> verdicts;  ///< one per map.variables, in the same order
};

/// The spaces as JSON: cdi::memory_map_json() of each, every variable with "verdict" and, when
/// known, "reason", "original": {"value", "bytes"} and "values": [{"value", "written", "read",
/// "read_value", "error", "ok"}]; each space with "verdicts": {"verified", "failed", "skipped",
/// "protected"} counts of its listed variables.
nlohmann::json memory_map_json(const std::vector<MemoryMapSpace>& spaces);

}  // namespace olcb::conform
