// A sink recording every frame of a segment as GridConnect lines and/or candump -L lines.
#pragma once

#include <chrono>
#include <fstream>
#include <functional>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "openlcb/can_frame.hpp"

namespace olcb {

/// Writes each recorded frame to every attached output, one line per frame.
///
/// GridConnect outputs get `:X19490343N;` lines (what the hub and the tests speak); candump
/// outputs get `(1700000000.123456) vcan0 19490343#` lines that canplayer replays. Lines are
/// flushed as written so a log survives a crash of the program that writes it.
class TrafficLog {
public:
    /// Microseconds since the Unix epoch; replaceable for deterministic tests.
    using Clock = std::function<std::chrono::microseconds()>;

    /// A log with no outputs, stamping candump lines with the system clock.
    TrafficLog();
    /// A log stamping candump lines with `clock`.
    explicit TrafficLog(Clock clock);

    /// Appends GridConnect lines to the file at `path`; false if it cannot be opened.
    bool add_gridconnect_file(const std::string& path);
    /// Appends candump -L lines naming `interface` to the file at `path`; false if not opened.
    bool add_candump_file(const std::string& path, const std::string& interface = "vcan0");
    /// Writes GridConnect lines to a caller-owned stream that outlives the log.
    void add_gridconnect_stream(std::ostream& out);
    /// Writes candump lines to a caller-owned stream that outlives the log.
    void add_candump_stream(std::ostream& out, const std::string& interface = "vcan0");

    /// Writes `frame` to every output, stamped with the clock.
    void record(const CanFrame& frame);
    /// Writes `frame` to every output with an explicit timestamp.
    void record(const CanFrame& frame, std::chrono::microseconds timestamp);

    /// False once any output failed to write.
    bool ok() const;
    /// Lines written per output so far.
    std::uint64_t frames_recorded() const { return frames_; }

private:
    struct Output {
        std::ostream* stream;
        bool candump;
        std::string interface;
    };
    Clock clock_;
    std::vector<std::unique_ptr<std::ofstream>> files_;
    std::vector<Output> outputs_;
    std::string line_;
    std::uint64_t frames_ = 0;
};

}  // namespace olcb
