#include "conformance/run/node_run.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>

#include "base/hex.hpp"
#include "cdi/parser.hpp"
#include "conformance/checks/events.hpp"
#include "conformance/checks/protocol_checks.hpp"
#include "memory/memory_config_codec.hpp"
#include "memory/snip.hpp"

namespace olcb::conform {
namespace {

// A CDI larger than this is not downloaded for the encoding checks (protocol checks judge it).
constexpr std::uint32_t kMaxCdi = 4u << 20;
// Round trips measured at the start of a node's run, and how long each may take.
constexpr int kLatencySamples = 5;
constexpr Duration kLatencyTimeout = std::chrono::seconds(2);
// A node this slow gets a note on every failure that was a timeout.
constexpr Duration kSlowNode = std::chrono::milliseconds(100);
// Longest wait for the Initialization Complete after a deliberate Reset/Reboot.
constexpr std::chrono::seconds kRebootWait{10};
// Without a terminal, the longest a phase stays silent on stderr before a progress line.
constexpr Duration kHeartbeat = std::chrono::seconds(5);
// Phases that may take long on a slow node: announced when they start, not only when done.
constexpr std::string_view kLongPhases[] = {"measure",     "protocol checks", "stored strings",
                                            "layout",      "backup",          "encoding checks",
                                            "event write", "recovery",        "restore"};

// "1.4 s": elapsed time for the phase lines.
std::string elapsed_text(Duration d) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f s", std::chrono::duration<double>(d).count());
    return b;
}

auto wall() {
    return std::chrono::steady_clock::now();
}

// "space 0xFD at 0x00000157" for one run of bytes past the end of a space.
std::string past_end_text(const PastEndBytes& p) {
    return std::to_string(p.count) + (p.count == 1 ? " byte" : " bytes") +
           " past the end of space " + base::hex(p.space, 2) + " (at " + base::hex(p.address, 8) +
           ")";
}

// The restore line, computed from what was written (the ledger) and what read back.
std::string restore_line(const RestoreOutcome& outcome, const std::vector<PastEndBytes>& kept,
                         std::size_t writes) {
    const std::string counts = std::to_string(writes) + (writes == 1 ? " write" : " writes") +
                               " sent; " + std::to_string(outcome.bytes) +
                               " saved bytes read back, " + std::to_string(outcome.rewritten) +
                               " of them written back";
    if (!outcome.identical) return outcome.summary() + " (" + counts + ")";
    std::string others;
    if (!outcome.left_as_found.empty()) {
        others =
            "; changed during the run by writes this run did not send (another tool), left "
            "as found:";
        for (const auto& l : outcome.left_as_found) others += " " + l.difference + ";";
        others.pop_back();
    }
    if (kept.empty()) return "node memory byte-identical to before (" + counts + ")" + others;
    std::uint64_t total = 0;
    std::string where;
    for (const PastEndBytes& p : kept) {
        total += p.count;
        where += (where.empty() ? "" : ", ") + past_end_text(p);
    }
    return "node memory identical to before except " + std::to_string(total) +
           " unrestorable byte" + (total == 1 ? "" : "s") + " past the end: " + where +
           ", which the node may keep where no tool can read them back or restore them (" + counts +
           ")" + others;
}

bool inside(const RangeRequest& outer, std::uint8_t space, std::uint32_t address,
            std::uint32_t size) {
    return outer.space == space && address >= outer.address &&
           std::uint64_t{address} + size <= std::uint64_t{outer.address} + outer.length;
}

}  // namespace

NodeRun::NodeRun(Session& session, const NodeInfo& node, const RunOptions& options,
                 const ProtocolChecks& protocol_checks, std::ostream& progress)
    : session_(session),
      node_(node),
      options_(options),
      protocol_checks_(protocol_checks),
      progress_(progress),
      bar_(progress, options.progress),
      watch_(session, node),
      memory_(session, node),
      cover_(session, node,
             options.backup_path.empty() ? default_backup_path(node.id.to_string())
                                         : options.backup_path,
             options.read_only) {}

