// The check families: each file of conformance/checks/ owns its registry entries (ID, order,
// clause, strength, summary, function) and returns them from one list function here;
// check_registry.cpp joins the lists and sorts them by order. Helpers shared between families
// and the probes only they share are declared below the lists; probes.hpp has the others.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "cdi/rule_finding.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/check_run.hpp"
#include "conformance/checks/probes.hpp"
#include "openlcb/train_control.hpp"

namespace olcb::conform::checks {

/// The CDI variables of layout that overlap the ACDI blocks ("space 252 bytes 0..3, ..."); ""
/// when none or without a layout (cdi.cpp).
std::string acdi_conflict(const std::optional<cdi::Layout>& layout);

/// One string from the node a check judges, named for its messages ("user name").
struct NamedText {
    std::string name;
    std::string_view text;
};
/// PASS when every text is UTF-8, else `bad` (FAIL where the standard asks for UTF-8, WARN where
/// only a technical note does) naming each invalid one with its bytes in hex (snip.cpp).
void judge_utf8(CheckRun& run, const CheckSpec& spec, const std::vector<NamedText>& texts,
                const std::string& what, Status bad);

/// What the node sent in one silence window after four probes that must go unanswered: an
/// unknown global MTI, and Verify Node ID, Protocol Support Inquiry and an unknown MTI addressed
/// to an alias no node uses (a probe: message_addressing.cpp).
struct SilenceAnswers {
    bool judged = false;     ///< a window without other sources' traffic was had
    bool has_other = false;  ///< an unused alias was found to address
    std::uint16_t other = 0;
    std::string to_us;     ///< a message the node addressed to lcc-conform ("" none)
    std::string verified;  ///< a Verified Node ID from the node
    std::string psr;       ///< a Protocol Support Reply (to us, the inquiry's sender)
    std::string oir;       ///< an OIR echoing the unknown addressed MTI (to us)
    /// Standard frames sent in the judged window too (0: none, or the node spoke in that window
    /// and the probes were judged again without them); frame.standard-frames-ignored takes a
    /// window with them and nothing at all from the node as its own.
    unsigned standard_frames = 0;

    static SilenceAnswers ask(CheckRun& run);
};

/// Injects the first count of the standard (11-bit) frames frame.standard-frames-ignored sends
/// (frame_bus.cpp); kStandardFramesQuick without --thorough.
void inject_standard_frames(Session& s, unsigned count, bool every_id);
inline constexpr unsigned kStandardFramesQuick = 64;

/// Aliases no frame seen so far used, nor ours or the node's (frame_bus.cpp): sources for
/// made-up traffic and destinations "another node" has.
std::vector<std::uint16_t> unused_aliases(CheckRun& run, std::size_t count);

/// Sends a Traction Control Command to the node (train_control.cpp).
void train_send(CheckRun& run, const train::Command& command);
/// The first Traction Control Reply from the node among the messages since mark that wanted()
/// takes, awaited up to window (zero: the answer window); nullopt with why set when none came
/// (or only replies that do not decode).
std::optional<train::Reply> train_await(CheckRun& run, std::size_t mark,
                                        const std::function<bool(const train::Reply&)>& wanted,
                                        std::string& why, Duration window = {});
/// One command to the node and its reply of type R (a Query Speeds Reply, ...).
template <typename R>
std::optional<R> train_ask(CheckRun& run, const train::Command& command, std::string& why,
                           Duration window = {}) {
    const std::size_t mark = run.session().message_mark();
    train_send(run, command);
    auto r = train_await(
        run, mark, [](const train::Reply& x) { return std::holds_alternative<R>(x); }, why, window);
    if (!r) return std::nullopt;
    return std::get<R>(*r);
}

/// "" when a check may change the state of the train under test (train_control.cpp): only on a
/// node named with --node, never with --read-only (whole_layout: only with --thorough too, since
/// it stops every train on the segment); otherwise why it SKIPs.
std::string train_may_drive(CheckRun& run, bool whole_layout = false);

/// Control of the train for one check (train_control.cpp): taken unless another throttle holds
/// it; given back, the speed at zero in the train's own direction, when the check ends.
class TrainDriving {
public:
    explicit TrainDriving(CheckRun& run);
    TrainDriving(const TrainDriving&) = delete;
    TrainDriving& operator=(const TrainDriving&) = delete;
    ~TrainDriving();
    /// Why the train could not be taken ("" when it was).
    const std::string& blocked() const { return blocked_; }

private:
    CheckRun& run_;
    std::string blocked_;
    bool held_ = false;
    bool reverse_ = false;
};

/// The Broadcast Time clocks (their 6-byte Specific Upper Parts) a node generates, and those it
/// only consumes, from its answer to Identify Events addressed (clock_roles.cpp). Broadcast
/// Time has no PIP bit: this is how a check tells a clock. A generator identifies producing a
/// well-known clock's events (01.01.00.00.01.00 to .03), or a produced range of exactly one
/// clock's 16 bits with consumed events in the same block (§6.1's two ranges).
struct ClockRoles {
    std::vector<NodeId> generated;  ///< well-known clocks first, in their order
    std::vector<NodeId> consumed;   ///< consumed and not generated
    bool answered = false;          ///< Identify Events addressed got an answer

