// The memory map of a laid-out CDI for display: per memory space, the variables with their
// names, types, addresses and sizes, the bytes no variable uses (gaps) and the bytes several
// variables share (overlaps). Replication stays bounded: the first replicas of a group (and its
// last) are listed, the others summarized as one run, so replication="1000000" costs one entry.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "cdi/layout.hpp"

namespace olcb::cdi {

/// One listed variable of a memory map.
struct MapVariable {
    std::string name;     ///< variable_name(), e.g. "Settings.Port(1).On event"
    std::string replica;  ///< replica_names(), e.g. "Port 2" ("" when the CDI names none)
    std::string label;    ///< short bar label: its own name, else its replica's, else its part
    std::string type;     ///< "int", "string", ... (the element name for unknown elements)
    std::uint32_t segment = 0;  ///< index in Document::segments
    std::uint64_t address = 0;  ///< absolute address of the first byte
    std::uint64_t size = 0;     ///< bytes
    std::uint64_t ordinal = 0;  ///< Cursor::ordinal(): Layout::at() finds the variable again
};

/// The bytes [address, address + size).
struct MapRange {
    std::uint64_t address = 0;
    std::uint64_t size = 0;
    bool operator==(const MapRange&) const = default;
};

/// Consecutive replicas of a group that are not listed, or (group "") the variables beyond
/// MemoryMapOptions::max_variables.
struct MapSummary {
    std::string group;                ///< the group's name ("(group)" when unnamed)
    std::string first_name;           ///< variable_name() of the first variable not listed
    std::uint64_t first_replica = 0;  ///< 0-based index of the first replica not listed
    std::uint64_t replicas = 0;       ///< replicas not listed (0 for the max_variables cut)
    std::uint64_t variables = 0;      ///< variables not listed
    MapRange range;                   ///< the bytes they span (their replicas' strides)
};

/// The map of one memory space.
struct SpaceMap {
    std::uint32_t space = 0;
    std::vector<std::uint32_t> segments;  ///< indices of the segments with variables here
    std::string name;                     ///< their names joined with " / " ("" when unnamed)
    std::uint64_t begin = 0;              ///< first byte used by a variable
    std::uint64_t end = 0;                ///< one past the last byte used by a variable
    std::uint64_t variable_count = 0;     ///< every variable after replication
    std::vector<MapVariable> variables;   ///< the listed ones, in document order
    std::vector<MapSummary> summaries;    ///< what is not listed, in document order
    std::vector<MapRange> gaps;           ///< bytes in [begin, end) no variable or summary covers
    std::vector<MapRange> overlaps;       ///< bytes two or more listed variables share, ascending
};

/// Bounds of build_memory_map().
struct MemoryMapOptions {
    std::uint64_t replicas = 16;       ///< replicas listed from the start of each group
    std::size_t max_variables = 4096;  ///< variables listed per space
    /// Further replicas to list: the smallest index >= from of a group of count replicas that
    /// must be listed, or count when none (lcc-conform lists the replicas it tested). May be
    /// empty.
    std::function<std::uint64_t(std::uint64_t from, std::uint64_t count)> also_list;
};

/// The map of every space that holds variables, ascending by space.
std::vector<SpaceMap> build_memory_map(const Layout& layout, const MemoryMapOptions& options = {});

/// The map of one space as JSON: {"space", "segments", "name", "begin", "end", "variable_count",
/// "variables": [{"name", "replica", "label", "type", "segment", "address", "size", "ordinal"}],
/// "summaries":
/// [{"group", "first_name", "first_replica", "replicas", "variables", "address", "size"}],
/// "gaps": [{"address", "size"}], "overlaps": [{"address", "size"}]}.
nlohmann::json memory_map_json(const SpaceMap& map);

/// Every space's map as a JSON array of memory_map_json() objects.
nlohmann::json memory_map_json(const std::vector<SpaceMap>& maps);

}  // namespace olcb::cdi
