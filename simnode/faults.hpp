// Named, composable misbehaviours of a simulated node (docs/faults.md): each breaks one rule of
// a standard on purpose so a client's handling of it can be tested. Each fault is declared once,
// in its family's file under simnode/faults/ (fault_catalog.hpp); this header is what the hooks
// and callers need.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace olcb::simnode {

/// Which Protocol Support Reply bit pip-missing-bit drops.
enum class PipBit : std::uint8_t { kCdi, kAcdi, kSnip, kDatagram, kMemoryConfiguration, kEvents };

/// The faults of one node; all off by default (a well-behaved node).
struct FaultSet {
    bool snip_mismatch = false;         ///< SNIP model string differs from ACDI/CDI
    bool snip_invalid_utf8 = false;     ///< SNIP user name ends in bytes that are not UTF-8
    bool acdi_version = false;          ///< 252/251 version bytes are fixed+1 / var+1
    std::optional<PipBit> pip_missing;  ///< PSR lacks this bit although the node serves it
    bool cdi_unterminated = false;      ///< space 0xFF without the terminating NUL
    bool cdi_padding = false;           ///< NULs and garbage after the terminating NUL
    bool cdi_invalid = false;           ///< served CDI violates the schema (loads invalid CDIs)
    bool int_byte_order = false;        ///< ints stored little-endian
    bool string_unterminated = false;   ///< strings fill their field without a NUL
    bool eventid_byte_order = false;    ///< event IDs stored little-endian
    bool float_width = false;           ///< floats stored with the next smaller precision
    bool write_dropped = false;         ///< writes acknowledged but not stored
    bool write_not_persisted = false;   ///< writes kept in RAM only: lost on reboot
    bool readonly_writable = false;     ///< writes to 0xFF and 252 accepted
    bool read_past_end = false;         ///< read at/after the end returns zeros, not 0x1082
    bool space_info_short = false;      ///< space information highest address too small
    bool reply_form = false;            ///< replies in the other (short / byte-6) form
    bool no_datagram_ack = false;       ///< reply datagram sent before Datagram Received OK
    /// Reply datagrams held back this long (slow-reply=MS; 0 = off).
    std::chrono::milliseconds slow_reply{0};
    /// The first N datagrams are rejected with 0x2020 (reject-temporary=N; 0 = off).
    std::uint32_t reject_temporary = 0;
    bool alias_conflict_ignored = false;  ///< no RID on CID, no AMR on conflict
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
    bool reset_rejected = false;  ///< Reset/Reboot rejected with 0x1041
    bool lock_rejected = false;   ///< Lock/Reserve rejected with 0x1041
    /// Every restart factory-resets the writable spaces while the watched int differs from its
    /// value at creation.
    bool factory_reset_on_version_change = false;
    bool new_alias_on_reboot = false;    ///< every restart reserves a different alias
    bool field_reads_only = false;       ///< 251/252 reads return one ACDI field (or 1 byte)
    bool unknown_space_0x1041 = false;   ///< read/write of an unknown space rejected 0x1041
    bool readonly_0x1041 = false;        ///< write to a read-only space rejected 0x1041
    bool read_past_end_garbage = false;  ///< 0xFD read at/after the end returns 0xA5 bytes
    bool write_past_end_spills = false;  ///< crossing writes accepted; 251's tail lands in 253
    /// Crossing writes accepted; the bytes past the end are kept (on disk) where no read reaches.
    bool write_past_end_grows = false;
    bool highest_unreadable = false;        ///< 251/253 Space Info highest = size (one too high)
    bool events_stale_after_write = false;  ///< identifies the start-up event IDs until restart
    bool events_missing = false;            ///< eventid slots 1, 3, 5... never identified
    bool duplicate_id_silent = false;       ///< no PCER on a duplicate node ID
    bool burst_drops = false;               ///< addressed messages dropped during frame bursts
    bool answers_standard_frames = false;   ///< any 11-bit frame answered with Verified Node ID
    bool stream_wrong_count = false;        ///< Data Complete counts one byte more than sent
    bool stream_no_complete = false;        ///< stream reads never end with Data Complete
    bool stream_ignore_proceed = false;     ///< sends the whole read without Data Proceed
    bool stream_exceed_buffer = false;      ///< sends twice the granted buffer per Proceed
    /// Every answer is sent this long after its request arrived (latency=MS[:JITTER]; 0 = off).
    std::chrono::milliseconds latency{0};
    /// Up to this much more, uniformly random per answer, seeded by the node ID.
    std::chrono::milliseconds latency_jitter{0};

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
