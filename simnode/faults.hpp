// Named, composable misbehaviours of a simulated node (docs/faults.md): each breaks one rule of
// a standard on purpose so a client's handling of it can be tested. Each fault is declared once,
// in its family's file under simnode/faults/ (fault_catalog.hpp); this header is what the hooks
// and callers need.
#pragma once

#include <chrono>
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
    std::uint32_t jitter = 0;  ///< latency's JITTER, else 0
    friend bool operator==(const FaultValue&, const FaultValue&) = default;
};

/// The faults of one node; all off by default (a well-behaved node). A fault that reaches into
/// the node's life (restarts, storage, the CDI it loads) keeps a field here, read by SimNode and
/// NodeMemory; a fault whose hooks (fault_hooks.hpp) do all it does is kept in by_name.
struct FaultSet {
    bool acdi_version = false;         ///< 252/251 version bytes are fixed+1 / var+1
    bool cdi_unterminated = false;     ///< space 0xFF without the terminating NUL
    bool cdi_padding = false;          ///< NULs and garbage after the terminating NUL
    bool cdi_invalid = false;          ///< served CDI violates the schema (loads invalid CDIs)
    bool int_byte_order = false;       ///< ints stored little-endian
    bool string_unterminated = false;  ///< strings fill their field without a NUL
    bool eventid_byte_order = false;   ///< event IDs stored little-endian
    bool float_width = false;          ///< floats stored with the next smaller precision
    bool write_dropped = false;        ///< writes acknowledged but not stored
    bool write_not_persisted = false;  ///< writes kept in RAM only: lost on reboot
    bool readonly_writable = false;    ///< writes to 0xFF and 252 accepted
    /// The first N datagrams are rejected with 0x2020 (reject-temporary=N; 0 = off).
    std::uint32_t reject_temporary = 0;
    /// Period of unsolicited Verify Node ID Global messages (unsolicited-traffic=MS; 0 = off).
    std::chrono::milliseconds unsolicited_period{0};
    /// Silence after a SNIP request while the watched int differs from its value at creation,
    /// then a restart (abort-on-value=MS; 0 = off).
    std::chrono::milliseconds abort_on_value{0};
    /// Write Under Mask stores its data bytes whole, ignoring the masks, then the node is silent
    /// this long and restarts (mask-ignored=MS; 0 = off).
    std::chrono::milliseconds mask_ignored{0};
    /// The Nth stored write restarts the node without its Write Reply (reboot-on-write=N; 0 =
    /// off); once per process.
    std::uint32_t reboot_on_write = 0;
    /// Every restart factory-resets the writable spaces while the watched int differs from its
    /// value at creation.
    bool factory_reset_on_version_change = false;
    bool write_past_end_spills = false;  ///< crossing writes accepted; 251's tail lands in 253
    /// Crossing writes accepted; the bytes past the end are kept (on disk) where no read reaches.
    bool write_past_end_grows = false;
    bool events_stale_after_write = false;  ///< identifies the start-up event IDs until restart
    bool events_missing = false;            ///< eventid slots 1, 3, 5... never identified
    /// Every answer is sent this long after its request arrived (latency=MS[:JITTER]; 0 = off).
    std::chrono::milliseconds latency{0};
    /// Up to this much more, uniformly random per answer, seeded by the node ID.
    std::chrono::milliseconds latency_jitter{0};

    /// The values of the faults that keep no field, by name (set_fault(), fault_value()).
    std::map<std::string, FaultValue, std::less<>> by_name;

    /// True when no fault is set.
    bool none() const;
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
