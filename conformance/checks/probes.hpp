// The probes several check families share: what the node answered to one exchange, asked once
// per run on first use (CheckRun::probe<P>()), and hand_over(), which gives what they learned to
// the later phases of the node's run. A probe only one family uses lives in that family's file.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "cdi/document.hpp"
#include "cdi/layout.hpp"
#include "cdi/rule_finding.hpp"
#include "conformance/checks/check_context.hpp"
#include "conformance/checks/check_run.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/snip.hpp"
#include "openlcb/event_range.hpp"
#include "openlcb/pip.hpp"

namespace olcb::conform {

/// Answers to the injected control frames and first messages (AME, CID, unknown MTI, Verify).
struct FrameProbe {
    std::size_t amd = 0;               ///< AMD frames from the node with its node ID
    std::size_t rid = 0;               ///< RID frames from the node
    std::size_t segment_amd = 0;       ///< AMD frames from every other node (the global AME's)
    std::optional<std::uint16_t> oir;  ///< the code of an OIR echoing the unknown MTI
    bool verified = false;             ///< Verified Node ID to the addressed Verify
    std::optional<Mti> verified_mti;   ///< which Verified MTI (simple or full) it used

    static FrameProbe ask(CheckRun& run);
};

/// The SNIP request.
struct SnipProbe {
    std::optional<std::vector<std::uint8_t>> raw;  ///< the reply's payload (nullopt: no reply)
    std::optional<memory::Snip> snip;              ///< the payload decoded (when not empty)

    static SnipProbe ask(CheckRun& run);
};

/// The Protocol Support Inquiry.
struct PipProbe {
    std::optional<ProtocolSet> reply;  ///< the Protocol Support Reply (nullopt: none came)

    static PipProbe ask(CheckRun& run);
};

/// Get Configuration Options.
struct OptionsProbe {
    MemResult result;                                 ///< the exchange's outcome
    std::optional<memory::ConfigOptionsReply> reply;  ///< the reply, when one came
    std::string described;  ///< the reply in words, or the outcome when it failed

    static OptionsProbe ask(CheckRun& run);
};

/// Get Address Space Information of one space. Unanswered, it is asked again on the next use.
struct SpaceInfoProbe : SpaceInfo {
    using Key = std::uint8_t;
    static SpaceInfoProbe ask(CheckRun& run, std::uint8_t space);
    bool settled() const { return answered; }
};

/// What the node advertises about memory-config stream reads.
struct StreamSupport {
    bool pip = false;      ///< PIP Stream bit
    bool options = false;  ///< Options: stream reads (0x1000) or the stream lengths bit
    bool lengths = false;  ///< Options write-lengths 0x01 (the standard's stream bit)
    std::string skip;      ///< why the stream-read checks SKIP ("" = they run)

    static StreamSupport ask(CheckRun& run);
};

/// The whole CDI by one stream read with the largest buffer (Proceed at once), at most
/// max_cdi_bytes.
struct CdiStream : StreamReadResult {
    static CdiStream ask(CheckRun& run);
};

/// Space 0xFF downloaded, parsed and laid out: read once, by the fastest path the node offers.
/// With streams (StreamSupport) the CDI is the CdiStream's bytes up to their NUL, and datagram
/// reads fetch only its first and last 64 bytes to compare; without, or when the stream read
/// fails or brings no NUL, datagram reads fetch it all.
struct CdiDownload {
    MemResult result;        ///< the bytes and how they came (the stream's, or read_range()'s)
    bool read_ok = false;    ///< data came
    bool by_stream = false;  ///< the bytes came by the stream read
    /// The datagram reads of 0xFF without their data: the whole download, or with by_stream the
    /// two sample reads (their Datagram Received OK flags, latency and form are what the
    /// datagram checks judge; ok is false when one failed).
    MemResult datagram;
    /// With by_stream: where the datagram samples differ from the stream's bytes ("" = agree).
    std::string sample_difference;
    /// With by_stream: the bytes the datagram samples covered, as "0x0000-0x003F, ...".
    std::string sampled;
    /// Bytes that came from past Space Info's highest address (it is too small when not 0).
    std::uint32_t beyond_highest = 0;
    std::vector<std::uint8_t> text;  ///< the bytes up to (excluding) the NUL
    bool nul_found = false;          ///< the download ended at a NUL
    /// Parsed, when data came (on the heap: the layout points into it).
    std::unique_ptr<cdi::Document> document;
    std::optional<cdi::Layout> layout;    ///< its layout (when without errors)
    std::vector<cdi::RuleFinding> rules;  ///< cdi::check_rules() of the text, when data came

    static CdiDownload ask(CheckRun& run);
};

/// Spaces 252/251 read field by field, only with <acdi/> in the CDI.
struct AcdiProbe {
    std::optional<cdi::Acdi> acdi;  ///< the CDI's <acdi/> (nullopt: none, so nothing was read)
    MemResult manufacturer_result;  ///< the outcome of reading 252
    MemResult user_result;          ///< the outcome of reading 251
    std::optional<std::vector<std::uint8_t>> manufacturer;  ///< 252's 125 bytes, when read
    std::optional<std::vector<std::uint8_t>> user;          ///< 251's 128 bytes, when read