NodeReport NodeRun::run() {
    losses_before_ = session_.link().losses();
    report_.node_id = node_.id.to_string();
    if (!options_.protocol_only.empty()) report_.scope = "protocol only: " + options_.protocol_only;
    report_.started = std::chrono::system_clock::now();
    const auto began = wall();
    timed("measure", &NodeRun::measure);
    timed("identify", &NodeRun::identify);
    timed("protocol checks", &NodeRun::protocol);
    if (!writes_allowed()) {
        if (options_.read_only) timed("stored strings", &NodeRun::read_stored_strings);
    } else if (timed("layout", &NodeRun::load_layout)) {
        timed("plan", &NodeRun::plan);
        if (timed("backup", &NodeRun::capture_backup) && timed("lock", &NodeRun::take_lock)) {
            timed("encoding checks", &NodeRun::encode);
            timed("event write", &NodeRun::follow_event_write);
        }
    }
    // Whatever wrote (a protocol probe, the encoding checks) is restored from the ledger's backup.
    timed("recovery", &NodeRun::after_incident);
    timed("restore", &NodeRun::restore_and_verify);
    timed("unlock", &NodeRun::release_lock);
    timed("memory map", &NodeRun::map_memory);
    timed("findings", &NodeRun::findings);
    note_unsaved_backup();
    select_results();
    note_not_tested();
    report_.elapsed = wall() - began;
    say("done in " + elapsed_text(report_.elapsed));
    return std::move(report_);
}

void NodeRun::say(const std::string& text) {
    // On a terminal the bars show progress; in a log one line at a time does.
    if (options_.progress) return;
    progress_ << "lcc-conform: " << report_.node_id << " " << text << '\n' << std::flush;
    last_line_ = wall();
}

void NodeRun::heartbeat(const std::string& text) {
    if (wall() - last_line_ >= kHeartbeat) say(text);
}

void NodeRun::begin_task(std::string label) {
    bar_.start(label, 0, wall());
    task_ = std::move(label);
}

void NodeRun::tick(std::size_t done, std::string_view unit) {
    if (options_.progress)
        bar_.update(done, wall());
    else
        heartbeat(task_ + ": " + std::to_string(done) + " " + std::string(unit));
}

void NodeRun::timed(std::string_view name, void (NodeRun::*step)()) {
    timed(name, [&] {
        (this->*step)();
        return true;
    });
}

bool NodeRun::timed(std::string_view name, bool (NodeRun::*step)()) {
    return timed(name, [&] { return (this->*step)(); });
}

bool NodeRun::timed(std::string_view name, const std::function<bool()>& step) {
    const std::size_t first = report_.checks.size();
    const auto since = wall();
    const bool long_phase =
        std::find(std::begin(kLongPhases), std::end(kLongPhases), name) != std::end(kLongPhases);
    if (long_phase) say(std::string(name) + "...");
    WriteLedger::Origin origin(session_.ledger(), std::string(name));
    const bool ok = step();
    // Results the phase judged together share its time, so durations add up to the run's.
    const Duration spent = wall() - since;
    say(std::string(name) + " done in " + elapsed_text(spent));
    std::size_t untimed = 0;
    for (std::size_t i = first; i < report_.checks.size(); ++i)
        if (report_.checks[i].duration == Duration{}) ++untimed;
    if (untimed == 0) return ok;
    for (std::size_t i = first; i < report_.checks.size(); ++i) {
        if (report_.checks[i].duration == Duration{})
            report_.checks[i].duration = spent / static_cast<long>(untimed);
    }
    return ok;
}

void NodeRun::select_results() {
    // One result per ID (per-variable SKIPs and the like become one, with details), and only
    // what --only / --skip asked for; the registry is the one source of every citation.
    merge_duplicate_ids(report_.checks);
    for (CheckResult& c : report_.checks) cite(c);
    // What happened to the node (a restart, a lost link, the restore) is reported whatever
    // --only / --skip chose: it is not a check one picks but what the run did to the node.
    std::erase_if(report_.checks, [&](const CheckResult& c) {
        const bool incident = c.id == "encoding.restore" || c.category == Category::kNode ||
                              c.category == Category::kLink;
        return !incident && !options_.selection.wants_id(c.id);
    });
}

void NodeRun::measure() {
    // A few round trips, before anything else: the answer and silence windows of the whole run
    // follow the slowest of them (a node on a busy segment, a slow node, a loaded machine).
    std::vector<Duration> samples;
    for (int i = 0; i < kLatencySamples; ++i) {
        auto rtt = session_.round_trip(node_, kLatencyTimeout);
        if (!rtt) break;  // the checks will say what does not answer
        samples.push_back(*rtt);
    }
    report_.timing = derive_timing(std::move(samples), options_.timeout_scale);
    ctx_.timing = report_.timing;
    session_.set_answer_timeout(report_.timing.answer);
    session_.set_reply_timeout(report_.timing.reply);
}