    static ClockRoles ask(CheckRun& run);
    /// "Default Fast Clock, Alternate Clock 1".
    std::string describe() const;
};

/// Why a check of a protocol no PIP bit announces does not apply ("" when it does): decided
/// from the node's answer to Identify Events addressed (the EventAnswers probe), `applies`
/// saying whether it makes the node one the check is for, `what` naming such a node ("a
/// Broadcast Time clock generator"). The one gate of such checks (clock_roles.cpp).
std::string not_identified_as(CheckRun& run, const std::string& what,
                              const std::function<bool(const EventAnswers&)>& applies);

/// True when frame is a single-frame PCER of a clock the node generates or consumes: a report
/// §6.2 requires, or a display's Query (message.no-unsolicited does not count it).
bool is_clock_report(CheckRun& run, const CanFrame& frame);

/// A cdi/ rule verdict (check_rules, check_fdi_rules) as a check status (cdi.cpp).
Status status_of(cdi::RuleStatus status);

/// frame.cpp: AME answered, CID defended.
std::vector<CheckSpec> frame_checks();
/// message.cpp: Verify Node ID, unknown MTIs, Protocol Support Inquiry, unsolicited traffic.
std::vector<CheckSpec> message_checks();
/// snip.cpp: SNIP versions, UTF-8, agreement with ACDI and CDI.
std::vector<CheckSpec> snip_checks();
/// memory.cpp: Get Configuration Options, reply latency and forms, lock, read-only spaces.
std::vector<CheckSpec> memory_checks();
/// cdi.cpp: the CDI download and its text, schema and ACDI rules.
std::vector<CheckSpec> cdi_checks();
/// datagram.cpp: datagram OK before the reply, Reply Pending, temporary rejects.
std::vector<CheckSpec> datagram_checks();
/// acdi.cpp: the ACDI spaces' version bytes, UTF-8 and space information.
std::vector<CheckSpec> acdi_checks();
/// pip.cpp: each protocol bit against what the node does.
std::vector<CheckSpec> pip_checks();
/// encoding.cpp: the write/read-back phase (run = nullptr; run/encoding_run.cpp reports them).
std::vector<CheckSpec> encoding_checks();
/// node.cpp: the node's restarts, its silence and the link (reported by the node run's phases).
std::vector<CheckSpec> node_checks();
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
/// events.cpp: checks the encoding phase produces for events (run = nullptr).
std::vector<CheckSpec> event_phase_checks();
/// train_control.cpp: a train node's Is Train event, spaces, controller, reservation, and on a
/// node named with --node its speed, functions, emergency stops, listeners and heartbeat.
std::vector<CheckSpec> train_control_checks();
/// train_search.cpp: a train answering searches, a command station creating trains.
std::vector<CheckSpec> train_search_checks();
/// fdi.cpp: the FDI of space 0xFA: its space, download, XML and functions.
std::vector<CheckSpec> fdi_checks();
/// broadcast_time_checks.cpp: a Broadcast Time generator (Query, Set, reports, rollover,
/// start-up, the restore).
std::vector<CheckSpec> broadcast_time_checks();
/// clock_consumer_checks.cpp: a Broadcast Time consumer (start-up, Identify Consumer).
std::vector<CheckSpec> clock_consumer_checks();
/// message_addressing.cpp: disruptive checks that run last of all the protocol checks (e.g.
/// the duplicate node ID, behind --thorough).
std::vector<CheckSpec> final_checks();

}  // namespace olcb::conform::checks
