// The check functions of the registry (conformance/check_registry.cpp), one file per topic.
// Each function judges one check; lists of entries come from the topic files whose checks are
// wholly theirs.
#pragma once

#include <string>
#include <vector>

#include "conformance/check_registry.hpp"
#include "conformance/check_run.hpp"

namespace olcb::conform::checks {

// frame.cpp
void ame_answered(CheckRun& run);
void cid_defended(CheckRun& run);

// message.cpp
void oir_unknown_mti(CheckRun& run);
void verify_addressed(CheckRun& run);
void verify_global(CheckRun& run);
void unknown_global_ignored(CheckRun& run);
void pip_answered(CheckRun& run);
void no_unsolicited(CheckRun& run);

// snip.cpp
void snip_version_bytes(CheckRun& run);
void snip_utf8(CheckRun& run);
void snip_matches_acdi(CheckRun& run);
void snip_matches_cdi(CheckRun& run);

// cdi.cpp
void cdi_space_info(CheckRun& run);
void cdi_read(CheckRun& run);
void cdi_nul_terminated(CheckRun& run);
void cdi_nul_at_highest(CheckRun& run);
void cdi_no_bom(CheckRun& run);
void cdi_utf8(CheckRun& run);
void cdi_xml_declaration(CheckRun& run);
void cdi_well_formed(CheckRun& run);
void cdi_valid(CheckRun& run);
void cdi_schema_location(CheckRun& run);
void cdi_acdi_spaces(CheckRun& run);
/// The CDI variables that overlap the ACDI blocks ("space 252 bytes 0..3, ..."); "" when none.
std::string acdi_conflict(const CheckContext& ctx);

// acdi.cpp
void acdi_manufacturer_version(CheckRun& run);
void acdi_user_version(CheckRun& run);
void acdi_utf8(CheckRun& run);
void acdi_space_info(CheckRun& run);

// pip.cpp
void pip_snip_bit(CheckRun& run);
void pip_datagram_bit(CheckRun& run);
void pip_memory_config_bit(CheckRun& run);
void pip_cdi_bit(CheckRun& run);
void pip_acdi_bit(CheckRun& run);

// datagram.cpp
void datagram_ok_before_reply(CheckRun& run);
void datagram_reply_pending(CheckRun& run);
void datagram_temporary_rejects(CheckRun& run);

// memory.cpp
void memory_config_options(CheckRun& run);
void memory_reply_latency(CheckRun& run);
void memory_options_acdi_flags(CheckRun& run);
void memory_space_info_layout(CheckRun& run);
void memory_read_byte6_form(CheckRun& run);
void memory_read_short_form(CheckRun& run);
void memory_reply_form(CheckRun& run);
void memory_read_short_at_end(CheckRun& run);
void memory_unknown_space(CheckRun& run);
void memory_lock(CheckRun& run);
void memory_readonly_refused(CheckRun& run);

/// One string from the node a check judges, named for its messages ("user name").
struct NamedText {
    std::string name;
    std::string_view text;
};
/// PASS (what) when every text is valid UTF-8; else FAIL naming each invalid one with its bytes
/// in hex (snip.cpp).
/// PASS when every text is UTF-8, else `bad` (FAIL where the standard asks for UTF-8, WARN where
/// only a technical note does) naming each invalid one with its bytes.
void judge_utf8(CheckRun& run, const std::vector<NamedText>& texts, const std::string& what,
                Status bad);

/// What the node sent in one silence window after four probes that must go unanswered: an
/// unknown global MTI, and Verify Node ID, Protocol Support Inquiry and an unknown MTI addressed
/// to an alias no node uses (message_addressing.cpp; asked once per run).
struct SilenceAnswers {
    bool judged = false;     ///< a window without other sources' traffic was had
    bool has_other = false;  ///< an unused alias was found to address
    std::uint16_t other = 0;
    std::string to_us;     ///< a message the node addressed to lcc-conform ("" none)
    std::string verified;  ///< a Verified Node ID from the node
    std::string psr;       ///< a Protocol Support Reply (to us, the inquiry's sender)
    std::string oir;       ///< an OIR echoing the unknown addressed MTI (to us)
};
/// The shared silence probe.
const SilenceAnswers& silence_probe(CheckRun& run);

/// Aliases no frame seen so far used, nor ours or the node's (frame_bus.cpp): sources for
/// made-up traffic and destinations "another node" has.
std::vector<std::uint16_t> unused_aliases(CheckRun& run, std::size_t count);

// Lists whose entries (ID, category, section, OlcbChecker, summary, function) live with their
// checks, spliced into the registry at their place in the run's order:
/// frame_bus.cpp: collision, AME with bit 28 clear, capacity bursts, standard frames, start-up.
std::vector<CheckSpec> frame_bus_checks();
/// message_addressing.cpp: messages addressed to another node, PIP bytes and simple bit.
std::vector<CheckSpec> message_addressing_checks();
/// datagram_protocol.cpp: unknown datagram protocols, out-of-order and overlapping frames.
std::vector<CheckSpec> datagram_protocol_checks();
/// memory_bounds.cpp: per-space highest address, past the end, crossing writes, write under
/// mask, Update Complete, Options write lengths.
std::vector<CheckSpec> memory_bounds_checks();
/// events.cpp: Identify Events / Producer / Consumer against the CDI's event IDs.
std::vector<CheckSpec> event_checks();
/// event_robustness.cpp: event messages a configurable node need not act on (ev60, ev70).
std::vector<CheckSpec> event_robustness_checks();
/// stream_checks.cpp: memory-config stream reads (CDI by stream, buffer, Proceed, Complete).
std::vector<CheckSpec> stream_checks();
/// Checks the encoding phase produces for events (run = nullptr; events.cpp documents them).
std::vector<CheckSpec> event_phase_checks();
/// Disruptive checks that run last of all the protocol checks (frame_bus.cpp,
/// message_addressing.cpp): e.g. the duplicate node ID, behind --thorough.
std::vector<CheckSpec> final_checks();

}  // namespace olcb::conform::checks
