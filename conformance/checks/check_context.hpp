// What the protocol checks hand to the later phases of a node's run (encoding, backup, report).
// The checks never read it: they read their probes (check_run.hpp), and hand_over() moves what
// the probes learned into it once the checks are done.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "conformance/report/run_timing.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/snip.hpp"
#include "openlcb/pip.hpp"

namespace olcb::conform {

/// Get Address Space Information result for one space.
struct SpaceInfo {
    bool answered = false;              ///< a 0x86/0x87 reply came
    bool present = false;               ///< 0x87
    bool read_only = false;             ///< flag bit 0
    std::uint32_t highest_address = 0;  ///< inclusive
    std::optional<std::uint32_t> lowest_address;
};

/// What run_protocol_checks() learned (empty members: not learned), and the run's inputs
/// (timing, progress callbacks) and outcome (lost_after, link_lost_during, not_run).
struct CheckContext {
    std::optional<ProtocolSet> pip;           ///< Protocol Support Reply
    std::optional<memory::Snip> snip;         ///< decoded SNIP reply
    std::vector<std::uint8_t> cdi_bytes;      ///< space 0xFF up to (excluding) the NUL
    bool cdi_nul_found = false;               ///< the download ended at a NUL
    std::unique_ptr<cdi::Document> document;  ///< parsed CDI (when it parsed)
    std::optional<cdi::Layout> layout;        ///< its layout (when without errors)
    std::optional<std::vector<std::uint8_t>> acdi_manufacturer;  ///< space 252, 125 bytes
    std::optional<std::vector<std::uint8_t>> acdi_user;          ///< space 251, 128 bytes
    std::optional<memory::ConfigOptionsReply> options;  ///< Get Configuration Options reply
    std::map<std::uint8_t, SpaceInfo> spaces;           ///< Space Info per space asked
    unsigned temporary_rejects = 0;                     ///< temporary rejects retried so far
    /// Windows derived from the node's latency (the protocol checks never wait less).
    std::optional<RunTiming> timing;
    /// Called with the bytes read so far while the CDI downloads (progress display).
    std::function<void(std::size_t)> cdi_progress;
    /// The protocol check after which the node stopped answering ("" when it never did), the
    /// one during which the link went down ("" when it stayed up), and how many selected checks
    /// were not run because of either.
    std::string lost_after;
    std::string link_lost_during;
    std::size_t not_run = 0;
    /// Called with each protocol check's ID as it starts (progress display).
    std::function<void(std::string_view)> check_started;
};

}  // namespace olcb::conform
