// Named, composable misbehaviours of a simulated node (docs/faults.md): each breaks one rule of
// a standard on purpose so a client's handling of it can be tested. Each fault is declared once,
// in its family's file under simnode/faults/ (fault_catalog.hpp); this header is what the hooks
// and callers need.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::simnode {

/// A fault's parameter as parse_faults() reads it; {0, 0} means the fault is off.
struct FaultValue {
    std::uint32_t value = 0;   ///< flag: 1; number: the number; choice: index + 1; latency: MS
    std::uint32_t jitter = 0;  ///< a second number: latency's JITTER, reply-pending's MS; else 0
    friend bool operator==(const FaultValue&, const FaultValue&) = default;
};

/// The faults of one node, by name with their values; none by default (a well-behaved node).
/// What each does is declared once, with its hooks, in its family's file (fault_catalog.hpp).
struct FaultSet {
    std::map<std::string, FaultValue, std::less<>> by_name;

    /// True when no fault is set.
    bool none() const { return by_name.empty(); }
    /// The value of the fault called name ({0, 0}: off or unknown).
    FaultValue value(std::string_view name) const;
    /// Same faults and parameters.
    friend bool operator==(const FaultSet&, const FaultSet&) = default;
};

/// One entry of the fault catalogue.
struct FaultInfo {
    std::string_view name;       ///< e.g. "reject-temporary"
    std::string_view parameter;  ///< "" when it takes none, else e.g. "N (default 3)"
    std::string_view summary;    ///< one line for --help
};

/// Every fault, in docs/faults.md order.
const std::vector<FaultInfo>& fault_catalog();

/// Every known fault name, for --help and docs.
std::vector<std::string> fault_names();

/// Parses fault names, each entry possibly a comma-separated list ("int-byte-order,
/// reject-temporary=3"); blanks are ignored. nullopt with `error` set on an unknown name or a bad
/// parameter.
std::optional<FaultSet> parse_faults(const std::vector<std::string>& names, std::string& error);

/// The names (with parameters) that parse_faults() reads back to `faults`.
std::vector<std::string> to_names(const FaultSet& faults);

}  // namespace olcb::simnode
