// The state one node's protocol checks share: the session, the results, what the node's answers
// showed so far, and the probes: what several checks judge from one exchange, asked once on first
// use (so any selection of checks works on its own) and kept in one typed cache, run.probe<P>().
// A probe type says how it is asked (P::ask); the shared ones are in probes.hpp, the others in
// the family file that uses them. Check functions live in conformance/checks/.
#pragma once

#include <concepts>
#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

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

/// A probe asked once per run: `static P P::ask(CheckRun&)` makes its exchange and returns what
/// it learned.
template <typename P>
concept CheckProbe = requires(CheckRun& run) {
    { P::ask(run) } -> std::same_as<P>;
};

/// A probe asked once per key (one space, one form of a request): `P::Key` (ordered) and
/// `static P P::ask(CheckRun&, const P::Key&)`. A result whose `settled()` is false (Space Info
/// that got no answer) is asked again on the next use.
template <typename P>
concept KeyedCheckProbe = requires(CheckRun& run, const typename P::Key& key) {
    { P::ask(run, key) } -> std::same_as<P>;
};

/// What the node's answers to every exchange of the checks showed so far.
struct Heard {
    unsigned temporary_rejects = 0;  ///< temporary rejects retried
    bool datagrams = false;          ///< a datagram was answered (Datagram Rejected too)
    bool memory = false;             ///< a memory-config command got a reply (not Rejected)
    /// Of the memory-config replies so far, the one slowest against its limit (750 ms, or the
    /// 2^N s its Datagram Received OK announced): its latency and N (0: none announced).
    std::optional<Duration> slowest_reply;
    std::uint8_t slowest_exponent = 0;
};

/// How long a memory-config reply may take: the options' 750 ms, or the 2^N s a Datagram Received
/// OK with timeout exponent N announced (MessageNetworkS §3.7, DatagramTransportS §4.2).
Duration reply_limit(const ProtocolOptions& options, unsigned exponent);

/// One node's protocol checks in progress.
class CheckRun {
public:
    CheckRun(Session& session, const NodeInfo& node, const ProtocolOptions& options);

    Session& session() { return s_; }
    const NodeInfo& node() const { return node_; }
    const ProtocolOptions& options() const { return o_; }
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
    /// What the exchanges tallied so far showed.
    const Heard& heard() const { return heard_; }

    /// The probe P: asked on first use, the same result after.
    template <CheckProbe P>
    const P& probe() {
        std::optional<P>& held = slot<P, std::optional<P>>();
        if (!held) held.emplace(P::ask(*this));
        return *held;
    }
    /// The keyed probe P for key: asked on first use (and again while not settled()).
    template <KeyedCheckProbe P>
    const P& probe(const typename P::Key& key) {
        auto& held = slot<P, std::map<typename P::Key, P>>();
        auto it = held.find(key);
        if (it == held.end() || !settled(it->second))
            it = held.insert_or_assign(key, P::ask(*this, key)).first;
        return it->second;
    }
    /// The keyed probe P for key when some check asked it, else nullptr (never asks): for a
    /// check that judges whatever exchanges the selected checks made.
    template <KeyedCheckProbe P>
    const P* asked(const typename P::Key& key) {
        auto& held = slot<P, std::map<typename P::Key, P>>();
        const auto it = held.find(key);
        return it == held.end() ? nullptr : &it->second;
    }
    /// Takes P's result out of the cache (nullopt when never asked): once the checks are done,
    /// hand_over() gives it to the later phases this way.
    template <CheckProbe P>
    std::optional<P> release() {
        return std::exchange(slot<P, std::optional<P>>(), std::nullopt);
    }
    /// release() of a keyed probe: every key's result.
    template <KeyedCheckProbe P>
    std::map<typename P::Key, P> release_each() {
        return std::exchange(slot<P, std::map<typename P::Key, P>>(), {});
    }

private:
    // Turns the results from index first on into SKIPs saying why they prove nothing.
    void not_judged(std::size_t first, const std::string& why);

    // One cache entry per probe type, holding T (the result, or the results by key).
    struct Slot {
        virtual ~Slot() = default;
    };
    template <typename T>
    struct Held final : Slot {
        T value;
    };
    // A distinct address per probe type: the cache's key, without RTTI.
    template <typename P>
    static constexpr char kTag = 0;

    template <typename P, typename T>
    T& slot() {
        std::unique_ptr<Slot>& s = probes_[&kTag<P>];
        if (!s) s = std::make_unique<Held<T>>();
        return static_cast<Held<T>&>(*s).value;
    }
    template <typename P>
    static bool settled(const P& p) {
        if constexpr (requires { p.settled(); })
            return p.settled();
        else
            return true;
    }

    Session& s_;
    NodeInfo node_;
    ProtocolOptions o_;
    std::vector<CheckResult> out_;
    std::size_t start_frame_ = 0;
    TimePoint started_{};
    Heard heard_;
    std::map<const void*, std::unique_ptr<Slot>> probes_;
};

}  // namespace olcb::conform