    static AcdiProbe ask(CheckRun& run);
};

/// How long answers to an Identify message are awaited: quiet ends a stream of answers, answer
/// bounds the wait for the first one.
struct AnswerWindows {
    Duration quiet = std::chrono::milliseconds(250);
    Duration answer = std::chrono::seconds(1);
};

/// Any Producer/Consumer Identified (openlcb/event_range.hpp), or a Range Identified.
bool is_identification(Mti m);

/// Whom Identify Events is sent to: every node (global) or the node (addressed).
enum class IdentifyTo : std::uint8_t { kEveryNode, kTheNode };

/// What a node identified in answer to one Identify Events: exact events and ranges, per role.
/// The probe of the event checks and of the checks of protocols no PIP bit announces (Broadcast
/// Time: a clock generator is a node that identifies producing a clock's events), asked once per
/// run per form, so its quiet wait is made once.
struct EventAnswers {
    using Key = IdentifyTo;

    std::set<std::uint64_t> produced, consumed, produced_ranges, consumed_ranges;
    std::size_t messages = 0;

    static EventAnswers ask(CheckRun& run, IdentifyTo to);

    bool empty() const { return messages == 0; }
    /// Identified as produced, exactly or in a range.
    bool produces(std::uint64_t id) const;
    /// Identified as consumed, exactly or in a range.
    bool consumes(std::uint64_t id) const;
    /// Adds an Identified message (others are ignored).
    void add(const Message& m);
    /// "12 Identified messages (3 produced, 8 consumed, 1 ranges)".
    std::string describe() const;
};

/// One quiet window for two event checks whose answers tell each other apart (issue 32: a window
/// less per run). events.identify-producer-consumer's Identify Producer/Consumer go out first and
/// their owed answers are awaited; then events.pcer-payload-tolerated's PCERs with payload and a
/// Verify Node ID that shows they were carried. One window then holds both the silence a foreign
/// event is owed and the watch for a restart, and a second Verify shows the node still runs. A
/// node the PCERs upset has answered the asks before it saw them. Each part only when its check
/// is selected.
struct EventWindow {
    struct Ask {
        std::uint64_t id = 0;
        bool producer = false;
        bool owed = false;      ///< the node's own event (an answer is owed), else a foreign one
        bool answered = false;  ///< its Identified message (or a range covering it) came
    };
    std::vector<Ask> asks;       ///< empty when identify-producer-consumer is not selected
    bool pcers = false;          ///< the PCERs went out (pcer-payload-tolerated selected)
    bool carried = false;        ///< the node answered Verify Node ID after the PCERs
    bool restarted = false;      ///< a start or alias reservation of the node from the PCERs on
    bool still_answers = false;  ///< it answered Verify Node ID again after the window

    static EventWindow ask(CheckRun& run);
};

/// Messages from the node (alias) after mark that want accepts: awaited until done(got) holds
/// (at most first), then until quiet has passed since sending and since the last one (at most ten
/// answer windows in all). Waits in steps: a simulated link jumps to the end of a wait when
/// nothing is scheduled, so the end of each step is the next moment that matters.
std::vector<Message> await_answers(Session& s, std::uint16_t alias, std::size_t mark,
                                   const std::function<bool(const Message&)>& want,
                                   const std::function<bool(const std::vector<Message>&)>& done,
                                   Duration first, const AnswerWindows& w);

/// Identify Events (global or addressed to the node) and every Identified message it brought;
/// first bounds the wait for the first answer.
EventAnswers identify_events(Session& s, const NodeInfo& node, IdentifyTo to, Duration first,
                             const AnswerWindows& w);

/// Get Address Space Information of space, the exchange's outcome in outcome (the probe's
/// exchange; short_read_checks() asks it after the checks too).
SpaceInfo ask_space_info(Session& s, const NodeInfo& node, std::uint8_t space, MemResult& outcome);

/// "depends on <id>: why" when a check finds Space Info's highest address of space too small
/// (the CDI goes on past it, the layout or ACDI needs more), so a check at that address would
/// only repeat the finding; "" when nothing says so.
std::string highest_too_small(CheckRun& run, std::uint8_t space);
/// True when any memory-config exchange got an answer (asks Options when none was made).
bool memory_works(CheckRun& run);
/// True when any datagram got an answer, Datagram Rejected included (asks Options when none
/// did).
bool datagrams_answered(CheckRun& run);
/// The spaces the CDI's segments use, in ascending order.
std::vector<std::uint8_t> layout_spaces(CheckRun& run);

/// Once the checks are done: what the probes learned (PIP, SNIP, the CDI, its document and
/// layout, the ACDI blocks, Options, Space Info) and the temporary rejects, moved into ctx for
/// the later phases (encoding, backup, report). Probes never asked leave ctx as it was.
void hand_over(CheckRun& run, CheckContext& ctx);

}  // namespace olcb::conform
