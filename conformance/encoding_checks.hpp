// Encoding checks (write and read back): boundary values written to every sampled variable of the
// CDI layout, the raw bytes read back and compared with the standard's encoding (cdi::encode).
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "cdi/layout.hpp"
#include "cdi/value.hpp"
#include "conformance/backup.hpp"
#include "conformance/check_result.hpp"

namespace olcb::conform {

/// What the encoding checks may do.
struct EncodingOptions {
    std::size_t sample =
        3;                ///< replicas tested per replicated group (first, last, spread); 0 = all
    bool blob = false;    ///< also write <blob> variables
    bool reboot = false;  ///< reset the node and check the written values persisted
    bool acdi_user = false;  ///< the node has space 251: write the user name, check SNIP follows
    std::size_t max_variables = 4096;  ///< bound on the variables tested (after sampling)
};

/// What the checks need from the runner beyond byte access.
struct EncodingHooks {
    /// True when the run must stop (SIGINT/SIGTERM); checked before every write.
    std::function<bool()> stop;
    /// Resets the node (0x20 0xA9) and waits for its Initialization Complete; false on failure.
    std::function<bool()> reboot;
    /// The user name the node's SNIP reply carries now; nullopt when no reply came.
    std::function<std::optional<std::string>()> snip_user_name;
    /// Called with (values done, values planned) after each value.
    std::function<void(std::size_t, std::size_t)> progress;
};

/// One variable to test and the values to write to it, in order.
struct Probe {
    const cdi::Element* element = nullptr;
    std::uint8_t space = 0;
    std::uint32_t address = 0;
    std::uint32_t size = 0;
    std::string path;  ///< Cursor::path()
    std::vector<cdi::Value> values;
};

/// The boundary values the standard allows for a variable (check_value accepts each); empty for
/// elements never written (<action>, unknown elements, <blob> without `blob`).
std::vector<cdi::Value> boundary_values(const cdi::Element& element, bool blob);

/// True when replica `index` of `count` is tested with `sample` replicas per group.
bool replica_sampled(std::uint64_t index, std::uint64_t count, std::size_t sample);

/// Every variable to test with its values, in document order.
std::vector<Probe> plan_encoding(const cdi::Layout& layout, const EncodingOptions& options);

/// The byte ranges the planned run will write (for the safety backup), ACDI user name included.
std::vector<RangeRequest> ranges_to_backup(const std::vector<Probe>& probes,
                                           const EncodingOptions& options);

/// Runs the checks; the caller has captured ranges_to_backup() first and restores afterwards.
std::vector<CheckResult> run_encoding_checks(const std::vector<Probe>& probes, MemoryAccess& memory,
                                             const EncodingOptions& options,
                                             const EncodingHooks& hooks);

/// The encoding check results when writes are not allowed (--read-only): every one SKIP.
std::vector<CheckResult> skipped_encoding_checks(const std::string& reason);

}  // namespace olcb::conform