void NodeRun::identify() {
    if (auto snip = session_.snip_payload(node_)) {
        memory::Snip s = memory::decode_snip(*snip);
        report_.identity = {s.manufacturer,     s.model,     s.hardware_version,
                            s.software_version, s.user_name, s.user_description};
        report_.name = s.manufacturer + " " + s.model;
        if (!s.user_name.empty()) report_.name += " \"" + s.user_name + "\"";
    }
}

void NodeRun::protocol() {
    if (!protocol_checks_) return;
    ctx_.cdi_progress = [this](std::size_t n) { tick(n, "bytes of the CDI"); };
    ctx_.check_started = [this](std::string_view id) {
        if (!options_.progress) heartbeat("protocol checks: at " + std::string(id));
    };
    begin_task("protocol checks, reading CDI");
    report_.checks = protocol_checks_(session_, node_, ctx_);
    bar_.finish();
    // A check not run because the node or the link seemed gone is a hole in the verdict, never
    // a pass.
    if (!ctx_.link_lost_during.empty()) {
        mark_incomplete(std::to_string(ctx_.not_run) +
                        " checks not run: the link went down during " + ctx_.link_lost_during);
        return;  // the link, not the node: link.lost and the restore's wait say the rest
    }
    if (!ctx_.lost_after.empty())
        mark_incomplete(std::to_string(ctx_.not_run) +
                        " checks not run: the node stopped "
                        "answering after " +
                        ctx_.lost_after);
    // Nothing has been written yet; a node that died meanwhile gets no write at all.
    incident_ = watch_.check_now("running the protocol checks");
}

void NodeRun::skip_writes(const std::string& reason, const std::string& summary) {
    for (auto& c : skipped_encoding_checks(reason)) report_.checks.push_back(c);
    not_written_ = summary;
    evidence_.not_written = reason;
}

bool NodeRun::writes_allowed() {
    if (!options_.protocol_only.empty()) {
        skip_writes(options_.protocol_only, "nothing written (" + options_.protocol_only + ")");
        return false;
    }
    if (incident_) {
        skip_writes("the node stopped answering or restarted during the protocol checks",
                    "nothing written by the encoding checks (see node.*)");
        return false;
    }
    if (link_lost()) {
        // Reading a backup through a dead link costs every variable its full timeout.
        skip_writes("the link went down during the protocol checks",
                    "nothing written by the encoding checks (see link.lost)");
        return false;
    }
    if (options_.read_only) {
        skip_writes("--read-only: no write", "nothing written (--read-only)");
        return false;
    }
    if (!options_.selection.wants_writes()) {
        skip_writes("no check that writes is selected (--only / --skip)",
                    "nothing written (no writing check selected)");
        return false;
    }
    if (stop_requested()) {
        skip_writes("interrupted", "nothing written (interrupted)");
        return false;
    }
    return true;
}

bool NodeRun::load_layout() {
    if (ensure_layout()) return true;
    skip_writes("no usable CDI layout (see the cdi checks)", "nothing written");
    return false;
}

void NodeRun::read_stored_strings() {
    // The one encoding check that only reads: --read-only runs it too.
    if (incident_ || stop_requested() || link_lost() ||
        !options_.selection.wants_id("encoding.stored-strings"))
        return;
    const auto skipped =
        std::find_if(report_.checks.begin(), report_.checks.end(),
                     [](const CheckResult& c) { return c.id == "encoding.stored-strings"; });
    if (skipped == report_.checks.end()) return;
    if (!ensure_layout()) {
        skipped->message = "no usable CDI layout (see the cdi checks)";
        return;
    }
    EncodingOptions all = eo_;
    all.sample = options_.sample;
    all.protection = options_.protection;
    all.protection.write_protected = true;  // reading a protected setting is harmless
    all.protection.exclude.clear();         // --exclude keeps writes away, not reads
    all.protection.only.clear();
    const EncodingPlan read_plan = plan_encoding(*ctx_.layout, all);
    begin_task("stored strings");
    *skipped = check_stored_strings(read_plan.probes, memory_, hooks());
    bar_.finish();
}

