// What the report suites share (report/): one node's report with a check of every status and
// node text to escape, and the run it came from.
#pragma once

#include <chrono>

#include "conformance/report/report.hpp"

namespace olcb::conform::testing {

/// U+FFFD, what invalid UTF-8 from a node is shown as.
inline constexpr const char* kFffd = "\xEF\xBF\xBD";

/// A node's report: a PASS, a FAIL with expected and seen, a SKIP and a WARN with a control byte.
inline NodeReport sample() {
    NodeReport r;
    r.node_id = "05.01.01.01.22.00";
    r.name = "ACME Sim CDI Node";
    r.checks = {
        {"frame.ame-answered", Category::kFrame, Status::kPass, "AMD came",
         "CanFrameTransferS 6.2.3", "", ""},
        {"encoding.int", Category::kEncoding, Status::kFail, "bytes <differ> & \"x\"",
         "CDI S 5.1.4.2", "03 E8", "E8 03"},
        {"encoding.blob", Category::kEncoding, Status::kSkip, "not asked", "", "", ""},
        {"cdi.xml-declaration", Category::kCdi, Status::kWarn, "odd \x01 text", "CDI S 5", "", ""},
    };
    r.restore_summary = "node memory byte-identical to before";
    return r;
}

/// A run of lcc-conform over TCP that took 2.5 s and failed.
inline RunInfo sample_run() {
    RunInfo run;
    run.connection = "connect 127.0.0.1:12021";
    run.arguments = {"lcc-conform", "--connect", "127.0.0.1:12021"};
    run.started = std::chrono::system_clock::time_point{} + std::chrono::hours(24 * 365 * 57);
    run.elapsed = std::chrono::milliseconds(2500);
    run.exit_code = 1;
    return run;
}

}  // namespace olcb::conform::testing
