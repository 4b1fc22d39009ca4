// One node's conformance run as a list of short phases over shared state (run_node() in
// runner.hpp is its public face). The safety backup's restore is held by a RestoreGuard from the
// moment it is captured, so every way out of the run puts the node's bytes back.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "conformance/checks/check_context.hpp"
#include "conformance/link/session_memory.hpp"
#include "conformance/report/report.hpp"
#include "conformance/run/encoding_checks.hpp"
#include "conformance/run/memory_map.hpp"
#include "conformance/run/node_watch.hpp"
#include "conformance/run/runner.hpp"
#include "conformance/run/safety_backup.hpp"
#include "conformance/run/write_cover.hpp"

namespace olcb::conform {

/// The state and phases of one node's run.
class NodeRun {
public:
    /// A run of `node` through `session` as `options` say.
    NodeRun(Session& session, const NodeInfo& node, const RunOptions& options,
            const ProtocolChecks& protocol_checks, std::ostream& progress);
    /// Runs every phase in order and returns the report.
    NodeReport run();

private:
    /// Runs one phase of the run and gives its untimed results their share of its time.
    void timed(std::string_view name, void (NodeRun::*step)());
    /// The same for a phase that may stop the run (false: the later phases are not run).
    bool timed(std::string_view name, bool (NodeRun::*step)());
    bool timed(std::string_view name, const std::function<bool()>& step);
    void measure();
    void identify();
    void protocol();
    bool writes_allowed();
    bool load_layout();
    /// The CDI's layout in ctx_, read here when the protocol checks left none: true when there.
    bool ensure_layout();
    /// encoding.stored-strings by reads alone (--read-only).
    void read_stored_strings();
    void plan();
    using Missing = std::vector<std::pair<RangeRequest, std::string>>;
    bool capture_backup();
    bool retry_one_by_one(const Missing& missing, std::string& error);
    bool take_lock();
    /// Who else may write to the node, in words: a tool that sent it datagrams, another
    /// lcc-conform run on the segment ("" when none was seen).
    std::string other_configurer() const;
    void encode();
    void release_lock();
    void follow_event_write();
    void after_incident();
    void restore_and_verify();
    void findings();
    /// A backup file that could not be written kept writes back: the run is incomplete (exit
    /// 2), and stderr says so in one line.
    void note_unsaved_backup();
    void select_results();
    void note_slow_node();
    void map_memory();
    /// Fills report_.not_tested: what the options left out and the option that tests it.
    void note_not_tested();
    /// Without a terminal: one line "lcc-conform: NODE text" on the progress stream.
    void say(const std::string& text);
    /// say() when nothing was said for a while (a long phase is never silent).
    void heartbeat(const std::string& text);
    /// A task within a phase: its bar on a terminal, its heartbeat label otherwise.
    void begin_task(std::string label);
    /// Progress of the task: done units so far.
    void tick(std::size_t done, std::string_view unit);

    void skip_writes(const std::string& reason, const std::string& summary);
    EncodingHooks hooks();
    RebootOutcome reboot();
    bool link_lost() const;
    void wait_for_link();
    void keep_backup(const std::string& why);
    /// The run's verdict has a hole (checks not run, the node gone): exit status 2.
    void mark_incomplete(const std::string& why);

    Session& session_;
    NodeInfo node_;
    const RunOptions& options_;
    const ProtocolChecks& protocol_checks_;
    std::ostream& progress_;
    NodeReport report_;
    CheckContext ctx_;
    ProgressBar bar_;
    NodeWatch watch_;
    std::uint64_t losses_before_ = 0;
    EncodingOptions eo_;
    EncodingPlan plan_;
    std::size_t read_only_skipped_ = 0;
    SessionMemory memory_;
    WriteCover cover_;         // every write of the run saved first; owns the restore
    bool abandoned_ = false;   // the node never came back: the backup is kept, nothing restored
    std::string not_written_;  // why the encoding checks wrote nothing ("" when they ran)
    bool locked_ = false;
    std::optional<NodeIncident> incident_;
    std::vector<InFlight> in_flight_;
    MapEvidence evidence_;  // what the memory map's verdicts rest on
    std::string task_;
    std::chrono::steady_clock::time_point last_line_ = std::chrono::steady_clock::now();
};

}  // namespace olcb::conform