bool NodeRun::ensure_layout() {
    // Without the protocol checks' layout (none ran, or their read stopped at a wrong highest
    // address), the CDI is read here up to its NUL.
    if (!ctx_.document || !ctx_.layout) {
        begin_task("reading CDI");
        MemResult cdi_bytes = session_.read_range(node_, memory::Space::kCdi, 0, kMaxCdi, true,
                                                  [&](std::size_t n) { tick(n, "bytes"); });
        bar_.finish();
        std::string xml(cdi_bytes.data.begin(), cdi_bytes.data.end());
        if (auto nul = xml.find('\0'); nul != std::string::npos) xml.resize(nul);
        auto parsed = cdi::parse(xml);
        ctx_.layout.reset();
        ctx_.document.reset();
        if (cdi_bytes.ok && parsed.document) {
            ctx_.document = std::make_unique<cdi::Document>(std::move(*parsed.document));
            ctx_.layout = cdi::build_layout(*ctx_.document).layout;
        }
    }
    return ctx_.document && ctx_.layout;
}

void NodeRun::plan() {
    eo_.sample = options_.sample;
    eo_.blob = options_.blob;
    eo_.reboot = options_.reboot;
    eo_.acdi_user = ctx_.document->acdi.has_value();
    eo_.protection = options_.protection;
    plan_ = plan_encoding(*ctx_.layout, eo_);
    // Spaces the standard makes read-only (CDI, ACDI manufacturer) and the ACDI user version
    // byte (251 @0, refused by nodes as OlcbChecker's cd40 asks) are never written, even when a
    // CDI lays variables there: cdi.acdi-spaces reports such a CDI.
    const std::size_t planned = plan_.probes.size();
    std::erase_if(plan_.probes, [](const Probe& p) {
        return p.space == 0xFF || p.space == 0xFC || (p.space == 0xFB && p.address == 0);
    });
    read_only_skipped_ = planned - plan_.probes.size();
    for (const Probe& p : plan_.probes) evidence_.planned.push_back(p.ordinal);
}

bool NodeRun::capture_backup() {
    Missing missing;
    std::string error;
    bool saved = cover_.capture(ranges_to_backup(plan_.probes, eo_), missing, error);
    if (saved && !missing.empty()) saved = retry_one_by_one(missing, error);
    // Without the user name's original the ACDI user-name check writes nothing.
    const bool name_saved = cover_.backup() && cover_.backup()->uncovered(251, 1, 63).empty();
    if (eo_.acdi_user && !name_saved) {
        eo_.acdi_user = false;
        std::string why = "not readable";
        for (const auto& [range, reason] : missing) {
            if (inside(range, 251, 1, 63)) why = reason;
        }
        eo_.acdi_user_skipped =
            "the user name (space 251 @1) could not be saved (" + why + "): not written";
    }
    if (!saved) {
        skip_writes("no safety backup, nothing written: " + error,
                    "nothing written by the encoding checks (" + error + ")");
        return false;
    }
    return true;
}

bool NodeRun::retry_one_by_one(const Missing& missing, std::string& error) {
    // A merged range that could not be read is retried variable by variable: one unreadable
    // variable must not cost the test of its neighbours.
    std::vector<RangeRequest> singles;
    for (const Probe& p : plan_.probes) {
        for (const auto& [range, why] : missing) {
            if (inside(range, p.space, p.address, p.size))
                singles.push_back({p.space, p.address, p.size});
        }
    }
    Missing still;
    const bool saved = cover_.capture(singles, still, error);
    for (const auto& entry : still) {
        const RangeRequest& range = entry.first;
        const std::string& why = entry.second;
        auto unreadable = std::find_if(plan_.probes.begin(), plan_.probes.end(), [&](auto& p) {
            return inside(range, p.space, p.address, p.size);
        });
        if (unreadable == plan_.probes.end()) continue;
        report_.checks.push_back(
            {"encoding.unreadable", Category::kEncoding, Status::kSkip,
             unreadable->key + ": " + why + "; not tested (its original could not be saved)", "",
             "", ""});
        VariableVerdict unsaved;
        unsaved.reason = "original could not be saved: " + why;
        evidence_.tested.push_back({unreadable->ordinal, std::move(unsaved)});
        plan_.probes.erase(unreadable);
    }
    return saved;
}

