// The state one node's protocol checks share: the session, what earlier checks learned (the
// CheckContext), and probes that several checks judge (one exchange, asked once, on first use,
// so any selection of checks works on its own). Check functions live in conformance/checks/.
#pragma once

#include <any>
#include <cstdint>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cdi/rule_finding.hpp"
#include "conformance/checks/check_context.hpp"
#include "conformance/checks/check_registry.hpp"
#include "conformance/checks/protocol_checks.hpp"
#include "conformance/link/session.hpp"
#include "conformance/report/check_result.hpp"

namespace olcb::conform {

/// An MTI the fact sheet does not assign, with the address bit set (its own OIR example).
inline constexpr std::uint16_t kUnknownAddressedMti = 0x04F9;
/// An unassigned global MTI (no address or event bits): nodes must ignore it silently.
inline constexpr std::uint16_t kUnknownGlobalMti = 0x0930;
/// A node ID that is not ours nor the node's, for the CID probe and the lock check.
inline constexpr std::uint64_t kOtherNodeId = 0x0201'12FE'0001ull;
/// Silence windows a silence check tries while other sources keep speaking.
inline constexpr int kQuietAttempts = 3;

/// Answer windows the frame probe adds while the segment still answers its global AME (a
/// 1,000-node segment at 125 kbit/s needs about a second for their AMDs).
inline constexpr int kSegmentAnswerRounds = 30;

/// Answers to the injected control frames and first messages (AME, CID, unknown MTI, Verify).
struct FrameProbe {
    std::size_t amd = 0;               ///< AMD frames from the node with its node ID
    std::size_t rid = 0;               ///< RID frames from the node
    std::size_t segment_amd = 0;       ///< AMD frames from every other node (the global AME's)
    std::optional<std::uint16_t> oir;  ///< the code of an OIR echoing the unknown MTI
    bool verified = false;             ///< Verified Node ID to the addressed Verify
    std::optional<Mti> verified_mti;   ///< which Verified MTI (simple or full) it used
};

/// 8-byte reads of the data space in both forms (the short form only for 0xFD-0xFF).
struct FormProbe {
    std::uint8_t space = 0xFF;
    MemResult byte6;
    std::optional<MemResult> short_form;
};

/// The CDI download of space 0xFF.
struct CdiDownload {
    MemResult result;      ///< the read_range() outcome
    bool read_ok = false;  ///< data came
    /// Bytes that came from past Space Info's highest address (it is too small when not 0).
    std::uint32_t beyond_highest = 0;
};

/// Judges one request the standard refuses. MemoryConfigurationS requires a failure with an error
/// code (§4.5, §4.9); the code itself is only recommended (MemoryConfigurationTN §2.4.3).
struct Refusal {
    Status status = Status::kFail;  ///< PASS: the recommended code; WARN: another; FAIL: none
    std::string message;            ///< what happened, with the recommended code when it differs
    std::string seen;               ///< the code, "accepted", "returned N bytes" or "no answer"
};

/// "0x1082" (width hex digits).
std::string hex(unsigned value, int width = 4);
/// At most 80 bytes of node-supplied text, cut on a UTF-8 boundary, made printable, with the raw
/// bytes in hex after it when it is not clean UTF-8 (show_node_text()).
std::string clip(std::string_view text);
/// clip() in double quotes.
std::string quoted(std::string_view text);
/// What an exchange did, in words ("no answer", "Datagram Rejected 0x1081", "8 bytes").
std::string describe(const MemResult& r);
/// Judges r against the refusal the standard asks for `what`, `want` the recommended code.
Refusal judge_refusal(const MemResult& r, const std::string& what, std::uint16_t want);
/// "fd" for 0xFD: how per-space IDs carry the space.
std::string space_suffix(std::uint8_t space);

class CheckRun;

/// Results of one check: the entry's ID (or, per space, ID.<sp>), category and section.
class Verdict {
public:
    Verdict(CheckRun& run, std::string id) : run_(run), id_(std::move(id)) {}
    /// PASS when ok, else FAIL with what was expected and what came.
    void judge(bool ok, std::string message, std::string expected = {}, std::string seen = {});
    void pass(std::string message) { judge(true, std::move(message)); }
    void fail(std::string message, std::string expected, std::string seen) {
        judge(false, std::move(message), std::move(expected), std::move(seen));
    }
    void warn(std::string message, std::vector<std::string> details = {});
    void skip(std::string why);
    /// A judged refusal, `expected` naming what passes.
    void refusal(const Refusal& r, std::string expected);
    /// A result with every field given (details: one line each, e.g. every CDI error).
    void add(Status status, std::string message, std::string expected, std::string seen,
             std::vector<std::string> details = {});

private:
    CheckRun& run_;
    std::string id_;
};

/// One node's protocol checks in progress.
class CheckRun {
public:
    CheckRun(Session& session, const NodeInfo& node, const ProtocolOptions& options,
             CheckContext& ctx);

    Session& session() { return s_; }
    const NodeInfo& node() const { return node_; }
    const ProtocolOptions& options() const { return o_; }
    CheckContext& ctx() { return ctx_; }
    /// The node's alias now: a node that re-initialised may have taken another one.
    std::uint16_t alias() const;
    /// True when the frame is an extended frame from the node's current alias.
    bool from_node(const CanFrame& frame) const;

