// A node's memory map as lcc-conform found it: the CDI layout's map (cdi/memory_map.hpp) with a
// verdict on every listed variable (report/map_verdict.hpp) from what the run's phases learned.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/layout.hpp"
#include "cdi/memory_map.hpp"
#include "conformance/checks/protection.hpp"
#include "conformance/report/map_verdict.hpp"

namespace olcb::conform {

/// What a node's run knows about its variables, for node_memory_map().
struct MapEvidence {
    std::vector<TestedVariable> tested;  ///< the encoding checks' outcomes (and unsaved originals)
    std::vector<std::uint64_t> planned;  ///< ordinals of every probe planned, tested or not
    std::string not_written;  ///< why nothing was written at all ("" when the checks ran)
    std::string not_judged;   ///< why the outcomes do not count (the link went down), or ""
    std::size_t sample = 3;   ///< EncodingOptions::sample
    bool blob = false;        ///< EncodingOptions::blob
    std::size_t max_variables = 4096;  ///< EncodingOptions::max_variables
    ProtectionRules protection;        ///< EncodingOptions::protection
};

/// The map of every space of the layout with the verdicts the evidence supports; the replicas
/// the encoding checks sample are listed besides the first ones.
std::vector<MemoryMapSpace> node_memory_map(const cdi::Layout& layout, const MapEvidence& evidence);

}  // namespace olcb::conform