bool NodeRun::take_lock() {
    memory::Message reply;
    const std::uint64_t me = session_.tool_id().value();
    MemResult r = session_.command(node_, memory::encode(memory::Lock{me}), &reply);
    const auto* held = std::get_if<memory::LockReply>(&reply);
    if (r.ok && held != nullptr) {
        if (held->node_id == me) {
            locked_ = true;
            return true;
        }
        if (held->node_id != 0) {
            // The restore phase still reads back what the backup holds (a protocol probe may
            // have written): it writes only what differs.
            const std::string who = NodeId(held->node_id).to_string();
            skip_writes("node is locked by " + who + " (Lock/Reserve): nothing written",
                        "nothing written by the encoding checks (locked by " + who + ")");
            return false;
        }
    }
    // Lock/Reserve is optional: a node that rejects or ignores it is written without it, but
    // then nothing keeps a second tool from writing at the same time.
    std::string how = r.timed_out ? "not answered" : "rejected";
    if (!r.timed_out && r.error != 0) how += " with " + base::hex(r.error, 4);
    // An optional command: "not implemented" is no finding, only a caution for the user.
    const bool absent =
        !r.timed_out && r.error == base::to_u16(base::ErrorCode::kSubcommandUnknown);
    report_.checks.push_back(
        {"encoding.lock", Category::kEncoding, absent ? Status::kSkip : Status::kWarn,
         (absent ? "not implemented (0x1041): Lock/Reserve is optional" : "Lock/Reserve " + how) +
             "; a second tool writing at the same time cannot be excluded",
         "", "", ""});
    // Without the lock nothing keeps two writers apart: each reads the other's test values back
    // as the node's failures and saves them as the values to restore (two runs at once left
    // simnode's lock-rejected node changed, and made OpenMRN's io_board FAIL encoding checks).
    // A run does not write while another tool sends the node datagrams (memory configuration)
    // or another lcc-conform run is on the segment: OpenMRN's hub passes addressed frames only
    // to their destination, so there a run's datagrams to the node are never seen by the other.
    if (const std::string other = other_configurer(); !other.empty()) {
        skip_writes(other +
                        ", and the node has no Lock/Reserve to keep two writers apart: "
                        "nothing written",
                    "nothing written by the encoding checks (" + other +
                        ", and the node has no Lock/Reserve)");
        return false;
    }
    return true;
}

std::string NodeRun::other_configurer() const {
    const auto senders = session_.datagram_senders_to(session_.alias_of(node_));
    if (!senders.empty()) {
        const auto& [alias, id] = senders.front();
        return "another tool (" +
               (id ? (is_tool_id(*id) ? "lcc-conform run " : "node ") + id->to_string()
                   : "alias " + base::hex(alias, 3)) +
               ") sends the node datagrams";
    }
    if (const std::optional<NodeId> other = session_.other_tool())
        return "another lcc-conform run (" + other->to_string() + ") is on the segment";
    return "";
}

void NodeRun::release_lock() {
    if (!locked_ || abandoned_ || !session_.link().up()) return;
    session_.command(node_, memory::encode(memory::Lock{0}));
    locked_ = false;
}

EncodingHooks NodeRun::hooks() {
    EncodingHooks h;
    h.stop = [this] { return stop_requested() || link_lost(); };
    h.after_access = [this](const AccessStep& step) {
        if (!incident_) incident_ = watch_.after(step);
        return !incident_;
    };
    h.reboot = [this] { return reboot(); };
    h.snip_user_name = [this]() -> std::optional<std::string> {
        auto payload = session_.snip_payload(node_);
        if (!payload) return std::nullopt;
        return memory::decode_snip(*payload).user_name;
    };
    h.progress = [this](std::size_t done, std::size_t) { tick(done, "values"); };
    return h;
}

RebootOutcome NodeRun::reboot() {
    // A node may commit written configuration only on Update Complete (MemoryConfigurationS
    // §4.23: tools send it after writing); it may restart on it, so it is settled first.
    session_.command(node_, memory::encode(memory::UpdateComplete{}));
    session_.ping(node_, report_.timing.answer);
    watch_.rebase();
    const NodeTrack before = session_.track(node_.id);
    const std::uint8_t reset[] = {0x20, 0xA9};
    MemResult r = session_.command(node_, reset);
    if (r.rejected && !r.timed_out && r.error != 0 &&
        session_.track(node_.id).initializations == before.initializations) {
        return {false, r.error, false};
    }
    // The node may come back on another alias: the session takes it from the AMD and the
    // Initialization Complete, and every later request uses it.
    const bool back = session_.link().run_until(
        [&] { return session_.track(node_.id).initializations != before.initializations; },
        std::min<Duration>(options_.node_wait, kRebootWait));
    if (!back) {
        incident_ = watch_.check_now("waiting for the node to come back after Reset/Reboot");
        if (incident_) return {false, 0, true};
    }
    watch_.rebase();
    if (locked_) {
        // A reset clears the lock (MemoryConfigurationS §4.17): take it again, once the node
        // answers: OpenLcbCLib ignores requests sent the moment it is back (deaf-after-init),
        // and a lost Lock costs the ack and reply timeouts.
        session_.ping(node_, report_.timing.answer);
        session_.command(node_, memory::encode(memory::Lock{session_.tool_id().value()}));
    }
    return {true, 0, false};
}