    /// Results of the entry spec (the one a check function is given).
    Verdict out(const CheckSpec& spec);
    /// Results of the per-space entry spec for one space (ID.<sp>).
    Verdict out(const CheckSpec& spec, std::uint8_t space);
    /// True when the per-space entry spec is selected for space (--only/--skip name per-space
    /// results exactly: `--only memory.write-past-end.fd` probes 0xFD alone).
    bool space_selected(const CheckSpec& spec, std::uint8_t space) const;
    /// The spaces of `spaces` space_selected() keeps, in order.
    std::vector<std::uint8_t> selected_spaces(const CheckSpec& spec,
                                              const std::vector<std::uint8_t>& spaces) const;
    /// Runs one entry: calls its function with it.
    void run(const CheckSpec& spec);
    /// Adds a finished result (Verdict uses it).
    void add(CheckResult result);
    /// The results so far, in order.
    std::vector<CheckResult> take() { return std::move(out_); }
    /// Number of results so far.
    std::size_t result_count() const { return out_.size(); }
    /// Shares `spent` among the results from index `first` on (one check's per-space results).
    void share_duration(std::size_t first, Duration spent);
    /// Where the run started (the quiet window of message.no-unsolicited counts from here).
    std::size_t start_frame() const { return start_frame_; }
    TimePoint started() const { return started_; }

    /// Another lcc-conform run seen on the segment (its node ID), if any.
    std::optional<NodeId> other_tool();
    /// True when a frame since mark came from a source other than the node and lcc-conform
    /// (another tool or node spoke, so a silence window proves nothing).
    bool others_spoke(std::size_t mark);
    /// Counts temporary rejects and learns whether memory configuration works at all.
    MemResult note(MemResult r);
    /// note() without the copy.
    void tally(const MemResult& r);

    // --- probes: asked once, on first use ---
    const FrameProbe& frame_probe();
    /// The SNIP reply's payload (nullopt: no reply).
    const std::optional<std::vector<std::uint8_t>>& snip_raw();
    /// The Protocol Support Reply (also in ctx().pip).
    const std::optional<ProtocolSet>& pip();
    /// Get Configuration Options (also in ctx().options); the exchange's outcome.
    const MemResult& config_options();
    /// The reply the Options exchange got, in words ("" before config_options()).
    const std::string& config_options_reply() const { return options_reply_; }
    /// Get Address Space Information for space (cached in ctx().spaces).
    const SpaceInfo& space_info(std::uint8_t space);
    /// Space 0xFF downloaded, parsed and laid out into ctx().
    const CdiDownload& cdi();
    /// cdi::check_rules() of the downloaded CDI text: the verdicts of the text-only cdi.* checks.
    const std::vector<cdi::RuleFinding>& rules();
    /// Spaces 252/251 read field by field into ctx() (only with <acdi/>): true when read.
    bool acdi_blocks();
    /// The outcome of reading 252 (after acdi_blocks()).
    const MemResult& acdi_manufacturer_result() const { return acdi_manufacturer_result_; }
    /// The outcome of reading 251 (after acdi_blocks()).
    const MemResult& acdi_user_result() const { return acdi_user_result_; }
    /// "depends on <id>: why" when a check finds Space Info's highest address of space too small
    /// (the CDI goes on past it, the layout or ACDI needs more), so a check at that address would
    /// only repeat the finding; "" when nothing says so.
    std::string highest_too_small(std::uint8_t space);
    /// True when any memory-config exchange got an answer (asks Options when none was made).
    bool memory_works();
    /// True when any datagram got an answer, Datagram Rejected included (asks Options when none
    /// did).
    bool datagrams_answered();
    /// The spaces the CDI's segments use, in ascending order.
    std::vector<std::uint8_t> layout_spaces();
    /// The space the form checks read (a CDI space, 0xFD-0xFF preferred; else 0xFF).
    std::uint8_t data_space();
    /// The data space read in both forms.
    const FormProbe& form_probe();
    /// What a topic file's probe learned this run, by key (nullptr before it is remembered).
    template <typename T>
    const T* memo(const std::string& key) const {
        auto it = memos_.find(key);
        return it == memos_.end() ? nullptr : std::any_cast<T>(&it->second);
    }
    /// Keeps a probe's outcome for the other checks of this run.
    template <typename T>
    const T& remember(const std::string& key, T value) {
        return *std::any_cast<T>(&(memos_[key] = std::move(value)));
    }

private:
    /// Reads on past Space Info's highest address when the download ended there without a NUL.
    void read_past_highest(CdiDownload& d, std::uint32_t len);
    void count_probe_frames(FrameProbe& p, std::size_t& seen);
    void count_probe_messages(FrameProbe& p, std::size_t& seen);

    Session& s_;
    NodeInfo node_;
    ProtocolOptions o_;
    CheckContext& ctx_;
    std::vector<CheckResult> out_;
    std::size_t start_frame_ = 0;
    TimePoint started_{};
    bool memory_works_ = false;
    bool datagram_answered_ = false;
    std::optional<FrameProbe> frame_probe_;
    bool snip_asked_ = false;
    std::optional<std::vector<std::uint8_t>> snip_raw_;
    bool pip_asked_ = false;
    std::optional<MemResult> options_result_;
    std::string options_reply_;
    std::optional<CdiDownload> cdi_;
    std::optional<bool> acdi_read_;
    std::optional<std::vector<cdi::RuleFinding>> rules_;
    std::optional<FormProbe> form_probe_;
    std::map<std::string, std::any> memos_;
    MemResult acdi_manufacturer_result_, acdi_user_result_;
};

}  // namespace olcb::conform
