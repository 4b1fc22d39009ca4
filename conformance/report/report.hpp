// Reports of a conformance run: a text line per check for people, JSON and JUnit XML for machines,
// and a progress bar on a terminal while long reads run.
#pragma once

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>
#include <string_view>
#include <vector>

#include "base/utf8.hpp"
#include "conformance/report/check_result.hpp"

namespace olcb::conform {

/// Node text made safe for terminals, JSON and XML (base/utf8.hpp): every byte that is not part
/// of valid UTF-8 becomes U+FFFD, control characters (C0, DEL, C1) become '?', and the
/// non-characters U+FFFE and U+FFFF (not allowed in XML) become U+FFFD.
using base::printable;

/// Node-supplied bytes for a message: at most max_bytes of them (cut on a UTF-8 boundary, "..."
/// marking the cut), printable(), in double quotes when quote is set, then " (bytes 62 61 FF)"
/// with the raw bytes in hex whenever printable() had to change any of them.
std::string show_node_text(std::string_view text, bool quote = true, std::size_t max_bytes = 80);

/// Totals over every node of a run.
struct Summary {
    std::size_t pass = 0;
    std::size_t fail = 0;
    std::size_t warn = 0;
    std::size_t skip = 0;
    /// Number of checks counted.
    std::size_t total() const { return pass + fail + warn + skip; }
};

/// What a run says beyond its nodes' checks.
struct RunInfo {
    std::string error;                    ///< why the run ended early ("" when it did not)
    std::vector<std::string> late_nodes;  ///< nodes that appeared during the run, not checked
    std::vector<std::string> other_runs;  ///< other lcc-conform runs seen (their tool IDs)
    std::string connection;  ///< how the run reached the bus, e.g. "tcp 127.0.0.1:12021"
    std::vector<std::string> arguments;               ///< the command line, program first
    std::chrono::system_clock::time_point started{};  ///< when the run began
    std::chrono::steady_clock::duration elapsed{};    ///< how long it ran
    int exit_code = 0;                                ///< the program's exit status
};

/// UTC ISO 8601 with milliseconds: "2026-12-01T23:40:05.123Z".
std::string iso_timestamp(std::chrono::system_clock::time_point t);

/// The totals of some node reports.
Summary summarize(const std::vector<NodeReport>& reports);

/// One line for a check: "PASS  id  message", failures followed by expected/seen and the section;
/// ANSI colour on the status word when colour is true. No trailing newline.
std::string format_check(const CheckResult& check, bool colour);

/// How much of a node's report the text shows (lcc-conform's --failures-only and -q).
enum class TextDetail : std::uint8_t {
    kFull,          ///< header, findings, the passes and other skips, summary, what was not tested
    kFailuresOnly,  ///< the same without the passes and the skips that have no failed cause
    kQuiet,         ///< the findings and the summary only
};

/// The text report's form: colour on the status words, and how much it shows.
struct TextStyle {
    bool colour = false;
    TextDetail detail = TextDetail::kFull;
};

/// The whole text report of one node, what is wrong first, so a reader meets the first FAIL in
/// the first lines: the header (node, identity, timing); every FAIL and WARN in run order, each
/// followed by the SKIPs that "depend on" it (directly or through another SKIP); the passes as
/// one block of IDs ("PASS  89 checks: id id ...") and the other SKIPs, one line each; then the
/// summary: the restore outcome, the totals, the IDs that failed and warned, and one line per
/// thing not tested naming the option that tests it. The same on a terminal and in a file.
void write_text(std::ostream& out, const NodeReport& report, TextStyle style);
/// write_text() of everything, with colour or not.
inline void write_text(std::ostream& out, const NodeReport& report, bool colour) {
    write_text(out, report, TextStyle{colour, TextDetail::kFull});
}

/// The ID a SKIP "depends on <id>: why" names ("" for any other result).
std::string_view depends_on(const CheckResult& check);

/// The JSON report of docs/report.schema.json: {"schema_version", "tool", "run", "nodes": [...]}
/// for any number of nodes.
std::string to_json(const std::vector<NodeReport>& reports, const RunInfo& run = {});

/// The JUnit XML report (tests/support/junit.xsd): one <testsuite> per node named by node ID and
/// model, with <properties> (node ID, SNIP strings, tool version) and times; one <testcase> per
/// check (classname = category, name = "<id> on <node ID>": unique in the file); FAIL as
/// <failure> (a lost link or a dead node as <error>), SKIP as <skipped>, WARN as a passing case
/// with <system-out>. A run error is one more testsuite "lcc-conform" whose testcase has <error>.
std::string to_junit(const std::vector<NodeReport>& reports, const RunInfo& run = {});

/// True when file descriptor fd is a terminal (colour and progress bars only then).
bool is_terminal(int fd);

/// A one-line progress bar with bytes and ETA, redrawn in place (for stderr on a terminal).
class ProgressBar {
public:
    /// A bar writing to out; disabled bars print nothing.
    ProgressBar(std::ostream& out, bool enabled) : out_(out), enabled_(enabled) {}
    /// Starts a new task of `total` bytes (0 when unknown) at time now.
    void start(std::string label, std::size_t total, std::chrono::steady_clock::time_point now);
    /// Redraws for `done` bytes at time now.
    void update(std::size_t done, std::chrono::steady_clock::time_point now);
    /// Clears the line.
    void finish();
    /// The text update() draws (without the carriage return), for tests.
    std::string render(std::size_t done, std::chrono::steady_clock::time_point now) const;

private:
    std::ostream& out_;
    bool enabled_;
    std::string label_;
    std::size_t total_ = 0;
    std::chrono::steady_clock::time_point started_{};
    bool drawn_ = false;
};

}  // namespace olcb::conform