void NodeRun::encode() {
    begin_task("encoding checks");
    EncodingOutcome out = run_encoding_checks(plan_.probes, memory_, eo_, hooks());
    bar_.finish();
    for (auto& c : unwritten_checks(plan_.unwritten, eo_.protection.write_protected)) {
        report_.checks.push_back(std::move(c));
    }
    for (auto& c : out.results) report_.checks.push_back(std::move(c));
    for (auto& v : out.variables) evidence_.tested.push_back(std::move(v));
    if (read_only_skipped_ != 0) {
        report_.checks.push_back(CheckResult{
            "encoding.read-only-spaces", Category::kEncoding, Status::kSkip,
            std::to_string(read_only_skipped_) +
                " variables in the read-only spaces 252/255 or on the ACDI version byte (251 @0) "
                "not written (see cdi.acdi-spaces)",
            "", "", ""});
    }
    in_flight_ = std::move(out.in_flight);
}

void NodeRun::follow_event_write() {
    // Under the backup and the lock like the encoding checks, after them: one eventid variable
    // rewritten, Update Complete, identified anew, the original back.
    if (incident_ || link_lost() || stop_requested() ||
        !options_.selection.wants_id("events.follow-write"))
        return;
    for (auto& c : checks::events_follow_write(session_, node_, ctx_, options_.protection))
        report_.checks.push_back(std::move(c));
    if (!incident_) incident_ = watch_.check_now("checking events after a write");
}

void NodeRun::after_incident() {
    if (!incident_) return;
    const CheckResult failed = incident_result(*incident_);
    report_.checks.push_back(failed);
    // Nothing more was written or checked after it: a hole in the verdict, never a pass.
    mark_incomplete(std::string(incident_->kind == NodeIncident::Kind::kRebooted
                                    ? "the node restarted"
                                    : "the node stopped answering") +
                    " while lcc-conform was " + incident_->step +
                    ": the checks after it were not run");
    // The message names the node's own variable names: untrusted bytes.
    progress_ << "lcc-conform: " << printable(failed.message) << "; waiting up to "
              << options_.node_wait.count() << " s for it to come back\n"
              << std::flush;
    if (!watch_.wait_for_return(options_.node_wait)) {
        keep_backup("the node did not come back within " +
                    std::to_string(options_.node_wait.count()) + " s");
        abandoned_ = true;
        mark_incomplete("the node did not come back within " +
                        std::to_string(options_.node_wait.count()) + " s");
        return;
    }
    // The variable in flight first: it is the one a node may act on at its next start.
    WriteLedger::Restoring restoring(session_.ledger());
    for (const InFlight& f : in_flight_) memory_.write(f.space, f.address, f.original);
    in_flight_.clear();
}

void NodeRun::note_unsaved_backup() {
    // The gate kept every write the file was to cover back, so the node is safe, but the checks
    // that write were not run: a read-only directory or a full disk once gave exit 0 and a report
    // of SKIPs that read like a clean run.
    const std::string& why = cover_.save_error();
    if (why.empty()) return;
    const std::string text =
        "the safety backup could not be written (" + why + "), so " +
        (session_.ledger().sent(node_.id) == 0 ? "nothing was written to the node"
                                               : "no write after that was sent to the node");
    mark_incomplete(text);
    progress_ << "lcc-conform: " << report_.node_id << ": " << text << '\n' << std::flush;
}

void NodeRun::mark_incomplete(const std::string& why) {
    report_.incomplete = true;
    report_.incomplete_reasons.push_back(why);
}

