// Encoding checks (write and read back): boundary values written to every sampled variable of the
// CDI layout, one variable at a time, the raw bytes read back and compared with the standard's
// encoding (cdi::encode), and the original put back and read again before the next variable.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "cdi/layout.hpp"
#include "cdi/value.hpp"
#include "conformance/checks/protection.hpp"
#include "conformance/report/check_result.hpp"
#include "conformance/run/memory_map.hpp"
#include "conformance/run/safety_backup.hpp"

namespace olcb::conform {

/// What the encoding checks may do.
struct EncodingOptions {
    std::size_t sample =
        3;                ///< replicas tested per replicated group (first, last, spread); 0 = all
    bool blob = false;    ///< also write <blob> variables
    bool reboot = false;  ///< reset the node and check the written values persisted
    bool acdi_user = false;  ///< the node has space 251: write the user name, check SNIP follows
    /// Why the user name is not written although the node has 251 ("" when it is, or has none).
    std::string acdi_user_skipped;
    std::size_t max_variables = 4096;  ///< bound on the variables tested (after sampling)
    ProtectionRules protection;        ///< protected settings, --exclude / --only
};

/// One variable to test and the values to write to it, in order.
struct Probe {
    const cdi::Element* element = nullptr;
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::uint32_t size = 0;
    std::string key;  ///< the variable's name, its backup key (what --exclude / --only match)
    std::vector<cdi::Value> values;
    /// Why the variable is protected ("" when it is not); probed only with --write-protected
    /// and never given a test value across a Reset/Reboot.
    std::string protection;
    std::uint64_t ordinal = 0;  ///< Cursor::ordinal(): the variable in the layout's memory map
};

/// A sampled variable the run does not write, and why.
struct Unwritten {
    std::string key;
    std::string reason;
    bool is_protected = false;  ///< protected setting (encoding.protected), else deselected
};

/// The variables of a run: what is probed, and what is left alone.
struct EncodingPlan {
    std::vector<Probe> probes;
    std::vector<Unwritten> unwritten;
};

/// One access the encoding checks made, as given to EncodingHooks::after_access.
struct AccessStep {
    std::string what;                      ///< "writing", "reading back", "restoring", ...
    std::string key;                       ///< the variable's backup key
    std::string value;                     ///< the value written last ("" before any)
    std::span<const std::uint8_t> bytes;   ///< the bytes written last
    const AccessResult* result = nullptr;  ///< what the access returned
};

/// Outcome of EncodingHooks::reboot.
struct RebootOutcome {
    bool back = false;           ///< Initialization Complete seen after the Reset/Reboot
    std::uint16_t rejected = 0;  ///< the reject code when the node refused the command
    bool stopped = false;        ///< the node died meanwhile (after_access said so)
};

/// What the checks need from the runner beyond byte access.
struct EncodingHooks {
    /// True when the run must stop (SIGINT/SIGTERM, link lost); checked before every write.
    std::function<bool()> stop;
    /// Called after every access; false when the node stopped answering or restarted: the
    /// checks stop at once and leave the variable in flight to the runner.
    std::function<bool(const AccessStep&)> after_access;
    /// Resets the node (0x20 0xA9) and waits for its Initialization Complete.
    std::function<RebootOutcome()> reboot;
    /// The user name the node's SNIP reply carries now; nullopt when no reply came.
    std::function<std::optional<std::string>()> snip_user_name;
    /// Called with (values done, values planned) after each value.
    std::function<void(std::size_t, std::size_t)> progress;
};

/// A variable that may hold a test value when the checks stopped, and its original bytes.
struct InFlight {
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::vector<std::uint8_t> original;
    std::string key;
};

/// Everything run_encoding_checks() found.
struct EncodingOutcome {
    std::vector<CheckResult> results;
    std::vector<InFlight> in_flight;  ///< variables to put back first (node died mid-cycle)
    bool node_died = false;           ///< after_access reported the node gone or restarted
    bool restore_failed = false;      ///< an original did not read back: writing stopped
    /// Every probe the checks reached, with its verdict and values (the node's memory map).
    std::vector<TestedVariable> variables;
};

/// The boundary values the standard allows for a variable (check_value accepts each); empty for
/// elements never written (<action>, unknown elements, <blob> without `blob`).
std::vector<cdi::Value> boundary_values(const cdi::Element& element, bool blob);

/// True when replica `index` of `count` is tested with `sample` replicas per group.
bool replica_sampled(std::uint64_t index, std::uint64_t count, std::size_t sample);

/// Every variable to test with its values, in document order, and what is left alone.
EncodingPlan plan_encoding(const cdi::Layout& layout, const EncodingOptions& options);

/// The byte ranges the planned run will write (for the safety backup), ACDI user name included.
std::vector<RangeRequest> ranges_to_backup(const std::vector<Probe>& probes,
                                           const EncodingOptions& options);

/// Runs the checks, one variable at a time; the caller has captured ranges_to_backup() first
/// and verifies the backup afterwards.
EncodingOutcome run_encoding_checks(const std::vector<Probe>& probes, MemoryAccess& memory,
                                    const EncodingOptions& options, const EncodingHooks& hooks);

/// encoding.stored-strings by reads alone (--read-only): the original of every <string> probe
/// read and judged (a NUL within its size, valid UTF-8); nothing is written.
CheckResult check_stored_strings(const std::vector<Probe>& probes, MemoryAccess& memory,
                                 const EncodingHooks& hooks);

/// The SKIP results of a plan's unwritten variables (encoding.protected, encoding.excluded).
std::vector<CheckResult> unwritten_checks(const std::vector<Unwritten>& unwritten,
                                          bool write_protected);

/// The encoding check results when writes are not allowed (--read-only): every one SKIP.
std::vector<CheckResult> skipped_encoding_checks(const std::string& reason);

}  // namespace olcb::conform
