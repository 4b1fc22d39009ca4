// The outcome of one conformance check: what every check produces and every report consumes.
#pragma once

#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "conformance/report/map_verdict.hpp"
#include "conformance/report/run_timing.hpp"

namespace olcb::conform {

/// Result of a check; kWarn is a finding that does not fail the run.
enum class Status : std::uint8_t { kPass, kFail, kWarn, kSkip };

/// The check categories of docs/checks.md.
enum class Category : std::uint8_t {
    kFrame,
    kMessage,
    kPip,
    kSnip,
    kDatagram,
    kMemory,
    kCdi,
    kAcdi,
    kEncoding,
    kLink,    ///< the transport itself (an adapter unplugged, a hub gone): not the node's fault
    kNode,    ///< the node as a whole: it stopped answering or restarted during the run
    kEvents,  ///< event identification (Identify Events, Identify Producer/Consumer)
    kStream,  ///< memory-config stream reads and the stream transport under them
    kTrain,   ///< Train Control: a train node's commands, replies, state and memory spaces
    kSearch,  ///< Train Search: finding trains, a command station creating them
    kFdi,     ///< Function Description Information in space 0xFA
    kClock,   ///< Broadcast Time: clock generators and consumers
};

/// "PASS", "FAIL", "WARN" or "SKIP".
std::string_view status_name(Status status);
/// "frame", "message", "pip", "snip", "datagram", "memory", "cdi", "acdi", "encoding", "link",
/// "node", "events", "stream", "train", "search", "fdi" or "clock".
std::string_view category_name(Category category);

/// One executed check.
struct CheckResult {
    std::string id;  ///< stable ID from docs/checks.md, e.g. "cdi.nul-terminated"
    Category category = Category::kMessage;
    Status status = Status::kSkip;
    std::string message;  ///< one line: what was checked, and for failures what went wrong
    std::string
        section;  ///< the standard and section, e.g. "CDI S 5" or "MemoryConfigurationS 4.8"
    std::string expected;  ///< for failures: what the standard wants (may be empty)
    std::string seen;      ///< for failures: what the node did (may be empty)
    /// Further lines (every CDI error, every variable of a merged result); may be empty.
    std::vector<std::string> details{};
    /// How long the check took (a share of its phase when the phase judges several at once).
    Duration duration{};
};

/// Merges results that share an ID into one, at the first one's place, so IDs are unique in a
/// node's report: the worst status (FAIL, WARN, PASS, SKIP) with the first such result's message
/// (saying how many more), expected and seen; every merged message in details.
void merge_duplicate_ids(std::vector<CheckResult>& results);

/// What the node says it is (its SNIP strings, as sent: untrusted bytes).
struct NodeIdentity {
    std::string manufacturer;      ///< SNIP manufacturer name
    std::string model;             ///< SNIP model name
    std::string hardware_version;  ///< SNIP hardware version
    std::string software_version;  ///< SNIP software version
    std::string user_name;         ///< SNIP user-provided name
    std::string user_description;  ///< SNIP user-provided description
};

/// Consecutive bytes of one space.
struct ByteRun {
    std::uint8_t space = 0;
    std::uint32_t address = 0;  ///< the first byte
    std::uint32_t count = 0;
};

/// What the run wrote to a node and how the restore ended, from the write ledger.
struct RestoreRecord {
    std::size_t writes = 0;           ///< writes the node received (restores excluded)
    std::size_t saved_bytes = 0;      ///< bytes the safety backup held, read back at the end
    std::size_t rewritten_bytes = 0;  ///< of them, bytes that differed and were written back
    std::optional<bool> identical;    ///< every saved byte read back as saved (unset: no restore)
    /// Bytes a node may keep past the end of a space: written there, never readable or restorable.
    std::vector<ByteRun> past_end;
    /// Saved bytes that changed during the run though none of its writes reached them: another
    /// tool's change, left as found.
    std::vector<ByteRun> left_as_found;
    std::string backup_kept;  ///< the backup file's path when it was kept
};

/// Every check run against one node, in the order they ran.
struct NodeReport {
    std::string node_id;    ///< dotted hex, e.g. "05.01.01.01.22.00"
    std::string name;       ///< SNIP manufacturer + model + user name, for humans
    NodeIdentity identity;  ///< the SNIP strings ("" each when SNIP did not answer)
    std::chrono::system_clock::time_point started{};  ///< when the node's run began
    Duration elapsed{};                               ///< how long the node's run took
    std::vector<CheckResult> checks;
    std::string restore_summary;  ///< "memory byte-identical to before" or what differs
    RestoreRecord restore;        ///< the numbers behind restore_summary
    /// How the node was checked: "configurable" (every check) or "protocol only: WHY".
    std::string scope = "configurable";
    /// The windows the run used, from the node's measured latency.
    RunTiming timing;
    /// The run's verdict has a hole: checks were not run because the node stopped answering,
    /// or the node never came back (its backup file is kept); the exit status is then 2.
    bool incomplete = false;
    /// Why incomplete, one line each ("29 checks not run: the node stopped answering after ID").
    std::vector<std::string> incomplete_reasons;
    /// Every space of the node's CDI layout with each listed variable's verdict (empty when the
    /// CDI gave no layout).
    std::vector<MemoryMapSpace> memory_map;
    /// What the run's options left untested, each with the option that tests it, e.g.
    /// "persistence not tested (values surviving Reset/Reboot): add --reboot".
    std::vector<std::string> not_tested;

    /// Number of checks with this status.
    std::size_t count(Status status) const;
};

/// How bad a status is, for the worst of several: FAIL 3, WARN 2, PASS 1, SKIP 0.
int severity(Status s);

}  // namespace olcb::conform