void NodeRun::keep_backup(const std::string& why) {
    const std::size_t writes = session_.ledger().sent(node_.id);
    if (!cover_.armed() && writes == 0) {
        report_.restore_summary = "nothing written; " + why;
        return;
    }
    cover_.abandon();
    const std::string path = std::filesystem::absolute(cover_.path()).string();
    report_.restore.writes = writes;
    report_.restore.backup_kept = path;
    report_.restore_summary =
        "not restored: " + why + "; " + std::to_string(writes) +
        (writes == 1 ? " write" : " writes") + " sent; backup kept in " + path +
        "; when the node is reachable again run: " + options_.restore_command + " " + path;
    report_.checks.push_back(
        {"encoding.restore", Category::kEncoding, Status::kFail,
         "not restored: " + why + "; backup kept in " + path +
             "; when the node is reachable again run: " + options_.restore_command + " " + path,
         "", "every saved byte written back and read again", "not restored: " + why});
}

bool NodeRun::link_lost() const {
    Link& link = session_.link();
    return link.losses() != losses_before_ || !link.up();
}

void NodeRun::wait_for_link() {
    Link& link = session_.link();
    progress_ << "lcc-conform: the link went down"
              << (link.loss_reason().empty() ? "" : " (" + link.loss_reason() + ")")
              << "; waiting up to " << options_.link_wait.count()
              << " s for it to return to restore the node\n"
              << std::flush;
    // The link's clock: simulated in tests, steady on real transports.
    const TimePoint deadline = link.now() + options_.link_wait;
    while (!stop_requested() && link.now() < deadline) {
        const Duration left = deadline - link.now();
        if (!link.up() && !link.run_until([&] { return link.up() || stop_requested(); }, left)) {
            continue;
        }
        if (stop_requested()) return;
        // Up again: the node must answer before its memory is trusted to the restore.
        if (session_.find_node(node_.id)) {
            progress_ << "lcc-conform: link back; restoring\n" << std::flush;
            return;
        }
    }
}

void NodeRun::restore_and_verify() {
    if (abandoned_) return;  // the backup is kept for the user
    const std::size_t writes = session_.ledger().sent(node_.id);
    report_.restore.writes = writes;
    if (!cover_.armed() && writes == 0) {
        // The ledger is the only evidence: no write went out, so there is nothing to restore.
        report_.restore_summary = not_written_.empty() ? "nothing written" : not_written_;
        return;
    }
    if (link_lost()) {
        evidence_.not_judged = "not judged: the link went down mid-run";
        // What ran after the loss measured the link, not the node.
        for (CheckResult& c : report_.checks) {
            if (c.category == Category::kEncoding || c.id == "snip.follows-acdi-user-write") {
                c.status = Status::kSkip;
                c.message = "not judged: the link went down mid-run";
                c.expected.clear();
                c.seen.clear();
            }
        }
        wait_for_link();
        if (!session_.link().up()) {
            keep_backup("the link is still down");
            return;
        }
    }
    const RestoreOutcome outcome = cover_.finish();
    const std::vector<PastEndBytes> kept = session_.ledger().unrestorable(node_.id);
    report_.restore.saved_bytes = outcome.bytes;
    report_.restore.rewritten_bytes = outcome.rewritten;
    report_.restore.identical = outcome.identical;
    for (const PastEndBytes& p : kept)
        report_.restore.past_end.push_back({p.space, p.address, p.count});
    for (const auto& l : outcome.left_as_found)
        report_.restore.left_as_found.push_back({l.range.space, l.range.address, l.range.length});
    report_.restore_summary = restore_line(outcome, kept, writes);
    // What another tool changed is no failure of the node's, but the user should know of it.
    const bool whole = kept.empty() && outcome.left_as_found.empty();
    CheckResult restored{"encoding.restore",
                         Category::kEncoding,
                         !outcome.identical ? Status::kFail
                         : whole            ? Status::kPass
                                            : Status::kWarn,
                         report_.restore_summary,
                         "",
                         "",
                         ""};
    if (outcome.identical && outcome.left_as_found.empty()) {
        cover_.remove_file();
    } else if (outcome.identical) {
        // The values before the other tool's change stay at hand, should it have been unwanted.
        const std::string path = std::filesystem::absolute(cover_.path()).string();
        report_.restore.backup_kept = path;
        restored.message += "; the values from before the run are kept in " + path;
    } else {
        restored.expected = "memory byte-identical to before the run";
        restored.seen = outcome.summary();
        const std::string path = std::filesystem::absolute(cover_.path()).string();
        report_.restore.backup_kept = path;
        restored.message += "; backup kept in " + path +
                            "; when the node is reachable again run: " + options_.restore_command +
                            " " + path;
    }
    report_.checks.push_back(std::move(restored));
}

void NodeRun::map_memory() {
    // Whatever the run did, the map shows the layout; its verdicts say how far the run got.
    if (!ctx_.layout) return;
    evidence_.sample = options_.sample;
    evidence_.blob = options_.blob;
    evidence_.max_variables = eo_.max_variables;
    evidence_.protection = options_.protection;
    report_.memory_map = node_memory_map(*ctx_.layout, evidence_);
}

void NodeRun::note_slow_node() {
    const RunTiming& t = report_.timing;
    if (!t.latency || t.worst < kSlowNode) return;
    const auto ms = std::chrono::duration_cast<std::chrono::milliseconds>(t.worst).count();
    for (CheckResult& c : report_.checks) {
        if (c.status != Status::kFail) continue;
        const std::string text = c.message + " " + c.seen;
        if (text.find("no answer") == std::string::npos &&
            text.find("timed out") == std::string::npos &&
            text.find("no reply") == std::string::npos)
            continue;
        c.message += " (a slow node: its Verify round trip took up to " + std::to_string(ms) +
                     " ms at the start; --timeout-scale widens every window)";
    }
}

void NodeRun::note_not_tested() {
    // What this run left out and the option that tests it: a clean report must not read as
    // "everything is fine" when whole rules were never looked at.
    std::vector<std::string>& out = report_.not_tested;
    const CheckSelection& sel = options_.selection;
    if (!options_.protocol_only.empty()) {
        out.push_back(
            options_.protocol_only +
            ": checked for frame, message, SNIP, PIP, events, train, train search and FDI only");
        return;
    }
    if (options_.read_only && sel.wants_writes())
        out.push_back(
            "writes not tested (encoding checks, write refusals, persistence): run "
            "without --read-only");
    if (!options_.reboot && !options_.read_only && sel.wants_id("encoding.persist-after-reboot"))
        out.push_back("persistence not tested (values surviving Reset/Reboot): add --reboot");
    if (!options_.reboot && sel.wants_id("frame.startup-sequence"))
        out.push_back(
            "start-up sequence not tested (CID..RID, AMD, Initialization Complete "
            "after Reset/Reboot): add --reboot");
    if (!options_.blob && !options_.read_only && ctx_.layout) {
        std::size_t blobs = 0;
        ctx_.layout->visit([&](const cdi::Cursor& c) {
            blobs +=
                c.element().kind == cdi::ElementKind::kBlob && c.element().blob_mode == "readwrite";
            return true;
        });
        if (blobs != 0)
            out.push_back(std::to_string(blobs) +
                          " writable <blob> variables not written: add "
                          "--blob");
    }
    CheckSelection with_thorough = sel;
    with_thorough.thorough = true;
    std::string thorough;
    std::size_t count = 0;
    for (const CheckSpec& spec : check_registry()) {
        if (!spec.thorough || sel.thorough || !with_thorough.wants(spec)) continue;
        thorough += (count++ == 0 ? "" : ", ") + std::string(spec.id);
    }
    if (count != 0)
        out.push_back(std::to_string(count) + " thorough-only checks not run (" + thorough +
                      "): add --thorough");
    CheckSelection crossing = sel;
    crossing.write_past_end = true;
    crossing.thorough = true;
    for (const CheckSpec& spec : check_registry()) {
        if (!spec.past_end_writes || sel.write_past_end || options_.read_only ||
            !crossing.wants(spec))
            continue;
        out.push_back("writes crossing the end of a space not tested (" + std::string(spec.id) +
                      "): add --write-past-end (a node without a bounds check keeps the bytes "
                      "past the end for good)");
    }
}

void NodeRun::findings() {
    note_slow_node();
    Link& link = session_.link();
    if (!abandoned_ && link.up() && !link_lost()) {
        for (auto& c : short_read_checks(session_, node_, ctx_)) report_.checks.push_back(c);
    }
    if (link.losses() == losses_before_ && link.up()) return;
    std::string message = "the link went down during the run";
    if (!link.loss_reason().empty()) message += ": " + link.loss_reason();
    message += link.up() ? " (it came back)" : " (still down)";
    report_.checks.push_back(CheckResult{
        "link.lost", Category::kLink, Status::kFail, message, "", "the link up for the whole run",
        link.loss_reason().empty() ? "the link went down" : link.loss_reason()});
}

}  // namespace olcb::conform
